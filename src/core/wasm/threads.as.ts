// The protocol under which T kernel instances (threads) over one shared memory run a substep together: the
// dispatch of a substep to the helpers, and the phases within it. The single-thread build compiles none of it
// (ASC_FEATURE_THREADS is false there).
//
// A substep is a list of phases (integrate, the grab, each colour batch of each iteration, tethers, each stretch
// batch, contact), every phase cut into chunks and the chunks into T runs (run t: the t-th contiguous part of the
// cloth, thread t's own). Phases carry sequence numbers; one is open at a time. A thread waits for a phase to
// open, takes chunks of its own run and then of the others (compare-and-swap on the run's counter, which also holds
// the phase number, so a thread that arrives late takes nothing of a phase already over), and reports how many it
// did; whoever reports the last chunk opens the next phase. So thread 0 never waits for a helper that is not
// there (a helper descheduled by a busy machine): it does that helper's run itself. It only waits for chunks a
// helper has taken and not finished. Waiting spins a little, then sleeps (host Atomics.wait through an import: a
// wait inside the substep, once inlined next to live vectors, gave wrong cloths in Node 20), so no thread spins
// for long. A chunk is computed by the same arithmetic whichever thread takes it: the cloth does not depend on T.

import {
  COMMAND, DESC, DISPATCH, DISPATCH_SLEEPERS, DONE, PHASE, PHASE_SLEEPERS, RUN_STRIDE, RUNS, SPIN_LIMIT,
} from './layout.generated.as';

/** Springs per chunk (a multiple of 4: chunks keep the quads of the 1-thread pass). */
export const CHUNK_SPRINGS: i32 = 256;
/** Particles per chunk. */
export const CHUNK_PARTICLES: i32 = 1024;
/** Bending stencils per chunk (a stencil is 4–13 particles). */
export const CHUNK_STENCILS: i32 = 128;
/** longest single sleep [ms]: a safety net, the thread is woken when the word changes */
const SLEEP_MS: f64 = 20;

// @ts-ignore: decorator
@external("env", "wait")
declare function hostWait(address: usize, expected: i32, timeoutMs: f64): void;
// @ts-ignore: decorator
@external("env", "notify")
declare function hostNotify(address: usize): void;

/** Waits until the i32 at `at` is no longer `seen`: polls SPIN_LIMIT times, then sleeps, counted in `sleepers`. */
function waitChange(at: usize, seen: i32, sleepers: usize): void {
  if (ASC_FEATURE_THREADS) {
    const spins = load<i32>(SPIN_LIMIT);
    for (let s = 0; s < spins; s++) if (atomic.load<i32>(at) != seen) return;
    while (atomic.load<i32>(at) == seen) {
      atomic.add<i32>(sleepers, 1);
      if (atomic.load<i32>(at) == seen) hostWait(at, seen, SLEEP_MS);
      atomic.sub<i32>(sleepers, 1);
    }
  }
}

/** Waits until phase `seq` is open or over (sequence numbers compare by wrapping difference). */
export function waitPhase(seq: i32): void {
  if (ASC_FEATURE_THREADS) {
    let p = atomic.load<i32>(PHASE);
    while (p - seq < 0) {
      waitChange(PHASE, p, PHASE_SLEEPERS);
      p = atomic.load<i32>(PHASE);
    }
  }
}

/** Opens phase `seq` for T runs (by the thread that completed the one before), waking sleepers. */
function openPhase(seq: i32, T: i32): void {
  if (ASC_FEATURE_THREADS) {
    atomic.store<i32>(DONE, 0);
    const tag = (<i64><u32>seq) << 32;
    for (let v = 0; v < T; v++) atomic.store<i64>(RUNS + <usize>v * RUN_STRIDE, tag);
    atomic.store<i32>(PHASE, seq);
    if (atomic.load<i32>(PHASE_SLEEPERS) > 0) hostNotify(PHASE);
  }
}

// per instance: the run thread t is taking chunks from (0: its own), and the chunks it took in this phase
let runOf: i32 = 0;
let taken: i32 = 0;

/**
 * A chunk of phase `seq` (of `count`) for thread t, or -1 when none is left to take: first from t's own run, then
 * from runs t + 1, t + 2, …
 */
export function claim(t: i32, T: i32, seq: i32, count: i32): i32 {
  if (ASC_FEATURE_THREADS) {
    while (runOf < T) {
      const v = (t + runOf) % T;
      const at = RUNS + <usize>v * RUN_STRIDE;
      const lo = (v * count) / T, hi = ((v + 1) * count) / T;
      let cur = atomic.load<i64>(at);
      while (<i32>(cur >>> 32) == seq && lo + <i32>cur < hi) {
        const prev = atomic.cmpxchg<i64>(at, cur, cur + 1);
        if (prev == cur) {
          taken++;
          return lo + <i32>cur;
        }
        cur = prev;
      }
      runOf++;
    }
  }
  return -1;
}

/** After claim() gave -1: reports this thread's chunks of phase `seq`; the last report opens the next phase. */
export function report(seq: i32, T: i32, count: i32): void {
  if (ASC_FEATURE_THREADS) {
    if (taken > 0 && atomic.add<i32>(DONE, taken) + taken == count) openPhase(seq + 1, T);
    taken = 0;
    runOf = 0;
  }
}

/**
 * Helper thread t's loop: wait for a dispatch, take part in that substep, repeat until told to exit. It reads the

/** Thread 0: starts the substep described by `desc` (xpbd.as.ts describe()) on the helpers. */
export function dispatchSubstep(desc: i64): void {
  if (ASC_FEATURE_THREADS) {
    atomic.store<i64>(DESC, desc);
    atomic.store<i32>(COMMAND, 1);
    atomic.add<i32>(DISPATCH, 1);
    if (atomic.load<i32>(DISPATCH_SLEEPERS) > 0) hostNotify(DISPATCH);
  }
}

/** Thread 0: tells the helpers to leave their loop. */
export function dispatchExit(): void {
  if (ASC_FEATURE_THREADS) {
    atomic.store<i32>(COMMAND, 2);
    atomic.add<i32>(DISPATCH, 1);
    hostNotify(DISPATCH);
  }
}

/** A helper: waits for the dispatch after `seen` and returns its number. */
export function waitDispatch(seen: i32): i32 {
  if (ASC_FEATURE_THREADS) {
    waitChange(DISPATCH, seen, DISPATCH_SLEEPERS);
    return atomic.load<i32>(DISPATCH);
  }
  return seen;
}
