// The springs' coarse correction, 2, per aggregate g: its row of the right-hand side, Σ (L − len) over its springs that
// take part [m], and its part of the matrix's diagonal, α̃ = Σ α/h² over them [1/kg]; the right-hand side again in z,
// for coarseSolve to start from (twice where the last factor's step overshoots).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let g = flatIndex(gid, nwg);
  if (g >= arrayLength(&coarseRhs)) { return; }
  let a = coarseAggregates[g];
  var rhs = 0.0;
  var alpha = 0.0;
  for (var p = a.x; p < a.y; p++) {
    let s = coarseMembers[p];
    let d = coarseDir[s];
    if (any(d.xyz != vec3f(0.0))) {
      rhs += d.w;
      alpha += springData[s].y;
    }
  }
  coarseRhs[g] = vec4f(rhs, alpha * sub.invH2, rhs, 0.0);
}
