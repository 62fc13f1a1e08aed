// Self-contact grid, step 1 (selfGrid.wgsl), for the primitives of this build (batch.flags: SELF_TRIANGLES or
// SELF_EDGES; batch.end of them): each one's box over the substep (its corners at the substep's start and now),
// widened by the self-contact distance h for a triangle and h/2 for an edge (collideSelf's and collideEdges' boxes),
// into selfBoxes; the largest extent of any box into selfCounts[0] (atomicMax on the f32 bits, which order as the
// positive floats do). A box that is not finite (an unstable cloth) makes it +∞: the build then holds nothing, and
// the substep keeps nothing apart, as on the CPU. One thread per primitive.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= batch.end) { return; }
  var lo: vec3f;
  var hi: vec3f;
  var pad: f32;
  if (batch.flags == SELF_TRIANGLES) {
    let a = triangles[3u * i];
    let b = triangles[3u * i + 1u];
    let c = triangles[3u * i + 2u];
    lo = min(min(min(positions[a].xyz, previous[a].xyz), min(positions[b].xyz, previous[b].xyz)), min(positions[c].xyz, previous[c].xyz));
    hi = max(max(max(positions[a].xyz, previous[a].xyz), max(positions[b].xyz, previous[b].xyz)), max(positions[c].xyz, previous[c].xyz));
    pad = globals.selfDistance;
  } else {
    let e = edges[i];
    lo = min(min(positions[e.x].xyz, previous[e.x].xyz), min(positions[e.y].xyz, previous[e.y].xyz));
    hi = max(max(positions[e.x].xyz, previous[e.x].xyz), max(positions[e.y].xyz, previous[e.y].xyz));
    pad = 0.5 * globals.selfDistance;
  }
  lo -= vec3f(pad);
  hi += vec3f(pad);
  selfBoxes[2u * i] = vec4f(lo, 0.0);
  selfBoxes[2u * i + 1u] = vec4f(hi, 0.0);
  let extent = hi - lo;
  let finite = all(abs(lo) < vec3f(1e30)) && all(abs(hi) < vec3f(1e30));
  atomicMax(&selfCounts[0], select(SELF_NOT_FINITE, bitcast<u32>(max(extent.x, max(extent.y, extent.z))), finite));
}
