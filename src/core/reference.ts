/**
 * The TypeScript reference implementation of every phase of the schedule (schedule.ts), by phase id: what the
 * TypeScript backend runs, what the other backends are measured against, and what runs a phase on a backend's
 * memory where the backend does not implement it. Each entry only calls the phase functions (phases.ts, tethers.ts,
 * the solvers' own phases); nothing here allocates.
 */
import type { FrameVars } from './frame.js';
import type { ClothModel } from './model.js';
import type { SimParams } from './params.js';
import { accumulateWind, beginStep, carryPinned, collideParticles, collideTriangles, integrate, limitStretch, moveGrabbed, updateVelocities } from './phases.js';
import { PHASE, PHASES, phasePasses, type PhaseName } from './schedule.js';
import { accumulateSpringForces } from './solvers/mass-spring.js';
import { collideSelf } from './self-contact.js';
import { solveCoarseStretch } from './solvers/coarse-stretch.js';
import { solveGlobalBending } from './solvers/global-bending.js';
import { solveGlobalStretch } from './solvers/global-stretch.js';
import { solveBending, solveDistanceConstraints } from './solvers/xpbd.js';
import type { ClothState } from './state.js';
import { solveTethers } from './tethers.js';

/** A phase's reference implementation, for substep `frame.sub` of the frame. */
export type ReferencePhase = (model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars) => void;

/** One implementation per phase name (the compiler checks that none is missing) → a table by phase id. */
function byId(phases: Record<PhaseName, ReferencePhase>): readonly ReferencePhase[] {
  return PHASES.map((phase) => phases[phase.name]);
}

/** The reference implementation of each phase: REFERENCE[id] runs phase `id`. */
export const REFERENCE: readonly ReferencePhase[] = byId({
  begin: (model, state, params, frame) => beginStep(model, state, params, frame.h),
  wind(model, state, params, frame) {
    accumulateWind(model, state, params, state.time, frame.h);
    frame.forced = true;
  },
  springForces(model, state, params, frame) {
    if (!frame.forced) state.forces.fill(0);
    accumulateSpringForces(model, state, params, frame.h);
    frame.forced = true;
  },
  integrate: (_model, state, params, frame) => integrate(state, params, frame.h, frame.forced),
  carry: (_model, state, params, frame) => carryPinned(state, params, state.time, state.time + frame.h),
  grab: (_model, state, _params, frame) => moveGrabbed(state, frame.grabFrom, frame.grabTo, (frame.sub + 1) / frame.substeps),
  globalStretch: (model, state, params, frame) => solveGlobalStretch(model, state, params, frame.h, phasePasses(PHASE.globalStretch, params)),
  coarseStretch: (model, state, params, frame) => solveCoarseStretch(model, state, params, frame.h, frame.sub === 0),
  distance(model, state, params, frame) {
    const passes = phasePasses(PHASE.distance, params);
    // λ accumulates across the passes of a substep: from zero in each, or from the coarse correction's
    const coarse = params.stretch === 'two-level', accumulate = passes > 1 || coarse;
    if (accumulate && !coarse) state.lambdas.fill(0);
    for (let it = 0; it < passes; it++) solveDistanceConstraints(model, state, params, frame.h, accumulate);
  },
  bending(model, state, params, frame) {
    const passes = phasePasses(PHASE.bending, params);
    const accumulate = passes > 1;
    if (accumulate) state.bendingLambdas.fill(0);
    for (let it = 0; it < passes; it++) solveBending(model, state, params, frame.h, accumulate);
  },
  globalBending: (model, state, params, frame) => solveGlobalBending(model, state, params, frame.h),
  tethers: (_model, state, params) => solveTethers(state, params),
  stretchLimit(model, state, params) {
    const passes = phasePasses(PHASE.stretchLimit, params);
    for (let it = 0; it < passes; it++) limitStretch(model, state, params);
  },
  selfContact: (model, state, params, frame) => collideSelf(model, state, params, frame.h, frame.substeps - frame.sub),
  contact: (model, state, params, frame) => collideParticles(model, state, params, frame.h),
  contactTriangles: (model, state, params, frame) => collideTriangles(model, state, params, frame.h),
  velocities: (_model, state, _params, frame) => updateVelocities(state, frame.h),
});
