// The springs' coarse correction, 4 (in a frame's first substep, or where coarseCheck found the last factor stale:
// an indirect dispatch of coarseArgs), per (particle i, aggregate g) pair: v = Σ ±n_s over
// i's springs in g (+ where i is a spring's first end), and i's inverse mass, from which coarseAssemble adds
// w_i·v_g·v_h to entry (g, h) of J·M⁻¹·Jᵀ aggregated.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let p = flatIndex(gid, nwg);
  if (p >= arrayLength(&coarsePairVec)) { return; }
  let pair = coarsePairs[p];
  var v = vec3f(0.0);
  for (var k = pair.z; k < pair.w; k++) {
    let code = coarseIncidence[k];
    let n = coarseDir[code >> 1u].xyz;
    v += select(n, -n, (code & 1u) != 0u);
  }
  coarsePairVec[p] = vec4f(v, invMass[pair.x]);
}
