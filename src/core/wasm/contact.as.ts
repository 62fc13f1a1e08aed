// Particle contact against the collider records of the control block, four particles at a time in f32x4 lanes.
import { W, X, XP } from './arrays.as';
import {
  COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_PLANE, COLLIDER_RECORD_EXACT, COLLIDER_RECORD_FLOATS, COLLIDER_RECORD_MOVING, COLLIDER_RECORD_O,
  COLLIDER_RECORD_OD, COLLIDER_RECORD_R, COLLIDER_RECORD_RD, COLLIDER_RECORD_SHAPE, COLLIDER_RECORD_TYPE, COLLIDER_RECORDS,
  COLLIDER_SPHERE, COLLIDERS, DEPENETRATION, FRICTION, H, STATIC_FRICTION, THICKNESS,
} from './layout.generated.as';
import { dot3, hi2, lanesXY0, lanesXY1, lo2, store4 } from './simd.as';

const COLLIDER_BYTES: usize = <usize>COLLIDER_RECORD_FLOATS * 8;

/** Field k of a collider record at `rec` (COLLIDER_RECORD in gen-layout.mjs: offsets in f64s). */
@inline export function field(rec: usize, at: i32, k: i32 = 0): f64 {
  return load<f64>(rec + (<usize>(at + k) << 3));
}

/**
 * Radius about its frame's origin that holds the shape's whole surface [m] (the contact's early out), or −1 for a
 * half-space (floor, plane), which has none.
 */
function boundingRadius(type: i32, s0: f64, s1: f64, s2: f64): f64 {
  if (type == COLLIDER_SPHERE) return s0;
  if (type == COLLIDER_BOX) return Math.sqrt(s0 * s0 + s1 * s1 + s2 * s2);
  if (type == COLLIDER_CAPSULE) return s0 + s1;
  if (type == COLLIDER_CYLINDER) return Math.sqrt(s0 * s0 + s1 * s1);
  return -1;
}

/** Position-based Coulomb friction scale, as phases.ts frictionScale(). */
@inline export function frictionScale(tangential: f64, depth: f64): f64 {
  if (tangential < 1e-12) return 0;
  if (tangential < load<f64>(STATIC_FRICTION) * depth) return 1;
  return min((load<f64>(FRICTION) * depth) / tangential, 1);
}

/** The push-out depth that bounds friction, as phases.ts frictionScale() computes it (its pressed depth). */
@inline export function pressedDepth(overlap: f64, movedIn: f64, recover: f64): f64 {
  const over = overlap - movedIn;
  return over <= 0 ? overlap : movedIn + max(0, min(over, 2 * recover - over));
}

// how far the surface point at p moved over the substep, p − (RD·p + OD), of the last surfaceMotion()
export let SMX: f64 = 0, SMY: f64 = 0, SMZ: f64 = 0;

/** The surface motion of the moving collider record `rec` at world point p [m] (PosedCollider.surfaceMotion), to SMX…SMZ. */
@inline export function surfaceMotion(rec: usize, px: f64, py: f64, pz: f64): void {
  const D = COLLIDER_RECORD_RD;
  SMX = px - (field(rec, D) * px + field(rec, D, 1) * py + field(rec, D, 2) * pz + field(rec, COLLIDER_RECORD_OD));
  SMY = py - (field(rec, D, 3) * px + field(rec, D, 4) * py + field(rec, D, 5) * pz + field(rec, COLLIDER_RECORD_OD, 1));
  SMZ = pz - (field(rec, D, 6) * px + field(rec, D, 7) * py + field(rec, D, 8) * pz + field(rec, COLLIDER_RECORD_OD, 2));
}

// the outward normal in the shape's own frame of the last localDistance()
export let LX: f64 = 0, LY: f64 = 0, LZ: f64 = 0;

/**
 * Signed distance of point q (in the shape's own frame) from the shape (colliders/*.ts, built at the origin), its
 * outward normal in that frame to LX, LY, LZ: f64, as the TypeScript shapes compute it.
 */
export function localDistance(type: i32, s0: f64, s1: f64, s2: f64, qx: f64, qy: f64, qz: f64): f64 {
  if (type == COLLIDER_SPHERE) {
    const dd = Math.sqrt(qx * qx + qy * qy + qz * qz);
    if (dd > 1e-12) { LX = qx / dd; LY = qy / dd; LZ = qz / dd; } else { LX = 0; LY = 1; LZ = 0; }
    return dd - s0;
  }
  if (type == COLLIDER_BOX) {
    const ex = Math.abs(qx) - s0, ey = Math.abs(qy) - s1, ez = Math.abs(qz) - s2;
    if (ex > 0 || ey > 0 || ez > 0) {
      const ox = max(ex, 0), oy = max(ey, 0), oz = max(ez, 0);
      const d = Math.sqrt(ox * ox + oy * oy + oz * oz);
      LX = (Math.sign(qx) * ox) / d; LY = (Math.sign(qy) * oy) / d; LZ = (Math.sign(qz) * oz) / d;
      return d;
    }
    LX = 0; LY = 0; LZ = 0;
    if (ex >= ey && ex >= ez) { LX = qx < 0 ? -1 : 1; return ex; }
    if (ey >= ez) { LY = qy < 0 ? -1 : 1; return ey; }
    LZ = qz < 0 ? -1 : 1;
    return ez;
  }
  if (type == COLLIDER_CAPSULE) {
    const vy = qy - min(max(qy, -s0), s0);
    const dd = Math.sqrt(qx * qx + vy * vy + qz * qz);
    if (dd > 1e-12) { LX = qx / dd; LY = vy / dd; LZ = qz / dd; } else if (s0 > 0) { LX = 0; LY = 0; LZ = -1; } else { LX = 0; LY = 1; LZ = 0; }
    return dd - s1;
  }
  if (type == COLLIDER_CYLINDER) {
    const rho = Math.sqrt(qx * qx + qz * qz);
    let hx: f64 = 0, hz: f64 = -1;
    if (rho > 1e-12) { hx = qx / rho; hz = qz / rho; }
    const sy: f64 = qy < 0 ? -1 : 1;
    const er = rho - s0, ey = Math.abs(qy) - s1;
    if (er > 0 || ey > 0) {
      const or = max(er, 0), oy = max(ey, 0);
      const d = Math.sqrt(or * or + oy * oy);
      LX = (or * hx) / d; LY = (oy * sy) / d; LZ = (or * hz) / d;
      return d;
    }
    if (er >= ey) { LX = hx; LY = 0; LZ = hz; return er; }
    LX = 0; LY = sy; LZ = 0;
    return ey;
  }
  // floor, plane: the half-space y < 0
  LX = 0; LY = 1; LZ = 0;
  return qy;
}

/** Contact of particle i with the collider record at `rec`, exactly as phases.ts collideParticles() (f64 on f32 data): the tail. */
function contactParticle(i: i32, rec: usize, far: f64, th: f64, recover: f64): void {
  if (load<f32>(W + (<usize>i << 2)) == 0) return;
  const j = X + <usize>i * 12, jp = XP + <usize>i * 12;
  const px = <f64>load<f32>(j), py = <f64>load<f32>(j, 4), pz = <f64>load<f32>(j, 8);
  const R = COLLIDER_RECORD_R;
  const dx = px - field(rec, COLLIDER_RECORD_O), dy = py - field(rec, COLLIDER_RECORD_O, 1), dz = pz - field(rec, COLLIDER_RECORD_O, 2);
  if (far > 0 && dx * dx + dy * dy + dz * dz >= far * far) return;
  const d = localDistance(<i32>field(rec, COLLIDER_RECORD_TYPE),
    field(rec, COLLIDER_RECORD_SHAPE), field(rec, COLLIDER_RECORD_SHAPE, 1), field(rec, COLLIDER_RECORD_SHAPE, 2),
    field(rec, R) * dx + field(rec, R, 3) * dy + field(rec, R, 6) * dz,
    field(rec, R, 1) * dx + field(rec, R, 4) * dy + field(rec, R, 7) * dz,
    field(rec, R, 2) * dx + field(rec, R, 5) * dy + field(rec, R, 8) * dz);
  if (d >= th) return;
  const nx = field(rec, R) * LX + field(rec, R, 1) * LY + field(rec, R, 2) * LZ;
  const ny = field(rec, R, 3) * LX + field(rec, R, 4) * LY + field(rec, R, 5) * LZ;
  const nz = field(rec, R, 6) * LX + field(rec, R, 7) * LY + field(rec, R, 8) * LZ;
  const ex = <f64>load<f32>(jp), ey = <f64>load<f32>(jp, 4), ez = <f64>load<f32>(jp, 8);
  // motion over the substep so far relative to the surface: less the surface point's own (p − (RD·p + OD))
  let mx = px - ex, my = py - ey, mz = pz - ez;
  if (field(rec, COLLIDER_RECORD_MOVING) != 0) {
    surfaceMotion(rec, px, py, pz);
    mx -= SMX; my -= SMY; mz -= SMZ;
  }
  const mn = mx * nx + my * ny + mz * nz;
  const movedIn = max(-mn, 0);
  const depth = min(th - d, movedIn + recover);
  const tx = mx - mn * nx, ty = my - mn * ny, tz = mz - mn * nz;
  const s = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), pressedDepth(th - d, movedIn, recover));
  store<f32>(j, <f32>(px + (depth * nx - s * tx)));
  store<f32>(j, <f32>(py + (depth * ny - s * ty)), 4);
  store<f32>(j, <f32>(pz + (depth * nz - s * tz)), 8);
  // the outward normal motion the push-out made is not velocity
  const made = min(mn + depth, depth);
  if (made > 0) {
    store<f32>(jp, <f32>(ex + made * nx)); store<f32>(jp, <f32>(ey + made * ny), 4); store<f32>(jp, <f32>(ez + made * nz), 8);
  }
}

/**
 * Particle contact against the collider records, as phases.ts collideParticles() does: each particle within the
 * thickness of a shape (sphere, floor, plane, box, capsule, cylinder: in the shape's own frame through the record's
 * transform, R and O) is pushed out along the normal, then friction removes (static) or reduces (kinetic) its
 * tangential motion over the substep relative to the surface (less the surface point's own motion, p − (RD·p + OD),
 * for a moving collider), and the outward motion the push-out made moves x_prev too (a push-out never launches the
 * cloth). Floors, planes and spheres four particles at a time in f32x4 lanes; the last 1–3 particles of the cloth,
 * every particle of another shape and of a collider that also has triangle contact (the record's EXACT), one by
 * one in f64 (contactParticle).
 */
export function collideParticles(p0: i32, p1: i32): void {
  const x = X, xp = XP, w = W;
  const th = load<f64>(THICKNESS);
  const recover = load<f64>(DEPENETRATION) * load<f64>(H);
  const vTh = f32x4.splat(<f32>th), vRecover = f32x4.splat(<f32>recover);
  const vMuS = f32x4.splat(<f32>load<f64>(STATIC_FRICTION)), vMuK = f32x4.splat(<f32>load<f64>(FRICTION));
  const zero = f32x4.splat(0), one = f32x4.splat(1), tiny = f32x4.splat(1e-12), all = i32x4.splat(-1);
  const count = load<i32>(COLLIDERS);
  for (let c = 0; c < count; c++) {
    const rec = COLLIDER_RECORDS + <usize>c * COLLIDER_BYTES;
    const type = <i32>field(rec, COLLIDER_RECORD_TYPE);
    const moving = field(rec, COLLIDER_RECORD_MOVING) != 0;
    // lanes have the half-spaces (floor, plane) and the sphere; every other shape, and a shape that also has
    // triangle contact (f32 lanes under a triangle pass let a cloth resting on a sphere creep off it: measured,
    // docs/physics.md), goes one particle at a time in f64 (localDistance)
    const lanes = field(rec, COLLIDER_RECORD_EXACT) == 0 &&
      (type == COLLIDER_SPHERE || type == COLLIDER_FLOOR || type == COLLIDER_PLANE);
    const s0 = field(rec, COLLIDER_RECORD_SHAPE), s1 = field(rec, COLLIDER_RECORD_SHAPE, 1), s2 = field(rec, COLLIDER_RECORD_SHAPE, 2);
    const bound = boundingRadius(type, s0, s1, s2);
    const far = bound < 0 ? -1 : bound + th;
    const vFar2 = f32x4.splat(far > 0 ? <f32>(far * far) : Infinity);
    const vs0 = f32x4.splat(<f32>s0);
    const R = COLLIDER_RECORD_R, D = COLLIDER_RECORD_RD;
    const r0 = f32x4.splat(<f32>field(rec, R)), r1 = f32x4.splat(<f32>field(rec, R, 1)), r2 = f32x4.splat(<f32>field(rec, R, 2));
    const r3 = f32x4.splat(<f32>field(rec, R, 3)), r4 = f32x4.splat(<f32>field(rec, R, 4)), r5 = f32x4.splat(<f32>field(rec, R, 5));
    const r6 = f32x4.splat(<f32>field(rec, R, 6)), r7 = f32x4.splat(<f32>field(rec, R, 7)), r8 = f32x4.splat(<f32>field(rec, R, 8));
    const o0 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_O)), o1 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_O, 1));
    const o2 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_O, 2));
    const d0 = f32x4.splat(<f32>field(rec, D)), d1 = f32x4.splat(<f32>field(rec, D, 1)), d2 = f32x4.splat(<f32>field(rec, D, 2));
    const d3 = f32x4.splat(<f32>field(rec, D, 3)), d4 = f32x4.splat(<f32>field(rec, D, 4)), d5 = f32x4.splat(<f32>field(rec, D, 5));
    const d6 = f32x4.splat(<f32>field(rec, D, 6)), d7 = f32x4.splat(<f32>field(rec, D, 7)), d8 = f32x4.splat(<f32>field(rec, D, 8));
    const e0 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_OD)), e1 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_OD, 1));
    const e2 = f32x4.splat(<f32>field(rec, COLLIDER_RECORD_OD, 2));
    let i = p0;
    for (; lanes && i + 4 <= p1; i += 4) {
      const o = <usize>i * 12;
      const q0 = v128.load(x + o), q1 = v128.load(x + o, 12), q2 = v128.load(x + o, 24), q3 = v128.load(x + o, 36);
      const t0 = lo2(q0, q1), t1 = lo2(q2, q3);
      const px = lanesXY0(t0, t1), py = lanesXY1(t0, t1), pz = lanesXY0(hi2(q0, q1), hi2(q2, q3));
      const dx = f32x4.sub(px, o0), dy = f32x4.sub(py, o1), dz = f32x4.sub(pz, o2);
      let touching = all;
      if (far > 0) {
        touching = f32x4.lt(dot3(dx, dy, dz, dx, dy, dz), vFar2);
        if (!v128.any_true(touching)) continue;
      }
      // the particles in the shape's own frame: Rᵀ·(p − o)
      const qx = dot3(r0, r3, r6, dx, dy, dz), qy = dot3(r1, r4, r7, dx, dy, dz), qz = dot3(r2, r5, r8, dx, dy, dz);
      // signed distance and outward normal in that frame (localDistance() in lanes): floor and plane (y < 0), sphere
      let lx = zero, ly = one, lz = zero, d = qy;
      if (type == COLLIDER_SPHERE) {
        const dd = f32x4.sqrt(dot3(qx, qy, qz, qx, qy, qz));
        const away = f32x4.gt(dd, tiny);
        const inv = f32x4.div(one, f32x4.max(dd, tiny));
        lx = v128.bitselect(f32x4.mul(qx, inv), zero, away);
        ly = v128.bitselect(f32x4.mul(qy, inv), one, away);
        lz = v128.bitselect(f32x4.mul(qz, inv), zero, away);
        d = f32x4.sub(dd, vs0);
      }
      touching = v128.and(v128.and(touching, f32x4.lt(d, vTh)), f32x4.ne(v128.load(w + (<usize>i << 2)), zero));
      if (!v128.any_true(touching)) continue;
      // the normal in the world: R·l
      const nx = dot3(r0, r1, r2, lx, ly, lz), ny = dot3(r3, r4, r5, lx, ly, lz), nz = dot3(r6, r7, r8, lx, ly, lz);
      // motion over the substep so far relative to the surface, its normal part, and the push-out (contactParticle() in lanes)
      const f0 = v128.load(xp + o), f1 = v128.load(xp + o, 12), f2 = v128.load(xp + o, 24), f3 = v128.load(xp + o, 36);
      const u0 = lo2(f0, f1), u1 = lo2(f2, f3);
      const ex = lanesXY0(u0, u1), ey = lanesXY1(u0, u1), ez = lanesXY0(hi2(f0, f1), hi2(f2, f3));
      let mx = f32x4.sub(px, ex), my = f32x4.sub(py, ey), mz = f32x4.sub(pz, ez);
      if (moving) {
        // p − x_prev − (p − (RD·p + OD)) = RD·p + OD − x_prev
        mx = f32x4.sub(f32x4.add(dot3(d0, d1, d2, px, py, pz), e0), ex);
        my = f32x4.sub(f32x4.add(dot3(d3, d4, d5, px, py, pz), e1), ey);
        mz = f32x4.sub(f32x4.add(dot3(d6, d7, d8, px, py, pz), e2), ez);
      }
      const mn = dot3(mx, my, mz, nx, ny, nz);
      const movedIn = f32x4.max(f32x4.neg(mn), zero);
      // pressedDepth() in lanes
      const overlap = f32x4.sub(vTh, d), over = f32x4.sub(overlap, movedIn);
      const depth = f32x4.min(overlap, f32x4.add(movedIn, vRecover));
      const pressed = v128.bitselect(overlap,
        f32x4.add(movedIn, f32x4.max(zero, f32x4.min(over, f32x4.sub(f32x4.add(vRecover, vRecover), over)))), f32x4.le(over, zero));
      const tx = f32x4.sub(mx, f32x4.mul(mn, nx)), ty = f32x4.sub(my, f32x4.mul(mn, ny)), tz = f32x4.sub(mz, f32x4.mul(mn, nz));
      const tl = f32x4.sqrt(dot3(tx, ty, tz, tx, ty, tz));
      // frictionScale() of the pressed depth: 0 for no motion, 1 inside the static cone, else min(μk·pressed/|t|, 1)
      const kinetic = f32x4.min(f32x4.div(f32x4.mul(vMuK, pressed), f32x4.max(tl, tiny)), one);
      const scale = v128.and(v128.bitselect(one, kinetic, f32x4.lt(tl, f32x4.mul(vMuS, pressed))), f32x4.ge(tl, tiny));
      store4(x, o, o + 12, o + 24, o + 36,
        v128.bitselect(f32x4.add(px, f32x4.sub(f32x4.mul(depth, nx), f32x4.mul(scale, tx))), px, touching),
        v128.bitselect(f32x4.add(py, f32x4.sub(f32x4.mul(depth, ny), f32x4.mul(scale, ty))), py, touching),
        v128.bitselect(f32x4.add(pz, f32x4.sub(f32x4.mul(depth, nz), f32x4.mul(scale, tz))), pz, touching));
      // the outward normal motion the push-out made (mn + depth, at most depth) moves x_prev too: not velocity
      const made = f32x4.min(f32x4.add(mn, depth), depth);
      const launched = v128.and(touching, f32x4.gt(made, zero));
      if (v128.any_true(launched)) {
        store4(xp, o, o + 12, o + 24, o + 36,
          v128.bitselect(f32x4.add(ex, f32x4.mul(made, nx)), ex, launched),
          v128.bitselect(f32x4.add(ey, f32x4.mul(made, ny)), ey, launched),
          v128.bitselect(f32x4.add(ez, f32x4.mul(made, nz)), ez, launched));
      }
    }
    // the last 1–3 particles, or every particle of an exact record
    for (; i < p1; i++) contactParticle(i, rec, far, th, recover);
  }
}
