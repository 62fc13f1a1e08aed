/**
 * Triangle contact for convex shapes (box, capsule, cylinder): the deepest point of a triangle, i.e. the point of
 * the triangle where the shape's signed distance is smallest.
 *
 * The signed distance of a convex set is a convex function, and the outward normal at a point is a subgradient of
 * it (its gradient outside; inside, the normal of the nearest face, one of the active pieces of a max). Hence:
 *
 * - **Certificate at a vertex** (`vertexDeepest`): sd(p) ≥ sd(v) + n_v·(p − v) for every p. If the other vertices
 *   lie on or above vertex v's tangent plane (n_v·(v_k − v) ≥ 0), the whole triangle does, and v is the deepest
 *   point exactly. This is the common case: a triangle lying on a box's face or beside it, on a cylinder's cap.
 * - **Otherwise** (a box edge or corner, a cylinder's rim or curved side under the triangle), `goldenDeepest`
 *   minimises the convex f(u, v) = sd(a + u·(b − a) + v·(c − a)) over the triangle by nested golden-section searches:
 *   F(u) = min over v ∈ [0, 1 − u] of f(u, v) is convex in u (partial minimisation of a convex function over a
 *   set that depends affinely on u), so both searches are over unimodal functions. 12 iterations each shrink the
 *   bracket to 0.618¹² ≈ 3·10⁻³ of an edge; the result is the best point evaluated (never deeper than the truth,
 *   and sd is 1-Lipschitz, so at most 3·10⁻³ × the longest edge shallower: 0.1 mm on a 3 cm triangle, a fiftieth
 *   of the default thickness). About 200 evaluations: it runs only where the two exact answers do not apply.
 * - The capsule and the cylinder's curved side have an exact answer from the closest points of a segment (the
 *   axis) and the triangle (`segmentTriangleClosest`).
 *
 * Tested against brute-force sampling of the triangle (colliders/shapes.test.ts).
 */
import { GOLDEN_ITERATIONS } from '../layout.generated.js';
import { closestPointOnTriangle } from './sphere.js';
import { QUERY, TRIANGLE, pointQuery, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
/** GOLDEN_ITERATIONS as a module constant (see shape.ts QUERY) */
const ITERATIONS = GOLDEN_ITERATIONS;
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { WITHIN: TRIANGLE_WITHIN, D: TRIANGLE_D } = TRIANGLE;

const scratchN = new Float64Array(3);
const scratchB = new Float64Array(3);
const segST = new Float64Array(2);
/** the searches' point queries of their shape */
const convexQuery = pointQuery();

/**
 * Closest points of segments p1–q1 and p2–q2 (Ericson, Real-Time Collision Detection, §5.1.9): parameters s (on
 * the first) and t (on the second) to `out[0..1]`; returns the squared distance.
 */
export function segmentSegmentClosest(
  p1x: number, p1y: number, p1z: number, q1x: number, q1y: number, q1z: number,
  p2x: number, p2y: number, p2z: number, q2x: number, q2y: number, q2z: number,
  out: Float64Array,
): number {
  // through an array, as closestPointOnTriangle (sphere.ts): a small wrapper V8 inlines, so no number is boxed
  const v = segmentArgs;
  v[0] = p1x; v[1] = p1y; v[2] = p1z; v[3] = q1x; v[4] = q1y; v[5] = q1z;
  v[6] = p2x; v[7] = p2y; v[8] = p2z; v[9] = q2x; v[10] = q2y; v[11] = q2z;
  segmentSegmentIn(v, out);
  return v[12];
}

/** segmentSegmentClosest's arguments p1, q1, p2, q2, and (v[12]) its answer */
const segmentArgs = new Float64Array(13);

/** segmentSegmentClosest on p1, q1, p2, q2 in v[0…11]; the squared distance to v[12]. */
function segmentSegmentIn(v: Float64Array, out: Float64Array): void {
  const p1x = v[0], p1y = v[1], p1z = v[2], q1x = v[3], q1y = v[4], q1z = v[5];
  const p2x = v[6], p2y = v[7], p2z = v[8], q2x = v[9], q2y = v[10], q2z = v[11];
  const d1x = q1x - p1x, d1y = q1y - p1y, d1z = q1z - p1z;
  const d2x = q2x - p2x, d2y = q2y - p2y, d2z = q2z - p2z;
  const rx = p1x - p2x, ry = p1y - p2y, rz = p1z - p2z;
  const a = d1x * d1x + d1y * d1y + d1z * d1z;
  const e = d2x * d2x + d2y * d2y + d2z * d2z;
  const f = d2x * rx + d2y * ry + d2z * rz;
  let s: number, t: number;
  const eps = 1e-300;
  if (a <= eps && e <= eps) {
    s = 0; t = 0;
  } else if (a <= eps) {
    s = 0; t = Math.min(Math.max(f / e, 0), 1);
  } else {
    const c = d1x * rx + d1y * ry + d1z * rz;
    if (e <= eps) {
      t = 0; s = Math.min(Math.max(-c / a, 0), 1);
    } else {
      const b = d1x * d2x + d1y * d2y + d1z * d2z;
      const denom = a * e - b * b;
      s = denom > 1e-15 * a * e ? Math.min(Math.max((b * f - c * e) / denom, 0), 1) : 0;
      t = (b * s + f) / e;
      if (t < 0) { t = 0; s = Math.min(Math.max(-c / a, 0), 1); }
      else if (t > 1) { t = 1; s = Math.min(Math.max((b - c) / a, 0), 1); }
    }
  }
  out[0] = s; out[1] = t;
  const dx = p1x + d1x * s - (p2x + d2x * t), dy = p1y + d1y * s - (p2y + d2y * t), dz = p1z + d1z * s - (p2z + d2z * t);
  v[12] = dx * dx + dy * dy + dz * dz;
}

/**
 * Closest points of segment p–q and triangle (a, b, c): the barycentric weights of the triangle's point to `bary`,
 * the segment's parameter to `seg[0]`; returns the squared distance (0 where the segment crosses the triangle).
 * The closest pair of two convex polytopes is a vertex and the other's closest point, or two edges: so the segment
 * crossing the triangle, its end points against the triangle, and the segment against the triangle's three edges.
 */
export function segmentTriangleClosest(
  px: number, py: number, pz: number, qx: number, qy: number, qz: number,
  ax: number, ay: number, az: number, bx: number, by: number, bz: number, cx: number, cy: number, cz: number,
  bary: Float64Array, seg: Float64Array,
): number {
  // through an array, as closestPointOnTriangle (sphere.ts): a small wrapper V8 inlines, so no number is boxed
  const v = segmentTriangleArgs;
  v[0] = px; v[1] = py; v[2] = pz; v[3] = qx; v[4] = qy; v[5] = qz;
  v[6] = ax; v[7] = ay; v[8] = az; v[9] = bx; v[10] = by; v[11] = bz; v[12] = cx; v[13] = cy; v[14] = cz;
  segmentTriangleIn(v, bary, seg);
  return v[15];
}

/** segmentTriangleClosest's arguments p, q, a, b, c, and (v[15]) its answer */
const segmentTriangleArgs = new Float64Array(16);

/**
 * segmentTriangleClosest on p, q, a, b, c in v[0…14]; the squared distance to v[15] (a caller in a step fills its
 * own record: colliders/shape.ts).
 */
export function segmentTriangleIn(v: Float64Array, bary: Float64Array, seg: Float64Array): void {
  const px = v[0], py = v[1], pz = v[2], qx = v[3], qy = v[4], qz = v[5];
  const ax = v[6], ay = v[7], az = v[8], bx = v[9], by = v[10], bz = v[11], cx = v[12], cy = v[13], cz = v[14];
  const abx = bx - ax, aby = by - ay, abz = bz - az, acx = cx - ax, acy = cy - ay, acz = cz - az;
  const nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const nn = nx * nx + ny * ny + nz * nz;
  if (nn > 0) {
    const d0 = nx * (px - ax) + ny * (py - ay) + nz * (pz - az);
    const d1 = nx * (qx - ax) + ny * (qy - ay) + nz * (qz - az);
    if ((d0 <= 0 && d1 >= 0) || (d0 >= 0 && d1 <= 0)) {
      if (d0 !== d1) {
        const t = d0 / (d0 - d1);
        const ix = px + t * (qx - px) - ax, iy = py + t * (qy - py) - ay, iz = pz + t * (qz - pz) - az;
        // barycentric of the crossing: (n · (ab × ai)) / |n|² etc.
        const w = (nx * (aby * iz - abz * iy) + ny * (abz * ix - abx * iz) + nz * (abx * iy - aby * ix)) / nn;
        const u = (nx * (iy * acz - iz * acy) + ny * (iz * acx - ix * acz) + nz * (ix * acy - iy * acx)) / nn;
        if (u >= 0 && w >= 0 && u + w <= 1) {
          bary[0] = 1 - u - w; bary[1] = u; bary[2] = w; seg[0] = t;
          v[15] = 0;
          return;
        }
      }
    }
  }
  let best = Infinity;
  // end points against the triangle
  for (let k = 0; k < 2; k++) {
    const ex = k ? qx : px, ey = k ? qy : py, ez = k ? qz : pz;
    closestPointOnTriangle(ex, ey, ez, ax, ay, az, bx, by, bz, cx, cy, cz, scratchB);
    const tx = scratchB[0] * ax + scratchB[1] * bx + scratchB[2] * cx - ex;
    const ty = scratchB[0] * ay + scratchB[1] * by + scratchB[2] * cy - ey;
    const tz = scratchB[0] * az + scratchB[1] * bz + scratchB[2] * cz - ez;
    const d2 = tx * tx + ty * ty + tz * tz;
    if (d2 < best) { best = d2; bary[0] = scratchB[0]; bary[1] = scratchB[1]; bary[2] = scratchB[2]; seg[0] = k; }
  }
  // the segment against each edge
  for (let k = 0; k < 3; k++) {
    const ux = k === 0 ? ax : k === 1 ? bx : cx, uy = k === 0 ? ay : k === 1 ? by : cy, uz = k === 0 ? az : k === 1 ? bz : cz;
    const vx = k === 0 ? bx : k === 1 ? cx : ax, vy = k === 0 ? by : k === 1 ? cy : ay, vz = k === 0 ? bz : k === 1 ? cz : az;
    const d2 = segmentSegmentClosest(px, py, pz, qx, qy, qz, ux, uy, uz, vx, vy, vz, segST);
    if (d2 < best) {
      best = d2;
      const t = segST[1];
      bary[0] = 0; bary[1] = 0; bary[2] = 0;
      bary[k] = 1 - t; bary[(k + 1) % 3] = t;
      seg[0] = segST[0];
    }
  }
  v[15] = best;
}

/**
 * The certificate above: if some vertex's tangent plane has the whole triangle on or above it, that vertex is the
 * deepest point: its weights go to `bary`, its normal to `normal`, its signed distance to t[TRIANGLE_D], and true is
 * returned. If the tangent planes show that the whole triangle is at least t[TRIANGLE_WITHIN] away, that bound
 * (≥ within) goes there and true is returned. Otherwise false (and `bary` holds the deepest vertex, `normal` its
 * normal). Numbers in and out through the triangle query's record `t` (shape.ts: none boxed).
 */
export function vertexDeepest(
  shape: ColliderShape,
  a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
  bary: Float64Array, normal: Float64Array, t: Float64Array,
): boolean {
  const within = t[TRIANGLE_WITHIN];
  const ax = a[ia], ay = a[ia + 1], az = a[ia + 2];
  const bx = b[ib], by = b[ib + 1], bz = b[ib + 2];
  const cx = c[ic], cy = c[ic + 1], cz = c[ic + 2];
  let best = Infinity, bestK = 0, certified = false, certK = -1, certD = Infinity, bound = -Infinity;
  let n0 = 0, n1 = 0, n2 = 0;
  for (let k = 0; k < 3; k++) {
    const vx = k === 0 ? ax : k === 1 ? bx : cx, vy = k === 0 ? ay : k === 1 ? by : cy, vz = k === 0 ? az : k === 1 ? bz : cz;
    const q = convexQuery;
    q[QUERY_X] = vx; q[QUERY_Y] = vy; q[QUERY_Z] = vz; q[QUERY_WITHIN] = Infinity;
    shape.distanceIn(q, scratchN);
    const d = q[QUERY_D];
    const nx = scratchN[0], ny = scratchN[1], nz = scratchN[2];
    const nv = nx * vx + ny * vy + nz * vz;
    // the other vertices' height above this vertex's tangent plane (0.1 µm of rounding allowed)
    const lowest = Math.min(nx * ax + ny * ay + nz * az, nx * bx + ny * by + nz * bz, nx * cx + ny * cy + nz * cz) - nv;
    // the tangent plane bounds the signed distance over the whole triangle from below
    bound = Math.max(bound, d + Math.min(lowest, 0));
    if (lowest >= -1e-7 && d < certD) { certified = true; certK = k; certD = d; n0 = nx; n1 = ny; n2 = nz; }
    if (!certified && d < best) { best = d; bestK = k; normal[0] = nx; normal[1] = ny; normal[2] = nz; }
  }
  if (certified) {
    bary[0] = certK === 0 ? 1 : 0; bary[1] = certK === 1 ? 1 : 0; bary[2] = certK === 2 ? 1 : 0;
    normal[0] = n0; normal[1] = n1; normal[2] = n2;
    t[TRIANGLE_D] = certD;
    return true;
  }
  bary[0] = bestK === 0 ? 1 : 0; bary[1] = bestK === 1 ? 1 : 0; bary[2] = bestK === 2 ? 1 : 0;
  // no point of the triangle is nearer than `within`: the caller needs no more
  if (!(bound >= within)) return false;
  t[TRIANGLE_D] = bound;
  return true;
}

const GOLDEN = (Math.sqrt(5) - 1) / 2;

/**
 * Minimises the convex signed distance over triangle (a, b, c) by nested golden-section searches (see the file's
 * comment): the best point found goes to `bary`, its normal to `normal` and its signed distance to t[TRIANGLE_D].
 * The outer search over u ∈ [0, 1] evaluates F(u) = min over v ∈ [0, 1 − u] of f(u, v) at its two first points,
 * one more each iteration, then at its ends; each F(u) is the inner search over v the same way, its range's ends
 * last. Written as two loops with the one call of f in the inner: V8 inlines the shape's signedDistance there (its
 * budget for inlining per function would run out before six copies of it), and no number crosses a call (shape.ts).
 */
export function goldenDeepest(
  shape: ColliderShape,
  a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
  bary: Float64Array, normal: Float64Array, t: Float64Array,
): void {
  const ax = a[ia], ay = a[ia + 1], az = a[ia + 2];
  const ux = b[ib] - ax, uy = b[ib + 1] - ay, uz = b[ib + 2] - az;
  const vx = c[ic] - ax, vy = c[ic + 1] - ay, vz = c[ic + 2] - az;
  let bestU = 0, bestV = 0, bestD = Infinity;
  let lo = 0, hi = 1;
  let x1 = hi - GOLDEN * (hi - lo), x2 = lo + GOLDEN * (hi - lo), f1 = 0, f2 = 0;
  for (let k = -2; k < ITERATIONS + 2; k++) {
    // the outer search's next point: x1, x2, then the new one of each iteration, then the ends 0 and 1
    let u: number, left = k === -2;
    if (k === -2) u = x1;
    else if (k === -1) u = x2;
    else if (k >= ITERATIONS) u = k - ITERATIONS;
    else if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); u = x1; left = true; }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); u = x2; }
    // F(u): the inner search over v, the same way, the ends of its range 0 and 1 − u last
    let vlo = 0, vhi = 1 - u;
    let y1 = vhi - GOLDEN * (vhi - vlo), y2 = vlo + GOLDEN * (vhi - vlo), g1 = 0, g2 = 0, g3 = 0, g4 = 0;
    for (let j = -2; j < ITERATIONS + 2; j++) {
      let v: number, low = j === -2;
      if (j === -2) v = y1;
      else if (j === -1) v = y2;
      else if (j === ITERATIONS) v = 0;
      else if (j > ITERATIONS) v = 1 - u;
      else if (g1 <= g2) { vhi = y2; y2 = y1; g2 = g1; y1 = vhi - GOLDEN * (vhi - vlo); v = y1; low = true; }
      else { vlo = y1; y1 = y2; g1 = g2; y2 = vlo + GOLDEN * (vhi - vlo); v = y2; }
      const q = convexQuery;
      q[QUERY_X] = ax + u * ux + v * vx; q[QUERY_Y] = ay + u * uy + v * vy; q[QUERY_Z] = az + u * uz + v * vz; q[QUERY_WITHIN] = Infinity;
      shape.distanceIn(q, scratchN);
      const d = q[QUERY_D];
      if (d < bestD) { bestD = d; bestU = u; bestV = v; }
      if (j >= ITERATIONS) { if (j === ITERATIONS) g3 = d; else g4 = d; }
      else if (low) g1 = d;
      else g2 = d;
    }
    // (the minimum over the range: a minimum on the triangle's boundary is found exactly)
    const F = Math.min(g1, g2, g3, g4);
    if (k < ITERATIONS) { if (left) f1 = F; else f2 = F; }
  }
  bary[0] = 1 - bestU - bestV; bary[1] = bestU; bary[2] = bestV;
  const q = convexQuery;
  q[QUERY_X] = ax + bestU * ux + bestV * vx; q[QUERY_Y] = ay + bestU * uy + bestV * vy; q[QUERY_Z] = az + bestU * uz + bestV * vz;
  q[QUERY_WITHIN] = Infinity;
  shape.distanceIn(q, normal);
  t[TRIANGLE_D] = q[QUERY_D];
}

/** A convex shape with a support mapping: the point of the shape farthest in a direction. */
export interface SupportShape extends ColliderShape {
  /**
   * The shape's points farthest along the direction d[0..2] and along −d (any one where several are) to `hi[0..2]`
   * and `lo[0..2]`: the direction in an array, not as numbers (no number passes through a call in a step:
   * colliders/shape.ts).
   */
  support(d: Float64Array, hi: Float64Array, lo: Float64Array): void;
}

const scratchQ = new Float64Array(3);
const scratchQ2 = new Float64Array(3);
/** supportDeepest's direction for the support mapping */
const supportDirection = new Float64Array(3);

/**
 * Minimum of the convex signed distance along edge a + s·(b − a), s ∈ [0, 1], by golden-section search
 * (EDGE_ITERATIONS: the bracket shrinks to 0.618²⁰ ≈ 7·10⁻⁵ of the edge), the ends first: the parameter of the best
 * point to `at[0]`, the distance there to `at[1]`. The edge comes in `edge` (supportDeepest's), no number passed;
 * one call of the distance, as in goldenDeepest.
 */
function edgeDeepest(shape: ColliderShape, at: Float64Array): void {
  const e = edge;
  let bestT = 0, best = Infinity, lo = 0, hi = 1;
  let x1 = hi - GOLDEN * (hi - lo), x2 = lo + GOLDEN * (hi - lo), f1 = 0, f2 = 0;
  for (let k = -4; k < EDGE_ITERATIONS; k++) {
    // the ends 0 and 1, then x1, x2, then the new point of each iteration
    let s: number, left = k === -2;
    if (k < -2) s = k + 4;
    else if (k === -2) s = x1;
    else if (k === -1) s = x2;
    else if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); s = x1; left = true; }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); s = x2; }
    const q = convexQuery;
    q[QUERY_X] = e[0] + s * e[3]; q[QUERY_Y] = e[1] + s * e[4]; q[QUERY_Z] = e[2] + s * e[5]; q[QUERY_WITHIN] = Infinity;
    shape.distanceIn(q, scratchN);
    const d = q[QUERY_D];
    if (k === -4) best = d;
    else if (k === -3) { if (d < best) { best = d; bestT = 1; } }
    else if (left) f1 = d;
    else f2 = d;
  }
  if (f1 < best) { best = f1; bestT = x1; }
  if (f2 < best) { best = f2; bestT = x2; }
  at[0] = bestT; at[1] = best;
}
/** The edge edgeDeepest searches (a + s·u): a, then u (a record: colliders/shape.ts). */
const edge = new Float64Array(6);
const EDGE_ITERATIONS = 20;
const edgeAt = new Float64Array(2);
/** supportDeepest's vertices: signed distance and normal of each */
const boundary = new Float64Array(12);

/**
 * The deepest point of triangle T = (a, b, c) for a convex shape C with a support mapping, exact wherever T does not
 * cross C (the common case: a cloth resting on a rim or an edge). Where C lies wholly on one side of T's plane,
 * the plane's point nearest C is the projection p of C's support point towards the plane; if p is in T it is the
 * answer (the closest pair of T and C has T's point in T's interior exactly then). Otherwise, and where the plane
 * cuts C but C ∩ plane (a convex set: the support points' chord crosses the plane in it) misses T, the minimum of
 * the convex distance over T lies on T's boundary: the vertices and the three edges (edgeDeepest). If C ∩ plane
 * meets T, or an edge reaches into C, T crosses C and the golden-section search over the whole triangle decides.
 * `bary` and `normal` as triangleDeepest; the signed distance to t[TRIANGLE_D].
 */
export function supportDeepest(
  shape: SupportShape,
  a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
  bary: Float64Array, normal: Float64Array, t: Float64Array,
): void {
  const ax = a[ia], ay = a[ia + 1], az = a[ia + 2];
  const bx = b[ib], by = b[ib + 1], bz = b[ib + 2];
  const cx = c[ic], cy = c[ic + 1], cz = c[ic + 2];
  const abx = bx - ax, aby = by - ay, abz = bz - az, acx = cx - ax, acy = cy - ay, acz = cz - az;
  const nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const nn = nx * nx + ny * ny + nz * nz;
  if (!(nn > 1e-30)) { goldenDeepest(shape, a, ia, b, ib, c, ic, bary, normal, t); return; }
  const hi = scratchQ, lo = scratchQ2;
  const d = supportDirection;
  d[0] = nx; d[1] = ny; d[2] = nz;
  shape.support(d, hi, lo);
  // heights above the plane, in units of |n|
  const hHi = nx * (hi[0] - ax) + ny * (hi[1] - ay) + nz * (hi[2] - az);
  const hLo = nx * (lo[0] - ax) + ny * (lo[1] - ay) + nz * (lo[2] - az);
  // the candidate point of the plane: C's point nearest it, projected; or, where the plane cuts C, a point of C ∩ plane
  let px: number, py: number, pz: number;
  const cuts = hLo <= 0 && hHi >= 0;
  if (cuts) {
    const s = hHi > hLo ? -hLo / (hHi - hLo) : 0;
    px = lo[0] + s * (hi[0] - lo[0]); py = lo[1] + s * (hi[1] - lo[1]); pz = lo[2] + s * (hi[2] - lo[2]);
  } else {
    const q = hLo > 0 ? lo : hi, h = (hLo > 0 ? hLo : hHi) / nn;
    px = q[0] - h * nx; py = q[1] - h * ny; pz = q[2] - h * nz;
  }
  // its barycentric weights (n · (ab × ap)) / |n|² etc.
  const qx = px - ax, qy = py - ay, qz = pz - az;
  const w = (nx * (aby * qz - abz * qy) + ny * (abz * qx - abx * qz) + nz * (abx * qy - aby * qx)) / nn;
  const v = (nx * (qy * acz - qz * acy) + ny * (qz * acx - qx * acz) + nz * (qx * acy - qy * acx)) / nn;
  const inside = v >= 0 && w >= 0 && v + w <= 1;
  if (inside) {
    if (cuts) { goldenDeepest(shape, a, ia, b, ib, c, ic, bary, normal, t); return; }
    bary[0] = 1 - v - w; bary[1] = v; bary[2] = w;
    const q = convexQuery;
    q[QUERY_X] = px; q[QUERY_Y] = py; q[QUERY_Z] = pz; q[QUERY_WITHIN] = Infinity;
    shape.distanceIn(q, normal);
    t[TRIANGLE_D] = q[QUERY_D];
    return;
  }
  // on the boundary: the vertices, then the edges. Along an edge the distance is convex: where it does not fall
  // on leaving an end (n·(other end − end) ≥ 0) the edge's minimum is that end; and the tangent planes at the ends
  // bound it from below, so an edge that cannot beat the best so far is not searched
  const V = boundary;
  for (let k = 0; k < 3; k++) {
    const q = convexQuery;
    q[QUERY_X] = k === 0 ? ax : k === 1 ? bx : cx; q[QUERY_Y] = k === 0 ? ay : k === 1 ? by : cy; q[QUERY_Z] = k === 0 ? az : k === 1 ? bz : cz;
    q[QUERY_WITHIN] = Infinity;
    shape.distanceIn(q, scratchN);
    V[4 * k] = q[QUERY_D];
    V[4 * k + 1] = scratchN[0]; V[4 * k + 2] = scratchN[1]; V[4 * k + 3] = scratchN[2];
  }
  let best = V[0], b0 = 1, b1 = 0, b2 = 0;
  if (V[4] < best) { best = V[4]; b0 = 0; b1 = 1; }
  if (V[8] < best) { best = V[8]; b0 = 0; b1 = 0; b2 = 1; }
  for (let e = 0; e < 3; e++) {
    const i = e, j = (e + 1) % 3;
    const ex = (j === 0 ? ax : j === 1 ? bx : cx) - (i === 0 ? ax : i === 1 ? bx : cx);
    const ey = (j === 0 ? ay : j === 1 ? by : cy) - (i === 0 ? ay : i === 1 ? by : cy);
    const ez = (j === 0 ? az : j === 1 ? bz : cz) - (i === 0 ? az : i === 1 ? bz : cz);
    const si = V[4 * i + 1] * ex + V[4 * i + 2] * ey + V[4 * i + 3] * ez;
    const sj = -(V[4 * j + 1] * ex + V[4 * j + 2] * ey + V[4 * j + 3] * ez);
    if (si >= 0 || sj >= 0) continue;
    if (Math.max(V[4 * i] + si, V[4 * j] + sj) >= best) continue;
    // the edge from corner e to corner e + 1
    const g = edge;
    g[0] = e === 0 ? ax : e === 1 ? bx : cx; g[1] = e === 0 ? ay : e === 1 ? by : cy; g[2] = e === 0 ? az : e === 1 ? bz : cz;
    g[3] = ex; g[4] = ey; g[5] = ez;
    edgeDeepest(shape, edgeAt);
    const d = edgeAt[1];
    if (d < best) {
      best = d;
      const s = edgeAt[0];
      b0 = e === 0 ? 1 - s : e === 1 ? 0 : s;
      b1 = e === 0 ? s : e === 1 ? 1 - s : 0;
      b2 = e === 0 ? 0 : e === 1 ? s : 1 - s;
    }
  }
  // a vertex or an edge reaching into C: T crosses it
  if (best <= 0) { goldenDeepest(shape, a, ia, b, ib, c, ic, bary, normal, t); return; }
  bary[0] = b0; bary[1] = b1; bary[2] = b2;
  const q = convexQuery;
  q[QUERY_X] = b0 * ax + b1 * bx + b2 * cx; q[QUERY_Y] = b0 * ay + b1 * by + b2 * cy; q[QUERY_Z] = b0 * az + b1 * bz + b2 * cz;
  q[QUERY_WITHIN] = Infinity;
  shape.distanceIn(q, normal);
  t[TRIANGLE_D] = q[QUERY_D];
}

/** Parameter in [0, 1] of the point of segment a–b closest to p. */
export function closestPointOnSegment(
  px: number, py: number, pz: number, a: readonly number[], b: readonly number[],
): number {
  const ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const uu = ux * ux + uy * uy + uz * uz;
  if (uu === 0) return 0;
  const t = ((px - a[0]) * ux + (py - a[1]) * uy + (pz - a[2]) * uz) / uu;
  return t < 0 ? 0 : t > 1 ? 1 : t;
}

/**
 * Where a shape's axis (direction u) crosses a triangle, the deepest point has no closest-point direction: the
 * normal is the triangle's normal with its component along the axis removed (the way off the axis that is
 * shortest), the triangle's own normal if that leaves nothing. Returns −radius.
 */
export function axisCrossingNormal(
  a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
  ux: number, uy: number, uz: number, normal: Float64Array, radius: number,
): number {
  const abx = b[ib] - a[ia], aby = b[ib + 1] - a[ia + 1], abz = b[ib + 2] - a[ia + 2];
  const acx = c[ic] - a[ia], acy = c[ic + 1] - a[ia + 1], acz = c[ic + 2] - a[ia + 2];
  let nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const uu = ux * ux + uy * uy + uz * uz;
  if (uu > 0) {
    const k = (nx * ux + ny * uy + nz * uz) / uu;
    const sx = nx - k * ux, sy = ny - k * uy, sz = nz - k * uz;
    if (sx * sx + sy * sy + sz * sz > 1e-6 * (nx * nx + ny * ny + nz * nz)) { nx = sx; ny = sy; nz = sz; }
  }
  // (a square root of the sum, not Math.hypot, whose scaling and compensated sum the kernel could not repeat bit for bit)
  const l = Math.sqrt(nx * nx + ny * ny + nz * nz) || 1;
  normal[0] = nx / l; normal[1] = ny / l; normal[2] = nz / l;
  return -radius;
}
