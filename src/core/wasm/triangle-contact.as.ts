// Triangle contact (phases.ts collideTriangles) against the sphere, capsule and cylinder records that have it (the
// record's EXACT): the reference's culls, deepest point and push-out, one triangle after another in its order and
// its arithmetic (f64 on the f32 data, the corners turned into the shape's frame in f32 as a PosedCollider does; a
// capsule's deepest point by convex.ts segmentTriangleClosest, a cylinder's by its vertex certificate, the axis and
// the support points or golden-section searches, operation for operation), so that the cloth is the reference's
// bit for bit. The host asks for the phase only when every shape with triangle contact is one of these
// (xpbd-wasm.ts triangleRefusal); it runs on one thread, the triangles in order (Gauss–Seidel).
import { N, TRIANGLE_COUNT, TRIANGLES, W, X, XP } from './arrays.as';
import { LX, LY, LZ, SMX, SMY, SMZ, field, frictionScale, localDistance, pressedDepth, surfaceMotion } from './contact.as';
import {
  COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_RECORD_EXACT, COLLIDER_SPHERE, GOLDEN_ITERATIONS, COLLIDER_RECORD_FLOATS, COLLIDER_RECORD_MOVING, COLLIDER_RECORD_O, COLLIDER_RECORD_R,
  COLLIDER_RECORD_SHAPE, COLLIDER_RECORD_TYPE, COLLIDER_RECORDS, COLLIDERS, THICKNESS, TRIANGLE_REACH, TRIANGLE_RECOVER,
  TRIANGLE_SPREAD_MOST,
} from './layout.generated.as';

const COLLIDER_BYTES: usize = <usize>COLLIDER_RECORD_FLOATS * 8;

@inline function xAt(j: usize): f64 {
  return <f64>load<f32>(j);
}

// the cloth's box (phases.ts clothBox)
let BX0: f64 = 0, BY0: f64 = 0, BZ0: f64 = 0, BX1: f64 = 0, BY1: f64 = 0, BZ1: f64 = 0;

function clothBox(): void {
  BX0 = Infinity; BY0 = Infinity; BZ0 = Infinity; BX1 = -Infinity; BY1 = -Infinity; BZ1 = -Infinity;
  for (let i = 0; i < N; i++) {
    const j = X + <usize>i * 12;
    const vx = xAt(j), vy = xAt(j + 4), vz = xAt(j + 8);
    if (vx < BX0) BX0 = vx;
    if (vx > BX1) BX1 = vx;
    if (vy < BY0) BY0 = vy;
    if (vy > BY1) BY1 = vy;
    if (vz < BZ0) BZ0 = vz;
    if (vz > BZ1) BZ1 = vz;
  }
}

// closestPointOnTriangle's weights (sphere.ts)
let U0: f64 = 0, U1: f64 = 0, U2: f64 = 0;

/** sphere.ts closestPointIn: the weights of triangle (a, b, c)'s point closest to p, to U0, U1, U2. */
function closestPoint(
  px: f64, py: f64, pz: f64, ax: f64, ay: f64, az: f64, bx: f64, by: f64, bz: f64, cx: f64, cy: f64, cz: f64,
): void {
  const abx = bx - ax, aby = by - ay, abz = bz - az;
  const acx = cx - ax, acy = cy - ay, acz = cz - az;
  const apx = px - ax, apy = py - ay, apz = pz - az;
  const d1 = abx * apx + aby * apy + abz * apz;
  const d2 = acx * apx + acy * apy + acz * apz;
  if (d1 <= 0 && d2 <= 0) { U0 = 1; U1 = 0; U2 = 0; return; }
  const bpx = px - bx, bpy = py - by, bpz = pz - bz;
  const d3 = abx * bpx + aby * bpy + abz * bpz;
  const d4 = acx * bpx + acy * bpy + acz * bpz;
  if (d3 >= 0 && d4 <= d3) { U0 = 0; U1 = 1; U2 = 0; return; }
  const vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const v = d1 - d3 > 0 ? d1 / (d1 - d3) : 0;
    U0 = 1 - v; U1 = v; U2 = 0; return;
  }
  const cpx = px - cx, cpy = py - cy, cpz = pz - cz;
  const d5 = abx * cpx + aby * cpy + abz * cpz;
  const d6 = acx * cpx + acy * cpy + acz * cpz;
  if (d6 >= 0 && d5 <= d6) { U0 = 0; U1 = 0; U2 = 1; return; }
  const vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const w = d2 - d6 > 0 ? d2 / (d2 - d6) : 0;
    U0 = 1 - w; U1 = 0; U2 = w; return;
  }
  const va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const e = d4 - d3 + (d5 - d6);
    const w = e > 0 ? (d4 - d3) / e : 0;
    U0 = 0; U1 = 1 - w; U2 = w; return;
  }
  const sum = va + vb + vc;
  if (!(sum > 0)) {
    const da = apx * apx + apy * apy + apz * apz, db = bpx * bpx + bpy * bpy + bpz * bpz, dc = cpx * cpx + cpy * cpy + cpz * cpz;
    const k = da <= db && da <= dc ? 0 : db <= dc ? 1 : 2;
    U0 = k == 0 ? 1 : 0; U1 = k == 1 ? 1 : 0; U2 = k == 2 ? 1 : 0;
    return;
  }
  const v = vb / sum, w = vc / sum;
  U0 = 1 - v - w; U1 = v; U2 = w;
}

// segmentSegment's parameter on the second segment (the first's the reference keeps, no one here reads)
let ST: f64 = 0;

/** convex.ts segmentSegmentIn: the closest points of p1–q1 and p2–q2 (the second's parameter to ST); the squared distance. */
function segmentSegment(
  p1x: f64, p1y: f64, p1z: f64, q1x: f64, q1y: f64, q1z: f64, p2x: f64, p2y: f64, p2z: f64, q2x: f64, q2y: f64, q2z: f64,
): f64 {
  const d1x = q1x - p1x, d1y = q1y - p1y, d1z = q1z - p1z;
  const d2x = q2x - p2x, d2y = q2y - p2y, d2z = q2z - p2z;
  const rx = p1x - p2x, ry = p1y - p2y, rz = p1z - p2z;
  const a = d1x * d1x + d1y * d1y + d1z * d1z;
  const e = d2x * d2x + d2y * d2y + d2z * d2z;
  const f = d2x * rx + d2y * ry + d2z * rz;
  let s: f64, t: f64;
  const eps = 1e-300;
  if (a <= eps && e <= eps) {
    s = 0; t = 0;
  } else if (a <= eps) {
    s = 0; t = min(max(f / e, 0), 1);
  } else {
    const c = d1x * rx + d1y * ry + d1z * rz;
    if (e <= eps) {
      t = 0; s = min(max(-c / a, 0), 1);
    } else {
      const b = d1x * d2x + d1y * d2y + d1z * d2z;
      const denom = a * e - b * b;
      s = denom > 1e-15 * a * e ? min(max((b * f - c * e) / denom, 0), 1) : 0;
      t = (b * s + f) / e;
      if (t < 0) { t = 0; s = min(max(-c / a, 0), 1); }
      else if (t > 1) { t = 1; s = min(max((b - c) / a, 0), 1); }
    }
  }
  ST = t;
  const dx = p1x + d1x * s - (p2x + d2x * t), dy = p1y + d1y * s - (p2y + d2y * t), dz = p1z + d1z * s - (p2z + d2z * t);
  return dx * dx + dy * dy + dz * dz;
}

/**
 * convex.ts segmentTriangleIn: the closest points of segment p–q and triangle (a, b, c), the triangle's weights to
 * U0, U1, U2; the squared distance (0 where the segment crosses the triangle).
 */
function segmentTriangle(
  px: f64, py: f64, pz: f64, qx: f64, qy: f64, qz: f64,
  ax: f64, ay: f64, az: f64, bx: f64, by: f64, bz: f64, cx: f64, cy: f64, cz: f64,
): f64 {
  const abx = bx - ax, aby = by - ay, abz = bz - az, acx = cx - ax, acy = cy - ay, acz = cz - az;
  const nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const nn = nx * nx + ny * ny + nz * nz;
  if (nn > 0) {
    const d0 = nx * (px - ax) + ny * (py - ay) + nz * (pz - az);
    const d1 = nx * (qx - ax) + ny * (qy - ay) + nz * (qz - az);
    if ((d0 <= 0 && d1 >= 0) || (d0 >= 0 && d1 <= 0)) {
      if (d0 != d1) {
        const t = d0 / (d0 - d1);
        const ix = px + t * (qx - px) - ax, iy = py + t * (qy - py) - ay, iz = pz + t * (qz - pz) - az;
        const w = (nx * (aby * iz - abz * iy) + ny * (abz * ix - abx * iz) + nz * (abx * iy - aby * ix)) / nn;
        const u = (nx * (iy * acz - iz * acy) + ny * (iz * acx - ix * acz) + nz * (ix * acy - iy * acx)) / nn;
        if (u >= 0 && w >= 0 && u + w <= 1) {
          U0 = 1 - u - w; U1 = u; U2 = w;
          return 0;
        }
      }
    }
  }
  let best = Infinity, b0: f64 = 0, b1: f64 = 0, b2: f64 = 0;
  // end points against the triangle
  for (let k = 0; k < 2; k++) {
    const ex = k ? qx : px, ey = k ? qy : py, ez = k ? qz : pz;
    closestPoint(ex, ey, ez, ax, ay, az, bx, by, bz, cx, cy, cz);
    const tx = U0 * ax + U1 * bx + U2 * cx - ex;
    const ty = U0 * ay + U1 * by + U2 * cy - ey;
    const tz = U0 * az + U1 * bz + U2 * cz - ez;
    const d2 = tx * tx + ty * ty + tz * tz;
    if (d2 < best) { best = d2; b0 = U0; b1 = U1; b2 = U2; }
  }
  // the segment against each edge
  for (let k = 0; k < 3; k++) {
    const ux = k == 0 ? ax : k == 1 ? bx : cx, uy = k == 0 ? ay : k == 1 ? by : cy, uz = k == 0 ? az : k == 1 ? bz : cz;
    const vx = k == 0 ? bx : k == 1 ? cx : ax, vy = k == 0 ? by : k == 1 ? cy : ay, vz = k == 0 ? bz : k == 1 ? cz : az;
    const d2 = segmentSegment(px, py, pz, qx, qy, qz, ux, uy, uz, vx, vy, vz);
    if (d2 < best) {
      best = d2;
      const t = ST;
      b0 = k == 0 ? 1 - t : k == 2 ? t : 0;
      b1 = k == 1 ? 1 - t : k == 0 ? t : 0;
      b2 = k == 2 ? 1 - t : k == 1 ? t : 0;
    }
  }
  U0 = b0; U1 = b1; U2 = b2;
  return best;
}

// the deepest point's normal in the shape's frame
let LNX: f64 = 0, LNY: f64 = 1, LNZ: f64 = 0;

/**
 * capsule.ts signedDistance for the capsule of half length `half` along y and `radius` [m], at local (px, py, pz),
 * with `within` [m] (Infinity: none): the normal to LNX…LNZ, unless it returns `within` (farther than that).
 */
function capsuleDistance(half: f64, radius: f64, px: f64, py: f64, pz: f64, within: f64): f64 {
  // closestPointOnSegment from a = (0, −half, 0) to b = (0, half, 0)
  const a0: f64 = 0, a1 = -half, a2: f64 = 0, b0: f64 = 0, b1 = half, b2: f64 = 0;
  const ux = b0 - a0, uy = b1 - a1, uz = b2 - a2;
  const uu = ux * ux + uy * uy + uz * uz;
  let t: f64 = 0;
  if (uu != 0) {
    const s = ((px - a0) * ux + (py - a1) * uy + (pz - a2) * uz) / uu;
    t = s < 0 ? 0 : s > 1 ? 1 : s;
  }
  const dx = px - (a0 + t * (b0 - a0)), dy = py - (a1 + t * (b1 - a1)), dz = pz - (a2 + t * (b2 - a2));
  const d2 = dx * dx + dy * dy + dz * dz;
  const far = radius + within;
  if (far > 0 && d2 >= far * far) return within;
  const d = Math.sqrt(d2);
  // the perpendicular for a point on the axis: the axis × the world axis it is least aligned with (CapsuleCollider)
  if (d > 1e-12) { LNX = dx / d; LNY = dy / d; LNZ = dz / d; } else if (half > 0) { LNX = 0; LNY = 0; LNZ = -1; } else { LNX = 0; LNY = 1; LNZ = 0; }
  return d - radius;
}

/**
 * capsule.ts triangleDeepest on the local corners: the triangle's point closest to the axis (weights to U0…U2), its
 * signed distance [m] and normal (LNX…LNZ); where the axis crosses the triangle, convex.ts axisCrossingNormal.
 */
function capsuleDeepest(half: f64, radius: f64, ax: f64, ay: f64, az: f64, bx: f64, by: f64, bz: f64, cx: f64, cy: f64, cz: f64): f64 {
  const d2 = segmentTriangle(0, -half, 0, 0, half, 0, ax, ay, az, bx, by, bz, cx, cy, cz);
  const qx = U0 * ax + U1 * bx + U2 * cx, qy = U0 * ay + U1 * by + U2 * cy, qz = U0 * az + U1 * bz + U2 * cz;
  if (d2 > 1e-24) return capsuleDistance(half, radius, qx, qy, qz, Infinity);
  // the axis (from (0, −half, 0) to (0, half, 0)) crosses the triangle: off it sideways
  TAX = ax; TAY = ay; TAZ = az; TBX = bx; TBY = by; TBZ = bz; TCX = cx; TCY = cy; TCZ = cz;
  return axisCrossing(0 - 0, half - -half, 0 - 0, radius);
}

// The cylinder (cylinder.ts, convex.ts), in its own frame: centre at the origin, axis along y, radius CR, half
// height CH; and the box (box.ts), centred at the origin along its own axes, half extents BH0…BH2. Each function
// below repeats the reference's operations in its order (f64 on the f32 corners).
let CR: f64 = 0, CH: f64 = 0;
let BH0: f64 = 0, BH1: f64 = 0, BH2: f64 = 0;
/** the shape the searches below measure: a box or a cylinder */
let BOXED = false;
// the support point (CylinderCollider.support)
let SPX: f64 = 0, SPY: f64 = 0, SPZ: f64 = 0;

/** CylinderCollider.signedDistance at (px, py, pz) (no bound: `within` Infinity), the normal to LNX…LNZ. */
function cylinderDistance(px: f64, py: f64, pz: f64): f64 {
  const ux: f64 = 0, uy: f64 = 1, uz: f64 = 0;
  const dx = px - 0, dy = py - 0, dz = pz - 0;
  const y = dx * ux + dy * uy + dz * uz;
  const rx = dx - y * ux, ry = dy - y * uy, rz = dz - y * uz;
  const rho = Math.sqrt(rx * rx + ry * ry + rz * rz);
  let hx: f64, hy: f64, hz: f64;
  // the perpendicular for a point on the axis: (0, 0, −1) (CylinderCollider's constructor)
  if (rho > 1e-12) { hx = rx / rho; hy = ry / rho; hz = rz / rho; } else { hx = 0; hy = 0; hz = -1; }
  const sy: f64 = y < 0 ? -1 : 1;
  const er = rho - CR, ey = Math.abs(y) - CH;
  if (er > 0 || ey > 0) {
    const or = max(er, 0), oy = max(ey, 0);
    const d = Math.sqrt(or * or + oy * oy);
    LNX = (or * hx + oy * sy * ux) / d;
    LNY = (or * hy + oy * sy * uy) / d;
    LNZ = (or * hz + oy * sy * uz) / d;
    return d;
  }
  if (er >= ey) { LNX = hx; LNY = hy; LNZ = hz; return er; }
  LNX = sy * ux; LNY = sy * uy; LNZ = sy * uz;
  return ey;
}

/** CylinderCollider.support along (dx, dy, dz), to SPX…SPZ. */
function cylinderSupport(dx: f64, dy: f64, dz: f64): void {
  const ux: f64 = 0, uy: f64 = 1, uz: f64 = 0;
  const y = dx * ux + dy * uy + dz * uz;
  const rx = dx - y * ux, ry = dy - y * uy, rz = dz - y * uz;
  const rho = Math.sqrt(rx * rx + ry * ry + rz * rz);
  const s = y < 0 ? -CH : CH, r = rho > 1e-12 * Math.sqrt(dx * dx + dy * dy + dz * dz) ? CR / rho : 0;
  SPX = 0 + s * ux + r * rx;
  SPY = 0 + s * uy + r * ry;
  SPZ = 0 + s * uz + r * rz;
}

/**
 * BoxCollider.signedDistance at (px, py, pz) (its own frame, not turned; no bound), the normal to LNX…LNZ: particle
 * contact's localDistance (contact.as.ts), whose box is the reference's operation for operation.
 */
function boxDistance(px: f64, py: f64, pz: f64): f64 {
  const d = localDistance(COLLIDER_BOX, BH0, BH1, BH2, px, py, pz);
  LNX = LX; LNY = LY; LNZ = LZ;
  return d;
}

/** The distance (and normal, LNX…LNZ) of the shape the searches measure. */
@inline function shapeDistance(px: f64, py: f64, pz: f64): f64 {
  return BOXED ? boxDistance(px, py, pz) : cylinderDistance(px, py, pz);
}

// the triangle's corners in the shape's frame, for the searches below
let TAX: f64 = 0, TAY: f64 = 0, TAZ: f64 = 0, TBX: f64 = 0, TBY: f64 = 0, TBZ: f64 = 0, TCX: f64 = 0, TCY: f64 = 0, TCZ: f64 = 0;

/**
 * convex.ts vertexDeepest: a corner whose tangent plane has the triangle on or above it is the deepest point (its
 * weights to U0…U2, its normal to LNX…LNZ, its distance returned); a bound ≥ `within` where the tangent planes show
 * the triangle that far; else NaN (U0…U2 the deepest corner, LNX…LNZ its normal).
 */
function vertexDeepest(within: f64): f64 {
  let best = Infinity, bestK = 0, certified = false, certK = -1, certD = Infinity, bound = -Infinity;
  let n0: f64 = 0, n1: f64 = 0, n2: f64 = 0, b0: f64 = 0, b1: f64 = 0, b2: f64 = 0;
  for (let k = 0; k < 3; k++) {
    const vx = k == 0 ? TAX : k == 1 ? TBX : TCX, vy = k == 0 ? TAY : k == 1 ? TBY : TCY, vz = k == 0 ? TAZ : k == 1 ? TBZ : TCZ;
    const d = shapeDistance(vx, vy, vz);
    const nx = LNX, ny = LNY, nz = LNZ;
    const nv = nx * vx + ny * vy + nz * vz;
    const lowest = min(min(nx * TAX + ny * TAY + nz * TAZ, nx * TBX + ny * TBY + nz * TBZ), nx * TCX + ny * TCY + nz * TCZ) - nv;
    bound = max(bound, d + min(lowest, 0));
    if (lowest >= -1e-7 && d < certD) { certified = true; certK = k; certD = d; n0 = nx; n1 = ny; n2 = nz; }
    if (!certified && d < best) { best = d; bestK = k; b0 = nx; b1 = ny; b2 = nz; }
  }
  if (certified) {
    U0 = certK == 0 ? 1 : 0; U1 = certK == 1 ? 1 : 0; U2 = certK == 2 ? 1 : 0;
    LNX = n0; LNY = n1; LNZ = n2;
    return certD;
  }
  U0 = bestK == 0 ? 1 : 0; U1 = bestK == 1 ? 1 : 0; U2 = bestK == 2 ? 1 : 0;
  LNX = b0; LNY = b1; LNZ = b2;
  return bound >= within ? bound : NaN;
}

/** convex.ts GOLDEN, (√5 − 1)/2 (written out: a computed global would need a start function, which the kernel must not have) */
const GOLDEN: f64 = 0.6180339887498949;
// goldenDeepest's edge vectors and its best point so far
let GUX: f64 = 0, GUY: f64 = 0, GUZ: f64 = 0, GVX: f64 = 0, GVY: f64 = 0, GVZ: f64 = 0;
let BEST_U: f64 = 0, BEST_V: f64 = 0, BEST_D: f64 = Infinity;

/** convex.ts goldenF: the distance at (u, v), remembered if the best so far. */
function goldenF(u: f64, v: f64): f64 {
  const d = shapeDistance(TAX + u * GUX + v * GVX, TAY + u * GUY + v * GVY, TAZ + u * GUZ + v * GVZ);
  if (d < BEST_D) { BEST_D = d; BEST_U = u; BEST_V = v; }
  return d;
}

/** convex.ts goldenInner: min over v ∈ [0, 1 − u] of goldenF(u, v), the range's ends included. */
function goldenInner(u: f64): f64 {
  let lo: f64 = 0, hi: f64 = 1 - u;
  let x1 = hi - GOLDEN * (hi - lo), x2 = lo + GOLDEN * (hi - lo);
  let f1 = goldenF(u, x1), f2 = goldenF(u, x2);
  for (let k = 0; k < GOLDEN_ITERATIONS; k++) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); f1 = goldenF(u, x1); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); f2 = goldenF(u, x2); }
  }
  const e0 = goldenF(u, 0), e1 = goldenF(u, 1 - u);
  return min(min(min(f1, f2), e0), e1);
}

/** convex.ts goldenDeepest: the nested golden-section search over the triangle (weights to U0…U2, normal LNX…LNZ). */
function goldenDeepest(): f64 {
  GUX = TBX - TAX; GUY = TBY - TAY; GUZ = TBZ - TAZ;
  GVX = TCX - TAX; GVY = TCY - TAY; GVZ = TCZ - TAZ;
  BEST_U = 0; BEST_V = 0; BEST_D = Infinity;
  let lo: f64 = 0, hi: f64 = 1;
  let x1 = hi - GOLDEN * (hi - lo), x2 = lo + GOLDEN * (hi - lo);
  let f1 = goldenInner(x1), f2 = goldenInner(x2);
  for (let k = 0; k < GOLDEN_ITERATIONS; k++) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); f1 = goldenInner(x1); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); f2 = goldenInner(x2); }
  }
  goldenInner(0); goldenInner(1);
  const u = BEST_U, v = BEST_V;
  U0 = 1 - u - v; U1 = u; U2 = v;
  return shapeDistance(TAX + u * GUX + v * GVX, TAY + u * GUY + v * GVY, TAZ + u * GUZ + v * GVZ);
}

// edgeDeepest's best parameter
let EDGE_T: f64 = 0;

/** convex.ts edgeDeepest: the least distance along a + s·(b − a), s ∈ [0, 1], its parameter to EDGE_T. */
function edgeDeepest(ax: f64, ay: f64, az: f64, bx: f64, by: f64, bz: f64): f64 {
  const ux = bx - ax, uy = by - ay, uz = bz - az;
  let bestT: f64 = 0, best = cylinderDistance(ax + 0 * ux, ay + 0 * uy, az + 0 * uz);
  const fb = cylinderDistance(ax + 1 * ux, ay + 1 * uy, az + 1 * uz);
  if (fb < best) { best = fb; bestT = 1; }
  let lo: f64 = 0, hi: f64 = 1;
  let x1 = hi - GOLDEN * (hi - lo), x2 = lo + GOLDEN * (hi - lo);
  let f1 = cylinderDistance(ax + x1 * ux, ay + x1 * uy, az + x1 * uz), f2 = cylinderDistance(ax + x2 * ux, ay + x2 * uy, az + x2 * uz);
  for (let k = 0; k < EDGE_ITERATIONS; k++) {
    if (f1 <= f2) { hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); f1 = cylinderDistance(ax + x1 * ux, ay + x1 * uy, az + x1 * uz); }
    else { lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); f2 = cylinderDistance(ax + x2 * ux, ay + x2 * uy, az + x2 * uz); }
  }
  if (f1 < best) { best = f1; bestT = x1; }
  if (f2 < best) { best = f2; bestT = x2; }
  EDGE_T = bestT;
  return best;
}
/** convex.ts EDGE_ITERATIONS */
const EDGE_ITERATIONS = 20;

/** convex.ts supportDeepest for the cylinder (weights to U0…U2, normal LNX…LNZ). */
function supportDeepest(): f64 {
  const ax = TAX, ay = TAY, az = TAZ, bx = TBX, by = TBY, bz = TBZ, cx = TCX, cy = TCY, cz = TCZ;
  const abx = bx - ax, aby = by - ay, abz = bz - az, acx = cx - ax, acy = cy - ay, acz = cz - az;
  const nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const nn = nx * nx + ny * ny + nz * nz;
  if (!(nn > 1e-30)) return goldenDeepest();
  cylinderSupport(nx, ny, nz);
  const hiX = SPX, hiY = SPY, hiZ = SPZ;
  cylinderSupport(-nx, -ny, -nz);
  const loX = SPX, loY = SPY, loZ = SPZ;
  const hHi = nx * (hiX - ax) + ny * (hiY - ay) + nz * (hiZ - az);
  const hLo = nx * (loX - ax) + ny * (loY - ay) + nz * (loZ - az);
  let px: f64, py: f64, pz: f64;
  const cuts = hLo <= 0 && hHi >= 0;
  if (cuts) {
    const t = hHi > hLo ? -hLo / (hHi - hLo) : 0;
    px = loX + t * (hiX - loX); py = loY + t * (hiY - loY); pz = loZ + t * (hiZ - loZ);
  } else {
    const qx = hLo > 0 ? loX : hiX, qy = hLo > 0 ? loY : hiY, qz = hLo > 0 ? loZ : hiZ, h = (hLo > 0 ? hLo : hHi) / nn;
    px = qx - h * nx; py = qy - h * ny; pz = qz - h * nz;
  }
  const qx = px - ax, qy = py - ay, qz = pz - az;
  const w = (nx * (aby * qz - abz * qy) + ny * (abz * qx - abx * qz) + nz * (abx * qy - aby * qx)) / nn;
  const v = (nx * (qy * acz - qz * acy) + ny * (qz * acx - qx * acz) + nz * (qx * acy - qy * acx)) / nn;
  if (v >= 0 && w >= 0 && v + w <= 1) {
    if (cuts) return goldenDeepest();
    U0 = 1 - v - w; U1 = v; U2 = w;
    return cylinderDistance(px, py, pz);
  }
  // the corners' distances and normals, then the edges
  const d0 = cylinderDistance(ax, ay, az), m0x = LNX, m0y = LNY, m0z = LNZ;
  const d1 = cylinderDistance(bx, by, bz), m1x = LNX, m1y = LNY, m1z = LNZ;
  const d2 = cylinderDistance(cx, cy, cz), m2x = LNX, m2y = LNY, m2z = LNZ;
  let best = d0, b0: f64 = 1, b1: f64 = 0, b2: f64 = 0;
  if (d1 < best) { best = d1; b0 = 0; b1 = 1; }
  if (d2 < best) { best = d2; b0 = 0; b1 = 0; b2 = 1; }
  for (let e = 0; e < 3; e++) {
    const i = e, j = (e + 1) % 3;
    const ex = (j == 0 ? ax : j == 1 ? bx : cx) - (i == 0 ? ax : i == 1 ? bx : cx);
    const ey = (j == 0 ? ay : j == 1 ? by : cy) - (i == 0 ? ay : i == 1 ? by : cy);
    const ez = (j == 0 ? az : j == 1 ? bz : cz) - (i == 0 ? az : i == 1 ? bz : cz);
    const nix = i == 0 ? m0x : i == 1 ? m1x : m2x, niy = i == 0 ? m0y : i == 1 ? m1y : m2y, niz = i == 0 ? m0z : i == 1 ? m1z : m2z;
    const njx = j == 0 ? m0x : j == 1 ? m1x : m2x, njy = j == 0 ? m0y : j == 1 ? m1y : m2y, njz = j == 0 ? m0z : j == 1 ? m1z : m2z;
    const si = nix * ex + niy * ey + niz * ez;
    const sj = -(njx * ex + njy * ey + njz * ez);
    if (si >= 0 || sj >= 0) continue;
    if (max((i == 0 ? d0 : i == 1 ? d1 : d2) + si, (j == 0 ? d0 : j == 1 ? d1 : d2) + sj) >= best) continue;
    const d = e == 0 ? edgeDeepest(ax, ay, az, bx, by, bz) : e == 1 ? edgeDeepest(bx, by, bz, cx, cy, cz) : edgeDeepest(cx, cy, cz, ax, ay, az);
    if (d < best) {
      best = d;
      const t = EDGE_T;
      b0 = e == 0 ? 1 - t : e == 1 ? 0 : t;
      b1 = e == 0 ? t : e == 1 ? 1 - t : 0;
      b2 = e == 0 ? 0 : e == 1 ? t : 1 - t;
    }
  }
  if (best <= 0) return goldenDeepest();
  U0 = b0; U1 = b1; U2 = b2;
  return cylinderDistance(b0 * ax + b1 * bx + b2 * cx, b0 * ay + b1 * by + b2 * cy, b0 * az + b1 * bz + b2 * cz);
}

/** The triangle's point closest to the axis crossing it: convex.ts axisCrossingNormal for axis u (normal LNX…LNZ); −radius. */
function axisCrossing(ux: f64, uy: f64, uz: f64, radius: f64): f64 {
  const abx = TBX - TAX, aby = TBY - TAY, abz = TBZ - TAZ, acx = TCX - TAX, acy = TCY - TAY, acz = TCZ - TAZ;
  let nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
  const uu = ux * ux + uy * uy + uz * uz;
  if (uu > 0) {
    const k = (nx * ux + ny * uy + nz * uz) / uu;
    const sx = nx - k * ux, sy = ny - k * uy, sz = nz - k * uz;
    if (sx * sx + sy * sy + sz * sz > 1e-6 * (nx * nx + ny * ny + nz * nz)) { nx = sx; ny = sy; nz = sz; }
  }
  let l = Math.sqrt(nx * nx + ny * ny + nz * nz);
  if (l == 0 || l != l) l = 1;
  LNX = nx / l; LNY = ny / l; LNZ = nz / l;
  return -radius;
}

/** BoxCollider.segmentHitsIn in the box's frame: whether segment p–q meets the box (slabs). */
function segmentHits(px: f64, py: f64, pz: f64, qx: f64, qy: f64, qz: f64): bool {
  const dx = px - 0, dy = py - 0, dz = pz - 0;
  const ex = qx - px, ey = qy - py, ez = qz - pz;
  let lo: f64 = 0, hi: f64 = 1;
  for (let i = 0; i < 3; i++) {
    const o = i == 0 ? dx : i == 1 ? dy : dz, v = i == 0 ? ex : i == 1 ? ey : ez, h = i == 0 ? BH0 : i == 1 ? BH1 : BH2;
    if (Math.abs(v) < 1e-300) {
      if (Math.abs(o) > h) return false;
      continue;
    }
    let t0 = (-h - o) / v, t1 = (h - o) / v;
    if (t0 > t1) { const t = t0; t0 = t1; t1 = t; }
    lo = max(lo, t0); hi = min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

/**
 * BoxCollider.triangleDeepest on the corners TA…TC (the box's frame): the vertex certificate; a triangle crossing
 * the box to the golden-section search; else the deepest corner or the triangle's point nearest one of the box's 12
 * edges (each from corner k to corner k | bit, in the reference's order).
 */
function boxDeepest(within: f64): f64 {
  const dv = vertexDeepest(within);
  if (dv == dv) return dv;
  const ax = TAX, ay = TAY, az = TAZ, bx = TBX, by = TBY, bz = TBZ, cx = TCX, cy = TCY, cz = TCZ;
  const k = U0 == 1 ? 0 : U1 == 1 ? 1 : 2;
  const v0 = U0, v1 = U1, v2 = U2;
  const vertex = k == 0 ? boxDistance(ax, ay, az) : k == 1 ? boxDistance(bx, by, bz) : boxDistance(cx, cy, cz);
  const vnx = LNX, vny = LNY, vnz = LNZ;
  if (vertex <= 0 || segmentHits(ax, ay, az, bx, by, bz) || segmentHits(bx, by, bz, cx, cy, cz) || segmentHits(cx, cy, cz, ax, ay, az)) {
    return goldenDeepest();
  }
  let best = vertex, found = false, e0: f64 = 0, e1: f64 = 0, e2: f64 = 0;
  const gx = (ax + bx + cx) / 3, gy = (ay + by + cy) / 3, gz = (az + bz + cz) / 3;
  const ax1 = ax - gx, ay1 = ay - gy, az1 = az - gz, bx1 = bx - gx, by1 = by - gy, bz1 = bz - gz;
  const cx1 = cx - gx, cy1 = cy - gy, cz1 = cz - gz;
  const reach = Math.sqrt(max(max(ax1 * ax1 + ay1 * ay1 + az1 * az1, bx1 * bx1 + by1 * by1 + bz1 * bz1), cx1 * cx1 + cy1 * cy1 + cz1 * cz1));
  for (let c = 0; c < 8; c++) {
    for (let m = 0; m < 3; m++) {
      const bit = 1 << m;
      if ((c & bit) != 0) continue;
      const f = c | bit;
      // the corners (±h along each axis, the box's centre at the origin)
      const E0 = (c & 1) != 0 ? BH0 : -BH0, E1 = (c & 2) != 0 ? BH1 : -BH1, E2 = (c & 4) != 0 ? BH2 : -BH2;
      const E3 = (f & 1) != 0 ? BH0 : -BH0, E4 = (f & 2) != 0 ? BH1 : -BH1, E5 = (f & 4) != 0 ? BH2 : -BH2;
      // an edge farther from the triangle's centre than its reach plus the best so far cannot be nearer
      const ux = E3 - E0, uy = E4 - E1, uz = E5 - E2;
      const uu = ux * ux + uy * uy + uz * uz;
      const t = uu > 0 ? min(max(((gx - E0) * ux + (gy - E1) * uy + (gz - E2) * uz) / uu, 0), 1) : 0;
      const qx = E0 + t * ux - gx, qy = E1 + t * uy - gy, qz = E2 + t * uz - gz;
      if (Math.sqrt(qx * qx + qy * qy + qz * qz) - reach >= best) continue;
      const d2 = segmentTriangle(E0, E1, E2, E3, E4, E5, ax, ay, az, bx, by, bz, cx, cy, cz);
      if (d2 <= 1e-24) return goldenDeepest();
      if (d2 < best * best) {
        best = Math.sqrt(d2); found = true;
        e0 = U0; e1 = U1; e2 = U2;
      }
    }
  }
  if (!found) {
    U0 = v0; U1 = v1; U2 = v2; LNX = vnx; LNY = vny; LNZ = vnz;
    return vertex;
  }
  U0 = e0; U1 = e1; U2 = e2;
  return boxDistance(e0 * ax + e1 * bx + e2 * cx, e0 * ay + e1 * by + e2 * cy, e0 * az + e1 * bz + e2 * cz);
}

/**
 * CylinderCollider.triangleDeepest on the corners TA…TC (the shape's frame): the vertex certificate; else the
 * triangle's point closest to the axis where it lies against the curved side; else the support-point method.
 */
function cylinderDeepest(within: f64): f64 {
  const dv = vertexDeepest(within);
  if (dv == dv) return dv;
  const ax = TAX - 0, ay = TAY - 0, az = TAZ - 0, bx = TBX - 0, by = TBY - 0, bz = TBZ - 0;
  const ex = TCX - 0, ey0 = TCY - 0, ez = TCZ - 0;
  const reach = CH + 1 + max(max(Math.sqrt(ax * ax + ay * ay + az * az), Math.sqrt(bx * bx + by * by + bz * bz)), Math.sqrt(ex * ex + ey0 * ey0 + ez * ez));
  const ux: f64 = 0, uy: f64 = 1, uz: f64 = 0;
  const d2 = segmentTriangle(0 - reach * ux, 0 - reach * uy, 0 - reach * uz, 0 + reach * ux, 0 + reach * uy, 0 + reach * uz,
    TAX, TAY, TAZ, TBX, TBY, TBZ, TCX, TCY, TCZ);
  const qx = U0 * TAX + U1 * TBX + U2 * TCX, qy = U0 * TAY + U1 * TBY + U2 * TCY, qz = U0 * TAZ + U1 * TBZ + U2 * TCZ;
  const y = (qx - 0) * ux + (qy - 0) * uy + (qz - 0) * uz;
  const er = Math.sqrt(d2) - CR, ey = Math.abs(y) - CH;
  if (ey <= 0 && er >= ey) {
    if (d2 > 1e-24) return cylinderDistance(qx, qy, qz);
    return axisCrossing(ux, uy, uz, CR);
  }
  return supportDeepest();
}

/** Squared distance [m²] from (cx, cy, cz) to the particle at byte j of X (phases.ts collideTriangles' corners). */
@inline function cornerDistance2(j: usize, cx: f64, cy: f64, cz: f64): f64 {
  const dx = xAt(j) - cx, dy = xAt(j + 4) - cy, dz = xAt(j + 8) - cz;
  return dx * dx + dy * dy + dz * dz;
}

/** Whether the point (x, y, z) is farther than √ball2 [m] from (o0, o1, o2). */
@inline function outside(x: f64, y: f64, z: f64, o0: f64, o1: f64, o2: f64, ball2: f64): bool {
  const ex = x - o0, ey = y - o1, ez = z - o2;
  return ex * ex + ey * ey + ez * ez > ball2;
}

/** Adds w·(kx, ky, kz) [m] to the f32 point at byte j (the reference's `x[j] += w * k`). */
function nudge(j: usize, w: f64, kx: f64, ky: f64, kz: f64): void {
  store<f32>(j, <f32>(xAt(j) + w * kx));
  store<f32>(j + 4, <f32>(xAt(j + 4) + w * ky));
  store<f32>(j + 8, <f32>(xAt(j + 8) + w * kz));
}

/** Triangle contact with every sphere, capsule and cylinder record that has it (phases.ts collideTriangles, for those shapes). */
export function collideTriangles(): void {
  const th = load<f64>(THICKNESS), reach = load<f64>(TRIANGLE_REACH), recover = load<f64>(TRIANGLE_RECOVER);
  const count = load<i32>(COLLIDERS);
  let boxed = false;
  for (let k = 0; k < count; k++) {
    const rec = COLLIDER_RECORDS + <usize>k * COLLIDER_BYTES;
    if (field(rec, COLLIDER_RECORD_EXACT) == 0) continue;
    // a sphere's radius; a capsule's half length (its axis along y) and radius; a cylinder's radius and half height
    // (PosedCollider.shapeParams)
    const type = <i32>field(rec, COLLIDER_RECORD_TYPE), capsule = type == COLLIDER_CAPSULE, cylinder = type == COLLIDER_CYLINDER;
    const box = type == COLLIDER_BOX;
    const s0 = field(rec, COLLIDER_RECORD_SHAPE), s1 = field(rec, COLLIDER_RECORD_SHAPE, 1), s2 = field(rec, COLLIDER_RECORD_SHAPE, 2);
    // PosedCollider.boundingRadius (a cylinder's: the host's Math.hypot, here its square root of the sum; the ball
    // only culls triangles farther than the reach, so a last bit either way changes nothing), and its box's half
    // extents in its own frame
    const bound = capsule ? s0 + s1 : cylinder ? Math.sqrt(s0 * s0 + s1 * s1) : box ? Math.sqrt(s0 * s0 + s1 * s1 + s2 * s2) : s0;
    const e0 = capsule ? s1 : s0, e1 = capsule ? s0 + s1 : cylinder || box ? s1 : s0, e2 = box ? s2 : e0;
    CR = s0; CH = s1; BH0 = s0; BH1 = s1; BH2 = s2; BOXED = box;
    const o0 = field(rec, COLLIDER_RECORD_O), o1 = field(rec, COLLIDER_RECORD_O, 1), o2 = field(rec, COLLIDER_RECORD_O, 2);
    const ball = (bound + reach) * (1 + 1e-9), ball2 = ball * ball;
    if (!boxed) { clothBox(); boxed = true; }
    const gx = max(max(BX0 - o0, 0), o0 - BX1), gy = max(max(BY0 - o1, 0), o1 - BY1), gz = max(max(BZ0 - o2, 0), o2 - BZ1);
    if (gx * gx + gy * gy + gz * gz > ball2) continue;
    const moving = field(rec, COLLIDER_RECORD_MOVING) != 0;
    const R = COLLIDER_RECORD_R;
    const r0 = field(rec, R), r1 = field(rec, R, 1), r2 = field(rec, R, 2), r3 = field(rec, R, 3), r4 = field(rec, R, 4);
    const r5 = field(rec, R, 5), r6 = field(rec, R, 6), r7 = field(rec, R, 7), r8 = field(rec, R, 8);
    // PosedCollider.worldHalfExtents, widened by the thickness
    const h0 = Math.abs(r0) * e0 + Math.abs(r1) * e1 + Math.abs(r2) * e2;
    const h1 = Math.abs(r3) * e0 + Math.abs(r4) * e1 + Math.abs(r5) * e2;
    const h2 = Math.abs(r6) * e0 + Math.abs(r7) * e1 + Math.abs(r8) * e2;
    const lx = o0 - h0 - th, hx = o0 + h0 + th, ly = o1 - h1 - th, hy = o1 + h1 + th, lz = o2 - h2 - th, hz = o2 + h2 + th;
    const ballFirst = type != COLLIDER_SPHERE;
    for (let t = 0; t < TRIANGLE_COUNT; t++) {
      const tr = TRIANGLES + <usize>t * 12;
      const a = load<u32>(tr), b = load<u32>(tr, 4), c = load<u32>(tr, 8);
      const ja = X + <usize>a * 12, jb = X + <usize>b * 12, jc = X + <usize>c * 12;
      const ax = xAt(ja), ay = xAt(ja + 4), az = xAt(ja + 8);
      // the reference's two culls, the box and the first vertex's ball: both only skip, on the positions now, so
      // either order skips the same triangles; the ball first (it needs one vertex) where the shape is small
      // beside its reach, as a capsule limb is and a sphere is not (there most triangles pass it and the box is
      // the tighter)
      if (ballFirst && outside(ax, ay, az, o0, o1, o2, ball2)) continue;
      const bx = xAt(jb), by = xAt(jb + 4), bz = xAt(jb + 8);
      const cx0 = xAt(jc), cy0 = xAt(jc + 4), cz0 = xAt(jc + 8);
      if (max(max(ax, bx), cx0) < lx || min(min(ax, bx), cx0) > hx ||
        max(max(ay, by), cy0) < ly || min(min(ay, by), cy0) > hy ||
        max(max(az, bz), cz0) < lz || min(min(az, bz), cz0) > hz) continue;
      if (!ballFirst && outside(ax, ay, az, o0, o1, o2, ball2)) continue;
      // the triangle's own ball against the thickness: the posed shape's signedDistance(centroid, within = far)
      const mx0 = (ax + bx + cx0) / 3, my0 = (ay + by + cy0) / 3, mz0 = (az + bz + cz0) / 3;
      const rr = Math.sqrt(max(max(cornerDistance2(ja, mx0, my0, mz0), cornerDistance2(jb, mx0, my0, mz0)), cornerDistance2(jc, mx0, my0, mz0)));
      const far = th + rr * (1 + 1e-9);
      {
        const dx = mx0 - o0, dy = my0 - o1, dz = mz0 - o2;
        const qx = r0 * dx + r3 * dy + r6 * dz, qy = r1 * dx + r4 * dy + r7 * dz, qz = r2 * dx + r5 * dy + r8 * dz;
        if (capsule) {
          if (capsuleDistance(s0, s1, qx, qy, qz, far) >= far) continue;
        } else if (cylinder || box) {
          // (the reference's cylinder and box first return `far` itself where the centroid is farther than their
          // bound and far from the centre; their distance there is at least that too: the same triangles go on)
          if (shapeDistance(qx, qy, qz) >= far) continue;
        } else {
          const d2 = qx * qx + qy * qy + qz * qz;
          const farR = s0 + far;
          if (farR > 0 && d2 >= farR * farR) continue;
          if (Math.sqrt(d2) - s0 >= far) continue;
        }
      }
      // the corners in the shape's frame, in f32 (PosedCollider.triangleDeepest), and the deepest point: for a
      // sphere the one closest to the centre (SphereCollider.triangleDeepest), for a capsule the one closest to its
      // axis (CapsuleCollider.triangleDeepest)
      let dx = ax - o0, dy = ay - o1, dz = az - o2;
      const sax = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), say = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), saz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      dx = bx - o0; dy = by - o1; dz = bz - o2;
      const sbx = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), sby = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), sbz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      dx = cx0 - o0; dy = cy0 - o1; dz = cz0 - o2;
      const scx = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), scy = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), scz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      let d: f64, lnx: f64, lny: f64, lnz: f64;
      if (capsule) {
        d = capsuleDeepest(s0, s1, sax, say, saz, sbx, sby, sbz, scx, scy, scz);
        lnx = LNX; lny = LNY; lnz = LNZ;
      } else if (cylinder || box) {
        TAX = sax; TAY = say; TAZ = saz; TBX = sbx; TBY = sby; TBZ = sbz; TCX = scx; TCY = scy; TCZ = scz;
        d = box ? boxDeepest(th) : cylinderDeepest(th);
        lnx = LNX; lny = LNY; lnz = LNZ;
      } else {
        closestPoint(0, 0, 0, sax, say, saz, sbx, sby, sbz, scx, scy, scz);
        const qx = U0 * sax + U1 * sbx + U2 * scx, qy = U0 * say + U1 * sby + U2 * scy, qz = U0 * saz + U1 * sbz + U2 * scz;
        const qd = Math.sqrt(qx * qx + qy * qy + qz * qz);
        lnx = 0; lny = 1; lnz = 0;
        if (qd > 1e-12) { lnx = qx / qd; lny = qy / qd; lnz = qz / qd; }
        d = qd - s0;
      }
      const u0 = U0, u1 = U1, u2 = U2;
      if (d >= th) continue;
      const nx = r0 * lnx + r1 * lny + r2 * lnz, ny = r3 * lnx + r4 * lny + r5 * lnz, nz = r6 * lnx + r7 * lny + r8 * lnz;
      const wa = <f64>load<f32>(W + (<usize>a << 2)) * u0, wb = <f64>load<f32>(W + (<usize>b << 2)) * u1;
      const wc = <f64>load<f32>(W + (<usize>c << 2)) * u2;
      const denom = wa * u0 + wb * u1 + wc * u2;
      if (!(denom > 0)) continue;
      // no corner moves more than TRIANGLE_SPREAD_MOST × the point's correction (phases.ts)
      const spread = max(max(wa, wb), wc) / denom, scale = spread > TRIANGLE_SPREAD_MOST ? TRIANGLE_SPREAD_MOST / spread : 1;
      const pa = XP + <usize>a * 12, pb = XP + <usize>b * 12, pc = XP + <usize>c * 12;
      let mx = u0 * (ax - xAt(pa)) + u1 * (bx - xAt(pb)) + u2 * (cx0 - xAt(pc));
      let my = u0 * (ay - xAt(pa + 4)) + u1 * (by - xAt(pb + 4)) + u2 * (cy0 - xAt(pc + 4));
      let mz = u0 * (az - xAt(pa + 8)) + u1 * (bz - xAt(pb + 8)) + u2 * (cz0 - xAt(pc + 8));
      if (moving) {
        surfaceMotion(rec, u0 * ax + u1 * bx + u2 * cx0, u0 * ay + u1 * by + u2 * cy0, u0 * az + u1 * bz + u2 * cz0);
        mx -= SMX; my -= SMY; mz -= SMZ;
      }
      const mn = mx * nx + my * ny + mz * nz;
      const movedIn = max(-mn, 0);
      const depth = min(th - d, movedIn + recover);
      const tx = mx - mn * nx, ty = my - mn * ny, tz = mz - mn * nz;
      const fs = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), pressedDepth(th - d, movedIn, recover));
      const made = min(mn + depth, depth);
      const kx = ((depth * nx - fs * tx) / denom) * scale, ky = ((depth * ny - fs * ty) / denom) * scale, kz = ((depth * nz - fs * tz) / denom) * scale;
      nudge(ja, wa, kx, ky, kz); nudge(jb, wb, kx, ky, kz); nudge(jc, wc, kx, ky, kz);
      if (made > 0) {
        const px = ((made * nx) / denom) * scale, py = ((made * ny) / denom) * scale, pz = ((made * nz) / denom) * scale;
        nudge(pa, wa, px, py, pz); nudge(pb, wb, px, py, pz); nudge(pc, wc, px, py, pz);
      }
    }
  }
}
