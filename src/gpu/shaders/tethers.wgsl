// solveTethers (tethers.ts): a free particle farther than stretchFactor × its tether length from its anchor (a
// pinned particle, which this kernel never moves) is put back on that sphere. One thread per particle.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let t = tethers[i];
  if (t.anchor < 0 || invMass[i] == 0.0) { return; }
  let xa = positions[u32(t.anchor)].xyz;
  let d = positions[i].xyz - xa;
  let d2 = dot(d, d);
  let m = globals.stretchFactor * t.length;
  if (d2 <= m * m) { return; }
  positions[i] = vec4f(xa + d * (m / sqrt(d2)), 0.0);
}
