// The springs' coarse correction, 3b (after coarseCheckParts), one workgroup: whether the step μ of a solve with the
// factor of an earlier substep overshoots under the matrix of the springs' directions now (core coarse-stretch.ts
// overshoots): its Rayleigh quotient μᵀ·A·μ / μᵀ·r past COARSE_OVERSHOOT, μᵀ·r being μᵀ·A₀·μ under the factor's
// matrix, both summed from coarseCheckParts' terms (coarsePartials). Sets the indirect dispatches of the five
// kernels that make the matrix anew and solve again (coarseArgs[0 … 14]): their full dispatches (coarseArgs[15 … 29])
// where it overshoots, else none; the two totals into coarseArgs[30], [31] (their bits), which the tests read.

var<workgroup> before: array<f32, FACTOR_WORKGROUP>;
var<workgroup> now: array<f32, FACTOR_WORKGROUP>;

@compute @workgroup_size(FACTOR_WORKGROUP)
fn main(@builtin(local_invocation_index) t: u32) {
  var part = vec2f(0.0);
  for (var g = t; g < arrayLength(&coarsePartials); g += FACTOR_WORKGROUP) { part += coarsePartials[g]; }
  before[t] = part.x;
  now[t] = part.y;
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
  if (t == 0u) {
    coarseArgs[30] = bitcast<u32>(before[0]);
    coarseArgs[31] = bitcast<u32>(now[0]);
  }
}
