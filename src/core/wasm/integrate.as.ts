// Integration and the grab: the kernel's phases that move particles by what acts on them (scalar f64 on f32 data,
// exactly as the TypeScript reference computes them).
import { F, W, X, XP } from './arrays.as';
import { GRAB_AT, GRABBED, GRAVITY, H, TAYLOR } from './layout.generated.as';

/** Position Verlet as phases.ts integrate(): x ← 2x − x_prev + c·h²·(g + w·f), x_prev ← x. */
export function integrate(p0: i32, p1: i32, withForces: bool): void {
  const h = load<f64>(H);
  const h2 = load<f64>(TAYLOR) * h * h;
  const gx = load<f64>(GRAVITY) * h2, gy = load<f64>(GRAVITY + 8) * h2, gz = load<f64>(GRAVITY + 16) * h2;
  for (let i = p0; i < p1; i++) {
    const j = <usize>i * 12;
    const x0 = <f64>load<f32>(X + j), y0 = <f64>load<f32>(X + j, 4), z0 = <f64>load<f32>(X + j, 8);
    const wi = <f64>load<f32>(W + (<usize>i << 2));
    if (wi != 0) {
      let ax = gx, ay = gy, az = gz;
      if (withForces) {
        const s = wi * h2;
        ax += <f64>load<f32>(F + j) * s; ay += <f64>load<f32>(F + j, 4) * s; az += <f64>load<f32>(F + j, 8) * s;
      }
      store<f32>(X + j, <f32>(x0 + (x0 - <f64>load<f32>(XP + j)) + ax));
      store<f32>(X + j, <f32>(y0 + (y0 - <f64>load<f32>(XP + j, 4)) + ay), 4);
      store<f32>(X + j, <f32>(z0 + (z0 - <f64>load<f32>(XP + j, 8)) + az), 8);
    }
    store<f32>(XP + j, <f32>x0); store<f32>(XP + j, <f32>y0, 4); store<f32>(XP + j, <f32>z0, 8);
  }
}

/** The grab as phases.ts moveGrabbed(): the grabbed particle put where the host computed it is this substep. */
export function moveGrabbed(): void {
  // after integration (the grabbed particle's x_prev is its position before the grab moves it)
  const gp = X + <usize>load<i32>(GRABBED) * 12;
  store<f32>(gp, <f32>load<f64>(GRAB_AT));
  store<f32>(gp, <f32>load<f64>(GRAB_AT + 8), 4);
  store<f32>(gp, <f32>load<f64>(GRAB_AT + 16), 8);
}
