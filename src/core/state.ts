import type { ClothModel } from './model.js';

/**
 * Everything about a cloth that changes while it runs: flat typed arrays, one entry per particle (vec3 data with
 * stride 3), plus the interaction state (pins, grab) and scratch space so that a step never allocates.
 */
export interface ClothState {
  /** positions [m], stride 3 */
  readonly positions: Float32Array;
  /** positions at the start of the last substep [m], stride 3 */
  readonly previousPositions: Float32Array;
  /**
   * the part of each position finer than float32 resolves [m], stride 3: the position is positions + residuals.
   * Integration keeps what rounding to float32 drops here, so that the small steps of gravity (g·h², 7·10⁻⁸ m at 200
   * substeps) are not lost against a position's last bit (1.2·10⁻⁷ m at 1 m, 6·10⁻⁵ m at 1 km) (phases.ts integrate)
   */
  readonly residuals: Float32Array;
  /** the residuals of previousPositions [m], stride 3 */
  readonly previousResiduals: Float32Array;
  /** velocities at the end of the last step [m/s], stride 3 (a step derives them from positions) */
  readonly velocities: Float32Array;
  /** 1 where a particle is pinned (does not move), else 0 */
  readonly pinned: Uint8Array;
  /** effective inverse masses of the current step [1/kg]; 0 for pinned and grabbed particles (solver scratch) */
  readonly invMass: Float32Array;
  /** external force accumulator [N], stride 3 (solver scratch) */
  readonly forces: Float32Array;
  /** XPBD Lagrange multipliers of the last substep (damping included, the stretch cap not), one per spring [N·s²]; f = λ/h² */
  readonly lambdas: Float32Array;
  /**
   * XPBD Lagrange multipliers of the bending stencils (solver.bending 'hinges' or 'laplacian'), 3 per stencil of
   * the params' model (room for the larger of the two) [N·s²]: where solver.iterations > 1 they accumulate over a
   * substep's passes
   */
  readonly bendingLambdas: Float32Array;
  /**
   * long-range attachment of each particle: the nearest pinned particle, or -1 (derived from `pinned` by
   * updateTethers when `tethersStale` is set)
   */
  readonly tetherAnchors: Int32Array;
  /** rest distance from each particle to its tether anchor [m] */
  readonly tetherLengths: Float32Array;
  /** true when pins changed since the tethers were computed */
  tethersStale: boolean;
  /** grabbed particle index, -1 when nothing is grabbed */
  grabbed: number;
  /** where the grabbed particle is being moved to [m] */
  readonly grabTarget: Float64Array;
  /** simulated time since the start [s] */
  time: number;
  /** substeps taken since the start (0 means the next one is the very first) */
  substeps: number;
}

/** The typed arrays of a state, for createState to place somewhere else (a WebAssembly memory). */
export interface StateArrays {
  positions: Float32Array;
  previousPositions: Float32Array;
  residuals: Float32Array;
  previousResiduals: Float32Array;
  velocities: Float32Array;
  invMass: Float32Array;
  forces: Float32Array;
  lambdas: Float32Array;
  tetherAnchors: Int32Array;
  tetherLengths: Float32Array;
  /** λ of the bending stencils, 3 per stencil of the model's larger stencil set (new when not given) */
  bendingLambdas?: Float32Array;
}

/**
 * A state at the model's start pose, at rest. `arrays` (of the right lengths) are for a backend that keeps them in
 * its own memory (the WebAssembly kernel); by default the arrays are new.
 */
export function createState(model: ClothModel, arrays?: StateArrays): ClothState {
  const n = model.particleCount;
  const a: StateArrays = arrays ?? {
    positions: new Float32Array(3 * n),
    previousPositions: new Float32Array(3 * n),
    residuals: new Float32Array(3 * n),
    previousResiduals: new Float32Array(3 * n),
    velocities: new Float32Array(3 * n),
    invMass: new Float32Array(n),
    forces: new Float32Array(3 * n),
    lambdas: new Float32Array(model.restLengths.length),
    tetherAnchors: new Int32Array(n),
    tetherLengths: new Float32Array(n),
  };
  a.tetherAnchors.fill(-1);
  const state: ClothState = {
    ...a,
    bendingLambdas: a.bendingLambdas ?? new Float32Array(3 * Math.max(model.stencils.hinges.areas.length, model.stencils.laplacian.areas.length)),
    pinned: new Uint8Array(n),
    tethersStale: true,
    grabbed: -1,
    grabTarget: new Float64Array(3),
    time: 0,
    substeps: 0,
  };
  resetState(model, state);
  return state;
}

/** Puts the cloth back at its start pose, at rest; pins are kept, a grab is released. */
export function resetState(model: ClothModel, state: ClothState): void {
  state.positions.set(model.restPositions);
  state.previousPositions.set(model.restPositions);
  state.residuals.fill(0);
  state.previousResiduals.fill(0);
  state.velocities.fill(0);
  state.lambdas.fill(0);
  state.bendingLambdas.fill(0);
  state.grabbed = -1;
  state.time = 0;
  state.substeps = 0;
}

/** Farthest a grab may carry a particle from the origin, per coordinate [m] (the schema's positions reach ±1000). */
export const MAX_GRAB_COORDINATE = 10_000;

/** Throws a RangeError naming `fn` unless `particle` is an index of the state's particles. */
function checkParticle(fn: string, state: ClothState, particle: number): void {
  if (!(Number.isInteger(particle) && particle >= 0 && particle < state.pinned.length)) {
    throw new RangeError(`${fn}: particle must be an integer in 0…${state.pinned.length - 1}, got ${String(particle)}`);
  }
}

/** Pins or unpins one particle; takes effect on the next step. */
export function setPinned(state: ClothState, particle: number, pinned: boolean): void {
  checkParticle('setPinned', state, particle);
  if (typeof pinned !== 'boolean') throw new TypeError(`setPinned: pinned must be true or false, got ${String(pinned)}`);
  state.pinned[particle] = pinned ? 1 : 0;
  state.tethersStale = true;
  if (pinned) {
    state.velocities[3 * particle] = 0;
    state.velocities[3 * particle + 1] = 0;
    state.velocities[3 * particle + 2] = 0;
  }
}

/**
 * Starts (or moves) a grab: the particle is carried to `target` [m] over the next step and held there — with
 * self-contact on, at most at solver.selfContactSpeed (params.grabSpeed), so a far target takes more steps. The
 * target must be three finite numbers within ±MAX_GRAB_COORDINATE.
 */
export function grab(state: ClothState, particle: number, target: readonly [number, number, number]): void {
  checkParticle('grab', state, particle);
  if (!Array.isArray(target) && !ArrayBuffer.isView(target) || target.length !== 3 ||
      ![0, 1, 2].every((k) => Number.isFinite(target[k]) && Math.abs(target[k]) <= MAX_GRAB_COORDINATE)) {
    const shown = Array.isArray(target) ? `[${target.map(String).join(', ')}]` : String(target);
    throw new RangeError(`grab: target must be [x, y, z] of finite numbers within ±${MAX_GRAB_COORDINATE} m, got ${shown}`);
  }
  state.grabbed = particle;
  state.grabTarget[0] = target[0];
  state.grabTarget[1] = target[1];
  state.grabTarget[2] = target[2];
}

/** Lets the grabbed particle go; it keeps the velocity it was moved with. */
export function release(state: ClothState): void {
  state.grabbed = -1;
}

/** Copies positions and velocities from one state to another of the same model (e.g. a backend switch). */
export function copyState(from: ClothState, to: ClothState): void {
  to.positions.set(from.positions);
  to.previousPositions.set(from.previousPositions);
  to.residuals.set(from.residuals);
  to.previousResiduals.set(from.previousResiduals);
  to.velocities.set(from.velocities);
  to.pinned.set(from.pinned);
  to.tethersStale = true;
  to.grabbed = from.grabbed;
  to.grabTarget.set(from.grabTarget);
  to.time = from.time;
  to.substeps = from.substeps;
}
