// integrate (phases.ts), position Verlet: x ← x + (x − x_prev) + c·h²·(g + w·f), x_prev ← x, on the positions plus
// their residuals (precision.wgsl): what float32 drops of each new position is kept in its residual.
// c = ½ on the very first substep (Taylor start, exact for constant acceleration), else 1 (folded into sub.h2).
// Particles with zero inverse mass stay (the grabbed one is moved by the grab kernel after this one). The wind
// force is gathered from the incident triangles (no float atomics).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let x = positions[i].xyz;
  let r = residuals[i].xyz;
  let xp = previous[i].xyz;
  let rp = previousResiduals[i].xyz;
  previous[i] = vec4f(x, 0.0);
  previousResiduals[i] = vec4f(r, 0.0);
  let w = invMass[i];
  if (w == 0.0) { return; }
  var a = globals.gravity * sub.h2;
  if (sub.windOn != 0u) {
    var f = vec3f(0.0);
    let hi = adjacency[i + 1u];
    for (var k = adjacency[i]; k < hi; k++) {
      f += triForces[adjacency[k]].xyz;
    }
    a += f * (w * sub.h2);
  }
  // x + r + ((x − x_prev) + (r − r_prev) + a), the small part first; then s + (e + r) renormalised
  var e: vec3f;
  let s = twoSum(x, (x - xp) + (r - rp) + a, &e);
  var e2: vec3f;
  let next = twoSum(s, e + r, &e2);
  positions[i] = vec4f(next, 0.0);
  residuals[i] = vec4f(e2, 0.0);
}
