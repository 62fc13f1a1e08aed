// Self-contact grid, step 6 (selfGrid.wgsl): each primitive written into the bucket of each of its cells, at the
// bucket's start plus the place selfCount gave it there (the same cells in the same order: the same cell size, from
// the same bits). One thread per primitive.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= batch.end) { return; }
  let bits = selfStarts[0];
  if (bits >= SELF_NOT_FINITE) { return; }
  var span: vec3i;
  let c0 = boxCells(selfBoxes[2u * i].xyz, selfBoxes[2u * i + 1u].xyz, cellInverse(bits), &span);
  for (var s = 0u; s < 8u; s++) {
    var c: vec3i;
    if (!boxCell(c0, span, s, &c) || !firstInBucket(c0, span, s)) { continue; }
    selfEntries[selfStarts[1u + bucketOf(c)] + selfRanks[8u * i + s]] = i;
  }
}
