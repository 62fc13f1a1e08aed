// The global stretch step (core solvers/global-stretch.ts solveGlobalStretch), its start, per particle: y ← x, the
// predicted positions every pass of the substep starts from (what integrate, carry and grab left).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  globalY[i] = positions[i];
}
