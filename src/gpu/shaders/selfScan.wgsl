// Self-contact grid, step 3: the exclusive prefix sums of the bucket counts within each block of SCAN_BLOCK buckets
// (4 per thread, then a Hillis–Steele scan of the 64 threads' sums in workgroup memory) into selfStarts[1 + b], and
// each block's total into selfBlocks. One workgroup per block.

var<workgroup> sums: array<u32, WG>;

@compute @workgroup_size(WG)
fn main(@builtin(workgroup_id) wid: vec3u, @builtin(num_workgroups) nwg: vec3u, @builtin(local_invocation_index) l: u32) {
  let block = wid.x + wid.y * nwg.x;
  if (block >= globals.selfBlockCount) { return; }
  let first = block * SCAN_BLOCK + 4u * l;
  let c0 = selfCounts[1u + first];
  let c1 = selfCounts[2u + first];
  let c2 = selfCounts[3u + first];
  let c3 = selfCounts[4u + first];
  let own = c0 + c1 + c2 + c3;
  sums[l] = own;
  workgroupBarrier();
  for (var o = 1u; o < WG; o = o << 1u) {
    let add = select(0u, sums[max(l, o) - o], l >= o);
    workgroupBarrier();
    sums[l] += add;
    workgroupBarrier();
  }
  let before = sums[l] - own;
  selfStarts[1u + first] = before;
  selfStarts[2u + first] = before + c0;
  selfStarts[3u + first] = before + c0 + c1;
  selfStarts[4u + first] = before + c0 + c1 + c2;
  if (l == WG - 1u) { selfBlocks[block] = sums[l]; }
}
