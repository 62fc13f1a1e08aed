// Self-contact grid, step 5: each bucket's start made global (its start within its block plus the block's prefix),
// one past the last bucket's end written as the total (so bucket b's entries are selfStarts[1 + b] up to
// selfStarts[2 + b]), the build's largest box extent copied to selfStarts[0], and the counts zeroed for the next
// build. One thread per bucket.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let b = flatIndex(gid, nwg);
  if (b >= globals.selfBuckets) { return; }
  let start = selfStarts[1u + b] + selfBlocks[b / SCAN_BLOCK];
  selfStarts[1u + b] = start;
  let count = atomicLoad(&selfCounts[1u + b]);
  atomicStore(&selfCounts[1u + b], 0u);
  if (b == globals.selfBuckets - 1u) { selfStarts[1u + globals.selfBuckets] = start + count; }
  if (b == 0u) {
    selfStarts[0] = atomicLoad(&selfCounts[0]);
    atomicStore(&selfCounts[0], 0u);
  }
}
