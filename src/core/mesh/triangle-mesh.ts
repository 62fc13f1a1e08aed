/**
 * A cloth's triangle mesh as it comes from a generator or a file, and `prepareMesh`, which makes any such mesh fit
 * to simulate or says, in one line naming the source, why it is not: duplicate vertices welded, unused ones dropped,
 * degenerate, duplicated and non-manifold triangles refused, every piece oriented consistently.
 */
import { SceneError } from '../scene.js';
import { edgeTable } from './edges.js';

/** Positions and triangles of a cloth, before the model is built. */
export interface TriangleMesh {
  /** vertex positions [m], xyz interleaved */
  positions: Float32Array;
  /** vertex indices, triples */
  triangles: Uint32Array;
  /** texture coordinates, uv interleaved, one pair per vertex (optional) */
  uvs?: Float32Array;
}

/** Most particles a cloth may have: as many as the largest grid (1024 faces per side). */
export const MAX_MESH_PARTICLES = 1025 * 1025;

/**
 * Most edges that may meet at one vertex [-]. The parallel solve colours springs and triangles so that no two of a
 * colour share a vertex, with at most 32 colours; a vertex with more edges than this (a fan of slivers) can need
 * more. Inside a regular mesh it is 6.
 */
export const MAX_VERTEX_EDGES = 12;

/**
 * Distance below which two vertices are the same one, relative to the mesh's size [-]: files split vertices at
 * UV seams and normal creases, and the cloth must not come apart there. It is at most WELD_EDGE_FRACTION of the
 * median edge, so that a small piece far from the rest keeps its shape.
 */
export const WELD_TOLERANCE = 1e-6;
/** Largest weld distance as a fraction of the mesh's median edge length [-]. */
export const WELD_EDGE_FRACTION = 1e-3;

/** The weld distance of a mesh [its units]: WELD_TOLERANCE of its size, at most WELD_EDGE_FRACTION of its median edge. */
export function weldTolerance(p: Float32Array, tri: Uint32Array, size: number): number {
  const lengths = new Float64Array(tri.length);
  let count = 0;
  for (let k = 0; k < tri.length; k++) {
    const a = 3 * tri[k], b = 3 * tri[k - (k % 3) + ((k % 3) + 1) % 3];
    const l = Math.hypot(p[a] - p[b], p[a + 1] - p[b + 1], p[a + 2] - p[b + 2]);
    if (l > 0) lengths[count++] = l;
  }
  const tol = WELD_TOLERANCE * size;
  if (count === 0) return tol;
  const sorted = lengths.subarray(0, count).sort();
  return Math.min(tol, WELD_EDGE_FRACTION * sorted[count >> 1]);
}

const fail = (source: string, why: string): never => {
  throw new SceneError(`${source}: ${why}`);
};

/** Largest extent of a point set along any axis [the mesh's units]. */
export function extent(p: Float32Array): { size: number } {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      if (p[i + k] < lo[k]) lo[k] = p[i + k];
      if (p[i + k] > hi[k]) hi[k] = p[i + k];
    }
  }
  return { size: Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) };
}

/**
 * Representative of each vertex after welding: each vertex joins the first earlier kept vertex within `tol` [file
 * units], found through a hash of cells 4·tol wide (only the cells within `tol` of the vertex are looked in, and a
 * cell holds only kept vertices, which are more than `tol` apart: at most 125 of them).
 */
export function weldMap(p: Float32Array, tol: number): Uint32Array {
  const n = p.length / 3;
  const rep = new Uint32Array(n);
  const cells = new Map<string, number[]>();
  const size = 4 * tol, tol2 = tol * tol;
  const lo = [0, 0, 0], hi = [0, 0, 0], c = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      const x = p[3 * i + k], cell = Math.floor(x / size);
      c[k] = cell;
      lo[k] = x - cell * size < tol ? -1 : 0;
      hi[k] = (cell + 1) * size - x < tol ? 1 : 0;
    }
    let found = -1;
    for (let dx = lo[0]; dx <= hi[0] && found < 0; dx++) {
      for (let dy = lo[1]; dy <= hi[1] && found < 0; dy++) {
        for (let dz = lo[2]; dz <= hi[2] && found < 0; dz++) {
          const list = cells.get(`${c[0] + dx},${c[1] + dy},${c[2] + dz}`);
          if (!list) continue;
          for (const j of list) {
            const ex = p[3 * i] - p[3 * j], ey = p[3 * i + 1] - p[3 * j + 1], ez = p[3 * i + 2] - p[3 * j + 2];
            if (ex * ex + ey * ey + ez * ez <= tol2) { found = j; break; }
          }
        }
      }
    }
    if (found >= 0) { rep[i] = found; continue; }
    rep[i] = i;
    const key = `${c[0]},${c[1]},${c[2]}`;
    const list = cells.get(key);
    if (list) list.push(i); else cells.set(key, [i]);
  }
  return rep;
}

/** What a mesh resolver's result that is no TriangleMesh is told. */
export const NOT_A_MESH = 'not a mesh: expected { positions, triangles } (flat arrays: xyz per vertex, three vertex indices per face)';

/** Whether `v` has a TriangleMesh's shape: positions and triangles that are arrays or typed arrays. */
export function isTriangleMesh(v: unknown): v is TriangleMesh {
  const list = (a: unknown) => ArrayBuffer.isView(a) || Array.isArray(a);
  return v !== null && typeof v === 'object' && list((v as TriangleMesh).positions) && list((v as TriangleMesh).triangles);
}

/**
 * Checks and cleans a mesh for simulation; `source` names it in errors (a file name, or 'cloth.shape disc').
 * Returns a new mesh: vertices closer than the weld distance welded (WELD_TOLERANCE of the size, at most
 * WELD_EDGE_FRACTION of the median edge; the first one's UV kept), vertices no
 * triangle uses dropped, the triangles of each connected piece turned to agree with the piece's first triangle.
 * Throws SceneError for: no { positions, triangles }, no triangles, an index out of range, a non-finite position, a degenerate triangle (two
 * corners the same vertex, or no area), a triangle given twice, an edge shared by more than two triangles, a piece
 * that cannot be oriented (a Möbius strip), more than MAX_VERTEX_EDGES edges at a vertex, or more than
 * MAX_MESH_PARTICLES vertices.
 */
export function prepareMesh(mesh: TriangleMesh, source: string): TriangleMesh {
  // (what a library's mesh resolver returns is checked: a plain object of the wrong shape is named, not dereferenced)
  if (!isTriangleMesh(mesh)) fail(source, NOT_A_MESH);
  const { positions: p, triangles: inTri } = mesh;
  const n0 = p.length / 3;
  if (!Number.isInteger(n0) || p.length === 0) fail(source, 'no vertices');
  if (inTri.length === 0 || inTri.length % 3 !== 0) fail(source, 'no triangles: a cloth mesh needs faces');
  for (let j = 0; j < p.length; j++) if (!Number.isFinite(p[j])) fail(source, `vertex ${Math.floor(j / 3) + 1} has a coordinate that is not a finite number`);
  for (let k = 0; k < inTri.length; k++) {
    if (inTri[k] >= n0) fail(source, `face ${Math.floor(k / 3) + 1} uses vertex ${inTri[k] + 1}, but there are only ${n0}`);
  }
  const { size } = extent(p);
  if (!(size > 0)) fail(source, 'all vertices are at one point');
  const tol = weldTolerance(p, inTri, size);

  // weld, then renumber the vertices the triangles use, keeping the file's order
  const rep = weldMap(p, tol);
  const newIndex = new Int32Array(n0).fill(-1);
  let n = 0;
  const used = new Uint8Array(n0);
  for (let k = 0; k < inTri.length; k++) used[rep[inTri[k]]] = 1;
  for (let i = 0; i < n0; i++) if (used[i]) newIndex[i] = n++;
  if (n > MAX_MESH_PARTICLES) fail(source, `${n} vertices; a cloth may have at most ${MAX_MESH_PARTICLES}`);
  const positions = new Float32Array(3 * n);
  const uvs = mesh.uvs ? new Float32Array(2 * n) : undefined;
  for (let i = 0; i < n0; i++) {
    const j = newIndex[i];
    if (j < 0) continue;
    positions.set(p.subarray(3 * i, 3 * i + 3), 3 * j);
    if (uvs && mesh.uvs) uvs.set(mesh.uvs.subarray(2 * i, 2 * i + 2), 2 * j);
  }
  const m = inTri.length / 3;
  const tri = new Uint32Array(inTri.length);
  for (let k = 0; k < inTri.length; k++) tri[k] = newIndex[rep[inTri[k]]];

  // degenerate triangles: two corners one vertex, or no area for their size (a sine of the widest angle below what
  // float32 positions resolve)
  for (let t = 0; t < m; t++) {
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    if (a === b || b === c || c === a) {
      const raw = inTri[3 * t] === inTri[3 * t + 1] || inTri[3 * t + 1] === inTri[3 * t + 2] || inTri[3 * t + 2] === inTri[3 * t];
      fail(source, `face ${t + 1} is degenerate: two of its corners are the same vertex${raw ? '' : ` (after welding vertices closer than ${tol.toPrecision(2)} in the mesh's units)`}`);
    }
    const ux = positions[3 * b] - positions[3 * a], uy = positions[3 * b + 1] - positions[3 * a + 1], uz = positions[3 * b + 2] - positions[3 * a + 2];
    const vx = positions[3 * c] - positions[3 * a], vy = positions[3 * c + 1] - positions[3 * a + 1], vz = positions[3 * c + 2] - positions[3 * a + 2];
    const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    const wx = vx - ux, wy = vy - uy, wz = vz - uz;
    const longest2 = Math.max(ux * ux + uy * uy + uz * uz, vx * vx + vy * vy + vz * vz, wx * wx + wy * wy + wz * wz);
    if (Math.sqrt(cx * cx + cy * cy + cz * cz) <= 1e-7 * longest2) fail(source, `face ${t + 1} is degenerate: it has no area (its corners are in a line)`);
  }

  // edges: each shared by at most two triangles, and two triangles on one edge never with the same third corner
  const table = edgeTable(tri, n);
  if (table.overShared >= 0) {
    const a = table.ends[2 * table.overShared] + 1, b = table.ends[2 * table.overShared + 1] + 1;
    fail(source, `not a manifold surface: the edge between vertices ${a} and ${b} is shared by more than two faces`);
  }
  const degree = new Uint32Array(n);
  for (let e = 0; e < table.count; e++) {
    degree[table.ends[2 * e]]++;
    degree[table.ends[2 * e + 1]]++;
    if (table.faces[2 * e + 1] >= 0 && table.opposite[2 * e] === table.opposite[2 * e + 1]) {
      fail(source, `face ${Math.max(table.faces[2 * e], table.faces[2 * e + 1]) + 1} repeats face ${Math.min(table.faces[2 * e], table.faces[2 * e + 1]) + 1} (the same three vertices)`);
    }
  }
  for (let i = 0; i < n; i++) {
    if (degree[i] > MAX_VERTEX_EDGES) fail(source, `vertex ${i + 1} joins ${degree[i]} edges, more than the ${MAX_VERTEX_EDGES} the parallel solve allows; remesh or triangulate that fan more evenly`);
  }

  // orient each piece like its first triangle: two agreeing triangles run their shared edge in opposite directions
  const flip = new Int8Array(m).fill(-1); // -1 not reached yet, 0 kept, 1 flipped
  const forward = (t: number, e: number) => tri[3 * t + e] < tri[3 * t + (e + 1) % 3]; // corner e → e+1 runs a → b
  const edgeOf = (t: number, id: number) => (table.triangleEdges[3 * t] === id ? 0 : table.triangleEdges[3 * t + 1] === id ? 1 : 2);
  const queue = new Int32Array(m);
  for (let first = 0; first < m; first++) {
    if (flip[first] !== -1) continue;
    flip[first] = 0;
    let head = 0, tail = 0;
    queue[tail++] = first;
    while (head < tail) {
      const t = queue[head++];
      for (let e = 0; e < 3; e++) {
        const id = table.triangleEdges[3 * t + e];
        const u = table.faces[2 * id] === t ? table.faces[2 * id + 1] : table.faces[2 * id];
        if (u < 0) continue;
        // as stored after flipping, t runs the edge a → b iff forward xor flipped; u must run it the other way
        const tRuns = forward(t, e) !== (flip[t] === 1);
        const uForward = forward(u, edgeOf(u, id));
        const uFlip = uForward === tRuns ? 1 : 0;
        if (flip[u] === -1) {
          flip[u] = uFlip;
          queue[tail++] = u;
        } else if (flip[u] !== uFlip) {
          fail(source, `face ${u + 1} cannot be oriented like its neighbours: the surface is one-sided (a Möbius strip)`);
        }
      }
    }
  }
  for (let t = 0; t < m; t++) {
    if (flip[t] === 1) { const b = tri[3 * t + 1]; tri[3 * t + 1] = tri[3 * t + 2]; tri[3 * t + 2] = b; }
  }
  return { positions, triangles: tri, uvs };
}
