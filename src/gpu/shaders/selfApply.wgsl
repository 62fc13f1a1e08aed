// The end of a self-contact pass (selfPoints or selfEdges): each particle that a pair moved is moved by the mean
// of its corrections (their fixed-point sum, SELF_FIXED per metre, over their count: Jacobi with averaging, Macklin
// et al. 2014 §4.2), and its sums are zeroed for the next pass. One thread per particle.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let n = atomicLoad(&selfDelta[4u * i + 3u]);
  if (n == 0) { return; }
  let d = vec3f(f32(atomicLoad(&selfDelta[4u * i])), f32(atomicLoad(&selfDelta[4u * i + 1u])), f32(atomicLoad(&selfDelta[4u * i + 2u])));
  positions[i] = vec4f(positions[i].xyz + d / (SELF_FIXED * f32(n)), 0.0);
  for (var c = 0u; c < 4u; c++) { atomicStore(&selfDelta[4u * i + c], 0); }
}
