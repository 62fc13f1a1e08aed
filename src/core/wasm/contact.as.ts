// Particle contact against the collider records of the control block, four particles at a time in f32x4 lanes.
import { W, X, XP } from './arrays.as';
import {
  COLLIDER_RECORD_FLOATS, COLLIDER_RECORDS, COLLIDER_SPHERE, COLLIDERS, DEPENETRATION, FRICTION, H, STATIC_FRICTION, THICKNESS,
} from './layout.generated.as';
import { dot3, hi2, lanesXY0, lanesXY1, lo2, store4 } from './simd.as';

const COLLIDER_BYTES: usize = <usize>COLLIDER_RECORD_FLOATS * 8;

/** Position-based Coulomb friction scale, as phases.ts frictionScale(). */
@inline function frictionScale(tangential: f64, depth: f64): f64 {
  if (tangential < 1e-12) return 0;
  if (tangential < load<f64>(STATIC_FRICTION) * depth) return 1;
  return min((load<f64>(FRICTION) * depth) / tangential, 1);
}

/** Contact of particle i with one collider record, exactly as phases.ts collide() (f64 on f32 data): the tail. */
@inline function contactParticle(i: i32, sphere: bool, c0: f64, c1: f64, c2: f64, r: f64, far: f64, th: f64, recover: f64): void {
  if (load<f32>(W + (<usize>i << 2)) == 0) return;
  const j = X + <usize>i * 12, jp = XP + <usize>i * 12;
  const px = <f64>load<f32>(j), py = <f64>load<f32>(j, 4), pz = <f64>load<f32>(j, 8);
  let d: f64, nx: f64, ny: f64, nz: f64;
  if (sphere) {
    const dx = px - c0, dy = py - c1, dz = pz - c2;
    const d2 = dx * dx + dy * dy + dz * dz;
    if (far > 0 && d2 >= far * far) return;
    const dd = Math.sqrt(d2);
    if (dd > 1e-12) { nx = dx / dd; ny = dy / dd; nz = dz / dd; } else { nx = 0; ny = 1; nz = 0; }
    d = dd - r;
  } else {
    nx = 0; ny = 1; nz = 0;
    d = py - c0;
  }
  if (d >= th) return;
  const ex = <f64>load<f32>(jp), ey = <f64>load<f32>(jp, 4), ez = <f64>load<f32>(jp, 8);
  const mx = px - ex, my = py - ey, mz = pz - ez;
  const mn = mx * nx + my * ny + mz * nz;
  const depth = min(th - d, max(-mn, 0) + recover);
  const tx = mx - mn * nx, ty = my - mn * ny, tz = mz - mn * nz;
  const s = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), depth);
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
 * Particle contact against the collider records, as phases.ts collide() does for shapes that need no triangle
 * contact: each particle within the thickness is pushed out along the normal, then friction removes (static) or
 * reduces (kinetic) its tangential motion over the substep, and the outward motion the push-out made moves x_prev
 * too (a push-out never launches the cloth). Four particles at a time in f32x4 lanes; the last 1–3
 * particles of the cloth one by one in f64 (contactParticle).
 */
export function collideParticles(p0: i32, p1: i32): void {
  const x = X, xp = XP, w = W;
  const th = load<f64>(THICKNESS);
  const recover = load<f64>(DEPENETRATION) * load<f64>(H);
  const vTh = f32x4.splat(<f32>th), vRecover = f32x4.splat(<f32>recover);
  const vMuS = f32x4.splat(<f32>load<f64>(STATIC_FRICTION)), vMuK = f32x4.splat(<f32>load<f64>(FRICTION));
  const zero = f32x4.splat(0), one = f32x4.splat(1), tiny = f32x4.splat(1e-12);
  const count = load<i32>(COLLIDERS);
  for (let c = 0; c < count; c++) {
    const rec = COLLIDER_RECORDS + <usize>c * COLLIDER_BYTES;
    const sphere = load<f64>(rec) == <f64>COLLIDER_SPHERE;
    const c0 = load<f64>(rec, 8), c1 = load<f64>(rec, 16), c2 = load<f64>(rec, 24), r = load<f64>(rec, 32);
    const far = r + th;
    const vc0 = f32x4.splat(<f32>c0), vc1 = f32x4.splat(<f32>c1), vc2 = f32x4.splat(<f32>c2), vR = f32x4.splat(<f32>r);
    const vFar2 = f32x4.splat(far > 0 ? <f32>(far * far) : Infinity);
    let i = p0;
    for (; i + 4 <= p1; i += 4) {
      const o = <usize>i * 12;
      const q0 = v128.load(x + o), q1 = v128.load(x + o, 12), q2 = v128.load(x + o, 24), q3 = v128.load(x + o, 36);
      const t0 = lo2(q0, q1), t1 = lo2(q2, q3);
      const px = lanesXY0(t0, t1), py = lanesXY1(t0, t1), pz = lanesXY0(hi2(q0, q1), hi2(q2, q3));
      let nx = zero, ny = one, nz = zero, d: v128, touching: v128;
      if (sphere) {
        const dx = f32x4.sub(px, vc0), dy = f32x4.sub(py, vc1), dz = f32x4.sub(pz, vc2);
        const d2 = dot3(dx, dy, dz, dx, dy, dz);
        touching = f32x4.lt(d2, vFar2);
        if (!v128.any_true(touching)) continue;
        const dd = f32x4.sqrt(d2);
        // the outward normal, or up for a particle at the very centre
        const away = f32x4.gt(dd, tiny);
        const inv = f32x4.div(one, f32x4.max(dd, tiny));
        nx = v128.bitselect(f32x4.mul(dx, inv), zero, away);
        ny = v128.bitselect(f32x4.mul(dy, inv), one, away);
        nz = v128.bitselect(f32x4.mul(dz, inv), zero, away);
        d = f32x4.sub(dd, vR);
      } else {
        d = f32x4.sub(py, vc0);
        touching = i32x4.splat(-1);
      }
      touching = v128.and(v128.and(touching, f32x4.lt(d, vTh)), f32x4.ne(v128.load(w + (<usize>i << 2)), zero));
      if (!v128.any_true(touching)) continue;
      // motion over the substep so far, its normal part, and the push-out (contactParticle() in lanes)
      const e0 = v128.load(xp + o), e1 = v128.load(xp + o, 12), e2 = v128.load(xp + o, 24), e3 = v128.load(xp + o, 36);
      const u0 = lo2(e0, e1), u1 = lo2(e2, e3);
      const ex = lanesXY0(u0, u1), ey = lanesXY1(u0, u1), ez = lanesXY0(hi2(e0, e1), hi2(e2, e3));
      const mx = f32x4.sub(px, ex), my = f32x4.sub(py, ey), mz = f32x4.sub(pz, ez);
      const mn = dot3(mx, my, mz, nx, ny, nz);
      const depth = f32x4.min(f32x4.sub(vTh, d), f32x4.add(f32x4.max(f32x4.neg(mn), zero), vRecover));
      const tx = f32x4.sub(mx, f32x4.mul(mn, nx)), ty = f32x4.sub(my, f32x4.mul(mn, ny)), tz = f32x4.sub(mz, f32x4.mul(mn, nz));
      const tl = f32x4.sqrt(dot3(tx, ty, tz, tx, ty, tz));
      // frictionScale(): 0 for no motion, 1 inside the static cone, else min(μk·depth/|t|, 1)
      const kinetic = f32x4.min(f32x4.div(f32x4.mul(vMuK, depth), f32x4.max(tl, tiny)), one);
      const scale = v128.and(v128.bitselect(one, kinetic, f32x4.lt(tl, f32x4.mul(vMuS, depth))), f32x4.ge(tl, tiny));
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
    for (; i < p1; i++) contactParticle(i, sphere, c0, c1, c2, r, far, th, recover);
  }
}
