/**
 * The global stretch step (solver.stretch 'global', xpbd): the springs solved together instead of one at a time.
 *
 * XPBD's Gauss–Seidel pass carries a correction a spring or two per substep, so a hanging sheet of many rows
 * stretches several to hundreds of times more than its stiffness allows (docs/physics.md, "Converged stretch"). Here
 * the springs of a substep are one implicit-Euler problem, minimised over the positions x (Projective Dynamics:
 * Bouaziz, Martin, Liu, Kavan & Pauly 2014; for mass-springs Liu, Bargteil, O'Brien & Kavan 2013, "Fast Simulation
 * of Mass-Spring Systems"):
 *
 *   (1/2h²)·|M^½(x − y)|² + Σ_springs ½·k_s·|x_a − x_b − d_s|²,   |d_s| = L_s,
 *
 * with y the predicted positions (what integrate, carry and grab left). Each pass is a local step, d_s = L_s·(x_a −
 * x_b)/|x_a − x_b| for every spring, and a global step, the linear system
 *
 *   A·x = M/h²·y + Σ k_s·S_sᵀ·d_s,   A = M/h² + Σ k_s·S_sᵀS_s,
 *
 * one scalar matrix for the three coordinates, constant while the mesh, h, the stiffnesses and the pins are: it is
 * ordered once per model (nested dissection) and factored once (sparse Cholesky, sparse.ts); a pinned particle's
 * row is the identity (its position stays), and the factor is redone only when the pins change. The grabbed particle
 * is held without a refactor: with z = A⁻¹·e_g (one solve when the grab starts), the solution u of the unconstrained
 * system becomes x = u + z·(p_g − u_g)/z_g, which is exactly the solve with x_g = p_g.
 *
 * Every spring with stiffness takes part (structural, shear, and the skip-one bend springs unless solver.bending is a
 * stencil model, 'hinges' or 'laplacian', whose own phase follows). The springs' damping β (material.damping) is a
 * second projective term per spring, weight β/h, whose projection is the relative position x_a − x_b less its motion
 * along the spring since the substep's start: converged, it is ½(β/h)·((Δx_a − Δx_b)·n)², the damping of the stretching
 * rate only (as XPBD's, Macklin et al. 2016 §3.5); bending and swinging are not damped by it. The tethers and the
 * stretch limit do not run with this step: they are there to bound a sweep's overstretch, and projecting after a
 * converged solve fights it (a hammock pinned at four corners kept 10⁴ times the kinetic energy). The result is written
 * back as float32 positions beside their unchanged residuals.
 */
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';
import { PrefactoredSystem } from './prefactored.js';
import { REFERENCE_SOLVER, type FactorSolver } from './sparse.js';

/** The ordered, factored system of one model and params (built on first use; refactored when h or the pins change). */
export class StretchSystem extends PrefactoredSystem {
  /** springs with stiffness, their ends and constants */
  readonly springs: Int32Array;
  readonly k: Float64Array;
  readonly rest: Float64Array;
  /** each spring's damping β [N·s/m] (params.springDamping: its cloth's material.damping) */
  readonly damping: Float64Array;
  /** positions at the start of the substep [m], by particle (for the damping term) */
  readonly previous: Float64Array;
  /** predicted positions y at the start of the substep's passes [m], by particle */
  readonly y: Float64Array;
  /** the current positions of the passes [m], by particle (y before the first) */
  readonly x: Float64Array;

  constructor(model: ClothModel, params: SimParams) {
    const n = model.particleCount;
    const springCount = model.restLengths.length;
    let m = 0;
    for (let s = 0; s < springCount; s++) if (params.stiffness[s] > 0) m++;
    const springs = new Int32Array(2 * m);
    m = 0;
    for (let s = 0; s < springCount; s++) {
      if (!(params.stiffness[s] > 0)) continue;
      springs[2 * m] = model.springs[2 * s];
      springs[2 * m + 1] = model.springs[2 * s + 1];
      m++;
    }
    // the graph of the springs, in compressed rows, for the ordering and the factor's pattern
    const rowStart = new Int32Array(n + 1);
    for (let s = 0; s < 2 * m; s++) rowStart[springs[s] + 1]++;
    for (let i = 0; i < n; i++) rowStart[i + 1] += rowStart[i];
    const cols = new Int32Array(rowStart[n]);
    const fill = rowStart.slice(0, n);
    for (let s = 0; s < m; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1];
      cols[fill[a]++] = b;
      cols[fill[b]++] = a;
    }
    super(model, params.particleMass, rowStart, cols);
    this.springs = springs;
    this.k = new Float64Array(m);
    this.rest = new Float64Array(m);
    this.damping = new Float64Array(m);
    m = 0;
    for (let s = 0; s < springCount; s++) {
      if (!(params.stiffness[s] > 0)) continue;
      this.k[m] = params.stiffness[s];
      this.rest[m] = model.restLengths[s];
      this.damping[m] = params.springDamping[s];
      m++;
    }
    this.previous = new Float64Array(3 * n);
    this.y = new Float64Array(3 * n);
    this.x = new Float64Array(3 * n);
  }

  /** Assembles and factors A for substep h and the pins of `pinned`. */
  factor(pinned: Uint8Array, h: number): void {
    const { chol, row, springs, k, damping } = this;
    this.beginFactor(pinned, h);
    for (let s = 0; s < k.length; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1], w = k[s] + damping[s] / h;
      if (!pinned[a]) chol.add(row[a], row[a], w);
      if (!pinned[b]) chol.add(row[b], row[b], w);
      if (!pinned[a] && !pinned[b]) chol.add(row[a], row[b], -w);
    }
    chol.factor();
  }
}

/** One system per params object (params are rebuilt whenever a parameter changes, so a stale one is never reused). */
const systems = new WeakMap<SimParams, StretchSystem>();

/**
 * The global stretch step's system for `model` and `params`, factored for the pins of `pinned` and substep h (made on
 * first use, refactored where the pins or h changed since). The one system per params that solveGlobalStretch solves
 * with; the WebGPU solver reads its factor.
 */
export function globalStretchSystem(model: ClothModel, params: SimParams, pinned: Uint8Array, h: number): StretchSystem {
  let system = systems.get(params);
  if (system === undefined || system.model !== model) {
    system = new StretchSystem(model, params);
    systems.set(params, system);
  }
  if (!system.current(pinned, h)) system.factor(pinned, h);
  return system;
}

/**
 * `passes` local/global iterations of the springs over substep h, from the predicted positions in state.positions
 * (+ residuals). Pinned particles stay; the grabbed one stays where the grab phase put it. Allocates only when the
 * system is first built or refactored (pins changed). `solver` solves with the factor (the WebAssembly kernel passes its
 * own: the same solution).
 */
export function solveGlobalStretch(
  model: ClothModel, state: ClothState, params: SimParams, h: number, passes: number, solver: FactorSolver = REFERENCE_SOLVER,
): void {
  const pinned = state.pinned;
  const system = globalStretchSystem(model, params, pinned, h);
  const { y, x: cur, b, row, mass, chol, previous } = system;
  const x = state.positions, r = state.residuals, xp = state.previousPositions, rp = state.previousResiduals;
  const n = mass.length;
  for (let j = 0; j < 3 * n; j++) {
    cur[j] = y[j] = x[j] + r[j];
    previous[j] = xp[j] + rp[j];
  }
  const g = system.grabbed(state);
  for (let pass = 0; pass < passes; pass++) {
    // right-hand side: inertia, pinned rows, then each spring's projection d_s (local step) and pinned neighbours
    system.inertiaTerms(pinned, y, h);
    addSpringTerms(b, row, system, pinned, y, previous, cur, h);
    solver.solve3(chol, b);
    // hold the grabbed particle where the grab put it (the unconstrained solution corrected along z)
    if (g >= 0) system.hold(g, y[3 * g], y[3 * g + 1], y[3 * g + 2]);
    for (let i = 0; i < n; i++) {
      if (pinned[i] || i === g) continue;
      const q = 3 * row[i], j = 3 * i;
      cur[j] = b[q]; cur[j + 1] = b[q + 1]; cur[j + 2] = b[q + 2];
    }
  }
  for (let i = 0; i < n; i++) {
    if (pinned[i] || i === g) continue;
    const j = 3 * i;
    x[j] = Math.fround(cur[j] - r[j]); x[j + 1] = Math.fround(cur[j + 1] - r[j + 1]); x[j + 2] = Math.fround(cur[j + 2] - r[j + 2]);
  }
}

/**
 * The springs' part of the global step's right-hand side, added to b (three coordinates interleaved, by the system's
 * rows): each spring's projection d_s at the positions `cur` (the local step), its damping term, and the terms of a
 * pinned end at `target` (where the pinned particles are) on its free end; `previous`: the positions at the substep's
 * start (the damping's reference). By particle, xyz [m].
 */
export function addSpringTerms(
  b: Float64Array, row: Int32Array, system: StretchSystem, pinned: Uint8Array,
  target: Float64Array, previous: Float64Array, cur: Float64Array, h: number,
): void {
  const { springs, k, rest, damping } = system;
  for (let s = 0; s < k.length; s++) {
    const a = springs[2 * s], c = springs[2 * s + 1];
    const ja = 3 * a, jc = 3 * c;
    const dx = cur[ja] - cur[jc], dy = cur[ja + 1] - cur[jc + 1], dz = cur[ja + 2] - cur[jc + 2];
    const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
    const f = len > 1e-12 ? (k[s] * rest[s]) / len : 0;
    // damping, a second projective term on the same pair: its target is the current relative position less its
    // motion along the spring since the substep's start (u: that motion), so only the stretching rate is damped
    let px = 0, py = 0, pz = 0;
    const ds = damping[s] / h;
    if (ds > 0) {
      const ux = dx - (previous[ja] - previous[jc]), uy = dy - (previous[ja + 1] - previous[jc + 1]), uz = dz - (previous[ja + 2] - previous[jc + 2]);
      const along = len > 1e-12 ? (ux * dx + uy * dy + uz * dz) / (len * len) : 0;
      px = ds * (dx - along * dx); py = ds * (dy - along * dy); pz = ds * (dz - along * dz);
    }
    const pa = pinned[a], pc = pinned[c], w = k[s] + ds;
    if (!pa) {
      const q = 3 * row[a];
      b[q] += f * dx + px; b[q + 1] += f * dy + py; b[q + 2] += f * dz + pz;
      if (pc) { b[q] += w * target[jc]; b[q + 1] += w * target[jc + 1]; b[q + 2] += w * target[jc + 2]; }
    }
    if (!pc) {
      const q = 3 * row[c];
      b[q] -= f * dx + px; b[q + 1] -= f * dy + py; b[q + 2] -= f * dz + pz;
      if (pa) { b[q] += w * target[ja]; b[q + 1] += w * target[ja + 1]; b[q + 2] += w * target[ja + 2]; }
    }
  }
}
