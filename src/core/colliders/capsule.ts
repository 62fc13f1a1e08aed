import { axisCrossingNormal, closestPointOnSegment, segmentTriangleClosest } from './convex.js';
import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { D: TRIANGLE_D } = TRIANGLE;

const seg = new Float64Array(1);
/** the point queries a capsule makes of itself: through the record, not signedDistance (shape.ts) */
const capsuleQuery = pointQuery();

/**
 * The points within `radius` of the segment from `a` to `b`. Its surface is round (curvature radius = radius), and
 * a triangle's deepest point is the triangle's point closest to the segment (convex.ts segmentTriangleClosest):
 * exact, as for the sphere.
 */
export class CapsuleCollider implements ColliderShape {
  readonly type = 'capsule';
  get minCurvatureRadius(): number {
    return this.radius;
  }
  /** a unit vector perpendicular to the axis (the normal of a point on the axis) */
  private readonly px: number; private readonly py: number; private readonly pz: number;
  constructor(readonly a: readonly [number, number, number], readonly b: readonly [number, number, number], readonly radius: number) {
    const ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    // a perpendicular: the axis × the world axis it is least aligned with
    const ax = Math.abs(ux), ay = Math.abs(uy), az = Math.abs(uz);
    let px: number, py: number, pz: number;
    if (ax + ay + az === 0) { px = 0; py = 1; pz = 0; }
    else if (ay <= ax && ay <= az) { px = -uz; py = 0; pz = ux; }
    else if (ax <= az) { px = 0; py = uz; pz = -uy; }
    else { px = uy; py = -ux; pz = 0; }
    const l = Math.hypot(px, py, pz);
    this.px = px / l; this.py = py / l; this.pz = pz / l;
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    const px = q[QUERY_X], py = q[QUERY_Y], pz = q[QUERY_Z], within = q[QUERY_WITHIN];
    const t = closestPointOnSegment(px, py, pz, this.a, this.b);
    const dx = px - (this.a[0] + t * (this.b[0] - this.a[0]));
    const dy = py - (this.a[1] + t * (this.b[1] - this.a[1]));
    const dz = pz - (this.a[2] + t * (this.b[2] - this.a[2]));
    const d2 = dx * dx + dy * dy + dz * dz;
    const far = this.radius + within;
    if (far > 0 && d2 >= far * far) { q[QUERY_D] = within; return; }
    const d = Math.sqrt(d2);
    if (d > 1e-12) { normal[0] = dx / d; normal[1] = dy / d; normal[2] = dz / d; }
    else { normal[0] = this.px; normal[1] = this.py; normal[2] = this.pz; }
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
    bary: Float64Array, normal: Float64Array, out: Float64Array,
  ): void {
    const A = this.a, B = this.b;
    const d2 = segmentTriangleClosest(
      A[0], A[1], A[2], B[0], B[1], B[2],
      a[ia], a[ia + 1], a[ia + 2], b[ib], b[ib + 1], b[ib + 2], c[ic], c[ic + 1], c[ic + 2],
      bary, seg,
    );
    const qx = bary[0] * a[ia] + bary[1] * b[ib] + bary[2] * c[ic];
    const qy = bary[0] * a[ia + 1] + bary[1] * b[ib + 1] + bary[2] * c[ic + 1];
    const qz = bary[0] * a[ia + 2] + bary[1] * b[ib + 2] + bary[2] * c[ic + 2];
    if (d2 > 1e-24) {
      const r = capsuleQuery;
      r[QUERY_X] = qx; r[QUERY_Y] = qy; r[QUERY_Z] = qz; r[QUERY_WITHIN] = Infinity;
      this.distanceIn(r, normal);
      out[TRIANGLE_D] = r[QUERY_D];
      return;
    }
    // the axis crosses the triangle: push it off sideways, along the triangle's normal made perpendicular to the axis
    out[TRIANGLE_D] = axisCrossingNormal(a, ia, b, ib, c, ic, B[0] - A[0], B[1] - A[1], B[2] - A[2], normal, this.radius);
  }
}
