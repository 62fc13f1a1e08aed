// The global bending step, 3 of 4: L·Lᵀ·Δx = b with the CPU's factor (core SparseCholesky), in one workgroup, by
// blocks of rows (global-bending.ts FactorLayout): globalX holds b, then y, then Δx. Forward, L·y = b, for each block
// S of a level: its rows gather what the solved rows outside S give, t_k = b_k − Σ_{j∉S} L_kj·y_j (into globalT);
// then y_S = L_SS⁻¹·t_S. Backward, Lᵀ·Δx = y: its columns gather t_m = y_m − Σ_{i∉S} L_im·Δx_i, then
// Δx_S = L_SS⁻ᵀ·t_S. The rows of a level are shared among the workgroup's threads; a barrier ends each step.

var<workgroup> levels: vec2u;

/** The rows of level `l` of the table at `levelStart`/`levelRows`: their gathers (step 0) or their blocks' inverse (step 1). */
fn forwardStep(l: u32, step: u32, t: u32) {
  let levelStart = factorIndex[FACTOR_FORWARD_LEVEL_START];
  let levelRows = factorIndex[FACTOR_FORWARD_ROWS];
  let hi = factorIndex[levelStart + l + 1u];
  for (var q = factorIndex[levelStart + l] + t; q < hi; q += FACTOR_WORKGROUP) {
    let k = factorIndex[levelRows + q];
    if (step == 0u) {
      let lowerStart = factorIndex[FACTOR_LOWER_START];
      let lowerCols = factorIndex[FACTOR_LOWER_COLS];
      var y = globalX[k].xyz;
      let end = factorIndex[lowerStart + k + 1u];
      for (var p = factorIndex[lowerStart + k]; p < end; p++) {
        y -= factorValues[p] * globalX[factorIndex[lowerCols + p]].xyz;
      }
      globalT[k] = vec4f(y, 0.0);
    } else {
      // row r of the block's inverse, packed: entries (r, 0) … (r, r)
      let block = factorIndex[FACTOR_ROW_BLOCK] + 3u * k;
      let first = factorIndex[block];
      let at = factorIndex[block + 2u];
      var y = vec3f(0.0);
      for (var c = 0u; c <= k - first; c++) {
        y += factorValues[at + c] * globalT[first + c].xyz;
      }
      globalX[k] = vec4f(y, 0.0);
    }
  }
}

/** The same for the backward solve: its columns' gathers (step 0) or their blocks' transposed inverse (step 1). */
fn backwardStep(l: u32, step: u32, t: u32) {
  let levelStart = factorIndex[FACTOR_BACKWARD_LEVEL_START];
  let levelRows = factorIndex[FACTOR_BACKWARD_ROWS];
  let hi = factorIndex[levelStart + l + 1u];
  for (var q = factorIndex[levelStart + l] + t; q < hi; q += FACTOR_WORKGROUP) {
    let m = factorIndex[levelRows + q];
    if (step == 0u) {
      let upperStart = factorIndex[FACTOR_UPPER_START];
      let upperRows = factorIndex[FACTOR_UPPER_ROWS];
      let upperValues = factorIndex[FACTOR_UPPER_VALUES];
      var x = globalX[m].xyz;
      let end = factorIndex[upperStart + m + 1u];
      for (var p = factorIndex[upperStart + m]; p < end; p++) {
        x -= factorValues[upperValues + p] * globalX[factorIndex[upperRows + p]].xyz;
      }
      globalT[m] = vec4f(x, 0.0);
    } else {
      // column c of the block's inverse: entries (c, c) … (s − 1, c), row r's starting r·(r + 1)/2 after row 0's
      let block = factorIndex[FACTOR_ROW_BLOCK] + 3u * m;
      let first = factorIndex[block];
      let last = factorIndex[block + 1u];
      let c = m - first;
      let base = factorIndex[block + 2u] - (c * (c + 1u)) / 2u;
      var x = vec3f(0.0);
      for (var r = c; r < last - first; r++) {
        x += factorValues[base + (r * (r + 1u)) / 2u + c] * globalT[first + r].xyz;
      }
      globalX[m] = vec4f(x, 0.0);
    }
  }
}

@compute @workgroup_size(FACTOR_WORKGROUP)
fn main(@builtin(local_invocation_index) t: u32) {
  if (t == 0u) {
    levels = vec2u(factorIndex[FACTOR_FORWARD_LEVELS], factorIndex[FACTOR_BACKWARD_LEVELS]);
  }
  let counts = workgroupUniformLoad(&levels);
  for (var l = 0u; l < counts.x; l++) {
    forwardStep(l, 0u, t);
    storageBarrier();
    forwardStep(l, 1u, t);
    storageBarrier();
  }
  for (var l = 0u; l < counts.y; l++) {
    backwardStep(l, 0u, t);
    storageBarrier();
    backwardStep(l, 1u, t);
    storageBarrier();
  }
}
