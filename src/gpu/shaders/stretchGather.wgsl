// The global stretch step, each pass 2 of 4, per particle i: its row of the right-hand side, Σ ±f_s over its springs
// (+ where it is the spring's first end; stretchForces), into globalX at the particle's row of the stretch factor. A
// pinned particle's row is the identity and its correction 0.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let row = factorIndex[factorIndex[FACTOR_ROW_OF] + i];
  var b = vec3f(0.0);
  if (pinned[i] == 0u) {
    let hi = springIncidence[i + 1u];
    for (var q = springIncidence[i]; q < hi; q++) {
      let e = springIncidence[q];
      let f = springForce[e >> 1u].xyz;
      b += select(f, -f, (e & 1u) != 0u);
    }
  }
  globalX[row] = vec4f(b, 0.0);
}
