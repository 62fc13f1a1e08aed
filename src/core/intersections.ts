/**
 * Self-intersections of a cloth (issue 12's measure): the number of pairs of triangles that share no vertex and
 * cross each other. Exact in double precision on the float32 positions: two such triangles cross when an edge of
 * one passes through the other (Möller & Trumbore 1997's segment–triangle test on each of the six edges), which is
 * every crossing except two triangles lying in one plane (they overlap without crossing; a simulated cloth meets
 * that with probability zero). Pairs come from a uniform grid over the triangles' bounding boxes (box-grid.ts, cells
 * of 1.5 mean box sizes), each pair tested once. A report, not a step.
 */
import { BoxGrid, triangleBoxes } from './box-grid.js';

/** One mesh's boxes, grid and marks, reused while the mesh keeps its size. */
interface Scratch {
  boxes: Float64Array;
  stamp: Int32Array;
  grid: BoxGrid;
}
const scratch = new WeakMap<Uint32Array, Scratch>();

/**
 * The pairs of triangles of `triangles` (vertex indices, three per triangle) that share no vertex and cross, at the
 * positions `x` (xyz per vertex) [count]. Non-finite positions count nothing (the cloth's `finite` says so).
 */
export function countIntersections(triangles: Uint32Array, x: ArrayLike<number>): number {
  const n = triangles.length / 3;
  if (n < 2) return 0;
  let s = scratch.get(triangles);
  if (!s || s.stamp.length !== n) {
    s = { boxes: new Float64Array(6 * n), stamp: new Int32Array(n), grid: new BoxGrid() };
    scratch.set(triangles, s);
  }
  const { boxes, stamp, grid } = s;
  stamp.fill(-1);
  if (!triangleBoxes(triangles, x, boxes, 0)) return 0; // NaN
  // cells of 1.5 mean boxes (an infinite position leaves a box not finite: nothing built, nothing counted)
  if (!grid.build(boxes, n, 1.5, 1e-9)) return 0;
  const { start, items, inv } = grid;
  let count = 0;
  for (let a = 0; a < n; a++) {
    const ba = 6 * a;
    const x0 = Math.floor(boxes[ba] * inv), x1 = Math.floor(boxes[ba + 3] * inv);
    const y0 = Math.floor(boxes[ba + 1] * inv), y1 = Math.floor(boxes[ba + 4] * inv);
    const z0 = Math.floor(boxes[ba + 2] * inv), z1 = Math.floor(boxes[ba + 5] * inv);
    for (let i = x0; i <= x1; i++) for (let j = y0; j <= y1; j++) for (let k = z0; k <= z1; k++) {
      const h = grid.slot(i, j, k);
      for (let e = start[h]; e < start[h + 1]; e++) {
        const b = items[e];
        if (b <= a || stamp[b] === a) continue;
        stamp[b] = a;
        const bb = 6 * b;
        if (boxes[ba] > boxes[bb + 3] || boxes[bb] > boxes[ba + 3] || boxes[ba + 1] > boxes[bb + 4] ||
          boxes[bb + 1] > boxes[ba + 4] || boxes[ba + 2] > boxes[bb + 5] || boxes[bb + 2] > boxes[ba + 5]) continue;
        if (sharesVertex(triangles, a, b)) continue;
        if (trianglesCross(triangles, x, a, b)) count++;
      }
    }
  }
  return count;
}

function sharesVertex(tri: Uint32Array, a: number, b: number): boolean {
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) if (tri[3 * a + i] === tri[3 * b + j]) return true;
  return false;
}

/** Whether an edge of triangle a passes through triangle b, or an edge of b through a. */
function trianglesCross(tri: Uint32Array, x: ArrayLike<number>, a: number, b: number): boolean {
  for (let e = 0; e < 3; e++) {
    if (segmentHitsTriangle(x, tri[3 * a + e], tri[3 * a + ((e + 1) % 3)], tri, b)) return true;
    if (segmentHitsTriangle(x, tri[3 * b + e], tri[3 * b + ((e + 1) % 3)], tri, a)) return true;
  }
  return false;
}

/** Möller–Trumbore: the segment from vertex p to vertex q meets triangle t (its interior or boundary). */
function segmentHitsTriangle(x: ArrayLike<number>, p: number, q: number, tri: Uint32Array, t: number): boolean {
  const i0 = 3 * tri[3 * t], i1 = 3 * tri[3 * t + 1], i2 = 3 * tri[3 * t + 2];
  const ox = x[3 * p], oy = x[3 * p + 1], oz = x[3 * p + 2];
  const dx = x[3 * q] - ox, dy = x[3 * q + 1] - oy, dz = x[3 * q + 2] - oz;
  const e1x = x[i1] - x[i0], e1y = x[i1 + 1] - x[i0 + 1], e1z = x[i1 + 2] - x[i0 + 2];
  const e2x = x[i2] - x[i0], e2y = x[i2 + 1] - x[i0 + 1], e2z = x[i2 + 2] - x[i0 + 2];
  const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  // parallel to the plane (or a degenerate triangle): no crossing
  const scale = Math.hypot(e1x, e1y, e1z) * Math.hypot(e2x, e2y, e2z) * Math.hypot(dx, dy, dz);
  if (Math.abs(det) <= 1e-12 * scale) return false;
  const f = 1 / det;
  const sx = ox - x[i0], sy = oy - x[i0 + 1], sz = oz - x[i0 + 2];
  const u = f * (sx * px + sy * py + sz * pz);
  if (u < 0 || u > 1) return false;
  const qx = sy * e1z - sz * e1y, qy = sz * e1x - sx * e1z, qz = sx * e1y - sy * e1x;
  const v = f * (dx * qx + dy * qy + dz * qz);
  if (v < 0 || u + v > 1) return false;
  const s = f * (e2x * qx + e2y * qy + e2z * qz);
  return s >= 0 && s <= 1;
}
