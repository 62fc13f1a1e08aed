// The springs' coarse correction, 5 (as coarseTouch), per aggregate g: row g of its cloth's banded matrix
// R·(J·M⁻¹·Jᵀ + α̃)·Rᵀ, entries (g, g − b … g): Σ w_i·v_g·v_h over the particles i whose springs are in both
// aggregates (coarseEntryPairs), and α̃ on the diagonal. A row without a spring taking part gets 1 there (its μ is 0).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let g = flatIndex(gid, nwg);
  if (g >= arrayLength(&coarseRhs)) { return; }
  let c = coarseAggregates[g].z;
  let block = coarseBlocks[2u * c];
  let bw = block.z;
  let first = coarseBlocks[2u * c + 1u].x + (g - block.x) * (bw + 1u);
  for (var o = 0u; o <= bw; o++) {
    let slot = first + o;
    var v = 0.0;
    for (var e = coarseEntryStart[slot]; e < coarseEntryStart[slot + 1u]; e++) {
      let pq = coarseEntryPairs[e];
      let a = coarsePairVec[pq.x];
      v += a.w * dot(a.xyz, coarsePairVec[pq.y].xyz);
    }
    if (o == bw) {
      v += coarseRhs[g].y;
      if (v == 0.0) { v = 1.0; }
    }
    coarseMatrix[slot] = v;
  }
}
