// collide (phases.ts), particle part, for colliders [batch.start, batch.end) in order: a particle closer than the
// contact thickness is pushed out along the surface normal (at once for what it moved in this substep, at most
// sub.recover for an overlap it did not move into), position-based friction removes (part of) its tangential
// motion over the substep, and the outward motion the push-out made moves x_prev too (not velocity). One thread
// per particle.

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
    var n: vec3f;
    let d = shapeDistance(globals.colliders[k], x, &n);
    if (d >= th) { continue; }
    let m = x - xp;
    let mn = dot(m, n);
    let depth = min(th - d, max(-mn, 0.0) + sub.recover);
    let t = m - mn * n;
    x += depth * n - frictionScale(length(t), depth) * t;
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
