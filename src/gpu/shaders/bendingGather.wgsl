// The global bending step, 2 of 4, per particle i: its row of the right-hand side, b_i = −Σ K_k·d_e over its stencil
// entries k (of stencils e; bendingForces), into globalX at the particle's row of the factor. A pinned particle's row
// is the identity and its correction 0.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let row = factorIndex[factorIndex[FACTOR_ROW_OF] + i];
  var b = vec3f(0.0);
  if (pinned[i] == 0u) {
    let hi = stencilIncidence[i + 1u];
    for (var q = stencilIncidence[i]; q < hi; q += 2u) {
      b -= stencilWeights[stencilIncidence[q]] * stencilForce[stencilIncidence[q + 1u]].xyz;
    }
  }
  globalX[row] = vec4f(b, 0.0);
}
