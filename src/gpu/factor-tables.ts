/**
 * A CPU factor on the GPU (the global stretch and bending steps: global-stretch.ts, global-bending.ts): its structure as
 * tables the triangular solves walk level by level (FactorLayout, factorSolve.wgsl), its values in float32, and the
 * grab's column z; FactorTables keeps them current with the CPU's system, which orders and factors the matrix in double
 * precision once per substep length and pins.
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { PrefactoredSystem } from '../core/solvers/prefactored.js';
import type { SparseCholesky } from '../core/solvers/sparse.js';
import type { ClothState } from '../core/state.js';
import type { ClothBuffers } from './buffers.js';
import { FACTOR_HEADER, FACTOR_SLOTS, type BufferName } from './layout.js';

/** the most rows of one block of a FactorLayout (its inverse: BLOCK_MOST·(BLOCK_MOST + 1)/2 values) */
export const BLOCK_MOST = 128;

/**
 * A factor's structure as factorSolve.wgsl reads it (the `factorIndex` buffer, layout.ts FACTOR_SLOTS), and its values
 * as `factorValues` holds them (values()).
 *
 * A triangular solve is a chain of dependencies: a row of L needs the rows its entries name. Solved row by row, the
 * chain is as long as the elimination tree is deep, and the separators of the nested-dissection order are long
 * chains (each separator row needs the one before it): 383 rows in a row at 64², 795 at 128². So the rows are solved
 * in blocks: runs of consecutive rows each the only child of the next in the elimination tree (the separators, the
 * small pieces numbered whole), at most BLOCK_MOST rows. A block S is solved in two parallel steps, its rows first
 * gathering what the rows outside it give (t_k = b_k − Σ_{j∉S} L_kj·y_j), then the block's own triangle through its
 * inverse, computed on the CPU (y_S = L_SS⁻¹·t_S), so that a block of s rows takes two steps instead of s. The
 * backward solve uses the same blocks and the transposed inverse. A block's level is one past the highest of the
 * blocks it needs, the blocks of one level are independent, and the chain is the separator tree's depth.
 *
 * L's entries outside the blocks are kept twice, by rows for the forward solve (a row gathers the solved rows it
 * names) and by columns for the backward one (a column gathers the solved rows below it), so that no thread writes
 * what another reads in the same step, and no atomics are needed.
 */
export class FactorLayout {
  /** the factorIndex buffer's contents */
  readonly index: Uint32Array<ArrayBuffer>;
  /** elements of the factorValues buffer: the entries outside the blocks twice, then the blocks' inverses */
  readonly valueCount: number;
  /** L's entries outside the blocks (off the diagonal), and the values of the blocks' inverses (packed) */
  readonly outside: number;
  readonly inverseValues: number;
  /** the levels of the forward and of the backward solve (each two steps of the workgroup) */
  readonly forwardLevels: number;
  readonly backwardLevels: number;
  /** the blocks: their first rows, then one past the last row */
  readonly blockStart: Int32Array;
  /** for each entry of L outside the blocks (in L's column order, diagonal and blocks skipped: −1), its place by rows */
  private readonly byRow: Int32Array;
  /** for each entry of L, its place in the columns' table (−1 for an entry of a block) */
  private readonly byColumn: Int32Array;
  /** where each block's inverse starts in factorValues */
  private readonly inverseAt: Int32Array;
  /** a block's triangle, dense, and its inverse, packed (double precision) */
  private readonly work: Float64Array;
  private readonly inverse: Float64Array;

  constructor(chol: SparseCholesky, row: Int32Array) {
    const n = chol.n, { colStart, rows } = chol;
    // the blocks: k + 1 continues k's block where it is k's parent in the elimination tree (the first entry below
    // the diagonal of column k) and k its only child
    const parent = new Int32Array(n).fill(-1), children = new Int32Array(n);
    for (let j = 0; j < n; j++) {
      if (colStart[j + 1] > colStart[j] + 1) { parent[j] = rows[colStart[j] + 1]; children[parent[j]]++; }
    }
    const starts: number[] = [];
    const blockOf = new Int32Array(n);
    for (let k = 0; k < n; k++) {
      const continues = k > 0 && parent[k - 1] === k && children[k] === 1 && k - starts[starts.length - 1] < BLOCK_MOST;
      if (!continues) starts.push(k);
      blockOf[k] = starts.length - 1;
    }
    starts.push(n);
    const blockStart = Int32Array.from(starts), blocks = blockStart.length - 1;
    this.blockStart = blockStart;
    // L's entries outside the blocks, by columns (column m's rows past its block) and by rows
    this.byColumn = new Int32Array(colStart[n]).fill(-1);
    const upperStart = new Uint32Array(n + 1), lowerCount = new Uint32Array(n + 1);
    let outside = 0;
    for (let m = 0; m < n; m++) {
      upperStart[m] = outside;
      for (let p = colStart[m] + 1; p < colStart[m + 1]; p++) {
        if (blockOf[rows[p]] === blockOf[m]) continue;
        this.byColumn[p] = outside++;
        lowerCount[rows[p] + 1]++;
      }
    }
    upperStart[n] = outside;
    const upperRows = new Uint32Array(outside);
    for (let p = 0; p < colStart[n]; p++) if (this.byColumn[p] >= 0) upperRows[this.byColumn[p]] = rows[p];
    const lowerStart = new Uint32Array(n + 1);
    for (let i = 0; i < n; i++) lowerStart[i + 1] = lowerStart[i] + lowerCount[i + 1];
    const lowerCols = new Uint32Array(outside), fill = lowerStart.slice(0, n);
    this.byRow = new Int32Array(colStart[n]).fill(-1);
    for (let m = 0; m < n; m++) {
      for (let p = colStart[m] + 1; p < colStart[m + 1]; p++) {
        if (this.byColumn[p] < 0) continue;
        const at = fill[rows[p]]++;
        lowerCols[at] = m;
        this.byRow[p] = at;
      }
    }
    // levels of the blocks: forward, a block after the blocks of the columns its rows name; backward, after those of
    // the rows its columns name
    const forward = new Int32Array(blocks), backward = new Int32Array(blocks);
    for (let b = 0; b < blocks; b++) {
      let level = 0;
      for (let k = blockStart[b]; k < blockStart[b + 1]; k++) {
        for (let p = lowerStart[k]; p < lowerStart[k + 1]; p++) level = Math.max(level, forward[blockOf[lowerCols[p]]] + 1);
      }
      forward[b] = level;
    }
    for (let b = blocks - 1; b >= 0; b--) {
      let level = 0;
      for (let m = blockStart[b]; m < blockStart[b + 1]; m++) {
        for (let q = upperStart[m]; q < upperStart[m + 1]; q++) level = Math.max(level, backward[blockOf[upperRows[q]]] + 1);
      }
      backward[b] = level;
    }
    const f = levelRows(forward, blockStart), bk = levelRows(backward, blockStart);
    this.forwardLevels = f.start.length - 1;
    this.backwardLevels = bk.start.length - 1;
    // each row's block: its first row, one past its last, and where the row's row of the inverse starts
    this.inverseAt = new Int32Array(blocks + 1);
    this.inverseAt[0] = 2 * outside;
    for (let b = 0; b < blocks; b++) {
      const s = blockStart[b + 1] - blockStart[b];
      this.inverseAt[b + 1] = this.inverseAt[b] + (s * (s + 1)) / 2;
    }
    const rowBlock = new Uint32Array(3 * n);
    for (let k = 0; k < n; k++) {
      const b = blockOf[k], r = k - blockStart[b];
      rowBlock[3 * k] = blockStart[b];
      rowBlock[3 * k + 1] = blockStart[b + 1];
      rowBlock[3 * k + 2] = this.inverseAt[b] + (r * (r + 1)) / 2;
    }
    const tables: [keyof typeof FACTOR_SLOTS, ArrayLike<number>][] = [
      ['rowOf', row], ['lowerStart', lowerStart], ['lowerCols', lowerCols], ['upperStart', upperStart], ['upperRows', upperRows],
      ['forwardLevelStart', f.start], ['forwardRows', f.rows], ['backwardLevelStart', bk.start], ['backwardRows', bk.rows],
      ['rowBlock', rowBlock],
    ];
    let length = FACTOR_HEADER;
    for (const [, table] of tables) length += table.length;
    const index = new Uint32Array(length);
    index[FACTOR_SLOTS.forwardLevels] = this.forwardLevels;
    index[FACTOR_SLOTS.backwardLevels] = this.backwardLevels;
    index[FACTOR_SLOTS.upperValues] = outside;
    let at = FACTOR_HEADER;
    for (const [slot, table] of tables) {
      index[FACTOR_SLOTS[slot]] = at;
      index.set(table, at);
      at += table.length;
    }
    this.index = index;
    this.valueCount = this.inverseAt[blocks];
    this.outside = outside;
    this.inverseValues = this.valueCount - 2 * outside;
    let most = 0;
    for (let b = 0; b < blocks; b++) most = Math.max(most, blockStart[b + 1] - blockStart[b]);
    this.work = new Float64Array(most * most);
    this.inverse = new Float64Array((most * (most + 1)) / 2);
  }

  /**
   * L's values (chol.values, after a factor) in factorValues' order, into `out` (valueCount long): the entries
   * outside the blocks by rows, then by columns, then each block's inverse L_SS⁻¹ (lower triangular, by rows, packed),
   * by forward substitution in double precision.
   */
  values(chol: SparseCholesky, out: Float32Array): void {
    const n = chol.n, { colStart, rows, values } = chol, { byRow, byColumn, blockStart, inverseAt, work, inverse } = this;
    const outside = inverseAt[0] / 2;
    for (let p = 0; p < colStart[n]; p++) {
      if (byColumn[p] < 0) continue;
      out[byRow[p]] = values[p];
      out[outside + byColumn[p]] = values[p];
    }
    for (let b = 0; b + 1 < blockStart.length; b++) {
      const first = blockStart[b], s = blockStart[b + 1] - first;
      // the block's triangle, dense, by rows: work[r·s + c] = L[first + r][first + c]
      work.fill(0, 0, s * s);
      for (let c = 0; c < s; c++) {
        const m = first + c;
        for (let p = colStart[m]; p < colStart[m + 1] && rows[p] < first + s; p++) work[(rows[p] - first) * s + c] = values[p];
      }
      // its inverse, column by column: L·v = e_c, v_r = (δ_rc − Σ_{c≤q<r} L_rq·v_q)/L_rr
      for (let c = 0; c < s; c++) {
        for (let r = c; r < s; r++) {
          let v = r === c ? 1 : 0;
          for (let q = c; q < r; q++) v -= work[r * s + q] * inverse[(q * (q + 1)) / 2 + c];
          inverse[(r * (r + 1)) / 2 + c] = v / work[r * s + r];
        }
      }
      for (let q = 0; q < (s * (s + 1)) / 2; q++) out[inverseAt[b] + q] = inverse[q];
    }
  }
}

/** The rows of the blocks of each level, level after level, and where each level starts. */
function levelRows(level: Int32Array, blockStart: Int32Array): { start: Uint32Array; rows: Uint32Array } {
  let most = -1;
  for (let b = 0; b < level.length; b++) most = Math.max(most, level[b]);
  const start = new Uint32Array(most + 2);
  for (let b = 0; b < level.length; b++) start[level[b] + 1] += blockStart[b + 1] - blockStart[b];
  for (let l = 0; l <= most; l++) start[l + 1] += start[l];
  const rows = new Uint32Array(blockStart[level.length]), fill = start.slice(0, most + 1);
  for (let b = 0; b < level.length; b++) for (let k = blockStart[b]; k < blockStart[b + 1]; k++) rows[fill[level[b]]++] = k;
  return { start, rows };
}

/** Where a step's factor lives on the GPU: its factorIndex, factorValues and grabColumn buffers. */
export interface FactorBuffers {
  index: BufferName;
  values: BufferName;
  z: BufferName;
}

/**
 * A global step's tables on the GPU of one cloth, kept current with the CPU's system (`update`): the factor's
 * structure for a new system, its values for a new factor (a pin set or let go, another substep length), z for a
 * newly grabbed particle; and what the step adds (`made`, `factored`). The solves' scratch rows (globalX, globalT) are
 * shared by the steps, which run one after the other.
 */
export abstract class FactorTables<S extends PrefactoredSystem> {
  protected readonly device: GPUDevice;
  protected readonly model: ClothModel;
  protected readonly buffers: ClothBuffers;
  private readonly names: FactorBuffers;
  /** the system whose tables the buffers hold (null: placeholders) */
  protected system: S | null = null;
  private layout: FactorLayout | null = null;
  private values = new Float32Array(0);
  /** the factor (chol.factors) whose values the buffers hold, and the grabbed particle whose z they hold */
  private factors = -1;
  private grabbed = -1;

  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers, names: FactorBuffers) {
    this.device = device;
    this.model = model;
    this.buffers = buffers;
    this.names = names;
  }

  /**
   * The factor the GPU holds as its solves read it: L's entries outside the blocks and the values of the blocks'
   * inverses (0 and 0 before the first)
   */
  get factorSize(): { outside: number; inverse: number } {
    return { outside: this.layout?.outside ?? 0, inverse: this.layout?.inverseValues ?? 0 };
  }

  /**
   * The GPU's tables made current with `system` (the CPU's, factored for the frame's pins and substep h [s]), before
   * the frame's kernels are encoded (it may make the buffers anew).
   */
  protected update(system: S, state: ClothState, params: SimParams, h: number): void {
    const q = this.device.queue, n = this.model.particleCount, { index, values, z } = this.names;
    if (system !== this.system) {
      const layout = new FactorLayout(system.chol, system.row);
      this.buffers.remake({ ...this.sizes(system), [index]: layout.index.length, [values]: layout.valueCount, globalX: n, globalT: n, [z]: n });
      q.writeBuffer(this.buffers.buffers[index], 0, layout.index);
      this.made(system);
      this.system = system;
      this.layout = layout;
      this.values = new Float32Array(layout.valueCount);
      this.factors = -1;
    }
    if (system.chol.factors !== this.factors) {
      this.layout!.values(system.chol, this.values);
      q.writeBuffer(this.buffers.buffers[values], 0, this.values);
      this.factored(system, params, h);
      this.factors = system.chol.factors;
      this.grabbed = -1;
    }
    const g = system.grabbed(state);
    if (g >= 0 && g !== this.grabbed) {
      q.writeBuffer(this.buffers.buffers[z], 0, Float32Array.from(system.z));
      this.grabbed = g;
    }
  }

  /** the sizes of the step's own buffers for a new system (made anew with the factor's) */
  protected abstract sizes(system: S): Partial<Record<BufferName, number>>;
  /** writes what the step keeps of a new system, into its buffers just made */
  protected abstract made(system: S): void;
  /** writes what the step keeps of a new factor (params and h are those it was made for) */
  protected abstract factored(system: S, params: SimParams, h: number): void;
}
