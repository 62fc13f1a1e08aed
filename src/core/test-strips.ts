/**
 * The crossed strips the edge pass's tests share (test-only: not built into the package, tsconfig.build.json):
 * self-contact.test.ts (both CPU kernels) and the GPU's.
 */
import { segmentSegmentClosest } from './colliders/convex.js';
import { validateScene, type Scene } from './scene.js';

/**
 * Two thin strips (1 m × 2 cm, one face each way) crossing like an X: the lower one pinned at its corners 30 cm up,
 * the upper one 3 cm above it, turned 90°, free to fall on it. Every vertex stays far outside the other strip's
 * triangles, so only the edge pass holds the upper one up. `solver`: the scene's solver fields.
 */
export function crossedStrips(solver: Partial<Scene['solver']>): Scene {
  return validateScene({
    name: 'crossed strips',
    solver,
    colliders: [{ type: 'floor', height: 0 }],
    cloths: [
      { cloth: { resolution: 1, width: 1, height: 0.02, position: [0, 0.3, 0] }, material: { fabric: 'cotton' }, pins: ['top-left', 'top-right', 'bottom-left', 'bottom-right'] },
      { cloth: { resolution: 1, width: 1, height: 0.02, position: [0, 0.33, 0], rotation: [0, 90, 0] }, material: { fabric: 'cotton' } },
    ],
  });
}

/** The nearest distance between an edge of the lower strip (particles 0–3) and one of the upper (4–7) [m]. */
export function stripGap(edges: Uint32Array, x: Float32Array): number {
  const st = new Float64Array(2), ne = edges.length / 2;
  let nearest = Infinity;
  for (let e = 0; e < ne; e++) {
    const a = 3 * edges[2 * e], b = 3 * edges[2 * e + 1];
    if (a >= 12 || b >= 12) continue;
    for (let f = 0; f < ne; f++) {
      const c = 3 * edges[2 * f], d = 3 * edges[2 * f + 1];
      if (c < 12 || d < 12) continue;
      const d2 = segmentSegmentClosest(x[a], x[a + 1], x[a + 2], x[b], x[b + 1], x[b + 2], x[c], x[c + 1], x[c + 2], x[d], x[d + 1], x[d + 2], st);
      nearest = Math.min(nearest, Math.sqrt(d2));
    }
  }
  return nearest;
}
