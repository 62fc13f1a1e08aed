/**
 * The hybrid stretch solve (solver.stretch 'hybrid', xpbd): the springs swept one at a time as XPBD sweeps them (the
 * `distance` phase), the bending as its own phase solves it, and then one Projective Dynamics pass (Bouaziz et al.
 * 2014) of the springs and, where they are solved together (solver.bendingSolve 'global'), the bending stencils in one
 * matrix, from the substep's prediction y:
 *
 *   (M/h² + Σ_s (k_s + β_s/h)·S_sᵀS_s + Σ_e (1 + τ_e/h)·K_e·K_eᵀ/α_e)·x = M/h²·y + Σ_s k_s·S_sᵀ·d_s + (damping, pins),
 *
 * with each spring's direction d_s = L_s·(x̂_a − x̂_b)/|x̂_a − x̂_b| taken where the sweep and the bending left the
 * cloth, x̂. The matrix is constant (ordered once per model, factored once per substep length and pins, as the two
 * global steps' are; the stencils' stiffness and damping are the global bending step's own, held hinges included).
 *
 * Why: the springs' global step (global-stretch.ts) converges stretch, but its local step takes the springs'
 * directions before the bending has turned them, and its constant matrix then resists each turn with the spring's
 * whole stiffness; after it, the bending step cannot undo that, so a clamped strip reads 1.23 of its bending length
 * (docs/physics.md, "The standard fabric tests"). The sweep turns the springs as it shortens them, the bending step
 * turns them further, and this pass, from those directions, converges what the sweep leaves of the stretch (a hanging
 * sheet's, which one sweep a substep leaves tens of times too long) with the bending in the same solve. A free cloth
 * falls exactly (nothing strains; the pass returns the prediction). The tethers and the stretch limit do not run with
 * it, as with the global step.
 *
 * The prediction is kept by the `keepPrediction` phase, before the sweep. The grabbed particle is held where the grab
 * put it (z = A⁻¹·e_g, prefactored.ts); the pinned ones stay.
 */
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';
import { globalBendingSystem, type BendingSystem } from './global-bending.js';
import { addSpringMatrix, addSpringTerms, springGraph, stiffSprings, type SpringSet } from './global-stretch.js';
import { PrefactoredSystem } from './prefactored.js';
import { REFERENCE_SOLVER, type FactorSolver, type SparseProduct } from './sparse.js';

/** The ordered, factored system of the springs and the stencils together, of one model and params. */
export class JointSystem extends PrefactoredSystem {
  readonly springs: SpringSet;
  /** the global bending step's system whose stencils this one holds (null: the springs alone) */
  readonly bending: BendingSystem | null;
  /** the stencils' damping pull P (the bending system's) on this system's rows, for the pins of the factor */
  product: SparseProduct | null = null;
  /** the substep's prediction y (+ residuals), kept before the sweep; the positions at its start; scratch [m], by particle */
  readonly y: Float64Array;
  readonly start: Float64Array;
  readonly directions: Float64Array;

  constructor(model: ClothModel, params: SimParams, bending: BendingSystem | null) {
    const n = model.particleCount;
    const springs = stiffSprings(model, params);
    const own = springGraph(springs.springs, n);
    // the union of the springs' graph and the stencils' (two particles joined where a spring or a stencil holds both)
    const rowStart = new Int32Array(n + 1), stamp = new Int32Array(n).fill(-1);
    const other = bending?.pullMatrix;
    const pass = (write: Int32Array | null): number => {
      stamp.fill(-1);
      let at = 0;
      for (let i = 0; i < n; i++) {
        rowStart[i] = at;
        stamp[i] = i;
        const add = (j: number) => {
          if (stamp[j] === i) return;
          stamp[j] = i;
          if (write) write[at] = j;
          at++;
        };
        for (let p = own.rowStart[i]; p < own.rowStart[i + 1]; p++) add(own.cols[p]);
        if (other) for (let p = other.start[i]; p < other.start[i + 1]; p++) add(other.cols[p]);
      }
      rowStart[n] = at;
      return at;
    };
    const cols = new Int32Array(pass(null));
    pass(cols);
    super(model, params.particleMass, rowStart, cols);
    this.springs = springs;
    this.bending = bending;
    this.y = new Float64Array(3 * n);
    this.start = new Float64Array(3 * n);
    this.directions = new Float64Array(3 * n);
  }

  /** Assembles and factors the matrix for substep h and the pins of `pinned` (the bending system factored for the same). */
  factor(pinned: Uint8Array, h: number): void {
    this.beginFactor(pinned, h);
    addSpringMatrix(this.chol, this.row, this.springs, pinned, h);
    const bending = this.bending;
    if (bending) {
      bending.addStencilMatrix(this.chol, this.row, pinned);
      this.product = bending.damped ? { ...bending.pullMatrix, row: this.row } : null;
    }
    this.chol.factor();
  }
}

/** One system per params object (params are rebuilt whenever a parameter changes). */
const systems = new WeakMap<SimParams, JointSystem>();

/**
 * The hybrid's system for `model` and `params`, factored for the pins of `pinned` and substep h (made on first use,
 * refactored where the pins or h changed since, after the bending system it holds).
 */
export function jointSystem(model: ClothModel, params: SimParams, pinned: Uint8Array, h: number): JointSystem {
  const bending = params.bendingSolve === 'global' ? globalBendingSystem(model, params, pinned, h) : null;
  let system = systems.get(params);
  if (system === undefined || system.model !== model) {
    system = new JointSystem(model, params, bending);
    systems.set(params, system);
  }
  if (!system.current(pinned, h)) system.factor(pinned, h);
  return system;
}

/** The `keepPrediction` phase: the substep's prediction (positions + residuals), for the pass after the sweep. */
export function keepPrediction(model: ClothModel, state: ClothState, params: SimParams, h: number): void {
  const y = jointSystem(model, params, state.pinned, h).y, x = state.positions, r = state.residuals;
  for (let j = 0; j < y.length; j++) y[j] = x[j] + r[j];
}

/**
 * The `jointPass` phase over substep h: the pass in one matrix from the kept prediction, the springs' directions where
 * state.positions (+ residuals) are now; the result written back as float32 positions beside their residuals.
 * Allocates only when the system is first built or its pins change. `solver` solves with the factor (the WebAssembly
 * kernel passes its own: the same solution).
 */
export function solveJointPass(
  model: ClothModel, state: ClothState, params: SimParams, h: number, solver: FactorSolver = REFERENCE_SOLVER,
): void {
  const pinned = state.pinned;
  const system = jointSystem(model, params, pinned, h);
  const { y, start, directions: cur, b, row, bending } = system;
  const x = state.positions, r = state.residuals, xp = state.previousPositions, rp = state.previousResiduals;
  const n = row.length;
  for (let j = 0; j < 3 * n; j++) {
    cur[j] = x[j] + r[j];
    start[j] = xp[j] + rp[j];
  }
  // a pinned particle's target is where it is (the prediction kept it there)
  system.inertiaTerms(pinned, y, h);
  addSpringTerms(b, row, system.springs, pinned, y, start, cur, h);
  bending?.pinnedStencilTerms(pinned, y, b, row);
  const g = system.grabbed(state);
  solver.solve3(system.chol, b, system.product ?? undefined, start);
  if (g >= 0) system.hold(g, y[3 * g], y[3 * g + 1], y[3 * g + 2]);
  for (let i = 0; i < n; i++) {
    if (pinned[i] || i === g) continue;
    const q = 3 * row[i], j = 3 * i;
    for (let c = 0; c < 3; c++) {
      const v = b[q + c], f = Math.fround(v);
      x[j + c] = f;
      r[j + c] = v - f;
    }
  }
}
