import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { SolverType } from '../scene.js';
import type { ClothState } from '../state.js';
import * as massSpring from './mass-spring.js';
import * as xpbd from './xpbd.js';

/** A stateless stepper: advances `state` by dt [s] using `model` and `params`; allocates nothing. */
export type StepFn = (model: ClothModel, state: ClothState, params: SimParams, dt: number) => void;

export const SOLVERS: Readonly<Record<SolverType, StepFn>> = {
  xpbd: xpbd.step,
  'mass-spring': massSpring.step,
};

/** Steps with the solver the params name. */
export function step(model: ClothModel, state: ClothState, params: SimParams, dt: number): void {
  SOLVERS[params.solver](model, state, params, dt);
}
