// keepGrabOutside (phases.ts) on the frame's own grab target (grabStart[1], from grabFrame), for colliders
// [batch.start, batch.end) in order, each where it is at the frame's end (dispatched with the last substep's
// record: sub.colliderBase): a point nearer a collider's surface than the contact thickness is moved out along the
// surface normal to that distance. The encoder dispatches it over every run of colliders twice (the CPU's two rounds:
// a point in a corner between two colliders settles). Why: the grabbed particle is kinematic, so contact never
// moves it; carried in a straight line through a collider (a fast drag capped at params.grabSpeed reaches its
// target over several frames, and the frames' points between lie on that line), it drags its neighbours inside,
// and contact then pushes those out by centimetres a substep, through the layer of cloth folded over them, after
// self-contact has run. The target itself is kept out on the CPU (GpuClothSolver.step). One thread. Two kernels:
// grabOutside over the analytic shapes (shapes.wgsl), grabOutsideMesh over mesh colliders (meshCollider.wgsl).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x != 0u || globals.grabbed < 0) { return; }
  var t = grabStart[1].xyz;
  let th = globals.thickness;
  for (var k = batch.start; k < batch.end; k++) {
    var n: vec3f;
    let d = colliderDistance(colliders[sub.colliderBase + k], t, th, &n);
    if (!(d < th)) { continue; }
    t += (th - d) * n;
  }
  grabStart[1] = vec4f(t, 0.0);
}
