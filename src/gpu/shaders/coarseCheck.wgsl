// The springs' coarse correction, 3 (after a solve with the factor of an earlier substep), one workgroup: whether that
// step μ overshoots under the matrix of the springs' directions now (core coarse-stretch.ts overshoots): its Rayleigh
// quotient μᵀ·A·μ / μᵀ·r past COARSE_OVERSHOOT, μᵀ·r being μᵀ·A₀·μ under the factor's matrix and
// μᵀ·A·μ = Σ_g α̃_g·μ_g² + Σ_i w_i·|Σ ±μ_g(s)·n_s|² over the springs at each particle. Sets the indirect dispatches
// of the five kernels that make the matrix anew and solve again (coarseArgs[0 … 14]): their full dispatches
// (coarseArgs[15 … 29]) where it overshoots, else none.

var<workgroup> before: array<f32, FACTOR_WORKGROUP>;
var<workgroup> now: array<f32, FACTOR_WORKGROUP>;

@compute @workgroup_size(FACTOR_WORKGROUP)
fn main(@builtin(local_invocation_index) t: u32) {
  var b = 0.0;
  var a = 0.0;
  for (var g = t; g < arrayLength(&coarseRhs); g += FACTOR_WORKGROUP) {
    let r = coarseRhs[g];
    b += r.x * r.z;
    a += r.y * r.x * r.x;
  }
  for (var i = t; i < globals.particleCount; i += FACTOR_WORKGROUP) {
    let w = invMass[i];
    if (w == 0.0) { continue; }
    var m = vec3f(0.0);
    for (var p = coarseIncidence[i]; p < coarseIncidence[i + 1u]; p++) {
      let code = coarseIncidence[p];
      let s = code >> 1u;
      let l = coarseRhs[coarseSpringAggregate[s]].x;
      m += select(l, -l, (code & 1u) != 0u) * coarseDir[s].xyz;
    }
    a += w * dot(m, m);
  }
  before[t] = b;
  now[t] = a;
  workgroupBarrier();
  for (var stride = FACTOR_WORKGROUP / 2u; stride > 0u; stride /= 2u) {
    if (t < stride) {
      before[t] += before[t + stride];
      now[t] += now[t + stride];
    }
    workgroupBarrier();
  }
  if (t < 15u) {
    let stale = before[0] > 0.0 && now[0] > COARSE_OVERSHOOT * before[0];
    coarseArgs[t] = select(0u, coarseArgs[15u + t], stale);
  }
}
