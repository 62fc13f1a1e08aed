// The XPBD substep as a WebAssembly kernel (AssemblyScript; built by src/core/wasm/gen-wasm.mjs into
// xpbd-kernel.generated.ts). The same phases, in the same order, as the TypeScript solver (solvers/xpbd.ts,
// phases.ts): integrate (+ the grab), distance constraints batch by batch, tethers, stretch limiting batch by
// batch, particle contact. The constraint and stretch passes run four springs of a colour batch at once in f32x4
// SIMD lanes (springs of a batch share no particle, so the lanes never write the same particle), contact four
// particles at once; integration and tethers are scalar f64 on f32 data exactly as the TypeScript code computes
// them.
//
// Threads: with the threads build, T instances over one shared memory run the same substep, under the phase
// protocol described at "---- threads ----" below; the result does not depend on T. Thread 0 is the caller's;
// helpers sit in helperLoop() and are started by a dispatch counter in the control block. The single-thread
// build compiles no atomics and runs every phase whole.
//
// Memory: the caller (xpbd-wasm.ts) lays out every array and passes their byte offsets to configure(); the
// control block at CTRL holds the per-substep scalars (its layout is generated, for both sides, by gen-layout.mjs).

// ---- the control block's layout, type ids and flags: generated from the one table (src/core/gen-layout.mjs) ----
import {
  BEND, COLLIDER_RECORD_FLOATS, COLLIDER_SPHERE, KERNEL_FLAG_ACCUMULATE, KERNEL_FLAG_CONTACT, KERNEL_FLAG_FORCES,
  KERNEL_FLAG_STORE_LAMBDA, RUN_STRIDE,
  COLLIDERS, COLLIDER_RECORDS, COMMAND, DAMPING, DEPENETRATION, DESC, DISPATCH, DISPATCH_SLEEPERS, DONE, FLAGS, FRICTION,
  GRAB_AT, GRABBED, GRAVITY, H, ITERATIONS, PHASE, PHASE_SLEEPERS, READY, RUNS, SPIN_LIMIT, STATIC_FRICTION, STRETCH,
  TAYLOR, THICKNESS, THREADS,
} from './layout.generated.as';

const COLLIDER_BYTES: usize = <usize>COLLIDER_RECORD_FLOATS * 8;

// ---- layout, set by configure() in every instance ----
let X: usize = 0; // positions, f32 × 3n
let XP: usize = 0; // previous positions, f32 × 3n
let W: usize = 0; // inverse masses, f32 × n
let F: usize = 0; // forces, f32 × 3n
let LAMBDA: usize = 0; // λ per spring, f32
let ANCHOR: usize = 0; // tether anchor per particle, i32
let TLEN: usize = 0; // tether length per particle, f32
let SPRINGS: usize = 0; // particle pairs, u32 × 2 per spring
let REST: usize = 0; // rest length per spring, f32
let ALPHA: usize = 0; // compliance per spring, f32
let BATCHES: usize = 0; // i32 × 3 per batch: start, end, kind
let BATCH_COUNT: i32 = 0;
let N: i32 = 0; // particles

export function configure(
  x: usize, xp: usize, w: usize, f: usize, lambda: usize, anchor: usize, tlen: usize,
  springs: usize, rest: usize, alpha: usize, batches: usize, batchCount: i32, particles: i32,
): void {
  X = x; XP = xp; W = w; F = f; LAMBDA = lambda; ANCHOR = anchor; TLEN = tlen;
  SPRINGS = springs; REST = rest; ALPHA = alpha; BATCHES = batches; BATCH_COUNT = batchCount; N = particles;
}

// ---- threads ----
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

/** Springs per chunk (a multiple of 4: chunks keep the quads of the 1-thread pass) and particles per chunk. */
const CHUNK_SPRINGS: i32 = 256;
const CHUNK_PARTICLES: i32 = 1024;
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
function waitPhase(seq: i32): void {
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
function claim(t: i32, T: i32, seq: i32, count: i32): i32 {
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
function report(seq: i32, T: i32, count: i32): void {
  if (ASC_FEATURE_THREADS) {
    if (taken > 0 && atomic.add<i32>(DONE, taken) + taken == count) openPhase(seq + 1, T);
    taken = 0;
    runOf = 0;
  }
}

/**
 * Helper thread t's loop: wait for a dispatch, take part in that substep, repeat until told to exit. It reads the
 * substep's phase list from DESC in one atomic load, so a helper that wakes late joins the newest substep.
 */
export function helperLoop(t: i32): void {
  if (ASC_FEATURE_THREADS) {
    let seen = atomic.load<i32>(DISPATCH);
    if (atomic.load<i32>(COMMAND) == 2) return; // the kernel was disposed before this helper started
    atomic.add<i32>(READY, 1);
    for (;;) {
      waitChange(DISPATCH, seen, DISPATCH_SLEEPERS);
      seen = atomic.load<i32>(DISPATCH);
      if (atomic.load<i32>(COMMAND) == 2) return;
      const desc = atomic.load<i64>(DESC);
      if (t < descThreads(desc)) substepPhases(t, desc, false);
    }
  }
}

/**
 * What a substep's phase list depends on, in one word: the first phase's sequence number (bits 0–31), iterations
 * (32–39), particle contact in the kernel (40), a grab (41), T (48–55).
 */
function describe(first: i32, T: i32): i64 {
  return (<i64><u32>first) | (<i64>(load<i32>(ITERATIONS) & 0xff) << 32) | (<i64>((load<i32>(FLAGS) & KERNEL_FLAG_CONTACT) != 0) << 40) |
    (<i64>(load<i32>(GRABBED) >= 0) << 41) | (<i64>T << 48);
}
@inline function descThreads(desc: i64): i32 { return <i32>((desc >>> 48) & 0xff); }

/** Thread 0: one substep (the scalars are in the control block), with the helpers unless THREADS is 1. */
export function substep(): void {
  if (ASC_FEATURE_THREADS) {
    const T = atomic.load<i32>(THREADS);
    if (T > 1) {
      const desc = describe(atomic.load<i32>(PHASE), T);
      atomic.store<i64>(DESC, desc);
      atomic.store<i32>(COMMAND, 1);
      atomic.add<i32>(DISPATCH, 1);
      if (atomic.load<i32>(DISPATCH_SLEEPERS) > 0) hostNotify(DISPATCH);
      waitPhase(substepPhases(0, desc, false));
      return;
    }
  }
  substepPhases(0, describe(0, 1), true);
}

/** Thread 0: tells the helpers to leave helperLoop. */
export function stopHelpers(): void {
  if (ASC_FEATURE_THREADS) {
    atomic.store<i32>(COMMAND, 2);
    atomic.add<i32>(DISPATCH, 1);
    hostNotify(DISPATCH);
  }
}

const INTEGRATE: i32 = 0, GRAB: i32 = 1, DISTANCE: i32 = 2, TETHERS: i32 = 3, STRETCH_LIMIT: i32 = 4, CONTACT: i32 = 5;

/**
 * Thread t's part of one substep: integrate, the grab, the distance constraints batch by batch (per iteration),
 * tethers, stretch limiting batch by batch, particle contact. `alone`: thread 0 runs every phase whole, without
 * the phase protocol. Returns the sequence number after the last phase (the next substep's first).
 */
function substepPhases(t: i32, desc: i64, alone: bool): i32 {
  const T = descThreads(desc);
  let seq = <i32>desc;
  seq = phase(t, T, seq, alone, INTEGRATE, 0, 0, N, CHUNK_PARTICLES);
  if (((desc >>> 41) & 1) != 0) seq = phase(t, T, seq, alone, GRAB, 0, 0, 1, 1);
  const iterations = <i32>((desc >>> 32) & 0xff);
  for (let it = 0; it < iterations; it++) {
    for (let b = 0; b < BATCH_COUNT; b++) {
      const rec = BATCHES + <usize>b * 12;
      seq = phase(t, T, seq, alone, DISTANCE, b, load<i32>(rec), load<i32>(rec, 4), CHUNK_SPRINGS);
    }
  }
  seq = phase(t, T, seq, alone, TETHERS, 0, 0, N, CHUNK_PARTICLES);
  for (let b = 0; b < BATCH_COUNT; b++) {
    const rec = BATCHES + <usize>b * 12;
    if (load<i32>(rec, 8) == BEND) continue;
    seq = phase(t, T, seq, alone, STRETCH_LIMIT, b, load<i32>(rec), load<i32>(rec, 4), CHUNK_SPRINGS);
  }
  if (((desc >>> 40) & 1) != 0) seq = phase(t, T, seq, alone, CONTACT, 0, 0, N, CHUNK_PARTICLES);
  return seq;
}

/**
 * One phase over items [start, end) in chunks of `size`: the whole range when alone, else thread t's chunks under
 * the phase protocol. An empty range is no phase. Returns the next phase's sequence number.
 */
function phase(t: i32, T: i32, seq: i32, alone: bool, kind: i32, batch: i32, start: i32, end: i32, size: i32): i32 {
  if (end <= start) return seq;
  if (alone) {
    run(kind, batch, start, end);
    return seq;
  }
  const count = (end - start + size - 1) / size;
  waitPhase(seq);
  for (let c = claim(t, T, seq, count); c >= 0; c = claim(t, T, seq, count)) {
    const c0 = start + c * size;
    run(kind, batch, c0, min(end, c0 + size));
  }
  report(seq, T, count);
  return seq + 1;
}

/** Items [i0, i1) of one phase; the scalars are read here, once the chunk is taken (they are this substep's). */
function run(kind: i32, batch: i32, i0: i32, i1: i32): void {
  const flags = load<i32>(FLAGS);
  switch (kind) {
    case INTEGRATE: integrate(i0, i1, (flags & KERNEL_FLAG_FORCES) != 0); break;
    case GRAB: {
      // after integration (the grabbed particle's x_prev is its position before the grab moves it)
      const gp = X + <usize>load<i32>(GRABBED) * 12;
      store<f32>(gp, <f32>load<f64>(GRAB_AT));
      store<f32>(gp, <f32>load<f64>(GRAB_AT + 8), 4);
      store<f32>(gp, <f32>load<f64>(GRAB_AT + 16), 8);
      break;
    }
    case DISTANCE: {
      const h = load<f64>(H);
      const bend = load<i32>(BATCHES + <usize>batch * 12, 8) == BEND;
      solveDistance(i0, i1, <f32>(1 / (h * h)), <f32>(load<f64>(DAMPING) / h), bend ? Infinity : <f32>load<f64>(STRETCH),
        (flags & KERNEL_FLAG_ACCUMULATE) != 0, (flags & KERNEL_FLAG_STORE_LAMBDA) != 0);
      break;
    }
    case TETHERS: solveTethers(i0, i1, load<f64>(STRETCH)); break;
    case STRETCH_LIMIT: limitStretch(i0, i1, <f32>load<f64>(STRETCH)); break;
    default: collideParticles(i0, i1);
  }
}

// ---- phases ----

/** Position Verlet as phases.ts integrate(): x ← 2x − x_prev + c·h²·(g + w·f), x_prev ← x. */
function integrate(p0: i32, p1: i32, withForces: bool): void {
  const h = load<f64>(H);
  const h2 = load<f64>(TAYLOR) * h * h;
  const gx = load<f64>(GRAVITY) * h2, gy = load<f64>(GRAVITY + 8) * h2, gz = load<f64>(GRAVITY + 16) * h2;
  for (let i = p0; i < p1; i++) {
    const j = <usize>i * 12;
    const x0 = <f64>load<f32>(X + j), y0 = <f64>load<f32>(X + j, 4), z0 = <f64>load<f32>(X + j, 8);
    const wi = <f64>load<f32>(W + (<usize>i << 2));
    if (wi != 0) {
      let ax = gx, ay = gy, az = gz;
      if (withForces) {
        const s = wi * h2;
        ax += <f64>load<f32>(F + j) * s; ay += <f64>load<f32>(F + j, 4) * s; az += <f64>load<f32>(F + j, 8) * s;
      }
      store<f32>(X + j, <f32>(x0 + (x0 - <f64>load<f32>(XP + j)) + ax));
      store<f32>(X + j, <f32>(y0 + (y0 - <f64>load<f32>(XP + j, 4)) + ay), 4);
      store<f32>(X + j, <f32>(z0 + (z0 - <f64>load<f32>(XP + j, 8)) + az), 8);
    }
    store<f32>(XP + j, <f32>x0); store<f32>(XP + j, <f32>y0, 4); store<f32>(XP + j, <f32>z0, 8);
  }
}

// Four f32 at byte offsets o0…o3 from base, as the lanes of one vector (and back).
@inline function gather(base: usize, o0: usize, o1: usize, o2: usize, o3: usize): v128 {
  let v = v128.load32_zero(base + o0);
  v = v128.load32_lane(base + o1, v, 1);
  v = v128.load32_lane(base + o2, v, 2);
  return v128.load32_lane(base + o3, v, 3);
}

@inline function scatter(base: usize, o0: usize, o1: usize, o2: usize, o3: usize, v: v128): void {
  v128.store32_lane(base + o0, v, 0);
  v128.store32_lane(base + o1, v, 1);
  v128.store32_lane(base + o2, v, 2);
  v128.store32_lane(base + o3, v, 3);
}

// Four particles' xyz as one v128 load each (x, y, z and the next float, never used), transposed to x, y, z lanes.
@inline function lo2(a: v128, b: v128): v128 { return v128.shuffle<f32>(a, b, 0, 4, 1, 5); }
@inline function hi2(a: v128, b: v128): v128 { return v128.shuffle<f32>(a, b, 2, 6, 3, 7); }
@inline function lanesXY0(t0: v128, t1: v128): v128 { return v128.shuffle<f32>(t0, t1, 0, 1, 4, 5); }
@inline function lanesXY1(t0: v128, t1: v128): v128 { return v128.shuffle<f32>(t0, t1, 2, 3, 6, 7); }

// Writes lanes x, y, z back to four particles: x and y as one 8-byte store, z as a 4-byte store (never past z).
@inline function store4(base: usize, o0: usize, o1: usize, o2: usize, o3: usize, x: v128, y: v128, z: v128): void {
  const u0 = lo2(x, y), u1 = hi2(x, y);
  v128.store64_lane(base + o0, u0, 0); v128.store32_lane(base + o0 + 8, z, 0);
  v128.store64_lane(base + o1, u0, 1); v128.store32_lane(base + o1 + 8, z, 1);
  v128.store64_lane(base + o2, u1, 0); v128.store32_lane(base + o2 + 8, z, 2);
  v128.store64_lane(base + o3, u1, 1); v128.store32_lane(base + o3 + 8, z, 3);
}

@inline function dot3(ax: v128, ay: v128, az: v128, bx: v128, by: v128, bz: v128): v128 {
  return f32x4.add(f32x4.add(f32x4.mul(ax, bx), f32x4.mul(ay, by)), f32x4.mul(az, bz));
}

/**
 * Distance constraints [s0, s1) of one batch, as solvers/xpbd.ts solveDistanceConstraints() in f32:
 * Δλ = (−C − α̃λ − γ∇C·(x − x_prev)) / ((1 + γ)(w_a + w_b) + α̃) with the hard cap at capFactor × rest.
 * Four springs per step; the last 1–3 repeat the last spring in the spare lanes (same values written twice).
 * λ is read only when it accumulates and written only when `storeLambda` (several iterations, or the frame's last
 * substep: what is read of λ after a frame is that substep's).
 */
function solveDistance(
  s0: i32, s1: i32, invH2: f32, betaOverH: f32, capFactor: f32, accumulate: bool, storeLambda: bool,
): void {
  // the layout's globals in locals: V8 keeps them in registers across the loop
  const x = X, xp = XP, w = W, sp = SPRINGS, restP = REST, alphaP = ALPHA, lamP = LAMBDA;
  const vInvH2 = f32x4.splat(invH2), vBeta = f32x4.splat(betaOverH), vCap = f32x4.splat(capFactor);
  const one = f32x4.splat(1), zero = f32x4.splat(0), tiny = f32x4.splat(1e-12), inf = f32x4.splat(Infinity);
  const damped = betaOverH > 0;
  for (let s = s0; s < s1; s += 4) {
    const k1 = min(s + 1, s1 - 1), k2 = min(s + 2, s1 - 1), k3 = min(s + 3, s1 - 1);
    const full = s + 4 <= s1;
    const pa0 = <usize>load<u32>(sp + (<usize>s << 3)), pb0 = <usize>load<u32>(sp + (<usize>s << 3), 4);
    const pa1 = <usize>load<u32>(sp + (<usize>k1 << 3)), pb1 = <usize>load<u32>(sp + (<usize>k1 << 3), 4);
    const pa2 = <usize>load<u32>(sp + (<usize>k2 << 3)), pb2 = <usize>load<u32>(sp + (<usize>k2 << 3), 4);
    const pa3 = <usize>load<u32>(sp + (<usize>k3 << 3)), pb3 = <usize>load<u32>(sp + (<usize>k3 << 3), 4);
    const a0 = pa0 * 12, a1 = pa1 * 12, a2 = pa2 * 12, a3 = pa3 * 12;
    const b0 = pb0 * 12, b1 = pb1 * 12, b2 = pb2 * 12, b3 = pb3 * 12;
    let rest: v128, alpha: v128, lambda = zero;
    const useLambda = accumulate || storeLambda;
    if (full) {
      rest = v128.load(restP + (<usize>s << 2));
      alpha = v128.load(alphaP + (<usize>s << 2));
      if (useLambda) lambda = v128.load(lamP + (<usize>s << 2));
    } else {
      const o0 = <usize>s << 2, o1 = <usize>k1 << 2, o2 = <usize>k2 << 2, o3 = <usize>k3 << 2;
      rest = gather(restP, o0, o1, o2, o3);
      alpha = gather(alphaP, o0, o1, o2, o3);
      if (useLambda) lambda = gather(lamP, o0, o1, o2, o3);
    }
    const wa = gather(w, pa0 << 2, pa1 << 2, pa2 << 2, pa3 << 2);
    const wb = gather(w, pb0 << 2, pb1 << 2, pb2 << 2, pb3 << 2);
    const qa0 = v128.load(x + a0), qa1 = v128.load(x + a1), qa2 = v128.load(x + a2), qa3 = v128.load(x + a3);
    const qb0 = v128.load(x + b0), qb1 = v128.load(x + b1), qb2 = v128.load(x + b2), qb3 = v128.load(x + b3);
    const ta0 = lo2(qa0, qa1), ta1 = lo2(qa2, qa3), tb0 = lo2(qb0, qb1), tb1 = lo2(qb2, qb3);
    const axv = lanesXY0(ta0, ta1), ayv = lanesXY1(ta0, ta1), azv = lanesXY0(hi2(qa0, qa1), hi2(qa2, qa3));
    const bxv = lanesXY0(tb0, tb1), byv = lanesXY1(tb0, tb1), bzv = lanesXY0(hi2(qb0, qb1), hi2(qb2, qb3));
    const dx = f32x4.sub(axv, bxv), dy = f32x4.sub(ayv, byv), dz = f32x4.sub(azv, bzv);
    const len0 = f32x4.sqrt(dot3(dx, dy, dz, dx, dy, dz));
    const wsum = f32x4.add(wa, wb);
    // skipped as in the TypeScript solver: no stiffness, both particles fixed, coincident particles
    const valid = v128.and(v128.and(f32x4.ne(alpha, inf), f32x4.ne(wsum, zero)), f32x4.ge(len0, tiny));
    const len = f32x4.max(len0, tiny);
    const alphaT = f32x4.mul(alpha, vInvH2);
    const gamma = f32x4.mul(alpha, vBeta);
    const D = f32x4.add(f32x4.mul(f32x4.add(one, gamma), wsum), alphaT);
    const q = f32x4.div(one, f32x4.mul(len, D));
    const lam = accumulate ? lambda : zero;
    const dlE = f32x4.mul(f32x4.mul(f32x4.sub(f32x4.sub(rest, len), f32x4.mul(alphaT, lam)), len), q);
    let dl = dlE;
    if (damped) {
      // x_prev of a and b, transposed as above: r = d − (x_prev,a − x_prev,b) is the relative motion
      const ea0 = v128.load(xp + a0), ea1 = v128.load(xp + a1), ea2 = v128.load(xp + a2), ea3 = v128.load(xp + a3);
      const eb0 = v128.load(xp + b0), eb1 = v128.load(xp + b1), eb2 = v128.load(xp + b2), eb3 = v128.load(xp + b3);
      const da0 = f32x4.sub(ea0, eb0), da1 = f32x4.sub(ea1, eb1), da2 = f32x4.sub(ea2, eb2), da3 = f32x4.sub(ea3, eb3);
      const u0 = lo2(da0, da1), u1 = lo2(da2, da3);
      const rx = f32x4.sub(dx, lanesXY0(u0, u1)), ry = f32x4.sub(dy, lanesXY1(u0, u1));
      const rz = f32x4.sub(dz, lanesXY0(hi2(da0, da1), hi2(da2, da3)));
      dl = f32x4.sub(dl, f32x4.mul(f32x4.mul(gamma, q), dot3(rx, ry, rz, dx, dy, dz)));
    }
    if (storeLambda) {
      const lamNew = v128.bitselect(f32x4.add(lam, dlE), lambda, valid);
      if (full) v128.store(lamP + (<usize>s << 2), lamNew);
      else scatter(lamP, <usize>s << 2, <usize>k1 << 2, <usize>k2 << 2, <usize>k3 << 2, lamNew);
    }
    // hard stretch limit: the new length len + wsum·dl may not exceed cap × rest (bend: cap ∞, and as in
    // TypeScript a NaN excess — ∞ × a zero rest length — does not count as over)
    const over = f32x4.sub(f32x4.add(len, f32x4.mul(wsum, dl)), f32x4.mul(vCap, rest));
    dl = f32x4.sub(dl, v128.and(f32x4.div(over, wsum), f32x4.gt(over, zero)));
    dl = v128.and(dl, valid);
    const invLen = v128.and(f32x4.mul(D, q), valid);
    const nx = f32x4.mul(dx, invLen), ny = f32x4.mul(dy, invLen), nz = f32x4.mul(dz, invLen);
    const sa = f32x4.mul(wa, dl), sb = f32x4.mul(wb, dl);
    store4(x, a0, a1, a2, a3, f32x4.add(axv, f32x4.mul(sa, nx)), f32x4.add(ayv, f32x4.mul(sa, ny)), f32x4.add(azv, f32x4.mul(sa, nz)));
    store4(x, b0, b1, b2, b3, f32x4.sub(bxv, f32x4.mul(sb, nx)), f32x4.sub(byv, f32x4.mul(sb, ny)), f32x4.sub(bzv, f32x4.mul(sb, nz)));
  }
}

/** Tethers as tethers.ts solveTethers(), f64 on f32 data. */
function solveTethers(p0: i32, p1: i32, sf: f64): void {
  for (let i = p0; i < p1; i++) {
    const a = load<i32>(ANCHOR + (<usize>i << 2));
    if (a < 0 || load<f32>(W + (<usize>i << 2)) == 0) continue;
    const j = X + <usize>i * 12, k = X + <usize>a * 12;
    const kx = <f64>load<f32>(k), ky = <f64>load<f32>(k, 4), kz = <f64>load<f32>(k, 8);
    const dx = <f64>load<f32>(j) - kx, dy = <f64>load<f32>(j, 4) - ky, dz = <f64>load<f32>(j, 8) - kz;
    const d2 = dx * dx + dy * dy + dz * dz;
    const max = sf * <f64>load<f32>(TLEN + (<usize>i << 2));
    if (d2 <= max * max) continue;
    const s = max / Math.sqrt(d2);
    store<f32>(j, <f32>(kx + dx * s)); store<f32>(j, <f32>(ky + dy * s), 4); store<f32>(j, <f32>(kz + dz * s), 8);
  }
}

/** Stretch limiting of springs [s0, s1) of one batch, as phases.ts limitStretch(), in f32. */
function limitStretch(s0: i32, s1: i32, sf: f32): void {
  // the layout's globals in locals: V8 keeps them in registers across the loop
  const x = X, w = W, sp = SPRINGS, restP = REST;
  const vSf = f32x4.splat(sf), zero = f32x4.splat(0);
  for (let s = s0; s < s1; s += 4) {
    const k1 = min(s + 1, s1 - 1), k2 = min(s + 2, s1 - 1), k3 = min(s + 3, s1 - 1);
    const pa0 = <usize>load<u32>(sp + (<usize>s << 3)), pb0 = <usize>load<u32>(sp + (<usize>s << 3), 4);
    const pa1 = <usize>load<u32>(sp + (<usize>k1 << 3)), pb1 = <usize>load<u32>(sp + (<usize>k1 << 3), 4);
    const pa2 = <usize>load<u32>(sp + (<usize>k2 << 3)), pb2 = <usize>load<u32>(sp + (<usize>k2 << 3), 4);
    const pa3 = <usize>load<u32>(sp + (<usize>k3 << 3)), pb3 = <usize>load<u32>(sp + (<usize>k3 << 3), 4);
    const a0 = pa0 * 12, a1 = pa1 * 12, a2 = pa2 * 12, a3 = pa3 * 12;
    const b0 = pb0 * 12, b1 = pb1 * 12, b2 = pb2 * 12, b3 = pb3 * 12;
    const rest = s + 4 <= s1 ? v128.load(restP + (<usize>s << 2))
      : gather(restP, <usize>s << 2, <usize>k1 << 2, <usize>k2 << 2, <usize>k3 << 2);
    const qa0 = v128.load(x + a0), qa1 = v128.load(x + a1), qa2 = v128.load(x + a2), qa3 = v128.load(x + a3);
    const qb0 = v128.load(x + b0), qb1 = v128.load(x + b1), qb2 = v128.load(x + b2), qb3 = v128.load(x + b3);
    const ta0 = lo2(qa0, qa1), ta1 = lo2(qa2, qa3), tb0 = lo2(qb0, qb1), tb1 = lo2(qb2, qb3);
    const axv = lanesXY0(ta0, ta1), ayv = lanesXY1(ta0, ta1), azv = lanesXY0(hi2(qa0, qa1), hi2(qa2, qa3));
    const bxv = lanesXY0(tb0, tb1), byv = lanesXY1(tb0, tb1), bzv = lanesXY0(hi2(qb0, qb1), hi2(qb2, qb3));
    const dx = f32x4.sub(axv, bxv), dy = f32x4.sub(ayv, byv), dz = f32x4.sub(azv, bzv);
    const len2 = dot3(dx, dy, dz, dx, dy, dz);
    const max = f32x4.mul(vSf, rest);
    const long = f32x4.gt(len2, f32x4.mul(max, max));
    if (!v128.any_true(long)) continue; // the common case: no spring of the four is too long
    const wa = gather(w, pa0 << 2, pa1 << 2, pa2 << 2, pa3 << 2);
    const wb = gather(w, pb0 << 2, pb1 << 2, pb2 << 2, pb3 << 2);
    const wsum = f32x4.add(wa, wb);
    const over = v128.and(long, f32x4.ne(wsum, zero));
    if (!v128.any_true(over)) continue;
    const len = f32x4.sqrt(len2);
    const scale = v128.and(f32x4.div(f32x4.sub(len, max), f32x4.mul(len, wsum)), over);
    const sa = f32x4.mul(wa, scale), sb = f32x4.mul(wb, scale);
    store4(x, a0, a1, a2, a3, f32x4.sub(axv, f32x4.mul(sa, dx)), f32x4.sub(ayv, f32x4.mul(sa, dy)), f32x4.sub(azv, f32x4.mul(sa, dz)));
    store4(x, b0, b1, b2, b3, f32x4.add(bxv, f32x4.mul(sb, dx)), f32x4.add(byv, f32x4.mul(sb, dy)), f32x4.add(bzv, f32x4.mul(sb, dz)));
  }
}

/** Position-based Coulomb friction scale, as phases.ts frictionScale(). */
@inline function frictionScale(tangential: f64, depth: f64): f64 {
  if (tangential < 1e-12) return 0;
  if (tangential < load<f64>(STATIC_FRICTION) * depth) return 1;
  return min((load<f64>(FRICTION) * depth) / tangential, 1);
}

/** Contact of particle i with one collider record, exactly as phases.ts collide() (f64 on f32 data): the tail. */
@inline function contactParticle(i: i32, sphere: bool, c0: f64, c1: f64, c2: f64, r: f64, far: f64, th: f64, recover: f64): void {
  if (load<f32>(W + (<usize>i << 2)) == 0) return;
  const j = X + <usize>i * 12, jp = XP + <usize>i * 12;
  const px = <f64>load<f32>(j), py = <f64>load<f32>(j, 4), pz = <f64>load<f32>(j, 8);
  let d: f64, nx: f64, ny: f64, nz: f64;
  if (sphere) {
    const dx = px - c0, dy = py - c1, dz = pz - c2;
    const d2 = dx * dx + dy * dy + dz * dz;
    if (far > 0 && d2 >= far * far) return;
    const dd = Math.sqrt(d2);
    if (dd > 1e-12) { nx = dx / dd; ny = dy / dd; nz = dz / dd; } else { nx = 0; ny = 1; nz = 0; }
    d = dd - r;
  } else {
    nx = 0; ny = 1; nz = 0;
    d = py - c0;
  }
  if (d >= th) return;
  const ex = <f64>load<f32>(jp), ey = <f64>load<f32>(jp, 4), ez = <f64>load<f32>(jp, 8);
  const mx = px - ex, my = py - ey, mz = pz - ez;
  const mn = mx * nx + my * ny + mz * nz;
  const depth = min(th - d, max(-mn, 0) + recover);
  const tx = mx - mn * nx, ty = my - mn * ny, tz = mz - mn * nz;
  const s = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), depth);
  store<f32>(j, <f32>(px + (depth * nx - s * tx)));
  store<f32>(j, <f32>(py + (depth * ny - s * ty)), 4);
  store<f32>(j, <f32>(pz + (depth * nz - s * tz)), 8);
  // the outward normal motion the push-out made is not velocity
  const made = min(mn + depth, depth);
  if (made > 0) {
    store<f32>(jp, <f32>(ex + made * nx)); store<f32>(jp, <f32>(ey + made * ny), 4); store<f32>(jp, <f32>(ez + made * nz), 8);
  }
}

/**
 * Particle contact against the collider records, as phases.ts collide() does for shapes that need no triangle
 * contact: each particle within the thickness is pushed out along the normal, then friction removes (static) or
 * reduces (kinetic) its tangential motion over the substep, and the outward motion the push-out made moves x_prev
 * too (a push-out never launches the cloth). Four particles at a time in f32x4 lanes; the last 1–3
 * particles of the cloth one by one in f64 (contactParticle).
 */
function collideParticles(p0: i32, p1: i32): void {
  const x = X, xp = XP, w = W;
  const th = load<f64>(THICKNESS);
  const recover = load<f64>(DEPENETRATION) * load<f64>(H);
  const vTh = f32x4.splat(<f32>th), vRecover = f32x4.splat(<f32>recover);
  const vMuS = f32x4.splat(<f32>load<f64>(STATIC_FRICTION)), vMuK = f32x4.splat(<f32>load<f64>(FRICTION));
  const zero = f32x4.splat(0), one = f32x4.splat(1), tiny = f32x4.splat(1e-12);
  const count = load<i32>(COLLIDERS);
  for (let c = 0; c < count; c++) {
    const rec = COLLIDER_RECORDS + <usize>c * COLLIDER_BYTES;
    const sphere = load<f64>(rec) == <f64>COLLIDER_SPHERE;
    const c0 = load<f64>(rec, 8), c1 = load<f64>(rec, 16), c2 = load<f64>(rec, 24), r = load<f64>(rec, 32);
    const far = r + th;
    const vc0 = f32x4.splat(<f32>c0), vc1 = f32x4.splat(<f32>c1), vc2 = f32x4.splat(<f32>c2), vR = f32x4.splat(<f32>r);
    const vFar2 = f32x4.splat(far > 0 ? <f32>(far * far) : Infinity);
    let i = p0;
    for (; i + 4 <= p1; i += 4) {
      const o = <usize>i * 12;
      const q0 = v128.load(x + o), q1 = v128.load(x + o, 12), q2 = v128.load(x + o, 24), q3 = v128.load(x + o, 36);
      const t0 = lo2(q0, q1), t1 = lo2(q2, q3);
      const px = lanesXY0(t0, t1), py = lanesXY1(t0, t1), pz = lanesXY0(hi2(q0, q1), hi2(q2, q3));
      let nx = zero, ny = one, nz = zero, d: v128, touching: v128;
      if (sphere) {
        const dx = f32x4.sub(px, vc0), dy = f32x4.sub(py, vc1), dz = f32x4.sub(pz, vc2);
        const d2 = dot3(dx, dy, dz, dx, dy, dz);
        touching = f32x4.lt(d2, vFar2);
        if (!v128.any_true(touching)) continue;
        const dd = f32x4.sqrt(d2);
        // the outward normal, or up for a particle at the very centre
        const away = f32x4.gt(dd, tiny);
        const inv = f32x4.div(one, f32x4.max(dd, tiny));
        nx = v128.bitselect(f32x4.mul(dx, inv), zero, away);
        ny = v128.bitselect(f32x4.mul(dy, inv), one, away);
        nz = v128.bitselect(f32x4.mul(dz, inv), zero, away);
        d = f32x4.sub(dd, vR);
      } else {
        d = f32x4.sub(py, vc0);
        touching = i32x4.splat(-1);
      }
      touching = v128.and(v128.and(touching, f32x4.lt(d, vTh)), f32x4.ne(v128.load(w + (<usize>i << 2)), zero));
      if (!v128.any_true(touching)) continue;
      // motion over the substep so far, its normal part, and the push-out (contactParticle() in lanes)
      const e0 = v128.load(xp + o), e1 = v128.load(xp + o, 12), e2 = v128.load(xp + o, 24), e3 = v128.load(xp + o, 36);
      const u0 = lo2(e0, e1), u1 = lo2(e2, e3);
      const ex = lanesXY0(u0, u1), ey = lanesXY1(u0, u1), ez = lanesXY0(hi2(e0, e1), hi2(e2, e3));
      const mx = f32x4.sub(px, ex), my = f32x4.sub(py, ey), mz = f32x4.sub(pz, ez);
      const mn = dot3(mx, my, mz, nx, ny, nz);
      const depth = f32x4.min(f32x4.sub(vTh, d), f32x4.add(f32x4.max(f32x4.neg(mn), zero), vRecover));
      const tx = f32x4.sub(mx, f32x4.mul(mn, nx)), ty = f32x4.sub(my, f32x4.mul(mn, ny)), tz = f32x4.sub(mz, f32x4.mul(mn, nz));
      const tl = f32x4.sqrt(dot3(tx, ty, tz, tx, ty, tz));
      // frictionScale(): 0 for no motion, 1 inside the static cone, else min(μk·depth/|t|, 1)
      const kinetic = f32x4.min(f32x4.div(f32x4.mul(vMuK, depth), f32x4.max(tl, tiny)), one);
      const scale = v128.and(v128.bitselect(one, kinetic, f32x4.lt(tl, f32x4.mul(vMuS, depth))), f32x4.ge(tl, tiny));
      store4(x, o, o + 12, o + 24, o + 36,
        v128.bitselect(f32x4.add(px, f32x4.sub(f32x4.mul(depth, nx), f32x4.mul(scale, tx))), px, touching),
        v128.bitselect(f32x4.add(py, f32x4.sub(f32x4.mul(depth, ny), f32x4.mul(scale, ty))), py, touching),
        v128.bitselect(f32x4.add(pz, f32x4.sub(f32x4.mul(depth, nz), f32x4.mul(scale, tz))), pz, touching));
      // the outward normal motion the push-out made (mn + depth, at most depth) moves x_prev too: not velocity
      const made = f32x4.min(f32x4.add(mn, depth), depth);
      const launched = v128.and(touching, f32x4.gt(made, zero));
      if (v128.any_true(launched)) {
        store4(xp, o, o + 12, o + 24, o + 36,
          v128.bitselect(f32x4.add(ex, f32x4.mul(made, nx)), ex, launched),
          v128.bitselect(f32x4.add(ey, f32x4.mul(made, ny)), ey, launched),
          v128.bitselect(f32x4.add(ez, f32x4.mul(made, nz)), ez, launched));
      }
    }
    for (; i < p1; i++) contactParticle(i, sphere, c0, c1, c2, r, far, th, recover);
  }
}
