// Integration and the grab: the kernel's phases that move particles by what acts on them (scalar f64 on f32 data,
// exactly as the TypeScript reference computes them).
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
 * Position Verlet as phases.ts integrate(): x ← 2x − x_prev + c·h²·(g + w·f), x_prev ← x, on the positions plus
 * their residuals (what float32 drops is kept).
 */
export function integrate(p0: i32, p1: i32, withForces: bool): void {
  const h = load<f64>(H);
  const h2 = load<f64>(TAYLOR) * h * h;
  const gx = load<f64>(GRAVITY) * h2, gy = load<f64>(GRAVITY + 8) * h2, gz = load<f64>(GRAVITY + 16) * h2;
  for (let i = p0; i < p1; i++) {
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
