// carryPinned (phases.ts): each particle a collider carries (pinned: integrate left it where it was and set x_prev
// there) put where its collider's pose at the end of the substep puts it, R·local + o. One thread per carried
// particle.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let k = flatIndex(gid, nwg);
  if (k >= globals.carriedCount) { return; }
  let e = carried[k];
  positions[e.particle] = vec4f(toWorld(colliders[sub.colliderBase + e.collider], e.local), 0.0);
  // nothing finer than float32 (precision.wgsl): the pose is float32 here
  residuals[e.particle] = vec4f(0.0);
}
