/**
 * The springs' coarse correction on the GPU (solver.stretch 'two-level'): the CPU's step (core solvers/coarse-
 * stretch.ts solveCoarseStretch), every part of it on the GPU, the banded factor included, since the matrix follows the
 * springs' directions, which live there. The aggregates, the bands and the interpolation are the CPU's (coarseSystem,
 * made once per model); this module lays them out as the kernels read them, once per model.
 *
 * Each substep: each spring's direction and residual (coarseDirections), each aggregate's right-hand side and α̃
 * (coarseRows); in a frame's first substep, as the CPU refactors, the matrix assembled (coarseTouch: each
 * (particle, aggregate) pair's Σ ±n_s; coarseAssemble: each row's entries from the pairs that meet at a particle),
 * factored by banded Cholesky (coarseFactor: one workgroup per cloth, a barrier per column) and its diagonal blocks
 * inverted (coarseInvert); then both triangular solves by blocks of rows (coarseSolve: one workgroup per cloth, two
 * barriers per block). In the later substeps the solve comes first, with the last factor, and the check asks whether
 * its step overshoots under the matrix now, as the CPU does (coarseCheckParts: each aggregate's and each particle's
 * terms; coarseCheck, one workgroup: their sums); the same five kernels then run
 * again as indirect dispatches it sets (coarseArgs): their full size where it does, no workgroups where it does not
 * (dispatched whole, each workgroup returning at once, they made a 16² frame 73 ms on SwiftShader here, 65 ms now,
 * the sweep alone 35: `drape run cotton-basic --frames 60 --backend gpu --set cloth.resolution=16 --set
 * solver.selfContact=false`, 2026-12-06). Then each spring's λ interpolated (coarseLambda) and the particles moved
 * (coarseMove). The GPU
 * computes in float32 where the CPU computes in double: the correction is a few millimetres at most, and the sweep
 * after it removes what it leaves.
 *
 * Memory, per model: per spring 64 B, per (particle, aggregate) pair 32 B and per pair of pairs at a particle 8 B
 * (about 7 and 30 a particle on a grid), per entry of the bands about 14 B (the matrix, its factor, the entries'
 * starts, the inverses of its blocks): 0.9–1.1 kB a particle, 3.9 MB at 65², 17 MB at 129², 75 MB at 257²
 * (scripts/coarse-sizes.mjs).
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import { coarseSystem } from '../core/solvers/coarse-stretch.js';
import type { ClothBuffers } from './buffers.js';
import { BUFFERS, FACTOR_WORKGROUP, workgroupsFor, type BufferName } from './layout.js';

/** The coarse correction's tables of one model, as its kernels read them (coarseTables). */
export interface CoarseLayout {
  /** the buffers' contents, by name (coarseDir, coarseRhs, coarsePairVec, coarseMatrix, coarseFactor: sizes only) */
  readonly data: Partial<Record<BufferName, Uint32Array | Float32Array>>;
  /** every buffer's size [elements] */
  readonly sizes: Partial<Record<BufferName, number>>;
  /** aggregates, (particle, aggregate) pairs, pairs of pairs, entries of the bands, values of the blocks' inverses, cloths */
  readonly aggregates: number;
  readonly pairs: number;
  readonly couples: number;
  readonly entries: number;
  readonly inverse: number;
  readonly cloths: number;
}

/** Rows of a block of the triangular solves of a band of half width `band` (coarseInvert.wgsl, coarseSolve.wgsl). */
export function coarseBlockRows(band: number): number {
  return Math.min(band + 1, FACTOR_WORKGROUP);
}

/** The tables of `model`'s coarse correction (see the file's comment), from the CPU's coarseSystem. */
export function coarseTables(model: ClothModel): CoarseLayout {
  const sys = coarseSystem(model);
  const n = model.particleCount, ns = model.restLengths.length, { aggregate, blockStart, band, matrixStart, start } = sys;
  const aggregates = blockStart[blockStart.length - 1], cloths = blockStart.length - 1;
  // the aggregates' springs, and their cloths
  const aggregateRows = new Uint32Array(4 * aggregates), members = new Uint32Array(ns);
  for (let s = 0; s < ns; s++) aggregateRows[4 * aggregate[s] + 1]++;
  for (let g = 0, at = 0; g < aggregates; g++) { aggregateRows[4 * g] = at; at += aggregateRows[4 * g + 1]; aggregateRows[4 * g + 1] = aggregateRows[4 * g]; }
  for (let s = 0; s < ns; s++) members[aggregateRows[4 * aggregate[s] + 1]++] = s;
  for (let c = 0; c < cloths; c++) for (let g = blockStart[c]; g < blockStart[c + 1]; g++) aggregateRows[4 * g + 2] = c;
  // the cloths' bands and blocks
  const blocks = new Uint32Array(8 * cloths);
  let inverse = 0;
  for (let c = 0; c < cloths; c++) {
    const size = blockStart[c + 1] - blockStart[c], rows = coarseBlockRows(band[c]);
    blocks.set([blockStart[c], size, band[c], rows, matrixStart[c], inverse], 8 * c);
    inverse += Math.ceil(size / rows) * ((rows * (rows + 1)) / 2);
  }
  // each particle's springs sorted by aggregate, and its (particle, aggregate) pairs
  const incidence = new Uint32Array(n + 1 + 2 * ns), pairRows: number[] = [], pairStart = new Uint32Array(n + 1);
  incidence[0] = n + 1;
  const order: number[] = [];
  for (let i = 0; i < n; i++) {
    order.length = 0;
    for (let p = start[i]; p < start[i + 1]; p++) order.push(sys.incidence[p]);
    order.sort((a, b) => aggregate[a >> 1] - aggregate[b >> 1] || a - b);
    let at = incidence[i];
    for (const code of order) {
      const g = aggregate[code >> 1];
      if (at === incidence[i] || g !== aggregate[incidence[at - 1] >> 1]) pairRows.push(i, g, at, at);
      incidence[at++] = code;
      pairRows[pairRows.length - 1] = at;
    }
    incidence[i + 1] = at;
    pairStart[i + 1] = pairRows.length / 4;
  }
  const pairs = pairRows.length / 4;
  // per entry of the bands, the pairs of pairs at one particle that add to it: (i, g) and (i, h), h ≤ g, at (g, h)
  const entries = matrixStart[cloths], entryStart = new Uint32Array(entries + 1);
  const slotOf = (g: number, h: number): number => {
    const c = aggregateRows[4 * g + 2], bw = band[c];
    return matrixStart[c] + (g - blockStart[c]) * (bw + 1) + bw - (g - h);
  };
  const each = (visit: (slot: number, p: number, q: number) => void): void => {
    for (let i = 0; i < n; i++) {
      for (let p = pairStart[i]; p < pairStart[i + 1]; p++) {
        for (let q = pairStart[i]; q <= p; q++) visit(slotOf(pairRows[4 * p + 1], pairRows[4 * q + 1]), p, q);
      }
    }
  };
  each((slot) => { entryStart[slot + 1]++; });
  for (let k = 0; k < entries; k++) entryStart[k + 1] += entryStart[k];
  const couples = entryStart[entries], entryPairs = new Uint32Array(2 * couples), fill = entryStart.slice(0, entries);
  each((slot, p, q) => { const at = fill[slot]++; entryPairs[2 * at] = p; entryPairs[2 * at + 1] = q; });
  return {
    data: {
      coarseAggregates: aggregateRows, coarseMembers: members, coarseBlocks: blocks, coarseIncidence: incidence,
      coarsePairs: Uint32Array.from(pairRows), coarseEntryStart: entryStart, coarseEntryPairs: entryPairs,
      coarseNear: Uint32Array.from(sys.nearId), coarseWeights: Float32Array.from(sys.nearWeight),
      coarseSpringAggregate: Uint32Array.from(sys.aggregate),
      // the five dispatches coarseCheck sets (none until it does), then their full sizes: coarseTouch over the pairs,
      // coarseAssemble over the aggregates, coarseFactor a workgroup per cloth, coarseInvert, coarseSolve; then the
      // check's two sums
      coarseArgs: Uint32Array.from([
        ...new Array<number>(15).fill(0), ...workgroupsFor(pairs), 1, ...workgroupsFor(aggregates), 1, cloths, 1, 1,
        ...workgroupsFor(aggregates), 1, cloths, 1, 1, 0, 0,
      ]),
    },
    sizes: {
      coarseDir: ns, coarseRhs: aggregates, coarseSpringAggregate: ns, coarseArgs: 32, coarsePartials: Math.max(n, aggregates), coarseAggregates: aggregates, coarseMembers: ns, coarseBlocks: 2 * cloths,
      coarseIncidence: incidence.length, coarsePairs: pairs, coarsePairVec: pairs, coarseEntryStart: entries + 1,
      coarseEntryPairs: couples, coarseMatrix: entries, coarseFactor: entries, coarseInverse: inverse, coarseNear: ns, coarseWeights: ns,
    },
    aggregates, pairs, couples, entries, inverse, cloths,
  };
}

/** The coarse correction's buffers of one cloth on the GPU: made on the first frame that needs them, kept after. */
export class CoarseTables {
  private readonly device: GPUDevice;
  private readonly model: ClothModel;
  private readonly buffers: ClothBuffers;
  /** the tables the buffers hold (null: placeholders) */
  layout: CoarseLayout | null = null;

  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers) {
    this.device = device;
    this.model = model;
    this.buffers = buffers;
  }

  /**
   * The buffers made and written, before the first frame that corrects the springs so is encoded. Throws, making
   * nothing, where one of them is larger than the device binds.
   */
  prepare(): void {
    if (this.layout) return;
    const layout = coarseTables(this.model);
    const limit = this.device.limits.maxStorageBufferBindingSize;
    for (const [name, size] of Object.entries(layout.sizes) as [BufferName, number][]) {
      if (size * BUFFERS[name].bytes > limit) {
        throw new Error(`GPU solver: solver.stretch 'two-level' needs ${Math.ceil((size * BUFFERS[name].bytes) / 2 ** 20)} MiB in one buffer (${name}) for ${this.model.particleCount} particles; this device binds at most ${Math.floor(limit / 2 ** 20)} MiB`);
      }
    }
    this.buffers.remake(layout.sizes);
    for (const [name, data] of Object.entries(layout.data) as [BufferName, Uint32Array | Float32Array][]) {
      if (data.length) this.device.queue.writeBuffer(this.buffers.buffers[name], 0, data as Uint32Array<ArrayBuffer>);
    }
    this.layout = layout;
  }
}
