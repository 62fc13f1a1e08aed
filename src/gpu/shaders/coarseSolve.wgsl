// The springs' coarse correction: each cloth's L·Lᵀ·μ = r (coarseRhs.x takes r from .z, then holds y, then μ), by one
// workgroup (workgroup c: cloth c), B rows at a time (coarseInvert's blocks); again, with the factor made anew, where
// coarseCheck found the last factor stale (an indirect dispatch of coarseArgs). Forward, L·y = r, block S after block:
// its rows gather t_i = r_i − Σ_{j before S} L_ij·y_j, then y_S = L_SS⁻¹·t_S. Backward, Lᵀ·μ = y, from the last block:
// t_m = y_m − Σ_{i after S} L_im·μ_i, then μ_S = L_SS⁻ᵀ·t_S. A zero factor (coarseFactor) gives μ = 0.

var<workgroup> shape: vec4u;
var<workgroup> zero: u32;
var<workgroup> gathered: array<f32, FACTOR_WORKGROUP>;

@compute @workgroup_size(FACTOR_WORKGROUP)
fn main(@builtin(workgroup_id) wid: vec3u, @builtin(local_invocation_index) t: u32) {
  if (t == 0u) {
    let block = coarseBlocks[2u * wid.x];
    let place = coarseBlocks[2u * wid.x + 1u];
    shape = block;
    zero = select(0u, 1u, block.y > 0u && coarseFactor[place.x + block.z] == 0.0);
  }
  let s = workgroupUniformLoad(&shape);
  let g0 = s.x;
  let size = s.y;
  let b = s.z;
  let rows = s.w;
  let place = coarseBlocks[2u * wid.x + 1u];
  let m = place.x;
  if (workgroupUniformLoad(&zero) != 0u) {
    for (var i = t; i < size; i += FACTOR_WORKGROUP) { coarseRhs[g0 + i].x = 0.0; }
    return;
  }
  for (var i = t; i < size; i += FACTOR_WORKGROUP) { coarseRhs[g0 + i].x = coarseRhs[g0 + i].z; }
  storageBarrier();
  let blocks = (size + rows - 1u) / rows;
  for (var k = 0u; k < blocks; k++) {
    let first = k * rows;
    let count = min(rows, size - first);
    let inverse = place.y + k * (rows * (rows + 1u) / 2u);
    if (t < count) {
      let i = first + t;
      var v = coarseRhs[g0 + i].x;
      for (var j = select(0u, i - b, i > b); j < first; j++) {
        v -= coarseFactor[m + i * b + b + j] * coarseRhs[g0 + j].x;
      }
      gathered[t] = v;
    }
    workgroupBarrier();
    if (t < count) {
      var y = 0.0;
      for (var c = 0u; c <= t; c++) { y += coarseInverse[inverse + t * (t + 1u) / 2u + c] * gathered[c]; }
      coarseRhs[g0 + first + t].x = y;
    }
    storageBarrier();
  }
  for (var kk = blocks; kk > 0u; kk--) {
    let k = kk - 1u;
    let first = k * rows;
    let count = min(rows, size - first);
    let inverse = place.y + k * (rows * (rows + 1u) / 2u);
    if (t < count) {
      let c = first + t;
      var v = coarseRhs[g0 + c].x;
      for (var i = first + count; i < min(size, c + b + 1u); i++) {
        v -= coarseFactor[m + i * b + b + c] * coarseRhs[g0 + i].x;
      }
      gathered[t] = v;
    }
    workgroupBarrier();
    if (t < count) {
      var x = 0.0;
      for (var r = t; r < count; r++) { x += coarseInverse[inverse + r * (r + 1u) / 2u + t] * gathered[r]; }
      coarseRhs[g0 + first + t].x = x;
    }
    storageBarrier();
  }
}
