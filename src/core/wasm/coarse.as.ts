// The springs' coarse correction (solver.stretch 'two-level'; solvers/coarse-stretch.ts solveCoarseStretch is the
// reference): the same operations in the same order, in f64 with the f32 arrays read and written as the reference
// reads and writes its Float32Arrays, so both give the same positions and multipliers bit for bit. The arrays are not
// the kernel's: the host (coarse-wasm.ts) runs this export over a memory of its own, laid out once per model, with the
// positions and inverse masses copied in and the positions and multipliers out at each call. `header` holds the
// arrays' byte offsets and counts as i32 words, in the order of the H_ constants.

import { COARSE_OVERSHOOT } from './layout.generated.as';

const H_N: i32 = 0, H_NS: i32 = 1, H_CLOTHS: i32 = 2;
const H_X: i32 = 4, H_W: i32 = 5, H_LAMBDAS: i32 = 6, H_SPRINGS: i32 = 7, H_REST: i32 = 8, H_COMPLIANCE: i32 = 9;
const H_AGGREGATE: i32 = 10, H_NEAR_ID: i32 = 11, H_NEAR_WEIGHT: i32 = 12, H_START: i32 = 13, H_INCIDENCE: i32 = 14;
const H_MOVE: i32 = 15, H_BLOCK_START: i32 = 16, H_BAND: i32 = 17, H_MATRIX_START: i32 = 18, H_BLOCK_OF: i32 = 19;
const H_MATRIX: i32 = 20, H_RHS: i32 = 21, H_DIR: i32 = 22, H_TOUCHED: i32 = 23, H_VEC: i32 = 24, H_RESIDUAL: i32 = 25;
const H_OWN: i32 = 26;

@inline function word(header: usize, k: i32): i32 {
  return load<i32>(header + (<usize>k << 2));
}
@inline function at(header: usize, k: i32): usize {
  return <usize>load<i32>(header + (<usize>k << 2));
}
@inline function i32At(base: usize, i: i32): i32 {
  return load<i32>(base + (<usize>i << 2));
}
@inline function f64Ref(base: usize, i: i32): usize {
  return base + (<usize>i << 3);
}

/**
 * One substep's coarse correction of substep length h [s]; `factor`: assemble and factor the matrix first (else the
 * last factor serves unless its step overshoots under the matrix now).
 */
export function coarseStretch(header: usize, h: f64, factor: bool): void {
  const n = word(header, H_N), ns = word(header, H_NS), cloths = word(header, H_CLOTHS);
  const x = at(header, H_X), w = at(header, H_W), springs = at(header, H_SPRINGS), rest = at(header, H_REST);
  const compliance = at(header, H_COMPLIANCE), aggregate = at(header, H_AGGREGATE), move = at(header, H_MOVE);
  const rhs = at(header, H_RHS), dir = at(header, H_DIR), residual = at(header, H_RESIDUAL);
  const invH2 = 1 / (h * h);
  const count = i32At(at(header, H_BLOCK_START), cloths);
  memory.fill(rhs, 0, <usize>count << 3);
  for (let s = 0; s < ns; s++) {
    const d = f64Ref(dir, 3 * s);
    store<f64>(d, 0); store<f64>(d, 0, 8); store<f64>(d, 0, 16);
    const alpha = <f64>load<f32>(compliance + (<usize>s << 2));
    const pa = i32At(springs, 2 * s), pb = i32At(springs, 2 * s + 1);
    if (alpha == Infinity || <f64>load<f32>(w + (<usize>pa << 2)) + <f64>load<f32>(w + (<usize>pb << 2)) == 0) continue;
    const a = x + <usize>pa * 12, b = x + <usize>pb * 12;
    const dx = <f64>load<f32>(a) - <f64>load<f32>(b), dy = <f64>load<f32>(a, 4) - <f64>load<f32>(b, 4), dz = <f64>load<f32>(a, 8) - <f64>load<f32>(b, 8);
    const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
    if (!(len > 1e-12)) continue;
    const inv = 1 / len;
    store<f64>(d, dx * inv); store<f64>(d, dy * inv, 8); store<f64>(d, dz * inv, 16);
    const r = f64Ref(rhs, i32At(aggregate, s));
    store<f64>(r, load<f64>(r) + (<f64>load<f32>(rest + (<usize>s << 2)) - len));
  }
  if (factor) factorNow(header, n, ns, cloths, invH2);
  else memory.copy(residual, rhs, <usize>count << 3);
  solveBlocks(header, cloths);
  if (factor) spread(header, ns, invH2, false);
  else if (overshoots(header, count, spread(header, ns, invH2, true) + ownEnergy(header, n))) {
    memory.copy(rhs, residual, <usize>count << 3);
    factorNow(header, n, ns, cloths, invH2);
    solveBlocks(header, cloths);
    spread(header, ns, invH2, false);
  }
  for (let i = 0; i < n; i++) {
    const wi = <f64>load<f32>(w + (<usize>i << 2));
    if (wi == 0) continue;
    const q = x + <usize>i * 12, m = f64Ref(move, 3 * i);
    store<f32>(q, <f32>(<f64>load<f32>(q) + wi * load<f64>(m)));
    store<f32>(q, <f32>(<f64>load<f32>(q, 4) + wi * load<f64>(m, 8)), 4);
    store<f32>(q, <f32>(<f64>load<f32>(q, 8) + wi * load<f64>(m, 16)), 8);
  }
}

/** Every block solved for the right-hand side with its factor (the reference's solveBlocks). */
function solveBlocks(header: usize, cloths: i32): void {
  const blockStart = at(header, H_BLOCK_START), band = at(header, H_BAND), matrixStart = at(header, H_MATRIX_START);
  const matrix = at(header, H_MATRIX), rhs = at(header, H_RHS);
  for (let c = 0; c < cloths; c++) solveBand(matrix, i32At(matrixStart, c), rhs, i32At(blockStart, c), i32At(blockStart, c + 1) - i32At(blockStart, c), i32At(band, c));
}

/** Each spring's λ and Jᵀ·λ, with `check` Jᵀ·Rᵀ·μ and the compliance's share of μᵀ·A·μ (the reference's spread). */
function spread(header: usize, ns: i32, invH2: f64, check: bool): f64 {
  const lambdas = at(header, H_LAMBDAS), compliance = at(header, H_COMPLIANCE), aggregate = at(header, H_AGGREGATE);
  const springs = at(header, H_SPRINGS), nearId = at(header, H_NEAR_ID), nearWeight = at(header, H_NEAR_WEIGHT);
  const rhs = at(header, H_RHS), dir = at(header, H_DIR), move = at(header, H_MOVE), own = at(header, H_OWN);
  const n = word(header, H_N);
  memory.fill(move, 0, <usize>(3 * n) << 3);
  if (check) memory.fill(own, 0, <usize>(3 * n) << 3);
  let energy: f64 = 0;
  for (let s = 0; s < ns; s++) {
    const k = 4 * s, d = f64Ref(dir, 3 * s);
    const nx = load<f64>(d), ny = load<f64>(d, 8), nz = load<f64>(d, 16);
    if (nx == 0 && ny == 0 && nz == 0) { store<f32>(lambdas + (<usize>s << 2), 0); continue; }
    const wk = nearWeight + (<usize>k << 2);
    const lf = <f32>(<f64>load<f32>(wk) * load<f64>(f64Ref(rhs, i32At(nearId, k))) +
      <f64>load<f32>(wk, 4) * load<f64>(f64Ref(rhs, i32At(nearId, k + 1))) +
      <f64>load<f32>(wk, 8) * load<f64>(f64Ref(rhs, i32At(nearId, k + 2))) +
      <f64>load<f32>(wk, 12) * load<f64>(f64Ref(rhs, i32At(nearId, k + 3))));
    store<f32>(lambdas + (<usize>s << 2), lf);
    const l = <f64>lf;
    const a = f64Ref(move, 3 * i32At(springs, 2 * s)), b = f64Ref(move, 3 * i32At(springs, 2 * s + 1));
    store<f64>(a, load<f64>(a) + l * nx); store<f64>(a, load<f64>(a, 8) + l * ny, 8); store<f64>(a, load<f64>(a, 16) + l * nz, 16);
    store<f64>(b, load<f64>(b) - l * nx); store<f64>(b, load<f64>(b, 8) - l * ny, 8); store<f64>(b, load<f64>(b, 16) - l * nz, 16);
    if (check) {
      const mu = load<f64>(f64Ref(rhs, i32At(aggregate, s)));
      energy += <f64>load<f32>(compliance + (<usize>s << 2)) * invH2 * mu * mu;
      const oa = f64Ref(own, 3 * i32At(springs, 2 * s)), ob = f64Ref(own, 3 * i32At(springs, 2 * s + 1));
      store<f64>(oa, load<f64>(oa) + mu * nx); store<f64>(oa, load<f64>(oa, 8) + mu * ny, 8); store<f64>(oa, load<f64>(oa, 16) + mu * nz, 16);
      store<f64>(ob, load<f64>(ob) - mu * nx); store<f64>(ob, load<f64>(ob, 8) - mu * ny, 8); store<f64>(ob, load<f64>(ob, 16) - mu * nz, 16);
    }
  }
  return energy;
}

/** The masses' share of μᵀ·A·μ over the free particles (the reference's ownEnergy). */
function ownEnergy(header: usize, n: i32): f64 {
  const w = at(header, H_W), own = at(header, H_OWN);
  let energy: f64 = 0;
  for (let i = 0; i < n; i++) {
    const wi = <f64>load<f32>(w + (<usize>i << 2));
    if (wi == 0) continue;
    const o = f64Ref(own, 3 * i), ox = load<f64>(o), oy = load<f64>(o, 8), oz = load<f64>(o, 16);
    energy += wi * (ox * ox + oy * oy + oz * oz);
  }
  return energy;
}

@inline function isZero(d: usize): bool {
  return load<f64>(d) == 0 && load<f64>(d, 8) == 0 && load<f64>(d, 16) == 0;
}

/** The matrices made from the directions now and factored (the reference's factorNow). */
function factorNow(header: usize, n: i32, ns: i32, cloths: i32, invH2: f64): void {
  const compliance = at(header, H_COMPLIANCE), aggregate = at(header, H_AGGREGATE), blockStart = at(header, H_BLOCK_START);
  const band = at(header, H_BAND), matrixStart = at(header, H_MATRIX_START), blockOf = at(header, H_BLOCK_OF);
  const matrix = at(header, H_MATRIX), dir = at(header, H_DIR);
  memory.fill(matrix, 0, <usize>i32At(matrixStart, cloths) << 3);
  for (let s = 0; s < ns; s++) {
    if (isZero(f64Ref(dir, 3 * s))) continue;
    const g = i32At(aggregate, s), c = i32At(blockOf, g), bw = i32At(band, c);
    const e = f64Ref(matrix, i32At(matrixStart, c) + (g - i32At(blockStart, c)) * (bw + 1) + bw);
    store<f64>(e, load<f64>(e) + <f64>load<f32>(compliance + (<usize>s << 2)) * invH2);
  }
  assemble(header, n);
  for (let c = 0; c < cloths; c++) factorBand(matrix, i32At(matrixStart, c), i32At(blockStart, c + 1) - i32At(blockStart, c), i32At(band, c));
}

/** Whether the step μ solved with an earlier factor overshoots under the matrix now (the reference's overshoots). */
function overshoots(header: usize, count: i32, energy: f64): bool {
  const rhs = at(header, H_RHS), residual = at(header, H_RESIDUAL);
  let before: f64 = 0;
  for (let g = 0; g < count; g++) before += load<f64>(f64Ref(rhs, g)) * load<f64>(f64Ref(residual, g));
  return before > 0 && energy > COARSE_OVERSHOOT * before;
}

/** J·M⁻¹·Jᵀ into the blocks' banded matrices (the reference's assemble). */
function assemble(header: usize, n: i32): void {
  const w = at(header, H_W), aggregate = at(header, H_AGGREGATE), start = at(header, H_START), incidence = at(header, H_INCIDENCE);
  const blockStart = at(header, H_BLOCK_START), band = at(header, H_BAND);
  const matrixStart = at(header, H_MATRIX_START), blockOf = at(header, H_BLOCK_OF), matrix = at(header, H_MATRIX);
  const dir = at(header, H_DIR), touched = at(header, H_TOUCHED), vec = at(header, H_VEC);
  for (let i = 0; i < n; i++) {
    const wi = <f64>load<f32>(w + (<usize>i << 2));
    if (wi == 0) continue;
    let m = 0;
    const p1 = i32At(start, i + 1);
    for (let p = i32At(start, i); p < p1; p++) {
      const code = i32At(incidence, p), s = code >> 1, ds = f64Ref(dir, 3 * s);
      if (isZero(ds)) continue;
      const g = i32At(aggregate, s);
      let k = 0;
      while (k < m && i32At(touched, k) != g) k++;
      const v = f64Ref(vec, 3 * k);
      if (k == m) { store<i32>(touched + (<usize>m << 2), g); store<f64>(v, 0); store<f64>(v, 0, 8); store<f64>(v, 0, 16); m++; }
      if (code & 1) {
        store<f64>(v, load<f64>(v) - load<f64>(ds)); store<f64>(v, load<f64>(v, 8) - load<f64>(ds, 8), 8); store<f64>(v, load<f64>(v, 16) - load<f64>(ds, 16), 16);
      } else {
        store<f64>(v, load<f64>(v) + load<f64>(ds)); store<f64>(v, load<f64>(v, 8) + load<f64>(ds, 8), 8); store<f64>(v, load<f64>(v, 16) + load<f64>(ds, 16), 16);
      }
    }
    if (m == 0) continue;
    const c = i32At(blockOf, i32At(touched, 0)), b0 = i32At(blockStart, c), bw = i32At(band, c), m0 = i32At(matrixStart, c);
    for (let k = 0; k < m; k++) {
      const gk = i32At(touched, k), vk = f64Ref(vec, 3 * k);
      const vx = wi * load<f64>(vk), vy = wi * load<f64>(vk, 8), vz = wi * load<f64>(vk, 16);
      const row = m0 + (gk - b0) * (bw + 1) + bw - gk;
      for (let l = 0; l < m; l++) {
        const gl = i32At(touched, l);
        if (gl <= gk) {
          const vl = f64Ref(vec, 3 * l), e = f64Ref(matrix, row + gl);
          store<f64>(e, load<f64>(e) + (vx * load<f64>(vl) + vy * load<f64>(vl, 8) + vz * load<f64>(vl, 16)));
        }
      }
    }
  }
}

/** Banded Cholesky of one block in place (the reference's factorBand). */
function factorBand(matrix: usize, m: i32, size: i32, bw: i32): void {
  const stride = bw + 1;
  for (let j = 0; j < size; j++) {
    const e = f64Ref(matrix, m + j * stride + bw);
    if (load<f64>(e) == 0) store<f64>(e, 1);
  }
  for (let j = 0; j < size; j++) {
    const rj = m + j * stride + bw - j;
    const k0 = max(0, j - bw);
    let d = load<f64>(f64Ref(matrix, rj + j)) - dot(f64Ref(matrix, rj + k0), f64Ref(matrix, rj + k0), j - k0);
    if (!(d > 0)) { memory.fill(f64Ref(matrix, m), 0, <usize>(size * stride) << 3); return; }
    d = Math.sqrt(d);
    store<f64>(f64Ref(matrix, rj + j), d);
    const i1 = min(size, j + bw + 1);
    for (let i = j + 1; i < i1; i++) {
      const ri = m + i * stride + bw - i, k = max(k0, i - bw);
      store<f64>(f64Ref(matrix, ri + j), (load<f64>(f64Ref(matrix, ri + j)) - dot(f64Ref(matrix, ri + k), f64Ref(matrix, rj + k), j - k)) / d);
    }
  }
}

/** Σ p[t]·q[t] over t < len as the reference's dot: four running sums in two f64x2, the tail into the first. */
@inline function dot(p: usize, q: usize, len: i32): f64 {
  let a = f64x2.splat(0), b = f64x2.splat(0), t = 0;
  for (; t + 4 <= len; t += 4) {
    const o = <usize>t << 3;
    a = f64x2.add(a, f64x2.mul(v128.load(p + o), v128.load(q + o)));
    b = f64x2.add(b, f64x2.mul(v128.load(p + o, 16), v128.load(q + o, 16)));
  }
  let s0 = f64x2.extract_lane(a, 0);
  for (; t < len; t++) s0 += load<f64>(p + (<usize>t << 3)) * load<f64>(q + (<usize>t << 3));
  return (s0 + f64x2.extract_lane(b, 0)) + (f64x2.extract_lane(a, 1) + f64x2.extract_lane(b, 1));
}

/** Solves one factored block for rhs[r…r + size) in place (the reference's solveBand). */
function solveBand(matrix: usize, m: i32, rhs: usize, r: i32, size: i32, bw: i32): void {
  const stride = bw + 1;
  if (size == 0) return;
  if (load<f64>(f64Ref(matrix, m + bw)) == 0) { memory.fill(f64Ref(rhs, r), 0, <usize>size << 3); return; }
  for (let i = 0; i < size; i++) {
    const ri = m + i * stride + bw - i, k = max(0, i - bw);
    const v = load<f64>(f64Ref(rhs, r + i)) - dot(f64Ref(matrix, ri + k), f64Ref(rhs, r + k), i - k);
    store<f64>(f64Ref(rhs, r + i), v / load<f64>(f64Ref(matrix, ri + i)));
  }
  // backward: x_i, then row i of L times x_i off the rows above it (two at a time: each lane the reference's)
  for (let i = size - 1; i >= 0; i--) {
    const ri = m + i * stride + bw - i, xi = load<f64>(f64Ref(rhs, r + i)) / load<f64>(f64Ref(matrix, ri + i));
    store<f64>(f64Ref(rhs, r + i), xi);
    const x2 = f64x2.splat(xi);
    let k = max(0, i - bw);
    for (; k + 2 <= i; k += 2) {
      const q = f64Ref(rhs, r + k);
      v128.store(q, f64x2.sub(v128.load(q), f64x2.mul(v128.load(f64Ref(matrix, ri + k)), x2)));
    }
    for (; k < i; k++) store<f64>(f64Ref(rhs, r + k), load<f64>(f64Ref(rhs, r + k)) - load<f64>(f64Ref(matrix, ri + k)) * xi);
  }
}
