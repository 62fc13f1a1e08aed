// The bending phase: XPBD on the linear bending stencils (the hinges of Bergou et al. 2006, the cotangent Laplacian
// of Wardetzky et al. 2007; model.ts BendingStencils), scalar f64 on f32 data in the TypeScript reference's order
// of operations (solvers/xpbd.ts solveBending), so that both give the same cloth bit for bit. Stencils of a colour
// batch share no particle: threads take a batch's stencils in chunks.
import {
  HINGE_OFFSETS, HINGE_VERTICES, HINGE_WEIGHTS, LAPLACIAN_OFFSETS, LAPLACIAN_VERTICES, LAPLACIAN_WEIGHTS, STENCIL_ALPHA,
  STENCIL_LAMBDA, W, X,
} from './arrays.as';

/**
 * Stencils [e0, e1) of model `kind` (0 the hinges, 1 the Laplacian): C = Σ K_k x_k, a 3-vector, with compliance
 * α (STENCIL_ALPHA), α̃ = α/h²:  Δλ = (−C − α̃λ) / (Σ w_k K_k² + α̃),  Δx_k = w_k·K_k·Δλ. λ is read when it
 * accumulates (several passes a substep) and always written.
 */
export function solveStencils(kind: i32, e0: i32, e1: i32, invH2: f64, accumulate: bool): void {
  const offsets = kind == 0 ? HINGE_OFFSETS : LAPLACIAN_OFFSETS;
  const vertices = kind == 0 ? HINGE_VERTICES : LAPLACIAN_VERTICES, weights = kind == 0 ? HINGE_WEIGHTS : LAPLACIAN_WEIGHTS;
  const x = X, w = W, alphaP = STENCIL_ALPHA, lamP = STENCIL_LAMBDA;
  for (let e = e0; e < e1; e++) {
    const alpha = <f64>load<f32>(alphaP + (<usize>e << 2));
    if (alpha == Infinity) continue;
    const from = <usize>load<u32>(offsets + (<usize>e << 2)), to = <usize>load<u32>(offsets + (<usize>(e + 1) << 2));
    let sum = 0.0, cx = 0.0, cy = 0.0, cz = 0.0;
    for (let k = from; k < to; k++) {
      const i = <usize>load<u32>(vertices + (k << 2)), kk = <f64>load<f32>(weights + (k << 2)), at = x + i * 12;
      sum += <f64>load<f32>(w + (i << 2)) * kk * kk;
      cx += kk * <f64>load<f32>(at); cy += kk * <f64>load<f32>(at, 4); cz += kk * <f64>load<f32>(at, 8);
    }
    const alphaT = alpha * invH2;
    const denom = sum + alphaT;
    if (!(denom > 0)) continue;
    const inv = 1 / denom;
    const l = lamP + <usize>e * 12;
    const lx = accumulate ? <f64>load<f32>(l) : 0.0, ly = accumulate ? <f64>load<f32>(l, 4) : 0.0, lz = accumulate ? <f64>load<f32>(l, 8) : 0.0;
    const dx = (-cx - alphaT * lx) * inv, dy = (-cy - alphaT * ly) * inv, dz = (-cz - alphaT * lz) * inv;
    store<f32>(l, <f32>(lx + dx)); store<f32>(l, <f32>(ly + dy), 4); store<f32>(l, <f32>(lz + dz), 8);
    for (let k = from; k < to; k++) {
      const i = <usize>load<u32>(vertices + (k << 2)), s = <f64>load<f32>(w + (i << 2)) * <f64>load<f32>(weights + (k << 2));
      const at = x + i * 12;
      store<f32>(at, <f32>(<f64>load<f32>(at) + s * dx));
      store<f32>(at, <f32>(<f64>load<f32>(at, 4) + s * dy), 4);
      store<f32>(at, <f32>(<f64>load<f32>(at, 8) + s * dz), 8);
    }
  }
}
