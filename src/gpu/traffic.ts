/**
 * What one frame of the GPU solver costs, counted from the model, the params and the pass lists (for the benchmark
 * and reports; docs/gpu.md, "Benchmark"): bytes each kernel moves per substep, and dispatches per frame.
 */
import { bendingStencils, type ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { CoarseLayout } from './coarse-stretch.js';
import { CARRY, COLLIDER, SCAN_BLOCK, SELF_EDGE_PASSES } from './layout.js';
import type { BatchRecords, CollidePass, SelfRecords, StencilBatchRecords } from './uniforms.js';

/** Bytes one substep's kernels read and write, as written (each element access counted once per thread). */
export interface SubstepTraffic {
  total: number;
  byKernel: Record<string, number>;
}

/**
 * Bytes one substep moves, by kernel; `self`: the self-contact grid's records (null: none), `hasTethers`: whether the
 * tethers kernel has work, `factor` and `stretchFactor`: the global bending and stretch steps' factors as their solves
 * read them, L's entries outside the blocks and the values of the blocks' inverses (global-bending.ts FactorLayout; 0
 * without the step); `coarse`: the coarse correction's tables (null until a frame made them).
 */
export function substepTraffic(
  model: ClothModel, params: SimParams, collidePasses: readonly CollidePass[], self: SelfRecords | null, hasTethers: boolean,
  factor = { outside: 0, inverse: 0 }, stretchFactor = { outside: 0, inverse: 0 }, coarse: CoarseLayout | null = null,
): SubstepTraffic {
  const n = model.particleCount, T = model.triangles.length / 3, S = model.restLengths.length;
  const by: Record<string, number> = {};
  const add = (k: string, bytes: number) => { by[k] = (by[k] ?? 0) + bytes; };
  if (params.wind.enabled) {
    add('wind', T * (12 + 3 * 16 + 3 * 16 + 12 + 16)); // indices, x, x_prev, base w, force
    add('integrate', n * 8 + 3 * T * 20); // adjacency offsets, then index + force per incident triangle
  }
  add('integrate', n * (16 + 16 + 4 + 16 + 16)); // x, x_prev, w in; x_prev, x out
  const together = params.stretch === 'global';
  // both triangular solves of a factor: per entry of L outside the blocks its index, value and the solved row it
  // names; per value of a block's inverse, it and a row of t; per row and solve its level's entry, its block (12 B),
  // its offsets, the row read, t written, the row written
  const solves = (f: { outside: number; inverse: number }) => 2 * f.outside * (4 + 4 + 16) + 2 * f.inverse * (4 + 16) + 2 * n * (4 + 12 + 8 + 16 + 16 + 16);
  if (together) {
    // y kept (x in, y out); per pass: per spring its ends, coefficients, x, y and x_prev of both, its force written;
    // per particle its pin, row, incidence offsets, per spring end its entry and force, the row written; the solves;
    // per particle its pin, row, Δx, y read and x written
    let pass = S * (8 + 16 + 3 * 32 + 16) + n * (4 + 4 + 8 + 16) + 2 * S * (4 + 16) + solves(stretchFactor) + n * (4 + 4 + 16 + 16 + 16);
    pass *= params.iterations;
    add('globalStretch', n * 32 + pass);
  } else {
    if (params.stretch === 'two-level' && coarse) add('coarseStretch', coarseTraffic(model, params, coarse));
    let solve = S * (8 + 8 + 8 + 32 + 32); // springData, springs, w×2, x×2 in and out
    if (params.damping > 0) solve += S * 32; // previous×2
    solve += S * 4; // λ written
    solve *= params.iterations;
    solve += S * 4 * (params.iterations - (params.stretch === 'two-level' ? 0 : 1)); // λ read after the first pass, or the coarse correction
    add('solve', solve);
  }
  const stencils = bendingStencils(model, params.bending);
  if (stencils && params.bendingSolve === 'global') {
    const H = stencils.areas.length, E = stencils.vertices.length;
    // per stencil: its offsets and coefficients, its force written; per entry: particle, K, x and x_prev
    add('globalBending', H * (8 + 8 + 16) + E * (4 + 4 + 16 + 16));
    // the right-hand side: per particle its row, pin and incidence offsets, the row written; per entry (k, e), K, d
    add('globalBending', n * (4 + 4 + 8 + 16) + E * (8 + 4 + 16));
    // both triangular solves
    add('globalBending', solves(factor));
    // Δx applied: per particle its pin, row, Δx, the position read and written
    add('globalBending', n * (4 + 4 + 16 + 16 + 16));
  } else if (stencils) {
    const H = stencils.areas.length, E = stencils.vertices.length;
    // per stencil: its two offsets, compliance, λ written; per entry: particle, K, w, x read to make C, then
    // particle, K, w, x read and written to move it
    let bending = H * (8 + 4 + 12) + E * ((4 + 4 + 4 + 16) + (4 + 4 + 4 + 16 + 16));
    bending *= params.iterations;
    bending += H * 12 * (params.iterations - 1); // λ read after the first pass
    add('bending', bending);
  }
  if (!together) {
    // (the global stretch step converges: it runs neither)
    if (hasTethers) add('tethers', n * (8 + 4 + 16 + 16 + 16));
    const stretchSprings = model.springCounts[0] + model.springCounts[1];
    add('limitStretch', stretchSprings * (8 + 8 + 8 + 32)); // springs, rest, w×2, x×2 in (written only when over)
  }
  if (self) {
    // per build of P primitives of k corners: boxes (corners now and then in, box out, the extent's atomic), counts
    // (box in, its cells' counts and ranks: 8 at most, counted as 2), the prefix sum over the B buckets (count in,
    // start out, twice, and the zeroing) and the scatter (box, starts, ranks in, entries out, 2 cells); then the
    // candidates' fixed part (a particle or edge in, its own cells' starts) and the corrections applied (n sums in,
    // positions in and out). What the candidates read of their cells' entries and the pairs they resolve depend on
    // where the cloth is, and are not counted.
    const n = model.particleCount, B = self.buckets;
    const build = (P: number, k: number) =>
      P * (k * 32 + 32 + 4) + P * (32 + 2 * 8) + B * (4 + 4 + 4 + 4 + 4 + 4) + (B / SCAN_BLOCK) * 12 + P * (32 + 4 + 2 * (4 + 4 + 4));
    add('selfContact', build(self.triangleCount, 3) + n * (16 + 16 + 4 + 8) + n * (16 + 32));
    add('selfContact', build(self.edgeCount, 2) + self.edgeCount * (32 + 8 + 64 + 8) + SELF_EDGE_PASSES * n * (16 + 32));
  }
  const carried = params.carried.particles.length;
  if (carried > 0) add('carry', carried * (CARRY.size + COLLIDER.size + 16)); // its record, its collider's, the position written
  for (const c of collidePasses) {
    // w, x and x_prev in, x out, and each collider's record (a mesh collider's walk of its tables is not counted:
    // how much of them a particle or triangle reads depends on where it is)
    if (!c.triangles) add(c.kernel, n * (4 + 16 + 16 + 16 + c.colliders * COLLIDER.size));
    // indices, positions and previous positions of 3 particles, the collider's record
    else add(c.kernel, c.count * (12 + 48 + 48 + COLLIDER.size));
  }
  add('perFrame', (n * (4 + 4 + 4 + 16 + 16 + 16) + n * 48) / params.substeps); // prepare + velocities, per substep
  let total = 0;
  for (const k of Object.keys(by)) { by[k] = Math.round(by[k]); total += by[k]; }
  return { total, byKernel: by };
}

/**
 * Bytes the coarse correction moves per substep (coarse-stretch.ts), its frame's assembly, factor and inverses spread
 * over the substeps: A aggregates, P (particle, aggregate) pairs, C pairs of pairs, E entries of the bands, I values
 * of their blocks' inverses.
 */
function coarseTraffic(model: ClothModel, params: SimParams, t: CoarseLayout): number {
  const n = model.particleCount, S = model.restLengths.length, A = t.aggregates;
  // directions: ends, data, w×2, x×2 in, the direction out; rows: per aggregate its range and row out, per spring its
  // member entry, direction and compliance
  let bytes = S * (8 + 8 + 8 + 32 + 16) + A * (16 + 8) + S * (4 + 16 + 8);
  // both solves: each band entry and the row it names read twice (forward by rows, backward by columns), each
  // inverse value with a gathered row twice, each row read and written four times
  bytes += 2 * t.entries * 8 + 2 * t.inverse * 8 + 4 * A * 16;
  // the check of a step of the last factor: per aggregate its row, per particle w and its incidence offsets, per
  // spring end its entry, aggregate, μ and direction; each thread's two terms written and read
  bytes += A * 16 + n * (4 + 8) + 2 * S * (4 + 4 + 16 + 16) + 2 * 8 * Math.max(n, A);
  // λ: direction, four aggregates, their weights and μ, λ out; the move: w, the incidence offsets, x in and out, per
  // spring end its entry, λ and direction
  bytes += S * (16 + 16 + 16 + 4 * 8 + 4) + n * (4 + 8 + 32) + 2 * S * (4 + 4 + 16);
  // once a frame: the pairs (pair, w, out; per spring end its entry and direction), each row's entries (starts, pairs
  // of pairs and their vectors, the entry out), the factor (per band entry read and written once, a trailing update
  // of the ~b²/2 entries below each column: three read, one written), the inverses (a column's entries of L and of
  // the inverse read, per value)
  let frame = t.pairs * (16 + 4 + 16) + 2 * S * (4 + 16) + A * (16 + 32 + 8) + t.entries * (4 + 4 + 4) + t.couples * (8 + 32);
  const band = t.entries / Math.max(A, 1);
  frame += t.entries * 8 + A * ((band * band) / 2) * 16 + t.inverse * band * 8;
  return bytes + frame / params.substeps;
}

/**
 * Dispatches one frame encodes with nothing grabbed (prepare, velocities and normals once; the rest per substep);
 * `stencilRecords` is empty unless params.bending is a stencil model (solved together: 4 dispatches per substep
 * instead of its batches), `self` null unless it has self-contact (then
 * per substep two grid builds of 6 dispatches, each followed by its candidates, their indirect arguments, the pairs
 * and the corrections applied, the edges' SELF_EDGE_PASSES times: 18 + 2 per edge pass); the coarse
 * correction (solver.stretch 'two-level') adds 9 in a frame's first substep and 12 in each later one (a solve and
 * the check of its step in two, then the matrix's five kernels again, dispatched with no workgroups unless its step
 * overshoots).
 */
export function dispatchesPerFrame(
  params: SimParams, batchRecords: readonly BatchRecords[], stencilRecords: readonly StencilBatchRecords[],
  collidePasses: readonly CollidePass[], self: SelfRecords | null, hasTethers: boolean,
): number {
  const stretchBatches = batchRecords.filter((r) => r.stretch).length;
  // the springs one colour batch at a time, then the tethers and the stretch limit; or solved together: y kept, then
  // 4 dispatches a pass
  const springs = params.stretch === 'global' ? 1 + 4 * params.iterations
    : params.iterations * batchRecords.length + stretchBatches + (hasTethers ? 1 : 0) + (params.stretch === 'two-level' ? 12 : 0);
  const perSubstep = (params.wind.enabled ? 1 : 0) + 1 + (params.carried.particles.length > 0 ? 1 : 0) + springs +
    (stencilRecords.length === 0 ? 0 : params.bendingSolve === 'global' ? 4 : params.iterations * stencilRecords.length) +
    collidePasses.length + (self ? 18 + 2 * SELF_EDGE_PASSES : 0);
  // (the coarse correction's first substep has no solve with the last factor and no check)
  return 3 - (params.stretch === 'two-level' ? 3 : 0) + params.substeps * perSubstep;
}
