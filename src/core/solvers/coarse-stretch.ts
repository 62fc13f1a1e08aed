/**
 * The springs' coarse correction (solver.stretch 'two-level', xpbd): each substep, one solve of the springs'
 * multipliers over a coarse space, before XPBD's sweep, which goes on from them.
 *
 * XPBD's one Gauss–Seidel sweep per substep corrects a spring from its neighbours' state, so a load travels a spring or
 * two per substep: a hanging sheet of n rows is left stretched by a residual that grows as n² (docs/physics.md,
 * "Converged stretch"). Multigrid's answer (a two-level method: smooth, then correct on a coarse space; here the
 * aggregation of algebraic multigrid, Vaněk, Mandel & Brezina 1996) is applied on XPBD's own side, the constraints'
 * multipliers λ (Macklin, Müller & Chentanez 2016), whose substep system is
 *
 *   (J·M⁻¹·Jᵀ + α̃)·λ = −C(y),   x = y + M⁻¹·Jᵀ·λ,   α̃ = α/h²,
 *
 * J the springs' unit directions at their particles (±n_s), M the masses, α the compliances, y the prediction. The
 * coarse space ties together the multipliers of the springs of one aggregate: the springs of one cloth whose midpoint
 * lies in one cell of a G × G grid over its texture coordinates, of one kind (structural, shear, bend), and whose rest
 * direction (in those coordinates) falls in one of COARSE_DIRECTIONS directions, so a column's tension and a row's,
 * and the two diagonals', are separate unknowns, and so are springs of very different stiffness (one multiplier, a
 * force, shared by cotton's 8600 N/m structural springs and its skip-one bend springs of a few N/m would be held back
 * by the soft ones' compliance: with the bend springs in the structural springs' aggregates a hanging cotton sheet
 * read 45 times theory at 32², as without the correction). G is about √(the cloth's particles) /
 * COARSE_CELL_PARTICLES, at least COARSE_MIN_CELLS: cells about 8 particles across. With R the springs' aggregates,
 * the step from λ = 0 is
 *
 *   R·(J·M⁻¹·Jᵀ + α̃)·Rᵀ·μ = R·(−C(x)),   λ_s = Σ_k φ_k(s)·μ_k,   x ← x + M⁻¹·Jᵀ·λ,
 *
 * with the directions where the cloth is now, φ_k(s) the bilinear weights of the four aggregates of the spring's
 * direction whose cells' centres surround its midpoint (λ piecewise constant, R·μ, left a sawtooth of ±0.4 % strain
 * in a hanging cotton sheet at 64², one per cell, which one sweep cannot smooth). The matrix is banded (an aggregate
 * meets those of the cells around its own), one block per cloth (no spring joins two cloths); it is assembled and
 * factored (banded Cholesky) in the frame's first substep and whenever h or the params change (and within the frame
 * where the factor's step would overshoot: `overshoots`), and each substep solves with that factor for its own
 * right-hand side (the matrix changes only with the springs' directions; the right-hand side, which holds the
 * strains, is always the substep's own). The sweep then starts each spring from its
 * λ_s (the distance phase accumulates) and removes what the coarse space cannot hold.
 *
 * Measured (docs/physics.md, "A coarse correction of the multipliers"): a hanging sheet's static elongation within a
 * few per cent of theory at the default 20 substeps × 1 pass from 16² to 128², where the sweep alone is 1.3–8 times
 * too long; free fall exact (C = 0 leaves μ = 0); the swinging and falling cloths keep their energy as the sweep's
 * do. A correction of the positions instead (one Gauss–Newton step of the same energy over the same cells) made stiff
 * cloth gain energy in motion. The step is not damped: the springs' damping acts in the sweep after it.
 */
import { BEND, COARSE_OVERSHOOT } from '../layout.generated.js';
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';

/** Rest directions told apart (in texture space, 180°/COARSE_DIRECTIONS apart) [-]. */
export const COARSE_DIRECTIONS = 4;
/** Spring kinds told apart (structural, shear, bend: ids 0 … BEND of the layout table) [-]. */
const KINDS = BEND + 1;
/** About how many particles across one cell of a cloth's grid of aggregates [-]. */
const COARSE_CELL_PARTICLES = 8;
/** The fewest cells per side of a cloth's grid of aggregates [-]. */
const COARSE_MIN_CELLS = 4;

/** Cells per side of the grid of aggregates of a cloth of `particles` particles [-]. */
export function coarseCells(particles: number): number {
  return Math.max(COARSE_MIN_CELLS, Math.round(Math.sqrt(particles) / COARSE_CELL_PARTICLES));
}

/** One model's aggregates, the springs at each particle, and the memory of its solves (made once per model). */
export interface CoarseSystem {
  /** each spring's aggregate (global index) */
  readonly aggregate: Int32Array;
  /** each spring's four nearest aggregates of its direction and their bilinear weights (the λ it is given) */
  readonly nearId: Int32Array;
  readonly nearWeight: Float32Array;
  /** the cloths' blocks of aggregates: cloth c has blockStart[c] … blockStart[c + 1] − 1 */
  readonly blockStart: Int32Array;
  /** each block's half bandwidth (entry (i, j) is zero where i − j exceeds it) */
  readonly band: Int32Array;
  /** where each block's rows start in `matrix`: row i of block c holds entries (i, i − band … i), band + 1 of them */
  readonly matrixStart: Int32Array;
  /** each aggregate's block (its cloth) */
  readonly blockOf: Int32Array;
  /**
   * the springs at each particle: CSR offsets (particles + 1), and 2·s + side per spring s (side 0 at the spring's
   * first particle, where its direction n_s counts +, 1 at its second, where it counts −)
   */
  readonly start: Int32Array;
  readonly incidence: Int32Array;
  /**
   * the blocks' banded matrices (then their factors), the right-hand side (then μ) and a copy of it, each spring's
   * unit direction now (0 where it takes no part)
   */
  readonly matrix: Float64Array;
  readonly rhs: Float64Array;
  readonly residual: Float64Array;
  readonly dir: Float64Array;
  /**
   * per particle (3 each), Jᵀ·λ [N·s²], made before the particles move by M⁻¹·Jᵀ·λ, and, where the step is checked,
   * Jᵀ·Rᵀ·μ with each spring's own aggregate's μ (`overshoots`)
   */
  readonly move: Float64Array;
  readonly own: Float64Array;
  /** one particle's aggregates and their sums of ±n_s (scratch, the most springs a particle has) */
  readonly touched: Int32Array;
  readonly vec: Float64Array;
  /** the params and substep length [s] the factor in `matrix` was made for */
  factoredFor: SimParams | null;
  factoredAt: number;
  /** the factors made so far (the reference's; scripts/coarse-factors.mjs counts them a frame) */
  factors: number;
}

const systems = new WeakMap<ClothModel, CoarseSystem>();

/** The aggregates of `model` (see the file's comment; the WebAssembly kernel copies them: wasm/coarse-wasm.ts). */
export function coarseSystem(model: ClothModel): CoarseSystem {
  const known = systems.get(model);
  if (known) return known;
  const n = model.particleCount, uv = model.uvs, springs = model.springs, ns = springs.length / 2;
  const starts = model.clothStarts, cloths = starts.length - 1;
  const clothOf = new Int32Array(n);
  for (let c = 0; c < cloths; c++) clothOf.fill(c, starts[c], starts[c + 1]);
  // each cloth's grid: its texture-coordinate bounds and cells per side
  const bounds = new Float64Array(4 * cloths), cells = new Int32Array(cloths), first = new Int32Array(cloths + 1);
  for (let c = 0; c < cloths; c++) {
    bounds.set([Infinity, -Infinity, Infinity, -Infinity], 4 * c);
    cells[c] = coarseCells(starts[c + 1] - starts[c]);
    first[c + 1] = first[c] + cells[c] * cells[c] * KINDS * COARSE_DIRECTIONS;
  }
  for (let i = 0; i < n; i++) {
    const o = 4 * clothOf[i];
    bounds[o] = Math.min(bounds[o], uv[2 * i]); bounds[o + 1] = Math.max(bounds[o + 1], uv[2 * i]);
    bounds[o + 2] = Math.min(bounds[o + 2], uv[2 * i + 1]); bounds[o + 3] = Math.max(bounds[o + 3], uv[2 * i + 1]);
  }
  /** spring s's midpoint in cell units (u, v), and its kind and direction class as one number */
  const place = new Float64Array(2 * ns), direction = new Int32Array(ns), kinds = model.springKinds;
  // every (cloth, cell, direction) slot: then, numbered in order among those that hold a spring
  const slot = new Int32Array(first[cloths]).fill(-1), slotOf = new Int32Array(ns);
  for (let s = 0; s < ns; s++) {
    const a = springs[2 * s], b = springs[2 * s + 1], c = clothOf[a], o = 4 * c, G = cells[c];
    const du = bounds[o + 1] - bounds[o] || 1, dv = bounds[o + 3] - bounds[o + 2] || 1;
    place[2 * s] = ((0.5 * (uv[2 * a] + uv[2 * b]) - bounds[o]) / du) * G;
    place[2 * s + 1] = ((0.5 * (uv[2 * a + 1] + uv[2 * b + 1]) - bounds[o + 2]) / dv) * G;
    const cu = Math.min(Math.max(Math.floor(place[2 * s]), 0), G - 1), cv = Math.min(Math.max(Math.floor(place[2 * s + 1]), 0), G - 1);
    let angle = Math.atan2((uv[2 * b + 1] - uv[2 * a + 1]) / dv, (uv[2 * b] - uv[2 * a]) / du);
    if (angle < 0) angle += Math.PI;
    direction[s] = kinds[s] * COARSE_DIRECTIONS + (Math.round(angle / (Math.PI / COARSE_DIRECTIONS)) % COARSE_DIRECTIONS);
    slotOf[s] = first[c] + (cu + G * cv) * KINDS * COARSE_DIRECTIONS + direction[s];
    slot[slotOf[s]] = 0;
  }
  let count = 0;
  const blockStart = new Int32Array(cloths + 1);
  for (let c = 0; c < cloths; c++) {
    blockStart[c] = count;
    for (let k = first[c]; k < first[c + 1]; k++) if (slot[k] === 0) slot[k] = count++;
  }
  blockStart[cloths] = count;
  const aggregate = new Int32Array(ns), blockOf = new Int32Array(count);
  for (let s = 0; s < ns; s++) aggregate[s] = slot[slotOf[s]];
  for (let c = 0; c < cloths; c++) blockOf.fill(c, blockStart[c], blockStart[c + 1]);
  // each spring's λ from the four aggregates of its direction around it: bilinear between the cells' centres
  // (clamped at the cloth's border; a cell without springs of that direction gives its weight to the others)
  const nearId = new Int32Array(4 * ns), nearWeight = new Float32Array(4 * ns), weight = new Float64Array(4);
  for (let s = 0; s < ns; s++) {
    const c = clothOf[springs[2 * s]], G = cells[c];
    const gu = place[2 * s] - 0.5, gv = place[2 * s + 1] - 0.5;
    const iu = Math.min(Math.max(Math.floor(gu), 0), G - 2), iv = Math.min(Math.max(Math.floor(gv), 0), G - 2);
    const fu = Math.min(Math.max(gu - iu, 0), 1), fv = Math.min(Math.max(gv - iv, 0), 1);
    let sum = 0;
    for (let k = 0; k < 4; k++) {
      const id = slot[first[c] + (iu + (k & 1) + G * (iv + (k >> 1))) * KINDS * COARSE_DIRECTIONS + direction[s]];
      const wk = ((k & 1) ? fu : 1 - fu) * ((k >> 1) ? fv : 1 - fv);
      nearId[4 * s + k] = id >= 0 ? id : aggregate[s];
      weight[k] = id >= 0 ? wk : 0;
      sum += weight[k];
    }
    for (let k = 0; k < 4; k++) nearWeight[4 * s + k] = sum > 0 ? weight[k] / sum : k === 0 ? 1 : 0;
  }
  // the springs at each particle
  const start = new Int32Array(n + 1);
  for (let s = 0; s < ns; s++) { start[springs[2 * s] + 1]++; start[springs[2 * s + 1] + 1]++; }
  let mostAt = 0;
  for (let i = 0; i < n; i++) { mostAt = Math.max(mostAt, start[i + 1]); start[i + 1] += start[i]; }
  const incidence = new Int32Array(2 * ns), fill = start.slice(0, n);
  for (let s = 0; s < ns; s++) {
    incidence[fill[springs[2 * s]]++] = 2 * s;
    incidence[fill[springs[2 * s + 1]]++] = 2 * s + 1;
  }
  // each block's bandwidth: the farthest apart two aggregates that meet at a particle
  const band = new Int32Array(cloths);
  for (let i = 0; i < n; i++) {
    let lo = Infinity, hi = -Infinity;
    for (let p = start[i]; p < start[i + 1]; p++) { lo = Math.min(lo, aggregate[incidence[p] >> 1]); hi = Math.max(hi, aggregate[incidence[p] >> 1]); }
    if (hi >= lo) band[clothOf[i]] = Math.max(band[clothOf[i]], hi - lo);
  }
  const matrixStart = new Int32Array(cloths + 1);
  for (let c = 0; c < cloths; c++) matrixStart[c + 1] = matrixStart[c] + (blockStart[c + 1] - blockStart[c]) * (band[c] + 1);
  const system: CoarseSystem = {
    aggregate, nearId, nearWeight, blockStart, band, matrixStart, blockOf, start, incidence,
    matrix: new Float64Array(matrixStart[cloths]), rhs: new Float64Array(count), residual: new Float64Array(count), dir: new Float64Array(3 * ns),
    move: new Float64Array(3 * n), own: new Float64Array(3 * n),
    touched: new Int32Array(mostAt), vec: new Float64Array(3 * mostAt), factoredFor: null, factoredAt: 0, factors: 0,
  };
  systems.set(model, system);
  return system;
}

/**
 * The coarse correction of one substep of length h [s] (see the file's comment): sets state.lambdas (every spring's
 * multiplier, 0 for a spring without stiffness) and moves the free particles by M⁻¹·Jᵀ·λ. `refactor`: assemble and
 * factor the matrix from the springs' directions now (the frame's first substep); otherwise the last factor serves,
 * unless h or the params changed, or the step it gives overshoots under the matrix now (`overshoots`: cloth that
 * crumples within a frame, its springs' chains no longer straight, is stiffer than the factor says), when the matrix
 * is made anew and the step solved again. Allocates nothing.
 */
export function solveCoarseStretch(model: ClothModel, state: ClothState, params: SimParams, h: number, refactor: boolean): void {
  const sys = coarseSystem(model);
  const w = state.invMass, lambdas = state.lambdas, compliance = params.compliance, { rhs, residual } = sys;
  const factor = refactor || sys.factoredFor !== params || sys.factoredAt !== h;
  const invH2 = 1 / (h * h);
  // (the loops live in functions of their own: in one function with the branches around them, V8 compiled the first
  // loop on the stack and dropped back to the interpreter at the branch after it, every substep: node --trace-deopt)
  directions(sys, model, state.positions, w, compliance);
  if (factor) factorNow(sys, model, params, h, w);
  else residual.set(rhs);
  solveBlocks(sys);
  if (factor) spread(sys, model, lambdas, compliance, invH2, false);
  else if (overshoots(sys, spread(sys, model, lambdas, compliance, invH2, true) + ownEnergy(sys, w))) {
    rhs.set(residual);
    factorNow(sys, model, params, h, w);
    solveBlocks(sys);
    spread(sys, model, lambdas, compliance, invH2, false);
  }
  apply(sys, state.positions, w);
}

/** Each spring's unit direction now into sys.dir (0 where it takes no part), its residual −C into its aggregate's row. */
function directions(sys: CoarseSystem, model: ClothModel, x: Float32Array, w: Float32Array, compliance: Float32Array): void {
  const { aggregate, rhs, dir } = sys, springs = model.springs, rest = model.restLengths;
  rhs.fill(0);
  for (let s = 0; s < rest.length; s++) {
    const d = 3 * s;
    dir[d] = 0; dir[d + 1] = 0; dir[d + 2] = 0;
    const alpha = compliance[s], pa = springs[2 * s], pb = springs[2 * s + 1];
    if (alpha === Infinity || w[pa] + w[pb] === 0) continue;
    const a = 3 * pa, b = 3 * pb;
    const dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
    const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
    if (!(len > 1e-12)) continue;
    const inv = 1 / len;
    dir[d] = dx * inv; dir[d + 1] = dy * inv; dir[d + 2] = dz * inv;
    rhs[aggregate[s]] += rest[s] - len;
  }
}

/** The free particles moved by M⁻¹·Jᵀ·λ (sys.move). */
function apply(sys: CoarseSystem, x: Float32Array, w: Float32Array): void {
  const move = sys.move;
  for (let i = 0; i < w.length; i++) {
    const wi = w[i];
    if (wi === 0) continue;
    x[3 * i] += wi * move[3 * i]; x[3 * i + 1] += wi * move[3 * i + 1]; x[3 * i + 2] += wi * move[3 * i + 2];
  }
}

/** Solves every block for sys.rhs with its factor (μ in place of the right-hand side). */
function solveBlocks(sys: CoarseSystem): void {
  const { blockStart, band, matrixStart, matrix, rhs } = sys;
  for (let c = 0; c + 1 < blockStart.length; c++) solveBand(matrix, matrixStart[c], rhs, blockStart[c], blockStart[c + 1] - blockStart[c], band[c]);
}

/**
 * Each spring's λ, interpolated between the aggregates of its direction (0 for a spring that takes no part), and
 * Jᵀ·λ into sys.move: +λ_s·n_s at the spring's first particle, −λ_s·n_s at its second. `check`: also Jᵀ·Rᵀ·μ into
 * sys.own, and returns Σ_s α̃_s·μ_g(s)² over the springs that take part (the compliance's share of μᵀ·A·μ,
 * `overshoots`); else 0.
 */
function spread(sys: CoarseSystem, model: ClothModel, lambdas: Float32Array, compliance: Float32Array, invH2: number, check: boolean): number {
  const { aggregate, nearId, nearWeight, rhs, dir, move, own } = sys, springs = model.springs;
  move.fill(0);
  if (check) own.fill(0);
  // (summed in an array: a local that starts as the integer 0 and gains fractions is boxed at every addition once
  // V8 has seen it stay 0 on the calls that check nothing, 1.9 MB a frame in the default scene's TypeScript kernel)
  const energy = energySum;
  energy[0] = 0;
  for (let s = 0; s < lambdas.length; s++) {
    const d = 3 * s, k = 4 * s;
    const nx = dir[d], ny = dir[d + 1], nz = dir[d + 2];
    if (nx === 0 && ny === 0 && nz === 0) { lambdas[s] = 0; continue; }
    const l = Math.fround(nearWeight[k] * rhs[nearId[k]] + nearWeight[k + 1] * rhs[nearId[k + 1]] + nearWeight[k + 2] * rhs[nearId[k + 2]] + nearWeight[k + 3] * rhs[nearId[k + 3]]);
    lambdas[s] = l;
    const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
    move[a] += l * nx; move[a + 1] += l * ny; move[a + 2] += l * nz;
    move[b] -= l * nx; move[b + 1] -= l * ny; move[b + 2] -= l * nz;
    if (check) {
      const mu = rhs[aggregate[s]];
      energy[0] += compliance[s] * invH2 * mu * mu;
      own[a] += mu * nx; own[a + 1] += mu * ny; own[a + 2] += mu * nz;
      own[b] -= mu * nx; own[b + 1] -= mu * ny; own[b + 2] -= mu * nz;
    }
  }
  return energy[0];
}

/** spread's sum of the energy */
const energySum = new Float64Array(1);

/** Σ_i w_i·|(Jᵀ·Rᵀ·μ)_i|² over the free particles (sys.own; the masses' share of μᵀ·A·μ, `overshoots`). */
function ownEnergy(sys: CoarseSystem, w: Float32Array): number {
  const own = sys.own;
  let energy = 0;
  for (let i = 0; i < w.length; i++) {
    const wi = w[i];
    if (wi === 0) continue;
    energy += wi * (own[3 * i] * own[3 * i] + own[3 * i + 1] * own[3 * i + 1] + own[3 * i + 2] * own[3 * i + 2]);
  }
  return energy;
}

/**
 * The blocks' matrices made from the springs' directions in sys.dir (α̃ on the diagonal of each spring's aggregate,
 * then J·M⁻¹·Jᵀ) and factored, for `params` and substep h [s].
 */
function factorNow(sys: CoarseSystem, model: ClothModel, params: SimParams, h: number, w: Float32Array): void {
  const { aggregate, blockStart, band, matrixStart, blockOf, matrix, dir } = sys;
  const compliance = params.compliance, invH2 = 1 / (h * h), cloths = blockStart.length - 1;
  matrix.fill(0);
  for (let s = 0; s < compliance.length; s++) {
    if (dir[3 * s] === 0 && dir[3 * s + 1] === 0 && dir[3 * s + 2] === 0) continue;
    const g = aggregate[s], c = blockOf[g], bw = band[c];
    matrix[matrixStart[c] + (g - blockStart[c]) * (bw + 1) + bw] += compliance[s] * invH2;
  }
  assemble(sys, model, w);
  for (let c = 0; c < cloths; c++) factorBand(matrix, matrixStart[c], blockStart[c + 1] - blockStart[c], band[c]);
  sys.factoredFor = params;
  sys.factoredAt = h;
  sys.factors++;
}

/**
 * Whether the step μ (sys.rhs) just solved for with a factor of an earlier substep, A₀, overshoots under the matrix
 * of the springs' directions now, A: its Rayleigh quotient μᵀ·A·μ / μᵀ·A₀·μ past COARSE_OVERSHOOT, where
 * μᵀ·A₀·μ = μᵀ·r (sys.residual, the right-hand side it was solved for) and `energy`, μᵀ·A·μ =
 * Σ_s α̃_s·μ_g(s)² + Σ_i w_i·|Σ ±μ_g(s)·n_s|² over the springs at each particle, with each spring's own aggregate's μ
 * (the matrix's), made by spread and ownEnergy beside the step's λ and move.
 */
function overshoots(sys: CoarseSystem, energy: number): boolean {
  const { rhs, residual } = sys;
  let before = 0;
  for (let g = 0; g < rhs.length; g++) before += rhs[g] * residual[g];
  return before > 0 && energy > COARSE_OVERSHOOT * before;
}

/**
 * Adds J·M⁻¹·Jᵀ of the springs' directions in sys.dir to the blocks' matrices. At each free particle i, the springs of
 * each aggregate g it touches sum to v_g = Σ ±n_s (+ at a spring's first particle), and the particle adds w_i·v_g·v_h
 * to entry (g, h): a handful of aggregates per particle instead of every pair of its springs (the lower triangle only).
 */
function assemble(sys: CoarseSystem, model: ClothModel, w: Float32Array): void {
  const { aggregate, blockStart, band, matrixStart, blockOf, start, incidence, matrix, dir, touched, vec } = sys;
  for (let i = 0; i < model.particleCount; i++) {
    const wi = w[i];
    if (wi === 0) continue;
    let m = 0;
    for (let p = start[i]; p < start[i + 1]; p++) {
      const code = incidence[p], s = code >> 1, ds = 3 * s;
      if (dir[ds] === 0 && dir[ds + 1] === 0 && dir[ds + 2] === 0) continue;
      const g = aggregate[s];
      let k = 0;
      while (k < m && touched[k] !== g) k++;
      if (k === m) { touched[m] = g; vec[3 * m] = 0; vec[3 * m + 1] = 0; vec[3 * m + 2] = 0; m++; }
      if (code & 1) { vec[3 * k] -= dir[ds]; vec[3 * k + 1] -= dir[ds + 1]; vec[3 * k + 2] -= dir[ds + 2]; }
      else { vec[3 * k] += dir[ds]; vec[3 * k + 1] += dir[ds + 1]; vec[3 * k + 2] += dir[ds + 2]; }
    }
    if (m === 0) continue;
    const c = blockOf[touched[0]], b0 = blockStart[c], bw = band[c], m0 = matrixStart[c];
    for (let k = 0; k < m; k++) {
      const gk = touched[k], vx = wi * vec[3 * k], vy = wi * vec[3 * k + 1], vz = wi * vec[3 * k + 2];
      const row = m0 + (gk - b0) * (bw + 1) + bw - gk;
      for (let l = 0; l < m; l++) {
        const gl = touched[l];
        if (gl <= gk) matrix[row + gl] += vx * vec[3 * l] + vy * vec[3 * l + 1] + vz * vec[3 * l + 2];
      }
    }
  }
}

/**
 * Factors one block in place by banded Cholesky: `size` rows at matrix[m…], row i holding entries (i, i − bw … i) in
 * its bw + 1 places (the lower triangle; places before column 0 unused). An aggregate with no spring taking part (all
 * without stiffness, or between pinned particles) has an empty row: its μ comes out 0. A block that is not positive
 * definite (a non-finite cloth) is left a zero factor, which solveBand takes for no correction.
 */
function factorBand(matrix: Float64Array, m: number, size: number, bw: number): void {
  const stride = bw + 1;
  for (let j = 0; j < size; j++) if (matrix[m + j * stride + bw] === 0) matrix[m + j * stride + bw] = 1;
  for (let j = 0; j < size; j++) {
    const rj = m + j * stride + bw - j; // entry (j, k) at rj + k
    const k0 = Math.max(0, j - bw);
    let d = matrix[rj + j] - dot(matrix, rj + k0, matrix, rj + k0, j - k0);
    if (!(d > 0)) { matrix.fill(0, m, m + size * stride); return; }
    d = Math.sqrt(d);
    matrix[rj + j] = d;
    for (let i = j + 1; i < Math.min(size, j + bw + 1); i++) {
      const ri = m + i * stride + bw - i, k = Math.max(k0, i - bw);
      matrix[ri + j] = (matrix[ri + j] - dot(matrix, ri + k, matrix, rj + k, j - k)) / d;
    }
  }
}

/**
 * Σ a[p + t]·b[q + t] over t < len, in four running sums (t mod 4; the last len mod 4 terms into the first), added as
 * (s0 + s2) + (s1 + s3): the order the kernel's two f64x2 lanes take (coarse.as.ts dot), which a single running sum
 * would make wait on each addition.
 */
function dot(a: Float64Array, p: number, b: Float64Array, q: number, len: number): number {
  let s0 = 0, s1 = 0, s2 = 0, s3 = 0, t = 0;
  for (; t + 4 <= len; t += 4) {
    s0 += a[p + t] * b[q + t]; s1 += a[p + t + 1] * b[q + t + 1];
    s2 += a[p + t + 2] * b[q + t + 2]; s3 += a[p + t + 3] * b[q + t + 3];
  }
  for (; t < len; t++) s0 += a[p + t] * b[q + t];
  return (s0 + s2) + (s1 + s3);
}

/** Solves one factored block (factorBand) for the right-hand side rhs[r…r + size), in place; 0 for a zero factor. */
function solveBand(matrix: Float64Array, m: number, rhs: Float64Array, r: number, size: number, bw: number): void {
  const stride = bw + 1;
  if (size === 0) return;
  if (matrix[m + bw] === 0) { rhs.fill(0, r, r + size); return; }
  // forward, L·y = b, each row's dot product with the solved y before it; backward, Lᵀ·x = y, from the last row up:
  // x_i, then row i of L (contiguous) times x_i off the rows above it, which lie within its band
  for (let i = 0; i < size; i++) {
    const ri = m + i * stride + bw - i, k = Math.max(0, i - bw);
    rhs[r + i] = (rhs[r + i] - dot(matrix, ri + k, rhs, r + k, i - k)) / matrix[ri + i];
  }
  for (let i = size - 1; i >= 0; i--) {
    const ri = m + i * stride + bw - i, xi = rhs[r + i] / matrix[ri + i];
    rhs[r + i] = xi;
    for (let k = Math.max(0, i - bw); k < i; k++) rhs[r + k] -= matrix[ri + k] * xi;
  }
}
