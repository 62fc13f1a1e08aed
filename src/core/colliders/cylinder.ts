import { axisCrossingNormal, segmentTriangleClosest, supportDeepest, vertexDeepest, type SupportShape } from './convex.js';
import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { D: TRIANGLE_D } = TRIANGLE;

const bary2 = new Float64Array(3);
const seg = new Float64Array(1);
/** the point queries a cylinder makes of itself: through the record, not signedDistance (shape.ts) */
const cylinderQuery = pointQuery();

/**
 * A closed cylinder: centre, axis direction, radius and height (caps included). Its rims are sharp
 * (minCurvatureRadius 0). Triangle contact: the vertex certificate (a triangle on a cap), then the triangle's point
 * closest to the axis, which is the exact answer where it lies against the curved side (sd ≥ ρ − r everywhere, ρ
 * the distance to the axis line, with equality there), else (a rim under the triangle) the support-point method,
 * exact while the triangle does not cross the cylinder, and the golden-section search where it does (convex.ts).
 */
export class CylinderCollider implements SupportShape {
  readonly type = 'cylinder';
  readonly minCurvatureRadius = 0;
  /** unit axis */
  readonly ux: number; readonly uy: number; readonly uz: number;
  /** half the height [m] */
  readonly halfHeight: number;
  /**
   * a unit vector perpendicular to the axis; in a Float64Array, not fields: a field holding a whole number (0, −1)
   * is kept as an integer, and distanceIn's normal, that or a quotient, would then be boxed (16 bytes a call)
   */
  private readonly perp = new Float64Array(3);
  private readonly bound: number;
  constructor(
    readonly center: readonly [number, number, number],
    axis: readonly [number, number, number],
    readonly radius: number,
    readonly height: number,
  ) {
    const l = Math.hypot(axis[0], axis[1], axis[2]);
    if (!(l > 0)) throw new RangeError('cylinder axis must not be zero');
    const ux = axis[0] / l, uy = axis[1] / l, uz = axis[2] / l;
    this.ux = ux; this.uy = uy; this.uz = uz;
    this.halfHeight = height / 2;
    const ax = Math.abs(ux), ay = Math.abs(uy), az = Math.abs(uz);
    let px: number, py: number, pz: number;
    if (ay <= ax && ay <= az) { px = -uz; py = 0; pz = ux; }
    else if (ax <= az) { px = 0; py = uz; pz = -uy; }
    else { px = uy; py = -ux; pz = 0; }
    const pl = Math.hypot(px, py, pz);
    this.perp[0] = px / pl; this.perp[1] = py / pl; this.perp[2] = pz / pl;
    this.bound = Math.hypot(radius, this.halfHeight);
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    const dx = q[QUERY_X] - this.center[0], dy = q[QUERY_Y] - this.center[1], dz = q[QUERY_Z] - this.center[2];
    const within = q[QUERY_WITHIN];
    if (within !== Infinity) {
      const far = this.bound + within;
      if (far > 0 && dx * dx + dy * dy + dz * dz >= far * far) { q[QUERY_D] = within; return; }
    }
    const y = dx * this.ux + dy * this.uy + dz * this.uz;
    const rx = dx - y * this.ux, ry = dy - y * this.uy, rz = dz - y * this.uz;
    const rho = Math.sqrt(rx * rx + ry * ry + rz * rz);
    let hx: number, hy: number, hz: number;
    if (rho > 1e-12) { hx = rx / rho; hy = ry / rho; hz = rz / rho; }
    else { const p = this.perp; hx = p[0]; hy = p[1]; hz = p[2]; }
    const sy = y < 0 ? -1 : 1;
    const er = rho - this.radius, ey = Math.abs(y) - this.halfHeight;
    if (er > 0 || ey > 0) {
      const or = Math.max(er, 0), oy = Math.max(ey, 0);
      const d = Math.sqrt(or * or + oy * oy);
      normal[0] = (or * hx + oy * sy * this.ux) / d;
      normal[1] = (or * hy + oy * sy * this.uy) / d;
      normal[2] = (or * hz + oy * sy * this.uz) / d;
      q[QUERY_D] = d;
      return;
    }
    if (er >= ey) { normal[0] = hx; normal[1] = hy; normal[2] = hz; q[QUERY_D] = er; return; }
    normal[0] = sy * this.ux; normal[1] = sy * this.uy; normal[2] = sy * this.uz;
    q[QUERY_D] = ey;
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
    if (vertexDeepest(this, a, ia, b, ib, c, ic, bary, normal, t)) return;
    // the triangle's point closest to the axis line (a segment reaching past every vertex's projection)
    const cx = this.center[0], cy = this.center[1], cz = this.center[2];
    // (square roots of the sums, not Math.hypot, whose compensated sum the WebAssembly kernel could not repeat)
    const ax = a[ia] - cx, ay = a[ia + 1] - cy, az = a[ia + 2] - cz, bx = b[ib] - cx, by = b[ib + 1] - cy, bz = b[ib + 2] - cz;
    const ex = c[ic] - cx, ey0 = c[ic + 1] - cy, ez = c[ic + 2] - cz;
    const reach = this.halfHeight + 1 + Math.max(
      Math.sqrt(ax * ax + ay * ay + az * az), Math.sqrt(bx * bx + by * by + bz * bz), Math.sqrt(ex * ex + ey0 * ey0 + ez * ez),
    );
    const d2 = segmentTriangleClosest(
      cx - reach * this.ux, cy - reach * this.uy, cz - reach * this.uz,
      cx + reach * this.ux, cy + reach * this.uy, cz + reach * this.uz,
      a[ia], a[ia + 1], a[ia + 2], b[ib], b[ib + 1], b[ib + 2], c[ic], c[ic + 1], c[ic + 2],
      bary2, seg,
    );
    const qx = bary2[0] * a[ia] + bary2[1] * b[ib] + bary2[2] * c[ic];
    const qy = bary2[0] * a[ia + 1] + bary2[1] * b[ib + 1] + bary2[2] * c[ic + 1];
    const qz = bary2[0] * a[ia + 2] + bary2[1] * b[ib + 2] + bary2[2] * c[ic + 2];
    const y = (qx - cx) * this.ux + (qy - cy) * this.uy + (qz - cz) * this.uz;
    const er = Math.sqrt(d2) - this.radius, ey = Math.abs(y) - this.halfHeight;
    if (ey <= 0 && er >= ey) {
      // on the curved side: sd = ρ − r there, and ρ − r ≤ sd everywhere, so this is the deepest point
      bary[0] = bary2[0]; bary[1] = bary2[1]; bary[2] = bary2[2];
      if (d2 > 1e-24) {
        const r = cylinderQuery;
        r[QUERY_X] = qx; r[QUERY_Y] = qy; r[QUERY_Z] = qz; r[QUERY_WITHIN] = Infinity;
        this.distanceIn(r, normal);
        t[TRIANGLE_D] = r[QUERY_D];
      } else t[TRIANGLE_D] = axisCrossingNormal(a, ia, b, ib, c, ic, this.ux, this.uy, this.uz, normal, this.radius);
      return;
    }
    supportDeepest(this, a, ia, b, ib, c, ic, bary, normal, t);
  }

  /**
   * The points farthest along d and −d: on the cap each points to (either, for d ⊥ axis: the same cap for both), at
   * the rim's point towards it.
   */
  support(d: Float64Array, hi: Float64Array, lo: Float64Array): void {
    const dx = d[0], dy = d[1], dz = d[2];
    const y = dx * this.ux + dy * this.uy + dz * this.uz;
    const rx = dx - y * this.ux, ry = dy - y * this.uy, rz = dz - y * this.uz;
    const rho = Math.sqrt(rx * rx + ry * ry + rz * rz);
    const r = rho > 1e-12 * Math.sqrt(dx * dx + dy * dy + dz * dz) ? this.radius / rho : 0;
    // along −d: the height −y, the radial part −(rx, ry, rz) (negation is exact), the same rho and r. (The caps'
    // heights as ±1 × the half height: a field read merged with its negation is boxed at every call.)
    const hh = this.halfHeight, s = (y < 0 ? -1 : 1) * hh, t = (-y < 0 ? -1 : 1) * hh;
    hi[0] = this.center[0] + s * this.ux + r * rx;
    hi[1] = this.center[1] + s * this.uy + r * ry;
    hi[2] = this.center[2] + s * this.uz + r * rz;
    lo[0] = this.center[0] + t * this.ux + r * -rx;
    lo[1] = this.center[1] + t * this.uy + r * -ry;
    lo[2] = this.center[2] + t * this.uz + r * -rz;
  }
}
