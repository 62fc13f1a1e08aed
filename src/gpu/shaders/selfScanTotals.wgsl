// Self-contact grid, step 4: the blocks' totals (selfScan) turned into their exclusive prefix sums in place, by one
// workgroup: SCAN_BLOCK totals at a time (4 per thread, a scan of the threads' sums), carrying the running total
// from one chunk to the next. Dispatched with one workgroup.

var<workgroup> sums: array<u32, WG>;

@compute @workgroup_size(WG)
fn main(@builtin(local_invocation_index) l: u32) {
  let count = globals.selfBlockCount;
  var base = 0u; // the total of the chunks before (the same in every thread)
  for (var chunk = 0u; chunk < (count + SCAN_BLOCK - 1u) / SCAN_BLOCK; chunk++) {
    let first = chunk * SCAN_BLOCK + 4u * l;
    var c = array<u32, 4>(0u, 0u, 0u, 0u);
    for (var j = 0u; j < 4u; j++) {
      if (first + j < count) { c[j] = selfBlocks[first + j]; }
    }
    let own = c[0] + c[1] + c[2] + c[3];
    sums[l] = own;
    workgroupBarrier();
    for (var o = 1u; o < WG; o = o << 1u) {
      let add = select(0u, sums[max(l, o) - o], l >= o);
      workgroupBarrier();
      sums[l] += add;
      workgroupBarrier();
    }
    var before = base + sums[l] - own;
    for (var j = 0u; j < 4u; j++) {
      if (first + j < count) { selfBlocks[first + j] = before; }
      before += c[j];
    }
    base += sums[WG - 1u];
    workgroupBarrier();
  }
}
