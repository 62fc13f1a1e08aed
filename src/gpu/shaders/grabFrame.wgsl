// grabFrameTarget (phases.ts), once per frame while a particle is grabbed, before the first substep's grab: where
// the grab carries its particle by the frame's end, into grabStart[1] — the grab target, or, where that is farther
// from the frame-start position (grabStart[0]) than sub.grabMaxMove (params.grabSpeed × dt; −1: no limit), the
// point that far along the way to it. grabOutside then keeps that point out of the colliders, and every substep's
// grab moves the particle a fraction of the way to it. One thread.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x != 0u || globals.grabbed < 0) { return; }
  let x0 = grabStart[0].xyz;
  let d = globals.grabTarget - x0;
  let len = length(d);
  let s = select(1.0, sub.grabMaxMove / len, sub.grabMaxMove >= 0.0 && len > sub.grabMaxMove);
  grabStart[1] = vec4f(x0 + d * s, 0.0);
}
