import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { D: TRIANGLE_D } = TRIANGLE;

/**
 * Closest point of triangle (a, b, c) to point p, as barycentric weights written to `bary`.
 * Region tests on the triangle's Voronoi regions (vertex, edge, face), as in Ericson, Real-Time Collision
 * Detection (2005), §5.1.5; a degenerate triangle (two vertices at one point, or all on a line) gets finite
 * weights of a point of it, never 0/0.
 */
export function closestPointOnTriangle(
  px: number, py: number, pz: number,
  ax: number, ay: number, az: number,
  bx: number, by: number, bz: number,
  cx: number, cy: number, cz: number,
  bary: Float64Array,
): void {
  // the twelve numbers go through an array: the body is too large for V8 to inline, and a call that is not
  // inlined boxes each non-integer number it passes (a heap allocation per argument, 4.8 MB a frame in the default
  // scene's triangle contact); this wrapper is small enough to be inlined, so nothing is boxed
  const v = triangleArgs;
  v[0] = px; v[1] = py; v[2] = pz; v[3] = ax; v[4] = ay; v[5] = az;
  v[6] = bx; v[7] = by; v[8] = bz; v[9] = cx; v[10] = cy; v[11] = cz;
  closestPointIn(v, bary);
}

/** the point queries a sphere makes of itself: through the record, not signedDistance (shape.ts) */
const sphereQuery = pointQuery();

/** closestPointOnTriangle's arguments p, a, b, c */
const triangleArgs = new Float64Array(12);

/** closestPointOnTriangle on p, a, b, c in args[0…11] (for callers that fill the array themselves: no number passed). */
export function closestPointIn(args: Float64Array, bary: Float64Array): void {
  const px = args[0], py = args[1], pz = args[2], ax = args[3], ay = args[4], az = args[5];
  const bx = args[6], by = args[7], bz = args[8], cx = args[9], cy = args[10], cz = args[11];
  const abx = bx - ax, aby = by - ay, abz = bz - az;
  const acx = cx - ax, acy = cy - ay, acz = cz - az;
  const apx = px - ax, apy = py - ay, apz = pz - az;
  const d1 = abx * apx + aby * apy + abz * apz;
  const d2 = acx * apx + acy * apy + acz * apz;
  if (d1 <= 0 && d2 <= 0) { bary[0] = 1; bary[1] = 0; bary[2] = 0; return; }
  const bpx = px - bx, bpy = py - by, bpz = pz - bz;
  const d3 = abx * bpx + aby * bpy + abz * bpz;
  const d4 = acx * bpx + acy * bpy + acz * bpz;
  if (d3 >= 0 && d4 <= d3) { bary[0] = 0; bary[1] = 1; bary[2] = 0; return; }
  const vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    // (a zero-length edge, a = b, gives 0/0: its end a)
    const v = d1 - d3 > 0 ? d1 / (d1 - d3) : 0;
    bary[0] = 1 - v; bary[1] = v; bary[2] = 0; return;
  }
  const cpx = px - cx, cpy = py - cy, cpz = pz - cz;
  const d5 = abx * cpx + aby * cpy + abz * cpz;
  const d6 = acx * cpx + acy * cpy + acz * cpz;
  if (d6 >= 0 && d5 <= d6) { bary[0] = 0; bary[1] = 0; bary[2] = 1; return; }
  const vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const w = d2 - d6 > 0 ? d2 / (d2 - d6) : 0;
    bary[0] = 1 - w; bary[1] = 0; bary[2] = w; return;
  }
  const va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const e = d4 - d3 + (d5 - d6);
    const w = e > 0 ? (d4 - d3) / e : 0;
    bary[0] = 0; bary[1] = 1 - w; bary[2] = w; return;
  }
  const sum = va + vb + vc;
  if (!(sum > 0)) {
    // a degenerate (collinear) triangle whose rounding reached the face region: its nearest vertex
    const da = apx * apx + apy * apy + apz * apz, db = bpx * bpx + bpy * bpy + bpz * bpz, dc = cpx * cpx + cpy * cpy + cpz * cpz;
    const k = da <= db && da <= dc ? 0 : db <= dc ? 1 : 2;
    bary[0] = k === 0 ? 1 : 0; bary[1] = k === 1 ? 1 : 0; bary[2] = k === 2 ? 1 : 0;
    return;
  }
  const v = vb / sum, w = vc / sum;
  bary[0] = 1 - v - w; bary[1] = v; bary[2] = w;
}

export class SphereCollider implements ColliderShape {
  readonly type = 'sphere';
  get minCurvatureRadius(): number {
    return this.radius;
  }
  constructor(
    /** centre x [m] */ readonly cx: number,
    /** centre y [m] */ readonly cy: number,
    /** centre z [m] */ readonly cz: number,
    /** radius [m] */ readonly radius: number,
  ) {}

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    const dx = q[QUERY_X] - this.cx, dy = q[QUERY_Y] - this.cy, dz = q[QUERY_Z] - this.cz, within = q[QUERY_WITHIN];
    const d2 = dx * dx + dy * dy + dz * dz;
    const far = this.radius + within;
    if (far > 0 && d2 >= far * far) { q[QUERY_D] = within; return; }
    const d = Math.sqrt(d2);
    if (d > 1e-12) {
      normal[0] = dx / d; normal[1] = dy / d; normal[2] = dz / d;
    } else {
      normal[0] = 0; normal[1] = 1; normal[2] = 0;
    }
    q[QUERY_D] = d - this.radius;
  }

  triangleDeepest(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, within = Infinity,
  ): number {
    return deepestOf(this, a, ia, b, ib, c, ic, bary, normal, within);
  }

  triangleDeepestIn(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, t: Float64Array,
  ): void {
    closestPointOnTriangle(
      this.cx, this.cy, this.cz,
      a[ia], a[ia + 1], a[ia + 2], b[ib], b[ib + 1], b[ib + 2], c[ic], c[ic + 1], c[ic + 2],
      bary,
    );
    const qx = bary[0] * a[ia] + bary[1] * b[ib] + bary[2] * c[ic];
    const qy = bary[0] * a[ia + 1] + bary[1] * b[ib + 1] + bary[2] * c[ic + 1];
    const qz = bary[0] * a[ia + 2] + bary[1] * b[ib + 2] + bary[2] * c[ic + 2];
    const r = sphereQuery;
    r[QUERY_X] = qx; r[QUERY_Y] = qy; r[QUERY_Z] = qz; r[QUERY_WITHIN] = Infinity;
    this.distanceIn(r, normal);
    t[TRIANGLE_D] = r[QUERY_D];
  }
}
