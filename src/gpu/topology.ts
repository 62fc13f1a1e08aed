/**
 * Mesh tables the GPU kernels need beyond the ClothModel, built once per model on the CPU: particle → triangle
 * adjacency (for the wind and normal gathers). Triangle contact walks the model's own colour batches (core sorts
 * triangles by colour).
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
