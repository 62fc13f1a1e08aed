// The XPBD substep as a WebAssembly kernel (AssemblyScript; built by src/core/wasm/gen-wasm.mjs into
// xpbd-kernel.generated.ts): the kernel's entry points and its walk of the phase schedule. The host (xpbd-wasm.ts)
// runs the frame loop (frame.ts) and hands the kernel, per substep, the run of the schedule's phases the kernel
// implements (a mask of phase ids from the one table, gen-layout.mjs); the kernel runs them in schedule order, as
// the TypeScript reference does (reference.ts): the wind, integrate, the grab, distance constraints batch by batch, bending
// stencils batch by batch, tethers, stretch limiting batch by batch, particle contact, triangle contact. The phases themselves live
// beside this file, one job each:
//   wind.as.ts         the air's force on each triangle (one thread, in order)
//   integrate.as.ts    integration and the grab
//   constraints.as.ts  distance constraints, tethers, stretch limiting
//   bending.as.ts      the bending stencils (hinges, Laplacian)
//   contact.as.ts      particle contact against the collider records
//   triangle-contact.as.ts  triangle contact against the sphere records that have it (one thread, in order)
//   self-contact.as.ts self-contact's passes over the candidate pairs (the host calls them between two substep()
//                      calls, on thread 0: the selfContact phase is never part of a substep() here)
//   self-search.as.ts  self-contact's search for those pairs (likewise called by the host, on thread 0)
//   factored.as.ts     the global steps' triangular solves (the host runs them over a memory of their own,
//                      factored-wasm.ts, between two substep() calls)
//   simd.as.ts         the f32x4 lane helpers they share
//   arrays.as.ts       the arrays' byte offsets (configure())
//   threads.as.ts      the protocol under which threads share a substep
//
// Threads: with the threads build, T instances over one shared memory run the same substep under that protocol;
// the result does not depend on T. Thread 0 is the caller's; helpers sit in helperLoop() and are started by a
// dispatch counter in the control block. The single-thread build compiles no atomics and runs every phase whole.
//
// Memory: the caller lays out every array and passes their byte offsets to configure(); the control block at
// CTRL holds the per-substep scalars (its layout is generated, for both sides, by gen-layout.mjs).

import { BATCH_COUNT, BATCHES, HINGE_BATCH_COUNT, HINGE_BATCHES, LAPLACIAN_BATCH_COUNT, LAPLACIAN_BATCHES, N } from './arrays.as';
import { solveStencils } from './bending.as';
import { collideParticles } from './contact.as';
import { collideTriangles } from './triangle-contact.as';
import { limitStretch, solveDistance, solveTethers } from './constraints.as';
import { integrate, moveGrabbed } from './integrate.as';
import { accumulateWind } from './wind.as';
import {
  BEND, COMMAND, DAMPING, DESC, DESC_ITERATIONS_MASK, DESC_ITERATIONS_SHIFT, DESC_PHASES_MASK, DESC_PHASES_SHIFT,
  DESC_SEQ_MASK, DESC_SEQ_SHIFT, DESC_THREADS_MASK, DESC_THREADS_SHIFT, DISPATCH, FLAGS, H, ITERATIONS,
  KERNEL_FLAG_ACCUMULATE, KERNEL_FLAG_FORCES, KERNEL_FLAG_STORE_LAMBDA, KERNEL_FLAG_TRACE, PHASE, PHASE_BENDING, PHASE_CONTACT, PHASE_CONTACT_TRIANGLES,
  PHASE_COUNT, PHASE_DISTANCE, PHASE_GRAB, PHASE_INTEGRATE, PHASE_STRETCH_LIMIT, PHASE_TETHERS, PHASE_WIND, READY, STRETCH,
  STENCILS, SUBSTEP_PHASES, THREADS, TRACE, TRACE_COUNT,
} from './layout.generated.as';
import {
  CHUNK_PARTICLES, CHUNK_SPRINGS, CHUNK_STENCILS, claim, dispatchExit, dispatchSubstep, report, waitDispatch, waitPhase,
} from './threads.as';

export { configure } from './arrays.as';
export { configureSelf, selfBoxes, selfEdgeBoxes, selfEdges, selfFound, selfFrame, selfParticles, selfEdgeRecords, selfStaleEdges, selfTriangleBoxes } from './self-contact.as';
export { configureSearch, foundEdgePairs, foundPairs, selfSearch, selfUpdate } from './self-search.as';
export { coarseStretch } from './coarse.as';
export { productAdd3, solveFactored3 } from './factored.as';

/**
 * Helper thread t's loop: wait for a dispatch, take part in that substep, repeat until told to exit. It reads the
 * substep's description from DESC in one atomic load, so a helper that wakes late joins the newest substep.
 */
export function helperLoop(t: i32): void {
  if (ASC_FEATURE_THREADS) {
    let seen = atomic.load<i32>(DISPATCH);
    if (atomic.load<i32>(COMMAND) == 2) return; // the kernel was disposed before this helper started
    atomic.add<i32>(READY, 1);
    for (;;) {
      seen = waitDispatch(seen);
      if (atomic.load<i32>(COMMAND) == 2) return;
      const desc = atomic.load<i64>(DESC);
      if (t < descField(desc, DESC_THREADS_SHIFT, DESC_THREADS_MASK)) substepPhases(t, desc, false);
    }
  }
}

/**
 * What a substep's phase list depends on, in one word (the DESC fields of gen-layout.mjs): the first phase's
 * sequence number, the distance passes, T, and the phases to run.
 */
function describe(first: i32, T: i32): i64 {
  return ((<i64><u32>first & DESC_SEQ_MASK) << DESC_SEQ_SHIFT) |
    ((<i64>load<i32>(ITERATIONS) & DESC_ITERATIONS_MASK) << DESC_ITERATIONS_SHIFT) |
    ((<i64>T & DESC_THREADS_MASK) << DESC_THREADS_SHIFT) |
    ((<i64>load<i32>(SUBSTEP_PHASES) & DESC_PHASES_MASK) << DESC_PHASES_SHIFT);
}
@inline function descField(desc: i64, shift: i64, mask: i64): i32 { return <i32>((desc >>> shift) & mask); }

/** Thread 0: the phases of SUBSTEP_PHASES for one substep (the scalars are in the control block), with the helpers unless THREADS is 1. */
export function substep(): void {
  store<i32>(TRACE_COUNT, 0);
  if (ASC_FEATURE_THREADS) {
    const T = atomic.load<i32>(THREADS);
    if (T > 1) {
      const desc = describe(atomic.load<i32>(PHASE), T);
      dispatchSubstep(desc);
      waitPhase(substepPhases(0, desc, false));
      return;
    }
  }
  substepPhases(0, describe(0, 1), true);
}

/** Thread 0: tells the helpers to leave helperLoop. */
export function stopHelpers(): void {
  dispatchExit();
}

/**
 * Thread t's part of one substep: the phases of the description, in schedule order (ascending ids). `alone`:
 * thread 0 runs every phase whole, without the phase protocol. Returns the sequence number after the last phase
 * (the next substep's first).
 */
function substepPhases(t: i32, desc: i64, alone: bool): i32 {
  const T = descField(desc, DESC_THREADS_SHIFT, DESC_THREADS_MASK);
  const phases = descField(desc, DESC_PHASES_SHIFT, DESC_PHASES_MASK);
  const trace = t == 0 && (load<i32>(FLAGS) & KERNEL_FLAG_TRACE) != 0;
  const iterations = descField(desc, DESC_ITERATIONS_SHIFT, DESC_ITERATIONS_MASK);
  let seq = descField(desc, DESC_SEQ_SHIFT, DESC_SEQ_MASK);
  for (let id = 0; id < PHASE_COUNT; id++) {
    if ((phases & (1 << id)) != 0) seq = schedulePhase(t, T, seq, alone, id, iterations, trace);
  }
  return seq;
}

/**
 * Thread t's part of phase `id` of the schedule, cut into protocol phases (a pass over the particles, one per
 * colour batch...); with `trace`, listed in TRACE once run. Returns the next sequence number. An id the kernel does
 * not implement runs nothing and is not listed (the host never asks for one).
 */
function schedulePhase(t: i32, T: i32, seq: i32, alone: bool, id: i32, iterations: i32, trace: bool): i32 {
  switch (id) {
    case PHASE_INTEGRATE:
    case PHASE_TETHERS:
    case PHASE_CONTACT:
      seq = phase(t, T, seq, alone, id, 0, 0, N, CHUNK_PARTICLES);
      break;
    case PHASE_WIND:
    case PHASE_GRAB:
    case PHASE_CONTACT_TRIANGLES:
      // one item: one thread (the wind sums each particle's force over its triangles in their order; triangle
      // contact goes through the triangles in order, Gauss–Seidel)
      seq = phase(t, T, seq, alone, id, 0, 0, 1, 1);
      break;
    case PHASE_DISTANCE:
      for (let it = 0; it < iterations; it++) {
        for (let b = 0; b < BATCH_COUNT; b++) {
          const rec = BATCHES + <usize>b * 12;
          seq = phase(t, T, seq, alone, id, b, load<i32>(rec), load<i32>(rec, 4), CHUNK_SPRINGS);
        }
      }
      break;
    case PHASE_BENDING: {
      // (the host asks for it only with stencils: STENCILS 1 or 2)
      const kind = load<i32>(STENCILS) - 1;
      if (kind < 0) return seq;
      const batches = kind == 0 ? HINGE_BATCHES : LAPLACIAN_BATCHES, count = kind == 0 ? HINGE_BATCH_COUNT : LAPLACIAN_BATCH_COUNT;
      for (let it = 0; it < iterations; it++) {
        for (let b = 0; b < count; b++) {
          const rec = batches + <usize>b * 8;
          seq = phase(t, T, seq, alone, id, b, load<i32>(rec), load<i32>(rec, 4), CHUNK_STENCILS);
        }
      }
      break;
    }
    case PHASE_STRETCH_LIMIT:
      for (let b = 0; b < BATCH_COUNT; b++) {
        const rec = BATCHES + <usize>b * 12;
        if (load<i32>(rec, 8) == BEND) continue;
        seq = phase(t, T, seq, alone, id, b, load<i32>(rec), load<i32>(rec, 4), CHUNK_SPRINGS);
      }
      break;
    default:
      return seq;
  }
  if (trace) {
    const k = load<i32>(TRACE_COUNT);
    store<i32>(TRACE + (<usize>k << 2), id);
    store<i32>(TRACE_COUNT, k + 1);
  }
  return seq;
}

/**
 * One protocol phase over items [start, end) in chunks of `size`: the whole range when alone, else thread t's
 * chunks under the phase protocol. An empty range is no phase. Returns the next phase's sequence number.
 */
function phase(t: i32, T: i32, seq: i32, alone: bool, id: i32, batch: i32, start: i32, end: i32, size: i32): i32 {
  if (end <= start) return seq;
  if (alone) {
    run(id, batch, start, end);
    return seq;
  }
  const count = (end - start + size - 1) / size;
  waitPhase(seq);
  for (let c = claim(t, T, seq, count); c >= 0; c = claim(t, T, seq, count)) {
    const c0 = start + c * size;
    run(id, batch, c0, min(end, c0 + size));
  }
  report(seq, T, count);
  return seq + 1;
}

/** Items [i0, i1) of phase `id`; the scalars are read here, once the chunk is taken (they are this substep's). */
function run(id: i32, batch: i32, i0: i32, i1: i32): void {
  const flags = load<i32>(FLAGS);
  switch (id) {
    case PHASE_WIND: accumulateWind(); break;
    case PHASE_INTEGRATE: integrate(i0, i1, (flags & KERNEL_FLAG_FORCES) != 0); break;
    case PHASE_GRAB: moveGrabbed(); break;
    case PHASE_DISTANCE: {
      const h = load<f64>(H);
      const bend = load<i32>(BATCHES + <usize>batch * 12, 8) == BEND;
      solveDistance(i0, i1, <f32>(1 / (h * h)), <f32>(load<f64>(DAMPING) / h), bend ? Infinity : <f32>load<f64>(STRETCH),
        (flags & KERNEL_FLAG_ACCUMULATE) != 0, (flags & KERNEL_FLAG_STORE_LAMBDA) != 0);
      break;
    }
    case PHASE_BENDING: {
      const h = load<f64>(H);
      solveStencils(load<i32>(STENCILS) - 1, i0, i1, 1 / (h * h), (flags & KERNEL_FLAG_ACCUMULATE) != 0);
      break;
    }
    case PHASE_TETHERS: solveTethers(i0, i1, load<f64>(STRETCH)); break;
    case PHASE_STRETCH_LIMIT: limitStretch(i0, i1, <f32>load<f64>(STRETCH)); break;
    case PHASE_CONTACT: collideParticles(i0, i1); break;
    case PHASE_CONTACT_TRIANGLES: collideTriangles();
  }
}
