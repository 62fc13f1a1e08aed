import type { ClothModel } from './model.js';
import type { ClothState } from './state.js';

export interface PickHit {
  /** the particle of the hit triangle nearest to the hit point */
  particle: number;
  /** hit triangle (index into model.triangles / 3) */
  triangle: number;
  /** ray parameter: hit = origin + t·direction [m when direction is a unit vector] */
  t: number;
  /** hit point [m] */
  point: [number, number, number];
}

/**
 * Nearest intersection of a ray with the cloth's triangles (Möller & Trumbore 1997, "Fast, minimum storage
 * ray-triangle intersection"), both faces. Returns null when the ray misses. The app's click-and-drag and the
 * tests share it.
 */
export function pickParticle(
  model: ClothModel, state: ClothState,
  origin: readonly [number, number, number], direction: readonly [number, number, number],
): PickHit | null {
  const x = state.positions, tri = model.triangles;
  const [ox, oy, oz] = origin;
  const [dx, dy, dz] = direction;
  let best = Infinity, bestTri = -1, bu = 0, bv = 0;
  for (let k = 0; k < tri.length; k += 3) {
    const a = 3 * tri[k], b = 3 * tri[k + 1], c = 3 * tri[k + 2];
    const e1x = x[b] - x[a], e1y = x[b + 1] - x[a + 1], e1z = x[b + 2] - x[a + 2];
    const e2x = x[c] - x[a], e2y = x[c + 1] - x[a + 1], e2z = x[c + 2] - x[a + 2];
    const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
    const det = e1x * px + e1y * py + e1z * pz;
    if (Math.abs(det) < 1e-14) continue;
    const inv = 1 / det;
    const sx = ox - x[a], sy = oy - x[a + 1], sz = oz - x[a + 2];
    const u = (sx * px + sy * py + sz * pz) * inv;
    if (u < 0 || u > 1) continue;
    const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
    const v = (dx * qx + dy * qy + dz * qz) * inv;
    if (v < 0 || u + v > 1) continue;
    const t = (e2x * qx + e2y * qy + e2z * qz) * inv;
    if (t > 0 && t < best) { best = t; bestTri = k / 3; bu = u; bv = v; }
  }
  if (bestTri < 0) return null;
  const weights = [1 - bu - bv, bu, bv];
  const corner = weights.indexOf(Math.max(...weights));
  return {
    particle: tri[3 * bestTri + corner],
    triangle: bestTri,
    t: best,
    point: [ox + best * dx, oy + best * dy, oz + best * dz],
  };
}
