// What the apply kernels of the global steps (bendingApply, stretchApply) share: the correction Δx of particle i that
// the triangular solves left in globalX at its row, with the grabbed particle g held where the grab put it. With z =
// A⁻¹·e_g (grabColumn), Δx − z·Δx_g/z_g is the exact solution with Δx_g = 0 (core PrefactoredSystem.hold), without a
// refactor; the grabbed particle itself gets none.

fn heldCorrection(i: u32) -> vec3f {
  let rowOf = factorIndex[FACTOR_ROW_OF];
  let row = factorIndex[rowOf + i];
  var d = globalX[row].xyz;
  let g = globals.grabbed;
  if (g >= 0 && pinned[u32(g)] == 0u) {
    if (u32(g) == i) { return vec3f(0.0); }
    let rg = factorIndex[rowOf + u32(g)];
    d -= (grabColumn[row] / grabColumn[rg]) * globalX[rg].xyz;
  }
  return d;
}
