// moveGrabbed (phases.ts), every substep while a particle is grabbed, after integrate (which left the grabbed
// particle, of zero inverse mass, where it was and set its x_prev): the particle is carried from its frame-start
// position (grabStart, copied at the frame start) the fraction sub.grabFraction of the way to the grab target, or,
// where that is farther than sub.grabMaxMove, of the way to the point that far along (grabFrameTarget). One thread.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x != 0u || globals.grabbed < 0) { return; }
  let x0 = grabStart[0].xyz;
  let g = u32(globals.grabbed);
  let d = globals.grabTarget - x0;
  let len = length(d);
  let s = select(1.0, sub.grabMaxMove / len, sub.grabMaxMove >= 0.0 && len > sub.grabMaxMove);
  positions[g] = vec4f(x0 + d * (s * sub.grabFraction), 0.0);
  residuals[g] = vec4f(0.0);
}
