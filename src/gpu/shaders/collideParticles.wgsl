// collide (phases.ts), particle part, for colliders [batch.start, batch.end) in order: a particle closer than the
// contact thickness is pushed out along the surface normal, then position-based friction removes (part of) its
// tangential motion over the substep. One thread per particle.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  if (invMass[i] == 0.0) { return; }
  var x = positions[i].xyz;
  let xp = previous[i].xyz;
  let th = globals.thickness;
  var moved = false;
  for (var k = batch.start; k < batch.end; k++) {
    var n: vec3f;
    let d = shapeDistance(globals.colliders[k], x, &n);
    if (d >= th) { continue; }
    let depth = th - d;
    x += depth * n;
    let m = x - xp;
    let t = m - dot(m, n) * n;
    x -= frictionScale(length(t), depth) * t;
    moved = true;
  }
  if (moved) { positions[i] = vec4f(x, 0.0); }
}
