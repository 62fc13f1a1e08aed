/**
 * The frame loop of every backend: one frame of dt in params.substeps substeps is the schedule (schedule.ts) walked
 * in order, each phase run by the backend where it implements it and by the TypeScript reference (reference.ts) on
 * the same memory where it does not (assignPhases says which). The TypeScript solvers run it with no backend, the
 * WebAssembly kernel and the GPU solver with themselves.
 */
import type { ClothModel } from './model.js';
import type { SimParams } from './params.js';
import { grabFrameTarget, keepGrabOutside } from './phases.js';
import { REFERENCE } from './reference.js';
import { PHASE_COUNT, SCOPE_PHASES, assignPhases, framePhases, type BackendPhases, type PhaseLog } from './schedule.js';
import type { ClothState } from './state.js';

/** What the phases of a frame share besides model, state and params: one object, reused by every frame. */
export interface FrameVars {
  /** substep length [s] */
  h: number;
  /** substeps of the frame */
  substeps: number;
  /** the substep running, 0…substeps − 1 (frame-start phases see 0, frame-end phases substeps − 1) */
  sub: number;
  /** whether a phase of this substep accumulated forces in state.forces (integrate applies them) */
  forced: boolean;
  /** position of the grabbed particle after the frame-start phases [m] (the grab carries it from there) */
  readonly grabFrom: Float64Array;
  /** where the grab carries it by the frame's end [m]: the grab target, or as far toward it as params.grabSpeed allows */
  readonly grabTo: Float64Array;
}

/** A backend the frame loop hands phases to. */
export interface PhaseBackend {
  /** what it implements */
  readonly phases: BackendPhases;
  /**
   * Runs the phases of `mask` (its own, consecutive among this frame's phases, of one scope) in schedule order, for
   * substep frame.sub, and appends each to `log` as it runs it.
   */
  run(mask: number, model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars, log: PhaseLog | undefined): void;
}

const vars: FrameVars = { h: 0, substeps: 0, sub: 0, forced: false, grabFrom: new Float64Array(3), grabTo: new Float64Array(3) };

/**
 * Advances the cloth by dt [s] in params.substeps substeps: the schedule's phases for params.solver, run by
 * `backend` where it implements them, else by the TypeScript reference; `state.time` and `state.substeps` count
 * the substeps. `log` (tests) receives every phase run, in order.
 */
export function runFrame(
  model: ClothModel, state: ClothState, params: SimParams, dt: number, backend?: PhaseBackend, log?: PhaseLog,
): void {
  const n = params.substeps;
  const f = vars;
  f.h = dt / n;
  f.substeps = n;
  f.sub = 0;
  f.forced = false;
  const own = backend ? assignPhases(backend.phases, model, params) : 0;
  const phases = framePhases(model, state, params);
  keepGrabOutside(state, params, state.time, state.time + dt);
  runPhases(phases & SCOPE_PHASES['frame-start'], own, backend, model, state, params, log);
  const g = state.grabbed, x = state.positions, from = f.grabFrom;
  if (g >= 0) {
    from[0] = x[3 * g]; from[1] = x[3 * g + 1]; from[2] = x[3 * g + 2];
    grabFrameTarget(from, state.grabTarget, params.grabSpeed * dt, f.grabTo);
    // short of the target, the frame's own end is kept out of the colliders too (the target already is)
    if (f.grabTo[0] !== state.grabTarget[0] || f.grabTo[1] !== state.grabTarget[1] || f.grabTo[2] !== state.grabTarget[2]) {
      keepGrabOutside(state, params, state.time, state.time + dt, f.grabTo);
    }
  }
  for (let sub = 0; sub < n; sub++) {
    f.sub = sub;
    f.forced = false;
    runPhases(phases & SCOPE_PHASES.substep, own, backend, model, state, params, log);
    state.time += f.h;
    state.substeps++;
  }
  f.sub = n - 1;
  runPhases(phases & SCOPE_PHASES['frame-end'], own, backend, model, state, params, log);
}

/** The phases of `mask` in order: runs of the backend's own (`own`) to the backend, the others to the reference. */
function runPhases(
  mask: number, own: number, backend: PhaseBackend | undefined,
  model: ClothModel, state: ClothState, params: SimParams, log: PhaseLog | undefined,
): void {
  let pending = 0;
  for (let id = 0; id < PHASE_COUNT; id++) {
    const bit = 1 << id;
    if ((mask & bit) === 0) continue;
    if ((own & bit) !== 0) {
      pending |= bit;
      continue;
    }
    if (pending !== 0) {
      backend!.run(pending, model, state, params, vars, log);
      pending = 0;
    }
    REFERENCE[id](model, state, params, vars);
    log?.push(id, true);
  }
  if (pending !== 0) backend!.run(pending, model, state, params, vars, log);
}
