/**
 * The cloth's contacts with itself, as the app's HUD counts them and its contact view marks them: the particles
 * within `distance` of a triangle of the model that does not have them as a corner (of their own cloth or another
 * one). A measure of the state, the same on every backend, as `countIntersections` is: with self-contact on, a
 * particle resting on another layer sits at the self-contact distance h from it (self-contact.ts), so a `distance`
 * of 1.5 h finds every resting contact and nothing of a flat sheet (h is at most half the smallest rest altitude:
 * at rest no particle is nearer than 2 h to a triangle not its own). Triangles from a uniform grid over their boxes
 * widened by `distance` (box-grid.ts). A report, not a step.
 */
import { BoxGrid, triangleBoxes } from './box-grid.js';
import { closestPointOnTriangle } from './colliders/sphere.js';

/** One mesh's triangle boxes and grid, reused while it keeps its size. */
interface Scratch {
  boxes: Float64Array;
  grid: BoxGrid;
}
const scratch = new WeakMap<Uint32Array, Scratch>();
const bary = new Float64Array(3);

/**
 * How many of the particles (of `particles`, positions `x`, xyz each) lie within `distance` [m] of a triangle of
 * `triangles` that does not have them as a corner; `flags` (one per particle, when given) gets 1 for those and 0 for
 * the rest. Nothing counts where a position is not finite.
 */
export function selfContacts(triangles: Uint32Array, x: ArrayLike<number>, particles: number, distance: number, flags?: Uint8Array): number {
  flags?.fill(0);
  const n = triangles.length / 3;
  if (n < 2 || !(distance > 0)) return 0;
  let s = scratch.get(triangles);
  if (!s || s.boxes.length !== 6 * n) {
    s = { boxes: new Float64Array(6 * n), grid: new BoxGrid() };
    scratch.set(triangles, s);
  }
  const { boxes, grid } = s;
  if (!triangleBoxes(triangles, x, boxes, distance)) return 0; // NaN
  // each box is listed in every cell it covers: a particle inside a widened box finds it in its own cell
  if (!grid.build(boxes, n, 1, distance)) return 0;
  const { start, items, inv } = grid, d2 = distance * distance;
  let count = 0;
  for (let p = 0; p < particles; p++) {
    const px = x[3 * p], py = x[3 * p + 1], pz = x[3 * p + 2];
    const h = grid.slot(Math.floor(px * inv), Math.floor(py * inv), Math.floor(pz * inv));
    for (let e = start[h]; e < start[h + 1]; e++) {
      const t = items[e], b = 6 * t;
      if (px < boxes[b] || px > boxes[b + 3] || py < boxes[b + 1] || py > boxes[b + 4] || pz < boxes[b + 2] || pz > boxes[b + 5]) continue;
      const ia = triangles[3 * t], ib = triangles[3 * t + 1], ic = triangles[3 * t + 2];
      if (ia === p || ib === p || ic === p) continue;
      const a = 3 * ia, bb = 3 * ib, c = 3 * ic;
      closestPointOnTriangle(px, py, pz, x[a], x[a + 1], x[a + 2], x[bb], x[bb + 1], x[bb + 2], x[c], x[c + 1], x[c + 2], bary);
      const dx = bary[0] * x[a] + bary[1] * x[bb] + bary[2] * x[c] - px;
      const dy = bary[0] * x[a + 1] + bary[1] * x[bb + 1] + bary[2] * x[c + 1] - py;
      const dz = bary[0] * x[a + 2] + bary[1] * x[bb + 2] + bary[2] * x[c + 2] - pz;
      if (dx * dx + dy * dy + dz * dz >= d2) continue;
      count++;
      if (flags) flags[p] = 1;
      break;
    }
  }
  return count;
}
