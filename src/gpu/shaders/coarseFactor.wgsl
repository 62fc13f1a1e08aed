// The springs' coarse correction, 6 (as coarseTouch): each cloth's banded matrix A factored, A = L·Lᵀ, by
// one workgroup (workgroup c: cloth c), column by column (right-looking Cholesky): column j of L is A's column j over
// √A_jj (into coarseFactor), and the entries (i, k) of the trailing triangle the column reaches, j < k ≤ i ≤ j + b,
// lose A_ij·A_kj/A_jj (in coarseMatrix, in place); a barrier ends each column. A matrix that is not positive definite
// (a cloth gone non-finite) leaves a factor of zeros, which coarseSolve takes for no correction, as the CPU does.

var<workgroup> shape: vec4u;
var<workgroup> failed: atomic<u32>;
var<workgroup> zeroed: u32;

/** entry (i, j) of a banded matrix whose rows start at m, b below the diagonal: row i holds (i, i − b … i) */
fn at(m: u32, b: u32, i: u32, j: u32) -> u32 {
  return m + i * b + b + j;
}

@compute @workgroup_size(FACTOR_WORKGROUP)
fn main(@builtin(workgroup_id) wid: vec3u, @builtin(local_invocation_index) t: u32) {
  if (t == 0u) {
    let block = coarseBlocks[2u * wid.x];
    shape = vec4u(block.y, block.z, coarseBlocks[2u * wid.x + 1u].x, 0u);
    atomicStore(&failed, 0u);
  }
  let s = workgroupUniformLoad(&shape);
  let size = s.x;
  let b = s.y;
  let m = s.z;
  for (var j = 0u; j < size; j++) {
    let d = coarseMatrix[at(m, b, j, j)];
    if (!(d > 0.0)) { atomicStore(&failed, 1u); }
    let root = sqrt(d);
    let span = min(size - 1u, j + b) - j;
    for (var r = t; r <= span; r += FACTOR_WORKGROUP) {
      coarseFactor[at(m, b, j + r, j)] = select(coarseMatrix[at(m, b, j + r, j)] / root, root, r == 0u);
    }
    // the trailing triangle's span·(span + 1)/2 entries, numbered row by row: e → (p, q), 1 ≤ q ≤ p ≤ span
    let count = span * (span + 1u) / 2u;
    for (var e = t; e < count; e += FACTOR_WORKGROUP) {
      var p = u32((sqrt(8.0 * f32(e) + 1.0) - 1.0) * 0.5);
      if ((p + 1u) * (p + 2u) / 2u <= e) { p++; }
      if (p * (p + 1u) / 2u > e) { p--; }
      let q = e - p * (p + 1u) / 2u;
      let i = j + p + 1u;
      let k = j + q + 1u;
      let ik = at(m, b, i, k);
      coarseMatrix[ik] = coarseMatrix[ik] - coarseMatrix[at(m, b, i, j)] * coarseMatrix[at(m, b, k, j)] / d;
    }
    storageBarrier();
  }
  if (t == 0u) { zeroed = atomicLoad(&failed); }
  if (workgroupUniformLoad(&zeroed) != 0u) {
    for (var k = t; k < size * (b + 1u); k += FACTOR_WORKGROUP) { coarseFactor[m + k] = 0.0; }
  }
}
