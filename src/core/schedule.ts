/**
 * The phase schedule: the one ordered list of what a frame does, which every backend follows (the TypeScript
 * reference, the WebAssembly kernel, WebGPU), and the one rule for a phase a backend does not implement. The list
 * is a table of the one table (PHASES in gen-layout.mjs, generated into layout.generated.ts, so that the kernel
 * shares its ids); this module gives it types and says which phases a frame runs and which backend runs each.
 * core/frame.ts walks it.
 */
import { PHASE, PHASE_COUNT, SCHEDULE } from './layout.generated.js';
import type { ClothModel } from './model.js';
import type { SimParams } from './params.js';
import { needsTriangleContact } from './phases.js';
import type { SolverType } from './scene.js';
import type { ClothState } from './state.js';

export { PHASE, PHASE_COUNT };

/** A phase's name in the schedule. */
export type PhaseName = keyof typeof PHASE;
/** A phase's id: its place in the schedule (ascending ids are the order; a set of phases is a mask of 1 << id). */
export type PhaseId = (typeof PHASE)[PhaseName];
/** When a phase runs: once before the substeps, every substep, or once after them. */
export type PhaseScope = 'frame-start' | 'substep' | 'frame-end';
/**
 * What a phase needs to be part of a frame: nothing, the air acting (wind.enabled: a wind, or still air), a
 * grabbed particle, pins a collider carries, a collider whose surface can poke between the cloth's vertices
 * (phases.ts needsTriangleContact), a stencil bending model (solver.bending 'hinges' or 'laplacian') solved one stencil at
 * a time (solver.bendingSolve 'gauss-seidel') or together ('global'), the springs solved together (solver.stretch
 * 'global') or one at a time ('gauss-seidel', or 'two-level': one at a time after the coarse correction, whose phase
 * is 'coarse'), self-contact (solver.selfContact).
 */
export type PhaseCondition = 'always' | 'wind' | 'grab' | 'carried' | 'triangles' | 'stencils' | 'stencils-global' | 'global' | 'local' | 'coarse' | 'self';

/** One row of the schedule (see PHASES in gen-layout.mjs). */
export interface Phase {
  readonly id: PhaseId;
  readonly name: PhaseName;
  readonly scope: PhaseScope;
  /** the solver types whose frame has this phase */
  readonly solvers: readonly SolverType[];
  readonly when: PhaseCondition;
  /** the solver types for which it runs solver.iterations passes per substep (others: one) */
  readonly repeat: readonly SolverType[];
  /** what it does, for messages and docs */
  readonly doc: string;
}

/** The schedule of one frame, in order: PHASES[id] is phase `id`. */
export const PHASES: readonly Phase[] = SCHEDULE;

/** The mask of the phases for which `test` holds. */
function maskOf(test: (phase: Phase) => boolean): number {
  let mask = 0;
  for (const phase of PHASES) if (test(phase)) mask |= 1 << phase.id;
  return mask;
}

/** The phases of each scope, as masks. */
export const SCOPE_PHASES: Readonly<Record<PhaseScope, number>> = {
  'frame-start': maskOf((p) => p.scope === 'frame-start'),
  substep: maskOf((p) => p.scope === 'substep'),
  'frame-end': maskOf((p) => p.scope === 'frame-end'),
};
const WIND_PHASES = maskOf((p) => p.when === 'wind');
const GRAB_PHASES = maskOf((p) => p.when === 'grab');
const CARRY_PHASES = maskOf((p) => p.when === 'carried');
const TRIANGLE_PHASES = maskOf((p) => p.when === 'triangles');
const STENCIL_PHASES = maskOf((p) => p.when === 'stencils');
const GLOBAL_STENCIL_PHASES = maskOf((p) => p.when === 'stencils-global');
const GLOBAL_PHASES = maskOf((p) => p.when === 'global');
const LOCAL_PHASES = maskOf((p) => p.when === 'local');
const COARSE_PHASES = maskOf((p) => p.when === 'coarse');
const SELF_PHASES = maskOf((p) => p.when === 'self');

/**
 * The phases the params' stretch solve leaves out: the Gauss–Seidel distance pass (and the coarse correction) for the
 * global step, else the global step (and the coarse correction unless 'two-level').
 */
function stretchExcluded(params: SimParams): number {
  if (params.stretch === 'global') return LOCAL_PHASES | COARSE_PHASES;
  return params.stretch === 'two-level' ? GLOBAL_PHASES : GLOBAL_PHASES | COARSE_PHASES;
}

/** The phases the params' bending leaves out: both stencil phases for the springs, else the solve not chosen. */
function bendingExcluded(params: SimParams): number {
  if (params.bending === 'springs') return STENCIL_PHASES | GLOBAL_STENCIL_PHASES;
  return params.bendingSolve === 'global' ? STENCIL_PHASES : GLOBAL_STENCIL_PHASES;
}

/** The mask of the phases a frame of `solver` has. */
export function solverPhases(solver: SolverType): number {
  let mask = 0;
  for (let id = 0; id < PHASE_COUNT; id++) if (PHASES[id].solvers.includes(solver)) mask |= 1 << id;
  return mask;
}

/**
 * The phases this frame runs: those of params.solver whose condition holds now (the air acting, a grab, carried pins,
 * a collider that needs triangle contact on this model, a stencil bending model, the stretch solve).
 */
export function framePhases(model: ClothModel, state: ClothState, params: SimParams): number {
  let mask = solverPhases(params.solver);
  if (!params.wind.enabled) mask &= ~WIND_PHASES;
  if (state.grabbed < 0) mask &= ~GRAB_PHASES;
  if (params.carried.particles.length === 0) mask &= ~CARRY_PHASES;
  if (!anyTriangleContact(model, params)) mask &= ~TRIANGLE_PHASES;
  mask &= ~bendingExcluded(params);
  mask &= ~stretchExcluded(params);
  if (!params.selfContact) mask &= ~SELF_PHASES;
  return mask;
}

/** Whether some collider of params needs triangle contact on this model (phases.ts needsTriangleContact). */
export function anyTriangleContact(model: ClothModel, params: SimParams): boolean {
  for (const shape of params.colliders) if (needsTriangleContact(model, shape, params.thickness)) return true;
  return false;
}

/** Passes of phase `id` per substep: params.iterations where the schedule repeats it for params.solver, else 1. */
export function phasePasses(id: PhaseId, params: SimParams): number {
  return PHASES[id].repeat.includes(params.solver) ? params.iterations : 1;
}

/** What a backend implements of the schedule: declared once, beside the backend. */
export interface BackendPhases {
  /** how messages name it */
  readonly name: string;
  /** where it runs, as messages end 'only the xpbd solver runs …' */
  readonly where: string;
  /**
   * whether the TypeScript reference can run a phase on the backend's memory between its own phases: true where
   * the CPU state's arrays are the backend's (the WebAssembly kernel), false where the cloth lives elsewhere (GPU
   * buffers)
   */
  readonly sharesMemory: boolean;
  /** the solver types whose phases it implements */
  readonly solvers: readonly SolverType[];
  /** the phases it implements, a mask of 1 << id */
  readonly phases: number;
  /**
   * Why it cannot run phase `id`, which it implements, for these inputs (a collider shape it does not know...), or
   * null when it can. Called every frame: a backend that shares memory returns constant strings (nothing allocated).
   */
  refusal?(id: PhaseId, model: ClothModel, params: SimParams): string | null;
}

/**
 * The rule for a phase a backend lacks, in one place: the mask of the phases of a params.solver frame that
 * `backend` runs itself. A phase of the frame that it does not implement, or refuses for these inputs, runs in the
 * TypeScript reference on the same memory when the backend shares the CPU's arrays (a frame of a solver it does not
 * implement runs there whole); a backend that does not share them cannot leave a phase to the reference and is
 * refused with an Error naming what it lacks.
 */
export function assignPhases(backend: BackendPhases, model: ClothModel, params: SimParams): number {
  if (!backend.solvers.includes(params.solver)) {
    if (backend.sharesMemory) return 0;
    throw new Error(`${backend.name}: only the ${backend.solvers.join(' and ')} solver runs ${backend.where} (params.solver is '${params.solver}')`);
  }
  // the phases these params can make a frame run (the wind and a grab come and go; carried pins are the scene's,
  // triangle contact the scene's and the mesh's, stencil bending the scene's solver.bending and bendingSolve, the stretch solve its
  // solver.stretch, self-contact its solver.selfContact)
  const wanted = solverPhases(params.solver) & ~(params.carried.particles.length === 0 ? CARRY_PHASES : 0) &
    ~(anyTriangleContact(model, params) ? 0 : TRIANGLE_PHASES) & ~bendingExcluded(params) &
    ~stretchExcluded(params) & ~(params.selfContact ? 0 : SELF_PHASES);
  let own = 0;
  for (let id = 0; id < PHASE_COUNT; id++) {
    const bit = 1 << id;
    if ((wanted & bit) === 0) continue;
    const phase = PHASES[id];
    const implemented = (backend.phases & bit) !== 0;
    const refusal = implemented ? backend.refusal?.(phase.id, model, params) ?? null : null;
    if (implemented && refusal === null) own |= bit;
    else if (!backend.sharesMemory) {
      throw new Error(`${backend.name}: ${refusal ?? `it does not implement phase '${phase.name}' (${phase.doc})`}`);
    }
  }
  return own;
}

/**
 * The phases frames ran, in order, and who ran each: the backend itself or the TypeScript reference in its place
 * (tests hold backends to the schedule with it). Its arrays are made once: logging allocates nothing.
 */
export class PhaseLog {
  /** phase ids in the order they ran (the first `length`) */
  readonly ids: Uint8Array;
  /** 1 where the TypeScript reference ran the phase, 0 where the backend did */
  readonly byReference: Uint8Array;
  /** entries logged */
  length = 0;

  /** A log with room for `capacity` phases. */
  constructor(capacity = 4096) {
    this.ids = new Uint8Array(capacity);
    this.byReference = new Uint8Array(capacity);
  }

  /** Appends phase `id`, run by the TypeScript reference (`byReference`) or by the backend itself. */
  push(id: number, byReference: boolean): void {
    if (this.length === this.ids.length) throw new RangeError(`PhaseLog: more than ${this.ids.length} phases`);
    this.ids[this.length] = id;
    this.byReference[this.length++] = byReference ? 1 : 0;
  }

  /** The logged phases by name, '(reference)' after those the reference ran. */
  names(): string[] {
    return Array.from(this.ids.subarray(0, this.length), (id, k) => PHASES[id].name + (this.byReference[k] ? ' (reference)' : ''));
  }
}
