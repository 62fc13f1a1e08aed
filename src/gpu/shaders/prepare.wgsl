// beginStep (phases.ts), once per frame: the effective inverse mass of every particle for this frame (0 for
// pinned particles and the grabbed one), and previous positions x − h·v, so that the substeps run position
// Verlet from the stored velocities whatever the last frame's substep length was (residuals included). One thread per particle;
// bound with the first substep's record (sub.h).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  var w = baseInvMass[i];
  if (pinned[i] != 0u || i32(i) == globals.grabbed) { w = 0.0; }
  invMass[i] = w;
  // x + r − h·v to float32 and its residual (precision.wgsl)
  var e: vec3f;
  let p = twoSum(positions[i].xyz, residuals[i].xyz - sub.h * velocities[i].xyz, &e);
  previous[i] = vec4f(p, 0.0);
  previousResiduals[i] = vec4f(e, 0.0);
}
