// collide (phases.ts), particle part, for colliders [batch.start, batch.end) in order, each where it is at the end
// of this substep (its record at sub.colliderBase): a particle closer than the contact thickness is pushed out along
// the surface normal (at once for what it moved into the surface in this substep, at most sub.recover for an
// overlap it did not move into), position-based friction removes (part of) its tangential motion over the substep,
// and the outward motion the push-out made moves x_prev too (not velocity). Every motion is taken relative to the
// collider's surface (its own motion over the substep subtracted), so a moving collider pushes and drags the cloth.
// One thread per particle. Two kernels: collideParticles over the analytic shapes (shapes.wgsl), collideMeshParticles
// over mesh colliders (meshCollider.wgsl: `localDistance` bounded by the thickness, as the reference asks).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  if (invMass[i] == 0.0) { return; }
  var x = positions[i].xyz;
  var xp = previous[i].xyz;
  let th = globals.thickness;
  var moved = false;
  var movedPrev = false;
  for (var k = batch.start; k < batch.end; k++) {
    let c = colliders[sub.colliderBase + k];
    var n: vec3f;
    let d = colliderDistance(c, x, th, &n);
    if (d >= th) { continue; }
    // motion over the substep so far relative to the surface, its normal part, and the push-out
    var m = x - xp;
    if (c.moving != 0u) { m -= surfaceMotion(c, x); }
    let mn = dot(m, n);
    let movedIn = max(-mn, 0.0);
    let depth = min(th - d, movedIn + sub.recover);
    let t = m - mn * n;
    // friction bounded by what presses on the surface, not by a depenetration
    x += depth * n - frictionScale(length(t), pressedDepth(th - d, movedIn, sub.recover)) * t;
    moved = true;
    let made = min(mn + depth, depth);
    if (made > 0.0) {
      xp += made * n;
      movedPrev = true;
    }
  }
  if (moved) { positions[i] = vec4f(x, 0.0); }
  if (movedPrev) { previous[i] = vec4f(xp, 0.0); }
}
