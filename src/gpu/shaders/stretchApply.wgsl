// The global stretch step, each pass 4 of 4, per particle: x ← y + Δx for the free particles (y: the pass's start,
// stretchStart; the residuals kept, as the CPU keeps them), the grabbed one held where the grab put it
// (heldCorrection.wgsl, on the stretch factor's z).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount || pinned[i] != 0u) { return; }
  positions[i] = vec4f(globalY[i].xyz + heldCorrection(i), 0.0);
}
