// The springs' coarse correction (core solvers/coarse-stretch.ts solveCoarseStretch), 1, per spring s: its unit
// direction n = (x_a − x_b)/|x_a − x_b| now and its residual L − |x_a − x_b| [m], or all 0 where it takes no part in the
// correction (no stiffness, both ends fixed, no length), as the CPU's `dir` and right-hand side.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let s = flatIndex(gid, nwg);
  if (s >= arrayLength(&coarseDir)) { return; }
  let data = springData[s];
  let ab = springs[s];
  var out = vec4f(0.0);
  if (data.y >= 0.0 && invMass[ab.x] + invMass[ab.y] != 0.0) {
    let d = positions[ab.x].xyz - positions[ab.y].xyz;
    let len = length(d);
    if (len > 1e-12) { out = vec4f(d / len, data.x - len); }
  }
  coarseDir[s] = out;
}
