/** Vertex normals of a triangle mesh, for exports: flat arrays in, a flat array out. */

/**
 * Each vertex's unit normal: the sum of its triangles' area-weighted normals (their edges' cross products),
 * normalised; a vertex whose triangles cancel or are degenerate gets +y. `positions` and the result have stride 3;
 * `triangles` index the vertices `first` … `first + count − 1` of `positions`, numbered from `first`.
 */
export function vertexNormals(positions: Float32Array, triangles: Uint32Array, first = 0, count = positions.length / 3 - first): Float32Array {
  const sum = new Float64Array(3 * count), x = positions, o = 3 * first;
  for (let k = 0; k < triangles.length; k += 3) {
    const a = 3 * triangles[k], b = 3 * triangles[k + 1], c = 3 * triangles[k + 2];
    const ux = x[o + b] - x[o + a], uy = x[o + b + 1] - x[o + a + 1], uz = x[o + b + 2] - x[o + a + 2];
    const vx = x[o + c] - x[o + a], vy = x[o + c + 1] - x[o + a + 1], vz = x[o + c + 2] - x[o + a + 2];
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
