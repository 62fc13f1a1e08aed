// beginStep (phases.ts refreshInverseMasses): the effective inverse mass of every particle for this frame,
// 0 for pinned particles and the grabbed one. One thread per particle.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  var w = baseInvMass[i];
  if (pinned[i] != 0u || i32(i) == globals.grabbed) { w = 0.0; }
  invMass[i] = w;
}
