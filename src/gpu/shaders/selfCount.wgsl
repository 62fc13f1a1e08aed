// Self-contact grid, step 2 (selfGrid.wgsl): each primitive of the build counted into the bucket of each of its
// cells (once per bucket), its place there (the count before it: atomicAdd's old value) kept in selfRanks for the
// scatter. selfCounts[1 + b] counts bucket b. One thread per primitive.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= batch.end) { return; }
  let bits = atomicLoad(&selfCounts[0]);
  if (bits >= SELF_NOT_FINITE) { return; }
  var span: vec3i;
  let c0 = boxCells(selfBoxes[2u * i].xyz, selfBoxes[2u * i + 1u].xyz, cellInverse(bits), &span);
  for (var s = 0u; s < 8u; s++) {
    var c: vec3i;
    if (!boxCell(c0, span, s, &c) || !firstInBucket(c0, span, s)) { continue; }
    selfRanks[8u * i + s] = atomicAdd(&selfCounts[1u + bucketOf(c)], 1u);
  }
}
