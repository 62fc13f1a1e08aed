// The global bending step, 4 of 4, per particle: x ← x + Δx for the free particles (the residuals kept, as the CPU
// keeps them), the grabbed one held where the grab put it (heldCorrection.wgsl).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount || pinned[i] != 0u) { return; }
  positions[i] = vec4f(positions[i].xyz + heldCorrection(i), 0.0);
}
