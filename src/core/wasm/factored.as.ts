// The triangular solves of a sparse Cholesky factor (solvers/sparse.ts SparseCholesky.solve3, the reference) for
// three right-hand sides: the global steps' per-substep work (solvers/global-bending.ts, global-stretch.ts). Each
// entry of L updates x and y as one f64x2 and z as a scalar: the reference's multiplications and subtractions, one
// rounding each, in its order, so both give the same solution bit for bit. The arrays are not the kernel's: the
// host (factored-wasm.ts) runs this export over a memory of its own, which grows with the factor.

/**
 * Solves L·Lᵀ·x = b in place. L by columns: column j's entries from colStart[j] (i32 × n + 1) to colStart[j + 1],
 * the diagonal first; their rows (i32) and values (f64). b: f64 × 3 per row (x, y, z), overwritten by x.
 */
export function solveFactored3(n: i32, colStart: usize, rows: usize, values: usize, b: usize): void {
  // forward: L·y = b, column by column
  for (let j = 0; j < n; j++) {
    const c0 = <usize>load<i32>(colStart + (<usize>j << 2)), c1 = <usize>load<i32>(colStart + (<usize>(j + 1) << 2));
    const d = 1 / load<f64>(values + (c0 << 3));
    const at = b + <usize>j * 24;
    const xy = f64x2.mul(v128.load(at), f64x2.splat(d)), z = load<f64>(at, 16) * d;
    v128.store(at, xy);
    store<f64>(at, z, 16);
    for (let p = c0 + 1; p < c1; p++) {
      const l = load<f64>(values + (p << 3)), r = b + <usize>load<i32>(rows + (p << 2)) * 24;
      v128.store(r, f64x2.sub(v128.load(r), f64x2.mul(f64x2.splat(l), xy)));
      store<f64>(r, load<f64>(r, 16) - l * z, 16);
    }
  }
  // backward: Lᵀ·x = y, row by row
  for (let j = n - 1; j >= 0; j--) {
    const c0 = <usize>load<i32>(colStart + (<usize>j << 2)), c1 = <usize>load<i32>(colStart + (<usize>(j + 1) << 2));
    const at = b + <usize>j * 24;
    let s = v128.load(at), sz = load<f64>(at, 16);
    for (let p = c0 + 1; p < c1; p++) {
      const l = load<f64>(values + (p << 3)), r = b + <usize>load<i32>(rows + (p << 2)) * 24;
      s = f64x2.sub(s, f64x2.mul(f64x2.splat(l), v128.load(r)));
      sz -= l * load<f64>(r, 16);
    }
    const d = 1 / load<f64>(values + (c0 << 3));
    v128.store(at, f64x2.mul(s, f64x2.splat(d)));
    store<f64>(at, sz * d, 16);
  }
}

/**
 * b += P·v (solvers/sparse.ts multiplyAdd3, the reference): for each particle i, its diagonal term diagonal[i]·v_i
 * and then its entries values[p]·v_cols[p], p from start[i] to start[i + 1], summed in that order, added to b's row
 * row[i]. diagonal, values: f64; start (n + 1), cols, row: i32; v and b: f64 × 3 per particle / row.
 */
export function productAdd3(n: i32, diagonal: usize, start: usize, cols: usize, values: usize, row: usize, v: usize, b: usize): void {
  for (let i = 0; i < n; i++) {
    const d = load<f64>(diagonal + (<usize>i << 3)), vi = v + <usize>i * 24;
    let s = f64x2.mul(f64x2.splat(d), v128.load(vi)), sz = d * load<f64>(vi, 16);
    const p1 = <usize>load<i32>(start + (<usize>(i + 1) << 2));
    for (let p = <usize>load<i32>(start + (<usize>i << 2)); p < p1; p++) {
      const w = load<f64>(values + (p << 3)), c = v + <usize>load<i32>(cols + (p << 2)) * 24;
      s = f64x2.add(s, f64x2.mul(f64x2.splat(w), v128.load(c)));
      sz += w * load<f64>(c, 16);
    }
    const q = b + <usize>load<i32>(row + (<usize>i << 2)) * 24;
    v128.store(q, f64x2.add(v128.load(q), s));
    store<f64>(q, load<f64>(q, 16) + sz, 16);
  }
}
