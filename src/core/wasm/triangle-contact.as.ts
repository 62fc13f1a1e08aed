// Triangle contact (phases.ts collideTriangles) against the sphere records that have it (the record's EXACT): the
// reference's culls, deepest point and push-out, one triangle after another in its order and its arithmetic (f64 on
// the f32 data, the corners turned into the sphere's frame in f32 as a PosedCollider does), so that the cloth is
// the reference's bit for bit. The host asks for the phase only when every shape with triangle contact is a sphere
// (xpbd-wasm.ts triangleRefusal); it runs on one thread, the triangles in order (Gauss–Seidel).
import { N, TRIANGLE_COUNT, TRIANGLES, W, X, XP } from './arrays.as';
import { SMX, SMY, SMZ, field, frictionScale, pressedDepth, surfaceMotion } from './contact.as';
import {
  COLLIDER_RECORD_EXACT, COLLIDER_RECORD_FLOATS, COLLIDER_RECORD_MOVING, COLLIDER_RECORD_O, COLLIDER_RECORD_R,
  COLLIDER_RECORD_SHAPE, COLLIDER_RECORDS, COLLIDERS, THICKNESS, TRIANGLE_REACH, TRIANGLE_RECOVER,
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

/** Squared distance [m²] from (cx, cy, cz) to the particle at byte j of X (phases.ts cornerDistance2). */
@inline function cornerDistance2(j: usize, cx: f64, cy: f64, cz: f64): f64 {
  const dx = xAt(j) - cx, dy = xAt(j + 4) - cy, dz = xAt(j + 8) - cz;
  return dx * dx + dy * dy + dz * dz;
}

/** Adds w·(kx, ky, kz) [m] to the f32 point at byte j (the reference's `x[j] += w * k`). */
function nudge(j: usize, w: f64, kx: f64, ky: f64, kz: f64): void {
  store<f32>(j, <f32>(xAt(j) + w * kx));
  store<f32>(j + 4, <f32>(xAt(j + 4) + w * ky));
  store<f32>(j + 8, <f32>(xAt(j + 8) + w * kz));
}

/** Triangle contact with every sphere record that has it (phases.ts collideTriangles, for spheres). */
export function collideTriangles(): void {
  const th = load<f64>(THICKNESS), reach = load<f64>(TRIANGLE_REACH), recover = load<f64>(TRIANGLE_RECOVER);
  const count = load<i32>(COLLIDERS);
  let boxed = false;
  for (let k = 0; k < count; k++) {
    const rec = COLLIDER_RECORDS + <usize>k * COLLIDER_BYTES;
    if (field(rec, COLLIDER_RECORD_EXACT) == 0) continue;
    const radius = field(rec, COLLIDER_RECORD_SHAPE);
    const o0 = field(rec, COLLIDER_RECORD_O), o1 = field(rec, COLLIDER_RECORD_O, 1), o2 = field(rec, COLLIDER_RECORD_O, 2);
    const ball = (radius + reach) * (1 + 1e-9), ball2 = ball * ball;
    if (!boxed) { clothBox(); boxed = true; }
    const gx = max(max(BX0 - o0, 0), o0 - BX1), gy = max(max(BY0 - o1, 0), o1 - BY1), gz = max(max(BZ0 - o2, 0), o2 - BZ1);
    if (gx * gx + gy * gy + gz * gz > ball2) continue;
    const moving = field(rec, COLLIDER_RECORD_MOVING) != 0;
    const R = COLLIDER_RECORD_R;
    const r0 = field(rec, R), r1 = field(rec, R, 1), r2 = field(rec, R, 2), r3 = field(rec, R, 3), r4 = field(rec, R, 4);
    const r5 = field(rec, R, 5), r6 = field(rec, R, 6), r7 = field(rec, R, 7), r8 = field(rec, R, 8);
    // PosedCollider.worldHalfExtents of the sphere's box (radius on every axis), widened by the thickness
    const h0 = Math.abs(r0) * radius + Math.abs(r1) * radius + Math.abs(r2) * radius;
    const h1 = Math.abs(r3) * radius + Math.abs(r4) * radius + Math.abs(r5) * radius;
    const h2 = Math.abs(r6) * radius + Math.abs(r7) * radius + Math.abs(r8) * radius;
    const lx = o0 - h0 - th, hx = o0 + h0 + th, ly = o1 - h1 - th, hy = o1 + h1 + th, lz = o2 - h2 - th, hz = o2 + h2 + th;
    for (let t = 0; t < TRIANGLE_COUNT; t++) {
      const tr = TRIANGLES + <usize>t * 12;
      const a = load<u32>(tr), b = load<u32>(tr, 4), c = load<u32>(tr, 8);
      const ja = X + <usize>a * 12, jb = X + <usize>b * 12, jc = X + <usize>c * 12;
      const ax = xAt(ja), ay = xAt(ja + 4), az = xAt(ja + 8);
      const bx = xAt(jb), by = xAt(jb + 4), bz = xAt(jb + 8);
      const cx0 = xAt(jc), cy0 = xAt(jc + 4), cz0 = xAt(jc + 8);
      if (max(max(ax, bx), cx0) < lx || min(min(ax, bx), cx0) > hx ||
        max(max(ay, by), cy0) < ly || min(min(ay, by), cy0) > hy ||
        max(max(az, bz), cz0) < lz || min(min(az, bz), cz0) > hz) continue;
      const ex = ax - o0, ey = ay - o1, ez = az - o2;
      if (ex * ex + ey * ey + ez * ez > ball2) continue;
      // the triangle's own ball against the thickness: the posed sphere's signedDistance(centroid, within = far)
      const mx0 = (ax + bx + cx0) / 3, my0 = (ay + by + cy0) / 3, mz0 = (az + bz + cz0) / 3;
      const rr = Math.sqrt(max(max(cornerDistance2(ja, mx0, my0, mz0), cornerDistance2(jb, mx0, my0, mz0)), cornerDistance2(jc, mx0, my0, mz0)));
      const far = th + rr * (1 + 1e-9);
      {
        const dx = mx0 - o0, dy = my0 - o1, dz = mz0 - o2;
        const qx = r0 * dx + r3 * dy + r6 * dz, qy = r1 * dx + r4 * dy + r7 * dz, qz = r2 * dx + r5 * dy + r8 * dz;
        const d2 = qx * qx + qy * qy + qz * qz;
        const farR = radius + far;
        if (farR > 0 && d2 >= farR * farR) continue;
        if (Math.sqrt(d2) - radius >= far) continue;
      }
      // the corners in the sphere's frame, in f32 (PosedCollider.triangleDeepest), and the deepest point: the one
      // closest to the centre (SphereCollider.triangleDeepest)
      let dx = ax - o0, dy = ay - o1, dz = az - o2;
      const sax = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), say = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), saz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      dx = bx - o0; dy = by - o1; dz = bz - o2;
      const sbx = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), sby = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), sbz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      dx = cx0 - o0; dy = cy0 - o1; dz = cz0 - o2;
      const scx = <f64><f32>(r0 * dx + r3 * dy + r6 * dz), scy = <f64><f32>(r1 * dx + r4 * dy + r7 * dz), scz = <f64><f32>(r2 * dx + r5 * dy + r8 * dz);
      closestPoint(0, 0, 0, sax, say, saz, sbx, sby, sbz, scx, scy, scz);
      const u0 = U0, u1 = U1, u2 = U2;
      const qx = u0 * sax + u1 * sbx + u2 * scx, qy = u0 * say + u1 * sby + u2 * scy, qz = u0 * saz + u1 * sbz + u2 * scz;
      const qd = Math.sqrt(qx * qx + qy * qy + qz * qz);
      let lnx: f64 = 0, lny: f64 = 1, lnz: f64 = 0;
      if (qd > 1e-12) { lnx = qx / qd; lny = qy / qd; lnz = qz / qd; }
      const d = qd - radius;
      if (d >= th) continue;
      const nx = r0 * lnx + r1 * lny + r2 * lnz, ny = r3 * lnx + r4 * lny + r5 * lnz, nz = r6 * lnx + r7 * lny + r8 * lnz;
      const wa = <f64>load<f32>(W + (<usize>a << 2)) * u0, wb = <f64>load<f32>(W + (<usize>b << 2)) * u1;
      const wc = <f64>load<f32>(W + (<usize>c << 2)) * u2;
      const denom = wa * u0 + wb * u1 + wc * u2;
      if (!(denom > 0)) continue;
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
      const kx = (depth * nx - fs * tx) / denom, ky = (depth * ny - fs * ty) / denom, kz = (depth * nz - fs * tz) / denom;
      nudge(ja, wa, kx, ky, kz); nudge(jb, wb, kx, ky, kz); nudge(jc, wc, kx, ky, kz);
      if (made > 0) {
        const px = (made * nx) / denom, py = (made * ny) / denom, pz = (made * nz) / denom;
        nudge(pa, wa, px, py, pz); nudge(pb, wb, px, py, pz); nudge(pc, wc, px, py, pz);
      }
    }
  }
}
