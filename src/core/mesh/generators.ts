/**
 * Cloth shapes made from a few numbers: a disc (concentric rings, six more vertices per ring, so no 4-fold grid
 * bias) and a tube (an open cylinder, for skirts and sleeves); and `placeMesh`, which puts any mesh where the
 * scene's cloth.position and cloth.rotation say. The rectangle is the seed's grid (model.ts buildGridModel).
 */
import type { TriangleMesh } from './triangle-mesh.js';
import { shownValue } from '../text.js';

/** How a generated or loaded mesh is laid out at the start (the scene's cloth fields; units as in the schema). */
export interface Placement {
  /** centre of the cloth at the start [m] */
  position: readonly [number, number, number];
  /** extra rotation about the centre, Euler XYZ [degrees] */
  rotation: readonly [number, number, number];
}

/** Rotation matrix (row-major 3×3) for Euler XYZ angles in degrees: R = Rz·Ry·Rx (about x first). */
export function eulerXYZ(deg: readonly [number, number, number]): number[] {
  const r = new Float64Array(9);
  eulerXYZInto(deg[0], deg[1], deg[2], r);
  return Array.from(r);
}

/** eulerXYZ into `r` (no allocation: per-substep collider motion). */
export function eulerXYZInto(xDeg: number, yDeg: number, zDeg: number, r: Float64Array): void {
  const x = (xDeg * Math.PI) / 180, y = (yDeg * Math.PI) / 180, z = (zDeg * Math.PI) / 180;
  const cx = Math.cos(x), sx = Math.sin(x), cy = Math.cos(y), sy = Math.sin(y), cz = Math.cos(z), sz = Math.sin(z);
  r[0] = cy * cz; r[1] = sx * sy * cz - cx * sz; r[2] = cx * sy * cz + sx * sz;
  r[3] = cy * sz; r[4] = sx * sy * sz + cx * cz; r[5] = cx * sy * sz - sx * cz;
  r[6] = -sy; r[7] = sx * cy; r[8] = cx * cy;
}

/**
 * Moves a mesh so that the centre of its bounding box is at `position`, turned by `rotation` about that centre.
 * Returns a new positions array.
 */
export function placeMesh(positions: Float32Array, place: Placement): Float32Array {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], positions[i + k]);
      hi[k] = Math.max(hi[k], positions[i + k]);
    }
  }
  const c = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  const R = eulerXYZ(place.rotation);
  const [px, py, pz] = place.position;
  const out = new Float32Array(positions.length);
  for (let i = 0; i < positions.length; i += 3) {
    const x = positions[i] - c[0], y = positions[i + 1] - c[1], z = positions[i + 2] - c[2];
    out[i] = px + R[0] * x + R[1] * y + R[2] * z;
    out[i + 1] = py + R[3] * x + R[4] * y + R[5] * z;
    out[i + 2] = pz + R[6] * x + R[7] * y + R[8] * z;
  }
  return out;
}

/**
 * Lays a shape given in sheet coordinates (u, v in the sheet, w out of it) into the world like the grid cloth:
 * 'horizontal' puts the sheet in the xz plane (x = u, y = w, z = v); 'hanging' in the xy plane (x = u, y = −v,
 * z = −w, a half turn about x of the horizontal pose). The centre of the sheet coordinates is the origin.
 */
function sheetToWorld(local: Float32Array, orientation: 'horizontal' | 'hanging'): Float32Array {
  const out = new Float32Array(local.length);
  for (let i = 0; i < local.length; i += 3) {
    const u = local[i], v = local[i + 1], w = local[i + 2];
    if (orientation === 'horizontal') { out[i] = u; out[i + 1] = w; out[i + 2] = v; }
    else { out[i] = u; out[i + 1] = -v; out[i + 2] = -w; }
  }
  return out;
}

/** Flips every triangle when the first one's normal points against `want` (generators then agree with the grid). */
function orientLike(mesh: TriangleMesh, want: readonly number[]): void {
  const p = mesh.positions, t = mesh.triangles;
  const a = 3 * t[0], b = 3 * t[1], c = 3 * t[2];
  const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
  const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
  const d = (uy * vz - uz * vy) * want[0] + (uz * vx - ux * vz) * want[1] + (ux * vy - uy * vx) * want[2];
  if (d < 0) for (let k = 0; k < t.length; k += 3) { const s = t[k + 1]; t[k + 1] = t[k + 2]; t[k + 2] = s; }
}

/** What the disc and tube generators read: the scene's cloth fields (see scene-schema.ts). */
export interface ShapeSpec extends Placement {
  /** the density knob: faces across the diameter (disc), faces along the longer of circumference and length (tube) */
  resolution: number;
  /** diameter [m] */
  width: number;
  /** length of a tube along its axis [m] (a disc ignores it) */
  height: number;
  orientation: 'horizontal' | 'hanging';
}

/** Throws RangeError naming the field of `spec` that no shape can be made of (the library's callers: scenes are checked by the schema). */
function checkSpec(spec: ShapeSpec, fn: string): void {
  if (spec === null || typeof spec !== 'object') throw new TypeError(`${fn}: the spec must be an object`);
  const vec = (v: unknown) => Array.isArray(v) && v.length === 3 && v.every(Number.isFinite);
  if (!(Number.isInteger(spec.resolution) && spec.resolution >= 1)) throw new RangeError(`${fn}: resolution must be an integer ≥ 1, got ${shownValue(spec.resolution)}`);
  if (!(spec.width > 0 && Number.isFinite(spec.width))) throw new RangeError(`${fn}: width must be a length > 0 [m], got ${shownValue(spec.width)}`);
  if (fn === 'tubeMesh' && !(spec.height > 0 && Number.isFinite(spec.height))) throw new RangeError(`${fn}: height must be a length > 0 [m], got ${shownValue(spec.height)}`);
  if (spec.orientation !== 'horizontal' && spec.orientation !== 'hanging') throw new RangeError(`${fn}: orientation must be 'horizontal' or 'hanging', got ${shownValue(spec.orientation)}`);
  if (!vec(spec.position)) throw new RangeError(`${fn}: position must be [x, y, z] of finite numbers [m]`);
  if (!vec(spec.rotation)) throw new RangeError(`${fn}: rotation must be [x, y, z] of finite numbers [degrees]`);
}

/**
 * A flat disc of diameter `width`: a centre vertex and ⌈resolution/2⌉ rings, ring k at radius k·r/K with 6k
 * vertices, neighbouring rings stitched by walking both in angle order. Faces point up (+y) when horizontal.
 */
export function discMesh(spec: ShapeSpec): TriangleMesh {
  checkSpec(spec, 'discMesh');
  const K = Math.max(1, Math.ceil(spec.resolution / 2));
  const R = spec.width / 2;
  const n = 1 + 3 * K * (K + 1);
  const local = new Float32Array(3 * n);
  const uvs = new Float32Array(2 * n);
  const first = (k: number) => (k === 0 ? 0 : 1 + 3 * k * (k - 1)); // index of ring k's first vertex
  uvs[0] = 0.5; uvs[1] = 0.5;
  for (let k = 1; k <= K; k++) {
    const count = 6 * k, r = (k * R) / K;
    for (let i = 0; i < count; i++) {
      const a = (2 * Math.PI * i) / count, j = first(k) + i;
      local[3 * j] = r * Math.cos(a);
      local[3 * j + 1] = r * Math.sin(a);
      uvs[2 * j] = 0.5 + local[3 * j] / spec.width;
      uvs[2 * j + 1] = 0.5 - local[3 * j + 1] / spec.width;
    }
  }
  const tri: number[] = [];
  for (let i = 0; i < 6; i++) tri.push(0, 1 + i, 1 + ((i + 1) % 6));
  for (let k = 2; k <= K; k++) {
    const a = 6 * (k - 1), b = 6 * k, fa = first(k - 1), fb = first(k);
    let i = 0, j = 0;
    while (i < a || j < b) {
      // advance along whichever ring's next vertex comes first in angle (the outer one on a tie)
      if (j < b && (i >= a || (j + 1) / b <= (i + 1) / a)) {
        tri.push(fa + (i % a), fb + j, fb + ((j + 1) % b));
        j++;
      } else {
        tri.push(fa + (i % a), fb + (j % b), fa + ((i + 1) % a));
        i++;
      }
    }
  }
  const mesh: TriangleMesh = { positions: sheetToWorld(local, spec.orientation), triangles: Uint32Array.from(tri), uvs };
  orientLike(mesh, spec.orientation === 'horizontal' ? [0, 1, 0] : [0, 0, -1]);
  mesh.positions = placeMesh(mesh.positions, spec);
  return mesh;
}

/**
 * An open cylinder of diameter `width` and length `height`, its axis along the sheet's v (vertical when hanging,
 * along z when horizontal): rings of M vertices, row 0 at the top (hanging), cells about square, with
 * `resolution` faces along the longer of circumference and length. Faces point outwards.
 */
export function tubeMesh(spec: ShapeSpec): TriangleMesh {
  checkSpec(spec, 'tubeMesh');
  const circumference = Math.PI * spec.width;
  const cell = Math.max(circumference, spec.height) / spec.resolution;
  const M = Math.max(3, Math.round(circumference / cell));
  const L = Math.max(1, Math.round(spec.height / cell));
  const R = spec.width / 2;
  const n = M * (L + 1);
  const local = new Float32Array(3 * n);
  const uvs = new Float32Array(2 * n);
  for (let r = 0; r <= L; r++) {
    for (let i = 0; i < M; i++) {
      const a = (2 * Math.PI * i) / M, j = r * M + i;
      local[3 * j] = R * Math.cos(a);
      local[3 * j + 1] = (r * spec.height) / L - spec.height / 2;
      local[3 * j + 2] = R * Math.sin(a);
      uvs[2 * j] = i / M;
      uvs[2 * j + 1] = 1 - r / L;
    }
  }
  const tri = new Uint32Array(6 * M * L);
  let t = 0;
  for (let r = 0; r < L; r++) {
    for (let i = 0; i < M; i++) {
      const a = r * M + i, b = r * M + (i + 1) % M, c = a + M, d = b + M;
      tri[t++] = a; tri[t++] = c; tri[t++] = d;
      tri[t++] = a; tri[t++] = d; tri[t++] = b;
    }
  }
  const mesh: TriangleMesh = { positions: sheetToWorld(local, spec.orientation), triangles: tri, uvs };
  // the first triangle sits at angle 0, where outwards is +x in both poses
  orientLike(mesh, [1, 0, 0]);
  mesh.positions = placeMesh(mesh.positions, spec);
  return mesh;
}
