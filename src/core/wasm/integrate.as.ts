// Integration and the grab: the kernel's phases that move particles by what acts on them (f64 on f32 data, exactly
// as the TypeScript reference computes them).
import { F, W, X, XP, XPR, XR } from './arrays.as';
import { GRAB_AT, GRABBED, GRAVITY, H, TAYLOR } from './layout.generated.as';

/** One coordinate (byte offset j) of integrate(): X = x + r moves by (X − X_prev) + a when `free`; previous ← X. */
@inline function verlet(j: usize, free: bool, a: f64): void {
  const x0 = load<f32>(X + j), r0 = load<f32>(XR + j);
  if (free) {
    const p = <f64>x0 + <f64>r0;
    const next = p + (p - (<f64>load<f32>(XP + j) + <f64>load<f32>(XPR + j))) + a;
    const q = <f32>next;
    store<f32>(X + j, q);
    store<f32>(XR + j, <f32>(next - <f64>q));
  }
  store<f32>(XP + j, x0);
  store<f32>(XPR + j, r0);
}

/**
 * Two coordinates at once (byte offset j, two f32 each): verlet() in f64x2 lanes, `free` a lane mask. The same
 * IEEE operations lane by lane, so the same bits as verlet().
 */
@inline function verlet2(j: usize, free: v128, a: v128): void {
  const x0 = v128.load64_zero(X + j), r0 = v128.load64_zero(XR + j);
  const p = f64x2.add(f64x2.promote_low_f32x4(x0), f64x2.promote_low_f32x4(r0));
  const prev = f64x2.add(f64x2.promote_low_f32x4(v128.load64_zero(XP + j)), f64x2.promote_low_f32x4(v128.load64_zero(XPR + j)));
  const next = f64x2.add(f64x2.add(p, f64x2.sub(p, prev)), a);
  const q = f32x4.demote_f64x2_zero(next);
  const r = f32x4.demote_f64x2_zero(f64x2.sub(next, f64x2.promote_low_f32x4(q)));
  // the lanes' masks are 64 bits wide; the f32 pairs' low 64 bits are what is stored
  const m = v128.shuffle<i32>(free, free, 0, 2, 0, 2);
  v128.store64_lane(X + j, v128.bitselect(q, x0, m), 0);
  v128.store64_lane(XR + j, v128.bitselect(r, r0, m), 0);
  v128.store64_lane(XP + j, x0, 0);
  v128.store64_lane(XPR + j, r0, 0);
}

/**
 * Position Verlet as phases.ts integrate(): x ← 2x − x_prev + c·h²·(g + w·f), x_prev ← x, on the positions plus
 * their residuals (what float32 drops is kept). Two particles at a time (their six coordinates as three f64x2
 * pairs: (x₀, y₀), (z₀, x₁), (y₁, z₁)), the last one alone.
 */
export function integrate(p0: i32, p1: i32, withForces: bool): void {
  const h = load<f64>(H);
  const h2 = load<f64>(TAYLOR) * h * h;
  const gx = load<f64>(GRAVITY) * h2, gy = load<f64>(GRAVITY + 8) * h2, gz = load<f64>(GRAVITY + 16) * h2;
  const gxy = f64x2(gx, gy), gzx = f64x2(gz, gx), gyz = f64x2(gy, gz), zero = f64x2.splat(0);
  let i = p0;
  for (; i + 2 <= p1; i += 2) {
    const j = <usize>i * 12;
    const w0 = <f64>load<f32>(W + (<usize>i << 2)), w1 = <f64>load<f32>(W + (<usize>i << 2), 4);
    const free0 = f64x2.ne(f64x2.splat(w0), zero), free1 = f64x2.ne(f64x2.splat(w1), zero);
    const free01 = f64x2.ne(f64x2(w0, w1), zero);
    let a0 = gxy, a1 = gzx, a2 = gyz;
    if (withForces) {
      // a fixed particle's sum is never used (verlet2 keeps it where it is), so its w·h² of 0 needs no branch
      const s0 = f64x2.splat(w0 * h2), s1 = f64x2.splat(w1 * h2), s01 = f64x2(w0 * h2, w1 * h2);
      a0 = f64x2.add(a0, f64x2.mul(f64x2.promote_low_f32x4(v128.load64_zero(F + j)), s0));
      a1 = f64x2.add(a1, f64x2.mul(f64x2.promote_low_f32x4(v128.load64_zero(F + j + 8)), s01));
      a2 = f64x2.add(a2, f64x2.mul(f64x2.promote_low_f32x4(v128.load64_zero(F + j + 16)), s1));
    }
    verlet2(j, free0, a0);
    verlet2(j + 8, free01, a1);
    verlet2(j + 16, free1, a2);
  }
  for (; i < p1; i++) {
    const j = <usize>i * 12;
    const wi = <f64>load<f32>(W + (<usize>i << 2));
    let ax = gx, ay = gy, az = gz;
    if (withForces && wi != 0) {
      const s = wi * h2;
      ax += <f64>load<f32>(F + j) * s; ay += <f64>load<f32>(F + j, 4) * s; az += <f64>load<f32>(F + j, 8) * s;
    }
    verlet(j, wi != 0, ax);
    verlet(j + 4, wi != 0, ay);
    verlet(j + 8, wi != 0, az);
  }
}

/** The grab as phases.ts moveGrabbed(): the grabbed particle put where the host computed it is this substep. */
export function moveGrabbed(): void {
  // after integration (the grabbed particle's x_prev is its position before the grab moves it)
  const at = <usize>load<i32>(GRABBED) * 12;
  for (let k: usize = 0; k < 12; k += 4) {
    const p = load<f64>(GRAB_AT + 2 * k);
    const q = <f32>p;
    store<f32>(X + at + k, q);
    store<f32>(XR + at + k, <f32>(p - <f64>q));
  }
}
