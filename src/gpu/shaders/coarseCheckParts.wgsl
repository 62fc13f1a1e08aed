// The springs' coarse correction, 3a (after a solve with the factor of an earlier substep): the terms of whether that
// step μ overshoots under the matrix now (core coarse-stretch.ts overshoots), thread k's into coarsePartials[k]:
// aggregate k's μ_g·r_g (μᵀ·r, the step's size under the factor's matrix) and α̃_g·μ_g², and particle k's
// w_k·|Σ ±μ_g(s)·n_s|² over its springs (together μᵀ·A·μ under the matrix now), k up to the larger count.
// coarseCheck adds them. (One workgroup walking every particle's springs, as the check was first written, leaves
// the rest of a large GPU idle while its threads' loads wait in turn; workgroups reducing their own sums cost
// SwiftShader a barrier a step: its 64² frames were 19 % slower than with these plain terms, which took as long as
// the one workgroup there: `drape run cotton-basic --frames 30 --backend gpu --set cloth.resolution=64 --set
// solver.selfContact=false`, 2026-12-06.)

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let k = flatIndex(gid, nwg);
  if (k >= arrayLength(&coarsePartials)) { return; }
  var part = vec2f(0.0);
  if (k < arrayLength(&coarseRhs)) {
    let r = coarseRhs[k];
    part = vec2f(r.x * r.z, r.y * r.x * r.x);
  }
  if (k < globals.particleCount && invMass[k] != 0.0) {
    var m = vec3f(0.0);
    for (var p = coarseIncidence[k]; p < coarseIncidence[k + 1u]; p++) {
      let code = coarseIncidence[p];
      let s = code >> 1u;
      let l = coarseRhs[coarseSpringAggregate[s]].x;
      m += select(l, -l, (code & 1u) != 0u) * coarseDir[s].xyz;
    }
    part.y += invMass[k] * dot(m, m);
  }
  coarsePartials[k] = part;
}
