/** Vertex normals of a triangle mesh, for exports: flat arrays in, a flat array out. */

/**
 * Each vertex's unit normal: the sum of its triangles' area-weighted normals (their edges' cross products),
 * normalised; a vertex whose triangles cancel or are degenerate (or none) gets +y. `positions` and the result have
 * stride 3.
 */
export function vertexNormals(positions: Float32Array, triangles: Uint32Array): Float32Array {
  const count = positions.length / 3, sum = new Float64Array(3 * count), x = positions;
  for (let k = 0; k < triangles.length; k += 3) {
    const a = 3 * triangles[k], b = 3 * triangles[k + 1], c = 3 * triangles[k + 2];
    const ux = x[b] - x[a], uy = x[b + 1] - x[a + 1], uz = x[b + 2] - x[a + 2];
    const vx = x[c] - x[a], vy = x[c + 1] - x[a + 1], vz = x[c + 2] - x[a + 2];
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    for (let j = 0; j < 3; j++) {
      const v = 3 * triangles[k + j];
      sum[v] += nx; sum[v + 1] += ny; sum[v + 2] += nz;
    }
  }
  const out = new Float32Array(3 * count);
  for (let v = 0; v < 3 * count; v += 3) {
    const len = Math.hypot(sum[v], sum[v + 1], sum[v + 2]);
    if (len > 0 && Number.isFinite(len)) { out[v] = sum[v] / len; out[v + 1] = sum[v + 1] / len; out[v + 2] = sum[v + 2] / len; } else out[v + 1] = 1;
  }
  return out;
}
