// moveGrabbed (phases.ts), every substep while a particle is grabbed, after integrate (which left the grabbed
// particle, of zero inverse mass, where it was and set its x_prev): the particle is carried from its frame-start
// position (grabStart[0], copied at the frame start) the fraction sub.grabFraction of the way to where the grab
// carries it by the frame's end (grabStart[1]: the grab target, or the point sub.grabMaxMove along the way to it,
// kept out of the colliders; grabFrame and grabOutside, at the first substep). One thread.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x != 0u || globals.grabbed < 0) { return; }
  let x0 = grabStart[0].xyz;
  let g = u32(globals.grabbed);
  positions[g] = vec4f(x0 + (grabStart[1].xyz - x0) * sub.grabFraction, 0.0);
  residuals[g] = vec4f(0.0);
}
