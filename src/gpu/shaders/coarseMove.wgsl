// The springs' coarse correction, 10, per free particle i: x_i += w_i·Σ ±λ_s·n_s over its springs (M⁻¹·Jᵀ·λ with
// the directions the step began with; + where i is a spring's first end).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let w = invMass[i];
  if (w == 0.0) { return; }
  var shift = vec3f(0.0);
  for (var p = coarseIncidence[i]; p < coarseIncidence[i + 1u]; p++) {
    let code = coarseIncidence[p];
    let s = code >> 1u;
    let l = select(lambdas[s], -lambdas[s], (code & 1u) != 0u);
    shift += l * coarseDir[s].xyz;
  }
  positions[i] = vec4f(positions[i].xyz + w * shift, 0.0);
}
