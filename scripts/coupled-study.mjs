#!/usr/bin/env node
// Issue 10: the global stretch step and the global bending step solved together instead of split (docs/physics.md,
// "The standard fabric tests", "Solving both together: the prototypes"). Prototypes outside the core: the TypeScript
// kernel runs the scene with its two global phases replaced by one of
//   split      the library's own split (stretch pass, then bending step): the baseline
//   sweep      the scene as it is (springs swept one at a time, the hinges solved together)
//   admm       ADMM (Boyd et al. 2011): a stretch copy x and a bending copy z of the positions, each step with the
//              share a (stretch) or 1 − a (bending) of the inertia M/h² and the penalty c·M/h² on x = z, the scaled
//              dual u carried from substep to substep (at rest the fixed point is the coupled equilibrium exactly)
//              [--a 0.5] [--c 10] [--iterations 3] [--relax ω (u += ω·(x − z))] [--reset (u = 0 each substep)]
//              [--from xi|prev|y (what the first iteration's bending step is pulled to, with u: the prediction without
//              gravity, x + h·v, the positions at the substep's start, or the prediction; xi and prev damp free motion:
//              --scene fall)]
//              [--contact-inside (the colliders' contact on x inside each iteration, before the dual's update)]
//              [--contact-dual (u gains what the contact after the substep moved, as if its last update had seen it)]
//              [--contact-carry (the particles' contact push carried into the next substep's prediction as a force,
//              friction bounded by it: carriedContact below)]
//   admm-q     the same with the penalty c·(M/h² + Q) (Q: the stencils' elastic Hessian on the free particles), so the
//              stretch copy's matrix holds c·Q and the bending copy's (1 + c)·Q (same options)
//   balanced   balanced splitting (Speth, Green, MacNamara & Strang 2013): the stretch step with the bending force at
//              the substep's start, −Q·x_n, then the bending step with only its increment, ½(x − x_n)ᵀQ(x − x_n)
//              [--dir y|xi|prev (where the local step takes the springs' directions: the prediction, the prediction
//              without gravity, the substep's start)] [--passes P (stretch passes)]
//   corrected  the split, then P passes of the springs and the stencils in one matrix (a third factor) from the
//              prediction, the springs' directions from the split's result [--passes P] [--carry ω (directions from
//              the split's result less b, b += ω·(the split's result − the corrected one − b) each substep; 0)]
//   joint      Projective Dynamics on the springs and the stencils in one matrix (the corrected split's factor): P
//              passes from the prediction, each local step where the last pass left the cloth [--passes P] [--rho ρ
//              (Chebyshev's acceleration, as cheb; 0: plain passes)] [--gamma γ]
//   cheb       the split with its P stretch passes accelerated by Chebyshev's semi-iterative method (Wang 2015,
//              "A Chebyshev Semi-Iterative Approach for Accelerating Projective and Position-based Dynamics")
//              [--passes P] [--rho ρ (the estimated spectral radius of one pass, 0.95)] [--gamma γ (under-relaxation, 0.9)]
//   sweep-pd   the springs swept one at a time (XPBD), the stencils' global step, then P passes of both in one matrix
//              from the prediction, the springs' directions from where those left the cloth [--passes P] [--carry ω (as
//              above)]
//              [--dir xi (the sweep and the bending from the prediction without gravity)] [--no-sweep] [--no-bend]
//              [--spring-force (the springs' elastic force at the substep's start added, h²/m times it, before the
//              bending step: exact at rest, explicit, and it blows up)] [--angles (the springs whose directions the
//              sweep and the bending left farthest from the result's)]
//   two-level  the sweep with a coarse correction over a grid of cells (coarse-correction.mjs): of the positions
//              (--space primal, a Gauss–Newton step) or of the springs' multipliers (--space dual); options below
// and prints the reading (the cantilever's c / c_theory, the Cusick disc's drape coefficient and folds, the hanging
// 1 m sheet's elongation and middle strain over theory, rubber or cotton, 32 faces; for `fall`, a free cloth's fall
// over 0.5 s as a share of ½gt², 1 where the step keeps free motion; for `swing`, a sheet hung by one corner, the
// centroid's height: it cannot rise above the 1.5 m of its start; for `pendulum`, dissipation.mjs's swing without
// damping, the share of its energy kept over 8 s), the elastic
// and kinetic energy, and ms per frame; then the reading every 0.5 s over the last 3 s.
//   npx tsc -p tsconfig.build.json && node scripts/coupled-study.mjs --mode M [--scene cantilever|cusick|hanging|fall|swing|pendulum|
//     any built-in scene (the reading: the centroid's height and the largest strain)]
//     [--fabric F] [--resolution R] [--substeps S] [--set path=value ...] [--no-pedestal (cusick without its pedestal collider: the clamp
//     only)] [--trace (the reading every 0.05 s)] [--where (the fastest particles at the end)] [--newton N (then Newton
//     on the model's static energy from the end state, as drape-equilibrium.mjs: the nearest equilibrium)] [--rows (the
//     hanging sheet's strain row by row)] [options of the mode]
import { builtinScene, FABRICS, setScenePath, Simulation, validateScene } from '../dist/core/index.js';
import { bendingStencils } from '../dist/core/model.js';
import { REFERENCE } from '../dist/core/reference.js';
import { PHASE } from '../dist/core/schedule.js';
import { BendingSystem, solveGlobalBending } from '../dist/core/solvers/global-bending.js';
import { addSpringTerms, StretchSystem, solveGlobalStretch } from '../dist/core/solvers/global-stretch.js';
import { PrefactoredSystem } from '../dist/core/solvers/prefactored.js';
import { REFERENCE_SOLVER } from '../dist/core/solvers/sparse.js';
import { solveDistanceConstraints } from '../dist/core/solvers/xpbd.js';
import { hangingScene, hangingTheory, measureHanging } from './solver-study-common.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const flag = (name) => process.argv.includes(`--${name}`);
const mode = arg('mode', 'admm');
if (!['prev', 'y', 'xi'].includes(arg('from', 'xi'))) throw new Error(`--from: prev, y or xi, got ${arg('from')}`);
if (!['split', 'sweep', 'admm', 'admm-q', 'balanced', 'corrected', 'sweep-pd', 'cheb', 'joint', 'two-level'].includes(mode)) throw new Error(`--mode: split, sweep, admm, admm-q, balanced, corrected, sweep-pd, cheb, joint or two-level, got ${mode}`);
const SHARE = Number(arg('a', '0.5')), PENALTY = Number(arg('c', '10')), ITERATIONS = Number(arg('iterations', '3'));
const RELAX = Number(arg('relax', '1')), CARRY = Number(arg('carry', '0')), PASSES = Number(arg('passes', '1')), DIR = arg('dir', 'y');

/**
 * The springs and the stencils in one matrix: s·M/h² + σ·Σ (k + β/h)·SᵀS + Σ (ε/α + δ·τ/(hα))·K·Kᵀ, over both graphs
 * (weights { mass: s, springs: σ, elastic: ε, damping: δ }; by default 1, 1, 1, 1: Projective Dynamics with both).
 */
class CombinedSystem extends PrefactoredSystem {
  constructor(model, params, stretch, bending, weights = {}) {
    const n = model.particleCount, near = Array.from({ length: n }, () => new Set());
    const join = (a, b) => { if (a !== b) { near[a].add(b); near[b].add(a); } };
    for (let s = 0; s < stretch.k.length; s++) join(stretch.springs[2 * s], stretch.springs[2 * s + 1]);
    const { start, cols } = bending.pullMatrix;
    for (let i = 0; i < n; i++) for (let p = start[i]; p < start[i + 1]; p++) join(i, cols[p]);
    const rowStart = new Int32Array(n + 1), all = [];
    for (let i = 0; i < n; i++) { all.push(...near[i]); rowStart[i + 1] = all.length; }
    const w = { mass: 1, springs: 1, elastic: 1, damping: 1, ...weights };
    super(model, Float64Array.from(params.particleMass, (m) => m * w.mass), rowStart, Int32Array.from(all));
    this.stretch = stretch;
    this.bending = bending;
    this.weights = w;
    this.product = { ...bending.pullMatrix, row: this.row };
  }

  factor(pinned, h) {
    const { chol, row, weights } = this, { springs, k, damping } = this.stretch;
    this.beginFactor(pinned, h);
    for (let s = 0; s < k.length && weights.springs > 0; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1], w = weights.springs * (k[s] + damping[s] / h);
      if (!pinned[a]) chol.add(row[a], row[a], w);
      if (!pinned[b]) chol.add(row[b], row[b], w);
      if (!pinned[a] && !pinned[b]) chol.add(row[a], row[b], -w);
    }
    const { stiffness, pull, stencils: { offsets, vertices, weights: K } } = this.bending;
    for (let e = 0; e + 1 < offsets.length; e++) {
      const we = weights.elastic * (stiffness[e] - pull[e]) + weights.damping * pull[e];
      if (!(we > 0)) continue;
      for (let p = offsets[e]; p < offsets[e + 1]; p++) {
        const a = vertices[p];
        if (pinned[a]) continue;
        const s = K[p] * we;
        chol.add(row[a], row[a], s * K[p]);
        for (let q = p + 1; q < offsets[e + 1]; q++) {
          const c = vertices[q];
          if (!pinned[c]) chol.add(row[a], row[c], (a === c ? 2 : 1) * s * K[q]);
        }
      }
    }
    chol.factor();
  }
}

// --- the right-hand sides' parts, by the system's rows; t: the target positions (pinned: where they are) --------

/** Solves (+ the stencils' damping P·prev where given) and writes the solution by particle (pinned: t). */
function solveInto(system, pinned, t, out, product, prev) {
  const { b, row, chol } = system;
  REFERENCE_SOLVER.solve3(chol, b, product, prev);
  for (let i = 0; i < row.length; i++) {
    const q = 3 * row[i], j = 3 * i;
    if (pinned[i]) { out[j] = t[j]; out[j + 1] = t[j + 1]; out[j + 2] = t[j + 2]; continue; }
    out[j] = b[q]; out[j + 1] = b[q + 1]; out[j + 2] = b[q + 2];
  }
}

/** One Projective Dynamics pass of the springs towards t, the local step at `cur`. */
function stretchStep(stretch, pinned, t, prev, cur, out, h) {
  stretch.inertiaTerms(pinned, t, h);
  addSpringTerms(stretch.b, stretch.row, stretch, pinned, t, prev, cur, h);
  solveInto(stretch, pinned, t, out);
}

/** The backward-Euler step of the stencils towards t. */
function bendingStep(bending, pinned, t, prev, out, h) {
  bending.inertiaTerms(pinned, t, h);
  bending.pinnedStencilTerms(pinned, t);
  solveInto(bending, pinned, t, out, bending.damped ? bending.pullMatrix : undefined, prev);
}

/** One pass of the springs and the stencils in one matrix towards t, the local step at `cur`. */
function bothStep(both, pinned, t, prev, cur, out, h) {
  both.inertiaTerms(pinned, t, h);
  addSpringTerms(both.b, both.row, both.stretch, pinned, t, prev, cur, h);
  both.bending.pinnedStencilTerms(pinned, t, both.b, both.row);
  solveInto(both, pinned, t, out, both.bending.damped ? both.product : undefined, prev);
}

/** f ← Q·x, the stencils' elastic forces' negative (their elastic part 1/α_e·K·Kᵀ, as the factor holds it). */
function stencilForce(bending, x, f) {
  const { stiffness, pull, stencils: { offsets, vertices, weights } } = bending;
  f.fill(0);
  for (let e = 0; e + 1 < offsets.length; e++) {
    const q = stiffness[e] - pull[e];
    if (!(q > 0)) continue;
    let cx = 0, cy = 0, cz = 0;
    for (let p = offsets[e]; p < offsets[e + 1]; p++) {
      const j = 3 * vertices[p], w = weights[p];
      cx += w * x[j]; cy += w * x[j + 1]; cz += w * x[j + 2];
    }
    for (let p = offsets[e]; p < offsets[e + 1]; p++) {
      const j = 3 * vertices[p], w = q * weights[p];
      f[j] += w * cx; f[j + 1] += w * cy; f[j + 2] += w * cz;
    }
  }
}

// --- the substep: the state's positions hold the prediction y; the result goes back as float32 + residual ------------

let work = null;
/** The systems (masses scaled by the mode's inertia shares) and scratch arrays, for these params and pins. */
function workFor(model, params, pinned, h) {
  if (!work || work.params !== params) {
    const n3 = 3 * model.particleCount;
    const scaled = (share) => (share === 1 ? params : { ...params, particleMass: Float64Array.from(params.particleMass, (m) => m * share) });
    const [stretchShare, bendingShare] = mode === 'admm' ? [SHARE + PENALTY, 1 - SHARE + PENALTY] : [1, 1];
    // (admm-q: these two only lend their springs and stencils to its own systems)
    const bendingParams = scaled(bendingShare);
    work = {
      params, bendingParams,
      stretch: new StretchSystem(model, scaled(stretchShare)),
      bending: new BendingSystem(model, bendingParams, bendingStencils(model, params.bending)),
      both: null,
      ...Object.fromEntries(['y', 'prev', 'xi', 'x', 'z', 't', 'u', 'f', 'split', 'bias'].map((name) => [name, new Float64Array(n3)])),
    };
  }
  if (!work.stretch.current(pinned, h)) {
    work.stretch.factor(pinned, h);
    work.u.fill(0);
    work.bias.fill(0);
  }
  if (!work.bending.current(pinned, h)) work.bending.factor(work.bendingParams, pinned, h);
  if (mode === 'corrected' || mode === 'sweep-pd' || mode === 'joint') {
    work.both ??= new CombinedSystem(model, params, work.stretch, work.bending);
    if (!work.both.current(pinned, h)) work.both.factor(pinned, h);
  }
  if (mode === 'admm-q') {
    // the penalty c·(M/h² + Q): the stretch copy's matrix gains c·Q, the bending copy's (1 + c)·Q
    work.xSystem ??= new CombinedSystem(model, params, work.stretch, work.bending, { mass: SHARE + PENALTY, elastic: PENALTY, damping: 0 });
    work.zSystem ??= new CombinedSystem(model, params, work.stretch, work.bending, { mass: 1 - SHARE + PENALTY, springs: 0, elastic: 1 + PENALTY });
    if (!work.xSystem.current(pinned, h)) work.xSystem.factor(pinned, h);
    if (!work.zSystem.current(pinned, h)) work.zSystem.factor(pinned, h);
  }
  return work;
}

function coupledStep(model, state, params, frame) {
  const h = frame.h, pinned = state.pinned, n3 = 3 * model.particleCount;
  const p = state.positions, r = state.residuals, pp = state.previousPositions, rp = state.previousResiduals;
  const w = workFor(model, params, pinned, h);
  const { y, prev, xi, x, z, t, u, f } = w;
  const free = (j) => !pinned[(j / 3) | 0];
  // the prediction, the substep's start, and the prediction without gravity
  const c = state.substeps === 0 ? 0.5 : 1;
  for (let j = 0; j < n3; j++) {
    y[j] = p[j] + r[j] + (carry && free(j) ? carry[j] : 0);
    prev[j] = pp[j] + rp[j];
    xi[j] = free(j) ? y[j] - c * h * h * params.gravity[j % 3] : y[j];
  }
  let result = x;
  if (mode === 'admm') {
    if (flag('reset')) u.fill(0);
    const a = SHARE, pen = PENALTY;
    if (flag('contact-dual') && w.last) {
      // what the contact after the last substep moved, as if the dual's last update had seen it
      for (let j = 0; j < n3; j++) if (free(j)) u[j] += RELAX * (prev[j] - w.last[j]);
    }
    for (let it = 0; it < ITERATIONS; it++) {
      const from = it === 0 ? { prev, y, xi }[arg('from', 'xi')] : x;
      for (let j = 0; j < n3; j++) t[j] = free(j) ? ((1 - a) * y[j] + pen * (from[j] + u[j])) / (1 - a + pen) : y[j];
      bendingStep(w.bending, pinned, t, prev, z, h);
      for (let j = 0; j < n3; j++) t[j] = free(j) ? (a * y[j] + pen * (z[j] - u[j])) / (a + pen) : y[j];
      stretchStep(w.stretch, pinned, t, prev, z, x, h);
      if (flag('contact-inside')) {
        // the colliders' contact on the stretch copy inside the iteration, so that the dual sees it
        for (let j = 0; j < n3; j++) if (free(j)) { p[j] = Math.fround(x[j]); r[j] = x[j] - p[j]; }
        REFERENCE[PHASE.contact](model, state, params, frame);
        REFERENCE[PHASE.contactTriangles](model, state, params, frame);
        for (let j = 0; j < n3; j++) x[j] = p[j] + r[j];
      }
      for (let j = 0; j < n3; j++) u[j] += RELAX * (x[j] - z[j]);
    }
    (w.last ??= new Float64Array(n3)).set(x);
  } else if (mode === 'admm-q') {
    if (flag('reset')) u.fill(0);
    const a = SHARE, pen = PENALTY, { xSystem, zSystem } = w, v = w.split;
    // c·Q_ff·v on the free rows (pinned entries of v zeroed: the penalty is on the free particles only)
    const penaltyTerms = (system, from, sign) => {
      for (let j = 0; j < n3; j++) v[j] = free(j) ? from[j] + sign * u[j] : 0;
      stencilForce(w.bending, v, f);
      const { b, row } = system;
      for (let i = 0; i < row.length; i++) {
        if (pinned[i]) continue;
        const q = 3 * row[i], j = 3 * i;
        b[q] += pen * f[j]; b[q + 1] += pen * f[j + 1]; b[q + 2] += pen * f[j + 2];
      }
    };
    for (let it = 0; it < ITERATIONS; it++) {
      const from = it === 0 ? { prev, y, xi }[arg('from', 'xi')] : x;
      for (let j = 0; j < n3; j++) t[j] = free(j) ? ((1 - a) * y[j] + pen * (from[j] + u[j])) / (1 - a + pen) : y[j];
      zSystem.inertiaTerms(pinned, t, h);
      w.bending.pinnedStencilTerms(pinned, t, zSystem.b, zSystem.row);
      penaltyTerms(zSystem, from, 1);
      solveInto(zSystem, pinned, t, z, w.bending.damped ? zSystem.product : undefined, prev);
      for (let j = 0; j < n3; j++) t[j] = free(j) ? (a * y[j] + pen * (z[j] - u[j])) / (a + pen) : y[j];
      xSystem.inertiaTerms(pinned, t, h);
      addSpringTerms(xSystem.b, xSystem.row, w.stretch, pinned, t, prev, z, h);
      penaltyTerms(xSystem, z, -1);
      solveInto(xSystem, pinned, t, x);
      for (let j = 0; j < n3; j++) u[j] += RELAX * (x[j] - z[j]);
    }
  } else if (mode === 'balanced') {
    stencilForce(w.bending, prev, f);
    const inertia = 1 / (h * h);
    for (let j = 0; j < n3; j++) t[j] = free(j) ? y[j] - f[j] / (w.stretch.mass[(j / 3) | 0] * inertia) : y[j];
    stretchStep(w.stretch, pinned, t, prev, DIR === 'prev' ? prev : DIR === 'xi' ? xi : y, x, h);
    for (let pass = 1; pass < PASSES; pass++) {
      z.set(x);
      stretchStep(w.stretch, pinned, t, prev, z, x, h);
    }
    for (let j = 0; j < n3; j++) t[j] = free(j) ? x[j] + f[j] / (w.bending.mass[(j / 3) | 0] * inertia) : x[j];
    bendingStep(w.bending, pinned, t, prev, z, h);
    result = z;
  } else if (mode === 'joint') {
    // Projective Dynamics on the springs and the stencils in one matrix (the corrected split's third factor), P passes
    // from the prediction, each pass's local step where the last left the cloth, accelerated by Chebyshev's method
    // (--rho ρ, --gamma γ; ρ = 0: plain passes)
    const rho = Number(arg('rho', '0')), gamma = rho > 0 ? Number(arg('gamma', '0.9')) : 1;
    const { split: older, bias: hat } = w;
    older.set(y); z.set(y);
    let omega = 1;
    for (let pass = 0; pass < PASSES; pass++) {
      bothStep(w.both, pinned, y, prev, z, hat, h);
      omega = rho === 0 || pass === 0 ? 1 : pass === 1 ? 2 / (2 - rho * rho) : 4 / (4 - rho * rho * omega);
      for (let j = 0; j < n3; j++) {
        const next = free(j) ? omega * (gamma * (hat[j] - z[j]) + z[j] - older[j]) + older[j] : y[j];
        older[j] = z[j];
        z[j] = next;
      }
    }
    x.set(z);
  } else if (mode === 'cheb') {
    // the split, its stretch passes accelerated by Chebyshev's semi-iterative method (Wang 2015): the estimated spectral
    // radius ρ of one pass, under-relaxation γ
    const rho = Number(arg('rho', '0.95')), gamma = Number(arg('gamma', '0.9'));
    const { split: older, bias: hat } = w;
    older.set(y); z.set(y);
    let omega = 1;
    for (let pass = 0; pass < PASSES; pass++) {
      stretchStep(w.stretch, pinned, y, prev, z, hat, h);
      omega = pass === 0 ? 1 : pass === 1 ? 2 / (2 - rho * rho) : 4 / (4 - rho * rho * omega);
      for (let j = 0; j < n3; j++) {
        const next = free(j) ? omega * (gamma * (hat[j] - z[j]) + z[j] - older[j]) + older[j] : y[j];
        older[j] = z[j];
        z[j] = next;
      }
    }
    for (let j = 0; j < n3; j++) if (free(j)) { p[j] = Math.fround(z[j]); r[j] = z[j] - p[j]; }
    solveGlobalBending(model, state, params, h);
    for (let j = 0; j < n3; j++) x[j] = p[j] + r[j];
  } else if (mode === 'sweep-pd') {
    // the springs swept one at a time (XPBD) and the stencils' global step (from the prediction, or with --dir xi from
    // it without gravity), then the passes of both in one matrix from the prediction, the springs' directions from
    // where those left the cloth
    if (DIR === 'xi') for (let j = 0; j < n3; j++) if (free(j)) { p[j] = Math.fround(xi[j]); r[j] = xi[j] - p[j]; }
    if (!flag('no-sweep')) solveDistanceConstraints(model, state, params, h, false);
    if (flag('spring-force')) {
      // the springs' elastic force at the substep's start, h²/m times it added to what the bending step starts from:
      // at rest (gravity, bending and springs in balance) the bending step then leaves the cloth where it was
      const { springs, k, rest } = w.stretch, mass = params.particleMass;
      f.fill(0);
      for (let s2 = 0; s2 < k.length; s2++) {
        const a = 3 * springs[2 * s2], b = 3 * springs[2 * s2 + 1];
        const dx = prev[a] - prev[b], dy = prev[a + 1] - prev[b + 1], dz = prev[a + 2] - prev[b + 2], len = Math.hypot(dx, dy, dz);
        const t = -k[s2] * (len - rest[s2]) / len;
        f[a] += t * dx; f[a + 1] += t * dy; f[a + 2] += t * dz; f[b] -= t * dx; f[b + 1] -= t * dy; f[b + 2] -= t * dz;
      }
      for (let j = 0; j < n3; j++) if (free(j)) { const v = p[j] + r[j] + (h * h * f[j]) / mass[(j / 3) | 0]; p[j] = Math.fround(v); r[j] = v - p[j]; }
    }
    if (!flag('no-bend')) solveGlobalBending(model, state, params, h);
    for (let k2 = 0; k2 < Number(arg('sweeps-after', '0')); k2++) solveDistanceConstraints(model, state, params, h, false);
    if (flag('contact-before')) REFERENCE_CONTACT(model, state, params, frame);
    const { split, bias } = w;
    for (let j = 0; j < n3; j++) { split[j] = p[j] + r[j]; z[j] = split[j] - bias[j]; }
    for (let pass = 0; pass < PASSES; pass++) {
      if (flag('angles') && pass === 0) (w.sb ??= new Float64Array(n3)).set(z);
      bothStep(w.both, pinned, y, prev, z, x, h);
      z.set(x);
    }
    for (let j = 0; j < n3; j++) bias[j] += CARRY * (split[j] - x[j] - bias[j]);
  } else {
    // corrected: the library's split, then the passes of both from the prediction, the directions from its result
    const { split, bias } = w;
    solveGlobalStretch(model, state, params, h, 1);
    solveGlobalBending(model, state, params, h);
    for (let j = 0; j < n3; j++) {
      split[j] = p[j] + r[j];
      z[j] = split[j] - bias[j];
    }
    for (let pass = 0; pass < PASSES; pass++) {
      bothStep(w.both, pinned, y, prev, z, x, h);
      z.set(x);
    }
    for (let j = 0; j < n3; j++) bias[j] += CARRY * (split[j] - x[j] - bias[j]);
  }
  for (let j = 0; j < n3; j++) {
    if (!free(j)) continue;
    p[j] = Math.fround(result[j]);
    r[j] = result[j] - p[j];
  }
}

// --contact-carry: the normal push of the particles' contact carried into the next substep's prediction, as a force
// (an accumulated normal impulse, warm-started), and friction bounded by it (a prototype of collideParticles for
// static shapes; C per particle, displacement units: the force is m·C/h²)
let carry = null;
function carriedContact(model, state, params, frame) {
  const h = frame.h, x = state.positions, xp = state.previousPositions, w = state.invMass, n = model.particleCount;
  const recover = params.depenetrationSpeed * h, th = params.perCloth.thickness[0];
  const mu = params.perCloth.friction[0], muS = params.perCloth.staticFriction[0];
  carry ??= new Float64Array(3 * n);
  const normal = new Float64Array(3);
  for (let i = 0; i < n; i++) {
    if (w[i] === 0) continue;
    const j = 3 * i;
    let kept = 0, nx = 0, ny = 0, nz = 0;
    for (const shape of params.colliders) {
      const d = shape.signedDistance(x[j], x[j + 1], x[j + 2], normal, th + 1);
      const cn = Math.max(0, carry[j] * normal[0] + carry[j + 1] * normal[1] + carry[j + 2] * normal[2]);
      if (d >= th + cn) continue;
      const mx = x[j] - xp[j], my = x[j + 1] - xp[j + 1], mz = x[j + 2] - xp[j + 2];
      const mn = mx * normal[0] + my * normal[1] + mz * normal[2];
      let depth = 0, press = cn - (d - th);
      if (d < th) {
        const movedIn = Math.max(-mn, 0), overlap = th - d;
        depth = Math.min(overlap, movedIn + recover);
        const over = overlap - movedIn;
        press = cn + (over <= 0 ? overlap : movedIn + Math.max(0, Math.min(over, 2 * recover - over)));
      }
      const tx = mx - mn * normal[0], ty = my - mn * normal[1], tz = mz - mn * normal[2], tl = Math.hypot(tx, ty, tz);
      const s = tl < 1e-12 ? 0 : tl < muS * press ? 1 : Math.min((mu * press) / tl, 1);
      x[j] += depth * normal[0] - s * tx; x[j + 1] += depth * normal[1] - s * ty; x[j + 2] += depth * normal[2] - s * tz;
      const made = Math.min(mn + depth, depth);
      if (made > 0) { xp[j] += made * normal[0]; xp[j + 1] += made * normal[1]; xp[j + 2] += made * normal[2]; }
      kept = Math.max(0, cn + depth - Math.max(0, d - th));
      nx = normal[0]; ny = normal[1]; nz = normal[2];
    }
    carry[j] = kept * nx; carry[j + 1] = kept * ny; carry[j + 2] = kept * nz;
  }
}
if (flag('contact-carry')) REFERENCE[PHASE.contact] = carriedContact;
const REFERENCE_CONTACT = REFERENCE[PHASE.contact];

if (mode === 'two-level') {
  // the sweep as the scene has it, with a coarse Gauss–Newton correction of the springs before it, after it or both
  // (coarse-correction.mjs) [--grid G (nodes per side, 8)] [--order pre|post|both] [--coarse-damping]
  // [--position-only (the correction moves the substep's start too, so it does not enter the velocity)] [--geometric
  // (a stretched spring's transverse stiffness too)] [--line-search (the step kept only as far as it lowers the
  // substep's energy)] [--omega ω (the step times ω, 1)]
  // [--space dual [--bins B] (DualCoarse: the correction on the springs' multipliers, piecewise constant: before the
  // sweep with --order pre, the sweep accumulating from it; the core's phase is solver.stretch 'two-level')] [--every K
  // (the dual correction in every K-th substep only, 1)]
  const { CoarseCorrection, DualCoarse } = await import('./coarse-correction.mjs');
  const dual = arg('space', 'primal') === 'dual';
  const sweepPhase = REFERENCE[PHASE.distance], grid = Number(arg('grid', '8')), order = arg('order', 'pre');
  let coarse = null, y = null;
  REFERENCE[PHASE.distance] = (model, state, params, frame) => {
    if (!coarse) {
      coarse = dual ? new DualCoarse(model, grid, Number(arg('bins', '4'))) : new CoarseCorrection(model, grid);
      y = new Float64Array(3 * model.particleCount);
      coarse.positionOnly = flag('position-only');
      coarse.omega = Number(arg('omega', '1'));
    }
    y.set(state.positions);
    const apply = () => coarse.apply(model, state, params, frame.h, y, flag('coarse-damping'), flag('geometric'), flag('line-search'));
    if (order !== 'post' && !dual) apply();
    const every = Number(arg('every', '1'));
    if (order !== 'post' && dual && (frame.sub % every) === every - 1) {
      // the coarse multipliers first, from zero; the sweep goes on from them
      state.lambdas.fill(0);
      coarse.apply(model, state, params, frame.h);
      solveDistanceConstraints(model, state, params, frame.h, true);
    } else sweepPhase(model, state, params, frame);
    if (order !== 'pre') apply();
  };
} else if (mode !== 'split' && mode !== 'sweep') {
  REFERENCE[PHASE.globalStretch] = coupledStep;
  REFERENCE[PHASE.globalBending] = () => {};
}

const sceneName = arg('scene', 'cantilever'), cusick = sceneName === 'cusick', hanging = sceneName === 'hanging';
const fabric = arg('fabric', 'cotton'), spec = FABRICS[fabric];
const cTheory = Math.cbrt(spec.bendingRigidity / (spec.arealDensity * 9.81));
// hanging: the 1 m sheet of scripts/hanging-strain.mjs (solver-study-common.mjs), its bending the hinges solved together
// fall: a free 1 m cloth (8 faces) falling for 0.5 s, nothing to strain it: the reading is how far it fell over ½gt²
const fall = sceneName === 'fall';
let scene = hanging
  ? setScenePath(hangingScene(fabric, 32, 20, 1, 'hinges', 'global'), 'solver.bendingSolve', 'global')
  : fall
    ? { cloth: { resolution: 8, position: [0, 1.2, 0] }, colliders: [], pins: [], material: { fabric }, solver: { bending: 'hinges', bendingSolve: 'global' }, duration: 0.5 }
    : sceneName === 'pendulum'
      // scripts/dissipation.mjs's pendulum: a 1 m sheet (16 faces) pinned along its top edge, let go 40° out of the
      // vertical, no damping, no air, 10 s; the reading is the share of the swing's energy kept over 8 s
      ? { cloth: { orientation: 'hanging', resolution: 16, position: [0, 1.5, 0], rotation: [40, 0, 0] }, colliders: [], pins: ['top-edge'], material: { fabric, damping: 0 }, solver: { bending: 'hinges', bendingSolve: 'global' }, duration: 10 }
    : sceneName === 'swing'
      // a 1 m sheet (32 faces) hung by one corner 1.5 m up, let go turned 60° out of the vertical: a fast, large turn
      ? { cloth: { orientation: 'hanging', resolution: 32, position: [0, 1.5, 0], rotation: [60, 0, 0] }, colliders: [], pins: ['top-left'], material: { fabric }, solver: { bending: 'hinges', bendingSolve: 'global' }, duration: 2 }
    : setScenePath(builtinScene(sceneName), 'material.fabric', fabric);
scene = setScenePath(scene, 'solver.stretch', mode === 'sweep' || mode === 'two-level' ? 'gauss-seidel' : 'global');
if (arg('resolution')) scene = setScenePath(scene, 'cloth.resolution', Number(arg('resolution')));
if (arg('substeps')) scene = setScenePath(scene, 'solver.substeps', Number(arg('substeps')));
for (let i = process.argv.indexOf('--set'); i >= 0; i = process.argv.indexOf('--set', i + 1)) {
  const [path, value] = process.argv[i + 1].split('=');
  scene = setScenePath(scene, path, value === 'true' ? true : value === 'false' ? false : Number.isNaN(Number(value)) ? value : Number(value));
}
if (flag('no-pedestal')) scene = { ...scene, colliders: scene.colliders.filter((c) => c.type !== 'cylinder') };
scene = validateScene(scene);
const sim = new Simulation(scene, { kernel: 'ts' });
const startHeight = sim.state.positions[1] + sim.state.residuals[1];
const swingZ = [];
const reading = (test) => {
  if (sceneName === 'pendulum') {
    const amp = [];
    for (let w = 0; w + 120 <= swingZ.length; w += 120) amp.push((Math.max(...swingZ.slice(w, w + 120)) - Math.min(...swingZ.slice(w, w + 120))) / 2);
    return amp.length < 5 ? 'amplitude (not yet 10 s)' : `amplitude ${amp.map((a) => (100 * a).toFixed(2)).join(', ')} cm, energy kept over 8 s ${(100 * (amp[4] / amp[0]) ** 2).toFixed(0)} %`;
  }
  if (fall) return `fallen / ½gt² ${((startHeight - sim.state.positions[1] - sim.state.residuals[1]) / (0.5 * 9.81 * sim.state.time ** 2)).toFixed(4)}`;
  if (hanging) {
    const m = measureHanging(sim.state.positions, scene.cloth.resolution), th = hangingTheory(fabric);
    return `elongation / theory ${(m.elongation / th.elongation).toFixed(3)}, middle strain / theory ${(m.strainMid / th.strainMid).toFixed(3)}`;
  }
  if (!test) return `centroid height ${sim.report().centroid[1].toFixed(3)} m, largest strain ${(100 * sim.report().maxStrain).toFixed(1)} %`;
  return cusick ? `DC ${test.drapeCoefficient.toFixed(3)} folds ${test.folds}` : `c/c_theory ${(test.bendingLength / cTheory).toFixed(3)}`;
};
const frames = Math.round((scene.duration ?? 6) * 60), trace = [];
const t0 = performance.now();
const chunk = flag("trace") ? 3 : 30;
for (let done = 0; done < frames; done += chunk) {
  if (sceneName === 'pendulum') for (let f = 0; f < Math.min(chunk, frames - done); f++) { sim.advance(1); swingZ.push(sim.report().centroid[2]); }
  else sim.advance(Math.min(chunk, frames - done));
  const { test, energy } = sim.report();
  trace.push(`${((done + chunk) / 60).toFixed(1)} s ${reading(test)} KE ${energy.kinetic.toExponential(1)}`);
}
const ms = (performance.now() - t0) / frames;
const { test, energy } = sim.report();
const options = { 'admm-q': `a ${SHARE} c ${PENALTY} iterations ${ITERATIONS} relax ${RELAX}${flag('reset') ? ' reset' : ''}`, admm: `a ${SHARE} c ${PENALTY} iterations ${ITERATIONS} relax ${RELAX} from ${arg('from', 'xi')}${flag('reset') ? ' reset' : ''}`, balanced: `dir ${DIR} passes ${PASSES}`, corrected: `passes ${PASSES} carry ${CARRY}` }[mode] ?? '';
console.log(`${mode} ${options} | ${sceneName} ${fabric} ${scene.cloth.resolution} faces, ${scene.solver.substeps} substeps: ${reading(test)}, ` +
  `elastic ${energy.elastic.toExponential(3)} J (bending ${energy.bending.toExponential(3)}), largest strain ${(100 * sim.report().maxStrain).toFixed(2)} %, kinetic ${energy.kinetic.toExponential(1)} J, ${ms.toFixed(1)} ms/frame`);
console.log((flag("trace") ? trace : trace.slice(-6)).join(" | "));
if (flag('angles') && work?.sb) {
  // the springs whose directions the sweep and the bending step left farthest from the result's, in the last substep
  const { springs, k } = work.stretch, zb = work.sb, xo = work.x, rows = [];
  for (let s = 0; s < k.length; s++) {
    const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
    const u = [0, 1, 2].map((c) => zb[a + c] - zb[b + c]), v = [0, 1, 2].map((c) => xo[a + c] - xo[b + c]);
    const cos = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (Math.hypot(...u) * Math.hypot(...v));
    const side = u[0] * v[1] - u[1] * v[0];
    rows.push([Math.acos(Math.min(1, cos)) * Math.sign(side || 1), xo[a], xo[a + 1], s]);
  }
  rows.sort((p, q) => Math.abs(q[0]) - Math.abs(p[0]));
  console.log(rows.slice(0, 8).map(([ang, x0, y0]) => `${(1e3 * ang).toFixed(3)} mrad at x ${(100 * x0).toFixed(2)} cm y ${(100 * y0).toFixed(2)} cm`).join('; '));
}
if (arg('newton')) {
  // Newton's method on the model's static energy (no contact, the pins fixed) from where the run left the cloth: the
  // nearest equilibrium (as scripts/drape-equilibrium.mjs)
  const { PDSolver, newtonStatic, withHeldHinges } = await import('./pd-solver.mjs');
  const { measureTest, resolveParams, scenePins } = await import('../dist/core/index.js');
  const model = sim.model, pinned = new Uint8Array(model.particleCount);
  for (const i of scenePins(model, scene)) pinned[i] = 1;
  const pd = new PDSolver(model, withHeldHinges(model, resolveParams(model, scene), pinned), pinned, sim.state.positions, { substeps: 1, iterations: 1 });
  const start = Float64Array.from(pd.x), r = newtonStatic(pd, Number(arg('newton')));
  let moved = 0;
  for (let j = 0; j < start.length; j += 3) moved = Math.max(moved, Math.hypot(pd.x[j] - start[j], pd.x[j + 1] - start[j + 1], pd.x[j + 2] - start[j + 2]));
  const t = measureTest(model, { positions: pd.x, pinned }, scene);
  console.log(`Newton (${r.iterations} iterations, energy ${r.energy.toExponential(5)} J, gradient ${r.gnorm.toExponential(1)}): ` +
    `${cusick ? `DC ${t.drapeCoefficient.toFixed(3)} folds ${t.folds}` : `c/c_theory ${(t.bendingLength / cTheory).toFixed(3)}`}, moved by up to ${(1000 * moved).toFixed(1)} mm`);
}
if (flag('rows') && hanging) {
  // the hanging sheet's vertical strain row by row (mean over the middle half of the columns), in 10⁻⁴
  const x = sim.state.positions, F = scene.cloth.resolution, nx = F + 1, rows = [];
  for (let j = 0; j < F; j++) {
    let sum = 0, count = 0;
    for (let i = Math.round(F / 4); i <= Math.round((3 * F) / 4); i++, count++) {
      const a = 3 * (j * nx + i), b = 3 * ((j + 1) * nx + i);
      sum += Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]) * F - 1;
    }
    rows.push(`${j}: ${(1e4 * sum / count).toFixed(1)}`);
  }
  console.log(`vertical strain by row [1e-4] (theory at the top ${(1e4 * hangingTheory(fabric).strainTop).toFixed(2)}): ${rows.join(', ')}`);
}
if (flag('where')) {
  // the fastest particles at the end: radius from the axis, height, speed
  const v = sim.state.velocities, x = sim.state.positions, speeds = [];
  for (let i = 0; i < sim.model.particleCount; i++) speeds.push([Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]), i]);
  speeds.sort((a, b) => b[0] - a[0]);
  console.log(speeds.slice(0, 8).map(([speed, i]) => `r ${(100 * Math.hypot(x[3 * i], x[3 * i + 2])).toFixed(2)} cm, y ${(100 * x[3 * i + 1]).toFixed(2)} cm: ${(1000 * speed).toFixed(2)} mm/s`).join('; '));
}
sim.dispose();
