import { eulerXYZ } from '../mesh/generators.js';
import { goldenDeepest, segmentTriangleIn, vertexDeepest } from './convex.js';
import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { D: TRIANGLE_D } = TRIANGLE;

/**
 * An oriented box: centre, half extents along its own axes, turned by Euler XYZ angles [degrees] as cloth.rotation
 * is (mesh/generators.ts eulerXYZ). Its edges are sharp (minCurvatureRadius 0), so triangle contact runs unless the
 * cloth's edges are shorter than its thickness (phases.ts needsTriangleContact).
 */
export class BoxCollider implements ColliderShape {
  readonly type = 'box';
  readonly minCurvatureRadius = 0;
  /** rotation, row-major: world = R·local + centre */
  readonly r: readonly number[];
  /** radius of the bounding sphere [m] */
  private readonly bound: number;
  /** whether it is turned at all (false: its axes are the frame's, as every box PosedCollider holds) */
  private readonly turned: boolean;
  /** the 12 edges, world space: x0 y0 z0 x1 y1 z1 each */
  private readonly edges = new Float64Array(72);
  constructor(
    readonly center: readonly [number, number, number],
    readonly halfExtents: readonly [number, number, number],
    readonly rotation: readonly [number, number, number] = [0, 0, 0],
  ) {
    this.r = eulerXYZ(rotation);
    this.turned = rotation[0] !== 0 || rotation[1] !== 0 || rotation[2] !== 0;
    this.bound = Math.hypot(halfExtents[0], halfExtents[1], halfExtents[2]);
    const corner = (k: number): number[] => {
      const l = [k & 1 ? halfExtents[0] : -halfExtents[0], k & 2 ? halfExtents[1] : -halfExtents[1], k & 4 ? halfExtents[2] : -halfExtents[2]];
      const r = this.r;
      return [0, 1, 2].map((i) => center[i] + r[3 * i] * l[0] + r[3 * i + 1] * l[1] + r[3 * i + 2] * l[2]);
    };
    let e = 0;
    for (let k = 0; k < 8; k++) {
      for (const bit of [1, 2, 4]) {
        if (k & bit) continue;
        this.edges.set([...corner(k), ...corner(k | bit)], 6 * e++);
      }
    }
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
    const r = this.r, h = this.halfExtents, turned = this.turned;
    // local coordinates: Rᵀ·d
    const q0 = turned ? r[0] * dx + r[3] * dy + r[6] * dz : dx;
    const q1 = turned ? r[1] * dx + r[4] * dy + r[7] * dz : dy;
    const q2 = turned ? r[2] * dx + r[5] * dy + r[8] * dz : dz;
    const e0 = Math.abs(q0) - h[0], e1 = Math.abs(q1) - h[1], e2 = Math.abs(q2) - h[2];
    let l0: number, l1: number, l2: number, d: number;
    if (e0 > 0 || e1 > 0 || e2 > 0) {
      // outside: distance to the nearest point of the box
      const o0 = Math.max(e0, 0), o1 = Math.max(e1, 0), o2 = Math.max(e2, 0);
      d = Math.sqrt(o0 * o0 + o1 * o1 + o2 * o2);
      l0 = (Math.sign(q0) * o0) / d; l1 = (Math.sign(q1) * o1) / d; l2 = (Math.sign(q2) * o2) / d;
    } else {
      // inside: the nearest face
      l0 = 0; l1 = 0; l2 = 0;
      if (e0 >= e1 && e0 >= e2) { d = e0; l0 = q0 < 0 ? -1 : 1; }
      else if (e1 >= e2) { d = e1; l1 = q1 < 0 ? -1 : 1; }
      else { d = e2; l2 = q2 < 0 ? -1 : 1; }
    }
    if (!turned) { normal[0] = l0; normal[1] = l1; normal[2] = l2; q[QUERY_D] = d; return; }
    normal[0] = r[0] * l0 + r[1] * l1 + r[2] * l2;
    normal[1] = r[3] * l0 + r[4] * l1 + r[5] * l2;
    normal[2] = r[6] * l0 + r[7] * l1 + r[8] * l2;
    q[QUERY_D] = d;
  }

  /**
   * Whether the segment p–q in s[0..5] meets the box (slabs in the box's frame): through the array, no number passed
   * (triangleDeepestIn, in a step: colliders/shape.ts).
   */
  private segmentHitsIn(s: Float64Array): boolean {
    const px = s[0], py = s[1], pz = s[2], qx = s[3], qy = s[4], qz = s[5];
    const r = this.r, h = this.halfExtents;
    const dx = px - this.center[0], dy = py - this.center[1], dz = pz - this.center[2];
    const ex = qx - px, ey = qy - py, ez = qz - pz;
    let lo = 0, hi = 1;
    for (let i = 0; i < 3; i++) {
      const o = r[i] * dx + r[3 + i] * dy + r[6 + i] * dz;
      const v = r[i] * ex + r[3 + i] * ey + r[6 + i] * ez;
      if (Math.abs(v) < 1e-300) {
        if (Math.abs(o) > h[i]) return false;
        continue;
      }
      let t0 = (-h[i] - o) / v, t1 = (h[i] - o) / v;
      if (t0 > t1) { const t = t0; t0 = t1; t1 = t; }
      lo = Math.max(lo, t0); hi = Math.min(hi, t1);
      if (lo > hi) return false;
    }
    return true;
  }

  /**
   * The vertex certificate (convex.ts) for a triangle on or beside a face; else, while the triangle is outside the
   * box, the closest features: the closest pair of two disjoint convex polytopes is a vertex of one and the nearest
   * point of the other, or a point on an edge of each, so the deepest point is a vertex of the triangle or the
   * triangle's point nearest one of the box's 12 edges (segmentTriangleClosest, which also takes the box's corners
   * as the edges' ends) — exact. A triangle that crosses the box (a vertex inside, an edge through it) goes to the
   * golden-section search.
   */
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
    const ax = a[ia], ay = a[ia + 1], az = a[ia + 2], bx = b[ib], by = b[ib + 1], bz = b[ib + 2];
    const cx = c[ic], cy = c[ic + 1], cz = c[ic + 2];
    // the deepest vertex, as vertexDeepest left it
    const k = bary[0] === 1 ? 0 : bary[1] === 1 ? 1 : 2;
    const r = boxQuery;
    r[QUERY_X] = k === 0 ? ax : k === 1 ? bx : cx; r[QUERY_Y] = k === 0 ? ay : k === 1 ? by : cy; r[QUERY_Z] = k === 0 ? az : k === 1 ? bz : cz;
    r[QUERY_WITHIN] = Infinity;
    this.distanceIn(r, normal);
    const vertex = r[QUERY_D];
    // crossing the box: a vertex in it, an edge of the triangle through it (or, below, an edge of the box through the triangle)
    // its edges a–b, b–c, c–a in that order (as the kernel's)
    const sg = segmentArgs;
    sg[0] = ax; sg[1] = ay; sg[2] = az; sg[3] = bx; sg[4] = by; sg[5] = bz;
    let crosses = vertex <= 0 || this.segmentHitsIn(sg);
    sg[0] = bx; sg[1] = by; sg[2] = bz; sg[3] = cx; sg[4] = cy; sg[5] = cz;
    crosses ||= this.segmentHitsIn(sg);
    sg[0] = cx; sg[1] = cy; sg[2] = cz; sg[3] = ax; sg[4] = ay; sg[5] = az;
    crosses ||= this.segmentHitsIn(sg);
    if (crosses) {
      goldenDeepest(this, a, ia, b, ib, c, ic, bary, normal, t);
      return;
    }
    let best = vertex, found = false;
    const gx = (ax + bx + cx) / 3, gy = (ay + by + cy) / 3, gz = (az + bz + cz) / 3;
    // (products, not `** 2`: the WebAssembly kernel repeats these operations exactly)
    const ax1 = ax - gx, ay1 = ay - gy, az1 = az - gz, bx1 = bx - gx, by1 = by - gy, bz1 = bz - gz;
    const cx1 = cx - gx, cy1 = cy - gy, cz1 = cz - gz;
    const reach = Math.sqrt(Math.max(
      ax1 * ax1 + ay1 * ay1 + az1 * az1, bx1 * bx1 + by1 * by1 + bz1 * bz1, cx1 * cx1 + cy1 * cy1 + cz1 * cz1,
    ));
    const E = this.edges, et = edgeTriangle;
    et[6] = ax; et[7] = ay; et[8] = az; et[9] = bx; et[10] = by; et[11] = bz; et[12] = cx; et[13] = cy; et[14] = cz;
    for (let e = 0; e < 72; e += 6) {
      // an edge farther from the triangle's centre than its reach plus the best so far cannot be nearer
      const ux = E[e + 3] - E[e], uy = E[e + 4] - E[e + 1], uz = E[e + 5] - E[e + 2];
      const uu = ux * ux + uy * uy + uz * uz;
      const s = uu > 0 ? Math.min(Math.max(((gx - E[e]) * ux + (gy - E[e + 1]) * uy + (gz - E[e + 2]) * uz) / uu, 0), 1) : 0;
      const qx = E[e] + s * ux - gx, qy = E[e + 1] + s * uy - gy, qz = E[e + 2] + s * uz - gz;
      if (Math.sqrt(qx * qx + qy * qy + qz * qz) - reach >= best) continue;
      et[0] = E[e]; et[1] = E[e + 1]; et[2] = E[e + 2]; et[3] = E[e + 3]; et[4] = E[e + 4]; et[5] = E[e + 5];
      segmentTriangleIn(et, edgeBary, seg);
      const d2 = et[15];
      if (d2 <= 1e-24) { goldenDeepest(this, a, ia, b, ib, c, ic, bary, normal, t); return; }
      if (d2 < best * best) {
        best = Math.sqrt(d2); found = true;
        bary[0] = edgeBary[0]; bary[1] = edgeBary[1]; bary[2] = edgeBary[2];
      }
    }
    if (!found) { t[TRIANGLE_D] = vertex; return; }
    r[QUERY_X] = bary[0] * ax + bary[1] * bx + bary[2] * cx; r[QUERY_Y] = bary[0] * ay + bary[1] * by + bary[2] * cy;
    r[QUERY_Z] = bary[0] * az + bary[1] * bz + bary[2] * cz; r[QUERY_WITHIN] = Infinity;
    this.distanceIn(r, normal);
    t[TRIANGLE_D] = r[QUERY_D];
  }
}

const edgeBary = new Float64Array(3);
/** segmentHitsIn's segment p–q */
const segmentArgs = new Float64Array(6);
/** segmentTriangleIn's record: a box edge p–q and the cloth triangle a, b, c, then the squared distance */
const edgeTriangle = new Float64Array(16);
/** the point queries a box makes of itself: through the record, not signedDistance (shape.ts) */
const boxQuery = pointQuery();
const seg = new Float64Array(1);
