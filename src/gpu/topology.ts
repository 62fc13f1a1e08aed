/**
 * Mesh tables the GPU kernels need beyond the ClothModel, built once per model on the CPU: particle → triangle
 * adjacency (for the wind and normal gathers) and a triangle colouring (for Gauss–Seidel triangle contact).
 */
import type { ClothModel } from '../core/model.js';

/**
 * Particle → incident triangles in CSR form, as one u32 array: entries 0…n are offsets into the array itself
 * (so the first is n + 1), followed by the triangle indices of particle 0, 1, …
 */
export function triangleAdjacency(model: ClothModel): Uint32Array {
  const n = model.particleCount;
  const tri = model.triangles;
  const out = new Uint32Array(n + 1 + tri.length);
  const count = new Uint32Array(n + 1);
  for (let k = 0; k < tri.length; k++) count[tri[k] + 1]++;
  out[0] = n + 1;
  for (let i = 0; i < n; i++) out[i + 1] = out[i] + count[i + 1];
  const fill = out.slice(0, n);
  for (let k = 0; k < tri.length; k++) out[fill[tri[k]]++] = (k / 3) | 0;
  return out;
}

export interface TriangleColouring {
  /** triangle indices sorted by colour */
  order: Uint32Array;
  /** colour c holds order[starts[c] .. starts[c + 1]) */
  starts: number[];
}

const MAX_TRIANGLE_COLOURS = 32;

/**
 * Greedy vertex-disjoint colouring of the triangles in index order: each triangle takes the lowest colour none
 * of its vertices has yet. A regular grid needs 6 (every vertex touches at most 6 triangles).
 */
export function colourTriangles(model: ClothModel): TriangleColouring {
  const tri = model.triangles;
  const m = tri.length / 3;
  const used = new Uint32Array(model.particleCount);
  const colours = new Uint8Array(m);
  let count = 0;
  for (let t = 0; t < m; t++) {
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    const free = ~(used[a] | used[b] | used[c]) >>> 0;
    if (free === 0) throw new Error(`GPU solver: triangle colouring needs more than ${MAX_TRIANGLE_COLOURS} colours`);
    const col = 31 - Math.clz32(free & -free);
    colours[t] = col;
    const bit = (1 << col) >>> 0;
    used[a] |= bit; used[b] |= bit; used[c] |= bit;
    if (col + 1 > count) count = col + 1;
  }
  const starts = new Array<number>(count + 1).fill(0);
  for (let t = 0; t < m; t++) starts[colours[t] + 1]++;
  for (let c = 0; c < count; c++) starts[c + 1] += starts[c];
  const fill = starts.slice(0, count);
  const order = new Uint32Array(m);
  for (let t = 0; t < m; t++) order[fill[colours[t]]++] = t;
  return { order, starts };
}

/**
 * The same model with its triangles listed in colour order. Greedy colouring of that list gives the same colours
 * again, so the GPU's colour-by-colour triangle contact then visits triangles in the CPU's order (triangles of one
 * colour commute): CPU and GPU contact agree to rounding. The GPU path does not need it; parity tests do.
 */
export function withColourSortedTriangles(model: ClothModel): ClothModel {
  const { order } = colourTriangles(model);
  const tri = model.triangles;
  const sorted = new Uint32Array(tri.length);
  for (let k = 0; k < order.length; k++) {
    const t = order[k];
    sorted[3 * k] = tri[3 * t];
    sorted[3 * k + 1] = tri[3 * t + 1];
    sorted[3 * k + 2] = tri[3 * t + 2];
  }
  return { ...model, triangles: sorted };
}
