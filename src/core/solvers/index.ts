import { runFrame } from '../frame.js';
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { SolverType } from '../scene.js';
import type { ClothState } from '../state.js';

/** A stateless stepper: advances `state` by dt [s] using `model` and `params`; allocates nothing. */
export type StepFn = (model: ClothModel, state: ClothState, params: SimParams, dt: number) => void;

/** XPBD (solvers/xpbd.ts), every phase in TypeScript (the kernel's frames: backend.ts WasmBackend). */
function stepXpbd(model: ClothModel, state: ClothState, params: SimParams, dt: number): void {
  runFrame(model, state, params, dt);
}

/** Mass-spring (solvers/mass-spring.ts): in TypeScript, whatever memory the state's arrays live in. */
function stepMassSpring(model: ClothModel, state: ClothState, params: SimParams, dt: number): void {
  runFrame(model, state, params, dt);
}

/**
 * The stepper of each solver type, for params whose `solver` is that type (a frame runs the schedule's phases of
 * params.solver).
 */
export const SOLVERS: Readonly<Record<SolverType, StepFn>> = {
  xpbd: stepXpbd,
  'mass-spring': stepMassSpring,
};

/** Steps with the solver the params name. */
export function step(model: ClothModel, state: ClothState, params: SimParams, dt: number): void {
  SOLVERS[params.solver](model, state, params, dt);
}
