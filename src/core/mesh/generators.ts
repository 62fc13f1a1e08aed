/**
 * Cloth shapes made from a few numbers: a disc (concentric rings, six more vertices per ring, so no 4-fold grid
 * bias; or the rectangle's lattice cut round, its threads along two directions as a woven fabric's) and a tube (an open cylinder, for skirts and sleeves); and `placeMesh`, which puts any mesh where the
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
  eulerXYZInto(deg, r);
  return Array.from(r);
}

/**
 * eulerXYZ into `r` (no allocation: per-substep collider motion), the angles read from `deg` (an array, not three
 * arguments: a number passed to a call V8 does not inline is boxed).
 */
export function eulerXYZInto(deg: ArrayLike<number>, r: Float64Array): void {
  const x = (deg[0] * Math.PI) / 180, y = (deg[1] * Math.PI) / 180, z = (deg[2] * Math.PI) / 180;
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
 * A tube's faces around and along (tubeMesh): `resolution` along the longer of circumference and length, the other
 * in proportion, with at least 3 around and 1 along (`raised`: that minimum raised one of them).
 */
export function tubeFaces(spec: Pick<ShapeSpec, 'width' | 'height' | 'resolution'>): { around: number; along: number; raised: boolean } {
  const circumference = Math.PI * spec.width;
  const cell = Math.max(circumference, spec.height) / spec.resolution;
  const around = Math.round(circumference / cell), along = Math.round(spec.height / cell);
  return { around: Math.max(3, around), along: Math.max(1, along), raised: around < 3 || along < 1 };
}

/**
 * An open cylinder of diameter `width` and length `height`, its axis along the sheet's v (vertical when hanging,
 * along z when horizontal): rings of M vertices, row 0 at the top (hanging), cells about square, with
 * `resolution` faces along the longer of circumference and length. Faces point outwards.
 */
export function tubeMesh(spec: ShapeSpec): TriangleMesh {
  checkSpec(spec, 'tubeMesh');
  const { around: M, along: L } = tubeFaces(spec);
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

/**
 * A flat disc of diameter `width` cut from the rectangle's lattice, its threads along the sheet's u and v (the warp
 * and the weft): `resolution` square cells across (at least 4), cell size h = width/resolution. A lattice vertex
 * within 0.3·h of the circle is moved onto it; one further out is dropped, and a lattice line from a vertex inside to
 * one dropped ends where it crosses the circle; each cell keeps the part of it inside (a whole cell is split into two
 * triangles, a cut one into a fan chosen for its widest smallest angle; a part with every corner on the circle, a
 * sliver, is left out). UVs as on the ring disc: u = ½ + x/width, v = ½ − y/width, so the threads run along u and v.
 */
export function wovenDiscMesh(spec: ShapeSpec): TriangleMesh {
  checkSpec(spec, 'wovenDiscMesh');
  const N = wovenDiscCells(spec.resolution), R = spec.width / 2, h = spec.width / N, snap = 0.3 * h;
  const side = N + 1, at = (i: number, j: number) => j * side + i;
  // each lattice vertex: its position, and whether it is inside (0), on the circle (1) or dropped (2)
  const gx = new Float64Array(side * side), gy = new Float64Array(side * side), kind = new Uint8Array(side * side);
  for (let j = 0; j < side; j++) {
    for (let i = 0; i < side; i++) {
      const v = at(i, j), x = (i - N / 2) * h, y = (j - N / 2) * h, r = Math.hypot(x, y);
      if (r <= R - snap) { gx[v] = x; gy[v] = y; kind[v] = 0; }
      else if (r < R + snap) { gx[v] = (x * R) / r; gy[v] = (y * R) / r; kind[v] = 1; }
      else { gx[v] = x; gy[v] = y; kind[v] = 2; }
    }
  }
  // the polygon each cell keeps, as points: a lattice vertex v (≥ 0) or the crossing of a lattice line −1 − c
  const cx: number[] = [], cy: number[] = [];
  const crossings = new Map<number, number>();
  const crossing = (u: number, w: number) => {
    const key = Math.min(u, w) * side * side + Math.max(u, w);
    let c = crossings.get(key);
    if (c === undefined) {
      const [a, b] = kind[u] === 0 ? [u, w] : [w, u];
      const ax = gx[a], ay = gy[a], dx = gx[b] - ax, dy = gy[b] - ay;
      // |a + t·d| = R for t in (0, 1): a·a + 2t·a·d + t²·d·d = R²
      const A = dx * dx + dy * dy, B = ax * dx + ay * dy, C = ax * ax + ay * ay - R * R;
      const t = (-B + Math.sqrt(B * B - A * C)) / A;
      c = cx.length;
      cx.push(ax + t * dx); cy.push(ay + t * dy);
      crossings.set(key, c);
    }
    return -1 - c;
  };
  const px: number[] = [], py: number[] = [];
  const index = new Int32Array(side * side).fill(-1), crossingIndex: number[] = [];
  const vertex = (point: number) => {
    if (point >= 0) {
      if (index[point] < 0) { index[point] = px.length; px.push(gx[point]); py.push(gy[point]); }
      return index[point];
    }
    const c = -1 - point;
    if (crossingIndex[c] === undefined) { crossingIndex[c] = px.length; px.push(cx[c]); py.push(cy[c]); }
    return crossingIndex[c];
  };
  const tri: number[] = [];
  const poly: number[] = [];
  for (let j = 0; j < N; j++) {
    for (let i = 0; i < N; i++) {
      const corners = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      if (corners.every((v) => kind[v] === 0)) {
        const [a, b, c, d] = corners.map(vertex);
        tri.push(a, b, c, a, c, d);
        continue;
      }
      poly.length = 0;
      for (let k = 0; k < 4; k++) {
        const u = corners[k], w = corners[(k + 1) % 4];
        if (kind[u] !== 2) poly.push(u);
        if ((kind[u] === 0 && kind[w] === 2) || (kind[u] === 2 && kind[w] === 0)) poly.push(crossing(u, w));
      }
      if (poly.length < 3 || poly.every((v) => v < 0 || kind[v] === 1)) continue;
      fanWidest(poly.map(vertex), px, py, tri);
    }
  }
  const n = px.length, local = new Float32Array(3 * n), uvs = new Float32Array(2 * n);
  for (let v = 0; v < n; v++) {
    local[3 * v] = px[v]; local[3 * v + 1] = py[v];
    uvs[2 * v] = 0.5 + px[v] / spec.width; uvs[2 * v + 1] = 0.5 - py[v] / spec.width;
  }
  const mesh: TriangleMesh = { positions: sheetToWorld(local, spec.orientation), triangles: Uint32Array.from(tri), uvs };
  orientLike(mesh, spec.orientation === 'horizontal' ? [0, 1, 0] : [0, 0, -1]);
  mesh.positions = placeMesh(mesh.positions, spec);
  return mesh;
}

/** The particles of a woven disc of a resolution (any diameter: the cut scales with the cells). */
export function wovenDiscParticles(resolution: number): number {
  return wovenDiscMesh({ resolution, width: 1, height: 1, orientation: 'horizontal', position: [0, 0, 0], rotation: [0, 0, 0] }).positions.length / 3;
}

/** Cells across a woven disc for a scene's cloth.resolution (at least 4: fewer leave no cell whole). */
export function wovenDiscCells(resolution: number): number {
  return Math.max(4, resolution);
}

/** Appends the fan over the convex polygon `poly` (counter-clockwise) whose smallest angle is the largest. */
function fanWidest(poly: readonly number[], px: readonly number[], py: readonly number[], out: number[]): void {
  const m = poly.length;
  const angle = (o: number, a: number, b: number) => {
    const ux = px[a] - px[o], uy = py[a] - py[o], vx = px[b] - px[o], vy = py[b] - py[o];
    return Math.atan2(Math.abs(ux * vy - uy * vx), ux * vx + uy * vy);
  };
  let best = -1, bestMin = -1;
  for (let s = 0; s < m; s++) {
    let least = Infinity;
    for (let k = 1; k + 1 < m; k++) {
      const a = poly[s], b = poly[(s + k) % m], c = poly[(s + k + 1) % m];
      least = Math.min(least, angle(a, b, c), angle(b, c, a), angle(c, a, b));
    }
    if (least > bestMin) { bestMin = least; best = s; }
  }
  for (let k = 1; k + 1 < m; k++) out.push(poly[best], poly[(best + k) % m], poly[(best + k + 1) % m]);
}
