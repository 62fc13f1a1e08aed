// The springs' coarse correction, 9, per spring s: its multiplier λ_s = Σ_k φ_k·μ_k, bilinear between the four
// aggregates of its kind and direction around it (0 where it takes no part), from which the sweep goes on.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let s = flatIndex(gid, nwg);
  if (s >= arrayLength(&coarseNear)) { return; }
  if (all(coarseDir[s].xyz == vec3f(0.0))) {
    lambdas[s] = 0.0;
    return;
  }
  let near = coarseNear[s];
  let w = coarseWeights[s];
  lambdas[s] = w.x * coarseRhs[near.x].x + w.y * coarseRhs[near.y].x + w.z * coarseRhs[near.z].x + w.w * coarseRhs[near.w].x;
}
