// The springs' coarse correction, 7 (as coarseTouch), per aggregate: one column of the inverse of the
// diagonal block of its cloth's factor L that holds it, the blocks being runs of B = min(b + 1, FACTOR_WORKGROUP)
// rows. Column c of block S by forward substitution, v_r = (δ_rc − Σ_{c ≤ q < r} L_rq·v_q)/L_rr for r = c … |S| − 1,
// into the block's packed lower triangle (row r's entries (r, 0) … (r, r) from r·(r + 1)/2): coarseSolve then takes
// a block of rows in two parallel steps instead of |S| steps.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let g = flatIndex(gid, nwg);
  if (g >= arrayLength(&coarseAggregates)) { return; }
  let cloth = coarseAggregates[g].z;
  let block = coarseBlocks[2u * cloth];
  let place = coarseBlocks[2u * cloth + 1u];
  let b = block.z;
  let rows = block.w;
  let local = g - block.x;
  let first = local - local % rows;
  let c = local - first;
  let count = min(rows, block.y - first);
  let inverse = place.y + (first / rows) * (rows * (rows + 1u) / 2u);
  let m = place.x;
  for (var r = c; r < count; r++) {
    var v = select(0.0, 1.0, r == c);
    let row = m + (first + r) * b + b + first;
    for (var q = c; q < r; q++) {
      v -= coarseFactor[row + q] * coarseInverse[inverse + q * (q + 1u) / 2u + c];
    }
    coarseInverse[inverse + r * (r + 1u) / 2u + c] = v / coarseFactor[row + r];
  }
}
