/**
 * The global bending step (solver.bendingSolve 'global', xpbd, with a stencil bending model): the bending stencils of
 * a substep solved together, exactly, instead of one XPBD pass over them.
 *
 * A stencil's constraint C_e = Σ_k K_k·x_k (the hinges of Bergou et al. 2006, the cotangent Laplacian of Wardetzky et
 * al. 2007; model.ts) is linear in the positions, so the bending energy Σ ½·|C_e|²/α_e (α_e = A_e/B, solvers/xpbd.ts
 * solveBending) is quadratic with a constant Hessian, the same for the three coordinates: Bergou et al. 2006 (§4)
 * point out that this makes its implicit integration one prefactored linear solve. Here, after the stretch solve has
 * left the positions x*, the substep's backward-Euler step of the bending energy alone,
 *
 *   min_x (1/2h²)·|M^½(x − x*)|² + Σ_e ½·|K_e·x|²/α_e,   i.e.   (M/h² + Σ_e K_e·K_eᵀ/α_e)·x = M/h²·x*,
 *
 * is solved exactly: the matrix is ordered once per model (nested dissection) and factored once per substep length,
 * stiffnesses and pins (sparse Cholesky, sparse.ts); a pinned particle's row is the identity. The grabbed particle is
 * held as in the global stretch step (z = A⁻¹·e_g, prefactored.ts). One XPBD pass carries a stiff
 * stencil's correction a stencil or two per substep, so a light strip held at one end bends several times too easily
 * (docs/physics.md, "Bending solved together"); this step has no such lag. It runs after the springs (solver.stretch
 * either way): the operator splitting of the two energies, stretch then bending, each substep.
 *
 * Damping: each stencil carries stiffness-proportional (Rayleigh) damping with the damping time τ_e of a bend
 * spring of its cloth (params.stencilDamping, β/k_b), the dissipation potential Σ_e (τ_e/2h)·|K_e·(x − x_prev)|²/α_e
 * with x_prev the positions at the substep's start, so the step solves
 *
 *   (M/h² + Σ_e (1 + τ_e/h)·K_e·K_eᵀ/α_e)·x = M/h²·x* + Σ_e (τ_e/h)·K_e·K_eᵀ·x_prev/α_e,
 *
 * whose matrix is as constant as before. Without it the flaps of a draped cloth swing on as pendulums: backward
 * Euler's own damping reaches only the bending's fast modes.
 */
import { bendingStencils, type BendingStencils, type ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';
import { PrefactoredSystem } from './prefactored.js';
import { REFERENCE_SOLVER, type FactorSolver, type SparseProduct } from './sparse.js';

/**
 * The ordered, factored system of one model and params (built on first use; refactored when h or the pins change).
 * The WebGPU solver solves with the same factor (src/gpu/global-bending.ts: globalBendingSystem).
 */
export class BendingSystem extends PrefactoredSystem {
  readonly stencils: BendingStencils;
  /**
   * each stencil's stiffness in the matrix, (1 + τ/h)/α [N/m], for the pins and h of the factor (α:
   * params.stencilCompliance, a held hinge's less; τ: params.stencilDamping); 0 for a stencil without stiffness
   */
  readonly stiffness: Float64Array;
  /** each stencil's pull towards its shape at the substep's start, (τ/h)/α [N/m] (damping; 0 without) */
  readonly pull: Float64Array;
  /**
   * the damping's pull as a matrix over the particles, P = Σ_e (τ_e/h)·K_e·K_eᵀ/α_e [N/m], on the free particles'
   * rows for the pins of the factor (a pinned particle's row is zero): its diagonal, and its other entries on the
   * graph's (two particles joined where a stencil holds both); `damped`: whether any stencil has damping
   */
  readonly pullMatrix: SparseProduct;
  damped = false;
  /** the positions at the substep's start (+ residuals), xyz per particle [m] */
  readonly start: Float64Array;
  /** the positions the step starts from (+ residuals), xyz per particle [m] */
  readonly target: Float64Array;
  /** the stencils with stiffness that hold a pinned particle and a free one, for the pins of the factor: the first `pinnedCount` */
  readonly pinnedStencils: Int32Array;
  pinnedCount = 0;

  constructor(model: ClothModel, params: SimParams, stencils: BendingStencils) {
    const n = model.particleCount;
    // the graph: two particles are joined where some stencil holds both (compressed rows, each neighbour once)
    const { offsets, vertices } = stencils;
    const byParticle = incidence(offsets, vertices, n);
    const stamp = new Int32Array(n);
    const rowStart = new Int32Array(n + 1);
    const pass = (write: Int32Array | null) => {
      stamp.fill(-1);
      let at = 0;
      for (let i = 0; i < n; i++) {
        rowStart[i] = at;
        stamp[i] = i;
        for (let q = byParticle.start[i]; q < byParticle.start[i + 1]; q++) {
          const e = byParticle.stencil[q];
          for (let k = offsets[e]; k < offsets[e + 1]; k++) {
            const j = vertices[k];
            if (stamp[j] === i) continue;
            stamp[j] = i;
            if (write) write[at] = j;
            at++;
          }
        }
      }
      rowStart[n] = at;
      return at;
    };
    const cols = new Int32Array(pass(null));
    pass(cols);
    super(model, params.particleMass, rowStart, cols);
    this.stencils = stencils;
    const m = offsets.length - 1;
    this.stiffness = new Float64Array(m);
    this.pull = new Float64Array(m);
    this.pullMatrix = {
      diagonal: new Float64Array(n), start: rowStart, cols, values: new Float64Array(cols.length), row: this.row, version: 0,
    };
    this.start = new Float64Array(3 * n);
    this.target = new Float64Array(3 * n);
    this.pinnedStencils = new Int32Array(m);
  }

  /**
   * Assembles and factors A = M/h² + Σ (1 + τ/h)·K·Kᵀ/α for substep h and the pins of `pinned`, and the damping's
   * pull P.
   */
  factor(params: SimParams, pinned: Uint8Array, h: number): void {
    const { chol, row, stiffness, pull, stencils: { offsets, vertices, weights } } = this;
    const hinges = params.bending === 'hinges', rest = this.model.restPositions;
    this.beginFactor(pinned, h);
    // a hinge beside a held triangle bends on its free side only (heldHingeShare)
    for (let e = 0; e < stiffness.length; e++) {
      let alpha = params.stencilCompliance[e];
      if (!(alpha < Infinity)) {
        stiffness[e] = pull[e] = 0;
        continue;
      }
      if (hinges) alpha *= heldHingeShare(rest, vertices, offsets[e], pinned);
      const s = params.stencilDamping[e] / h;
      stiffness[e] = (1 + s) / alpha;
      pull[e] = s / alpha;
    }
    // the damping's pull P (a stencil naming a particle twice adds to its diagonal twice, as in the matrix)
    const { diagonal: pullDiagonal, values: pullValues, start: graphStart, cols: graphCols } = this.pullMatrix;
    pullDiagonal.fill(0);
    pullValues.fill(0);
    this.pullMatrix.version++;
    this.damped = false;
    for (let e = 0; e + 1 < offsets.length; e++) {
      if (!(pull[e] > 0)) continue;
      this.damped = true;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) {
        const a = vertices[k];
        if (pinned[a]) continue;
        for (let l = offsets[e]; l < offsets[e + 1]; l++) {
          const c = vertices[l], v = pull[e] * weights[k] * weights[l];
          if (c === a) {
            pullDiagonal[a] += v;
            continue;
          }
          // (the graph joins every two particles of a stencil: c is in a's row)
          for (let p = graphStart[a]; p < graphStart[a + 1]; p++) {
            if (graphCols[p] === c) {
              pullValues[p] += v;
              break;
            }
          }
        }
      }
    }
    this.pinnedCount = 0;
    for (let e = 0; e < stiffness.length; e++) {
      if (stiffness[e] === 0) continue;
      let held = 0, free = 0;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) if (pinned[vertices[k]]) held++; else free++;
      if (held > 0 && free > 0) this.pinnedStencils[this.pinnedCount++] = e;
    }
    for (let e = 0; e + 1 < offsets.length; e++) {
      if (stiffness[e] === 0) continue;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) {
        const a = vertices[k];
        if (pinned[a]) continue;
        const s = weights[k] * stiffness[e];
        chol.add(row[a], row[a], s * weights[k]);
        // a pair k < l adds K_k·K_l/α at (a, c) and (c, a): twice to the diagonal if a stencil named a particle twice
        for (let l = k + 1; l < offsets[e + 1]; l++) {
          const c = vertices[l];
          if (!pinned[c]) chol.add(row[a], row[c], (a === c ? 2 : 1) * s * weights[l]);
        }
      }
    }
    chol.factor();
  }

  /**
   * Subtracts from b (after inertiaTerms) the terms of the stencils' pinned particles, at t (by particle, xyz [m]), on
   * their free particles: a pinned particle's part of K·Kᵀ/α moves to the right-hand side. By default into this
   * system's b by its rows; `into` and `rows`: another system's over the same particles.
   */
  pinnedStencilTerms(pinned: Uint8Array, t: ArrayLike<number>, into: Float64Array = this.b, rows: Int32Array = this.row): void {
    const { stiffness, pinnedStencils, pinnedCount, stencils: { offsets, vertices, weights } } = this, b = into, row = rows;
    for (let s = 0; s < pinnedCount; s++) {
      const e = pinnedStencils[s], ke = stiffness[e];
      for (let l = offsets[e]; l < offsets[e + 1]; l++) {
        const c = vertices[l];
        if (!pinned[c]) continue;
        const jc = 3 * c, px = t[jc], py = t[jc + 1], pz = t[jc + 2];
        for (let k = offsets[e]; k < offsets[e + 1]; k++) {
          const a = vertices[k];
          if (pinned[a]) continue;
          const v = weights[k] * weights[l] * ke, q = 3 * row[a];
          b[q] -= v * px; b[q + 1] -= v * py; b[q + 2] -= v * pz;
        }
      }
    }
  }
}

/**
 * The share of a hinge's compliance (the hinge x0 x1 x2 x3 from vertices[at]: edge x0 x1, wings x2 and x3) left for
 * the pins of `pinned`: where its edge and one wing are pinned, that triangle is held rigid (the cantilever's clamp, a
 * region pinned to a collider) and the continuous strip stores its curvature in the free triangle only, over that
 * triangle's area, so the hinge's area is that triangle's and its compliance scales by the free triangle's share of
 * the pair's rest area (a half on the grid; counted whole, a clamped strip's first hinge was half as stiff as the
 * strip beside the clamp: docs/physics.md "Bending solved together"). 1 where no triangle is held, or both.
 */
export function heldHingeShare(rest: Float32Array, vertices: Uint32Array, at: number, pinned: Uint8Array): number {
  const [x0, x1, x2, x3] = [vertices[at], vertices[at + 1], vertices[at + 2], vertices[at + 3]];
  if (!(pinned[x0] && pinned[x1]) || !pinned[x2] === !pinned[x3]) return 1;
  const area = (c: number) => {
    const ux = rest[3 * x1] - rest[3 * x0], uy = rest[3 * x1 + 1] - rest[3 * x0 + 1], uz = rest[3 * x1 + 2] - rest[3 * x0 + 2];
    const vx = rest[3 * c] - rest[3 * x0], vy = rest[3 * c + 1] - rest[3 * x0 + 1], vz = rest[3 * c + 2] - rest[3 * x0 + 2];
    return Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
  };
  const a2 = area(x2), a3 = area(x3);
  return (pinned[x2] ? a3 : a2) / (a2 + a3);
}

/** The stencils each particle is in (compressed rows). */
function incidence(offsets: Uint32Array, vertices: Uint32Array, n: number): { start: Int32Array; stencil: Int32Array } {
  const start = new Int32Array(n + 1);
  for (let k = 0; k < vertices.length; k++) start[vertices[k] + 1]++;
  for (let i = 0; i < n; i++) start[i + 1] += start[i];
  const stencil = new Int32Array(vertices.length), fill = start.slice(0, n);
  for (let e = 0; e + 1 < offsets.length; e++) for (let k = offsets[e]; k < offsets[e + 1]; k++) stencil[fill[vertices[k]]++] = e;
  return { start, stencil };
}

/** One system per params object (params are rebuilt whenever a parameter changes, so a stale one is never reused). */
const systems = new WeakMap<SimParams, BendingSystem>();

/**
 * The global bending step's system for `model` and `params`, factored for the pins of `pinned` and substep h (made on
 * first use, refactored where the pins or h changed since), or null where params bend with no stencil model. The one
 * system per params that solveGlobalBending solves with; the WebGPU solver reads its factor.
 */
export function globalBendingSystem(model: ClothModel, params: SimParams, pinned: Uint8Array, h: number): BendingSystem | null {
  const stencils = bendingStencils(model, params.bending);
  if (!stencils) return null;
  let system = systems.get(params);
  if (system === undefined || system.model !== model) {
    system = new BendingSystem(model, params, stencils);
    systems.set(params, system);
  }
  if (!system.current(pinned, h)) system.factor(params, pinned, h);
  return system;
}

/**
 * The backward-Euler step of the bending stencils over substep h, from the positions in state.positions (+
 * residuals). Pinned particles stay; the grabbed one stays where the grab phase put it. Allocates only when the
 * system is first built (a new model or params); a refactor (pins or h changed) allocates nothing. `solver` solves
 * with the factor (the WebAssembly kernel passes its own: the same solution).
 */
export function solveGlobalBending(
  model: ClothModel, state: ClothState, params: SimParams, h: number, solver: FactorSolver = REFERENCE_SOLVER,
): void {
  const system = globalBendingSystem(model, params, state.pinned, h);
  if (!system) return;
  const pinned = state.pinned;
  const { b, row, mass, chol, target } = system;
  const x = state.positions, r = state.residuals, n = mass.length;
  for (let j = 0; j < 3 * n; j++) target[j] = x[j] + r[j];
  system.inertiaTerms(pinned, target, h);
  system.pinnedStencilTerms(pinned, target);
  // damping: the free particles pulled towards the stencils' shapes at the substep's start, + P·x_prev (in the solve)
  const { start } = system;
  if (system.damped) {
    const xp = state.previousPositions, rp = state.previousResiduals;
    for (let j = 0; j < 3 * n; j++) start[j] = xp[j] + rp[j];
  }
  const g = system.grabbed(state);
  solver.solve3(chol, b, system.damped ? system.pullMatrix : undefined, start);
  if (g >= 0) system.hold(g, target[3 * g], target[3 * g + 1], target[3 * g + 2]);
  for (let i = 0; i < n; i++) {
    if (pinned[i] || i === g) continue;
    const q = 3 * row[i], j = 3 * i;
    x[j] = Math.fround(b[q] - r[j]); x[j + 1] = Math.fround(b[q + 1] - r[j + 1]); x[j + 2] = Math.fround(b[q + 2] - r[j + 2]);
  }
}
