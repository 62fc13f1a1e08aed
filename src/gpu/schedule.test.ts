/**
 * The GPU solver held to the phase schedule: what it implements (no GPU needed), and, on whatever adapter
 * `createNodeDevice` finds, that its encoder dispatches exactly the schedule's phases of a frame in order. No
 * adapter: as in gpu.test.ts, the device tests fail in CI and are skipped (saying why) elsewhere.
 */
import { afterAll, describe, expect, test } from 'vitest';
import type {} from 'webgpu';
import { FRAME_DT, Simulation, builtinScene, copyState, createState, grab, type ColliderSpec, type Scene } from '../core/index.js';
import { PHASE, PHASES, PhaseLog, assignPhases, solverPhases, type PhaseName } from '../core/schedule.js';
import { GPU_PHASES } from './encoder.js';
import { cubeMesh } from '../core/colliders/mesh-shapes.js';
import { testDevice } from './test-device.js';
import { GpuClothSolver } from './solver.js';

const gpu = await testDevice('src/gpu/schedule.test.ts');

/** The hanging flag in gusts, pinned along one edge (tethers), over a floor: 3 substeps of 2 iterations. */
function windyScene(edit: (s: Scene) => void = () => {}): Scene {
  const s = builtinScene('wind');
  s.cloth.resolution = 6;
  // the floor only (the flag's pole is a cylinder, whose rim adds triangle contact: the phases below are the floor's)
  s.colliders = [{ type: 'floor', height: 0 }];
  // the springs swept alone (the 'local' phases): the coarse correction, the default, has its own case
  s.solver = { ...s.solver, substeps: 3, iterations: 2, selfContact: false, stretch: 'gauss-seidel' };
  edit(s);
  return s;
}

/** A box beside the flag's free top corner, turning and rising, carrying that corner. */
const carrier: ColliderSpec = {
  type: 'box', center: [0.85, 2.5, 0], halfExtents: [0.05, 0.05, 0.05], rotation: [0, 0, 0], pins: ['top-right'],
  motion: { keyframes: [{ time: 0, translation: [0, 0, 0], rotation: [0, 0, 0] }, { time: 1, translation: [0, 0.2, 0], rotation: [0, 90, 0] }], loop: false },
};

/** A cube mesh where the box carrier is, turning and rising the same way, carrying the same corner. */
const meshCarrier: ColliderSpec = {
  type: 'mesh', mesh: 'cube.obj', scale: 0.1, position: [0.85, 2.5, 0], rotation: [0, 0, 0], pins: ['top-right'], motion: carrier.motion,
};

/** The phases an XPBD frame must run, straight from the table. */
function expected(
  substeps: number, wind: boolean, grabbed: boolean, carried = false, triangles = false, stencils = false, self = false,
): PhaseName[] {
  const runs = (name: PhaseName) => {
    const p = PHASES[PHASE[name]];
    return p.solvers.includes('xpbd') && (p.when === 'always' || (p.when === 'wind' && wind) ||
      (p.when === 'grab' && grabbed) || (p.when === 'carried' && carried) || (p.when === 'triangles' && triangles) ||
      (p.when === 'stencils' && stencils) || (p.when === 'self' && self) ||
      p.when === 'local'); // springs one at a time (solver.stretch 'gauss-seidel')
  };
  const of = (scope: string) => PHASES.filter((p) => p.scope === scope && runs(p.name)).map((p) => p.name);
  return [...of('frame-start'), ...Array.from({ length: substeps }, () => of('substep')).flat(), ...of('frame-end')];
}

describe('what the GPU implements of the schedule', () => {
  test('every phase of an XPBD frame: none is left to the TypeScript reference', () => {
    const sim = new Simulation(windyScene(), { kernel: 'ts' });
    // but carry, which a frame runs only for pins a collider carries (none here), triangle contact, only for a
    // collider that needs it at this mesh size (none here), and stencil bending, only for solver.bending 'hinges' or
    // 'laplacian' (one at a time or, with solver.bendingSolve 'global', together), self-contact, only for
    // solver.selfContact (below), the global stretch step, which solver.stretch 'global' asks for, and the coarse
    // correction, which solver.stretch 'two-level' asks for: below)
    const xpbd = solverPhases('xpbd') & ~(1 << PHASE.globalStretch) & ~(1 << PHASE.globalBending) & ~(1 << PHASE.selfContact) & ~(1 << PHASE.coarseStretch);
    const rare = (1 << PHASE.carry) | (1 << PHASE.contactTriangles) | (1 << PHASE.bending);
    expect(assignPhases(GPU_PHASES, sim.model, sim.params)).toBe(xpbd & ~rare);
    const coarse = new Simulation(windyScene((s) => { s.cloth.resolution = 1; s.colliders = [{ type: 'sphere', center: [0, 0, 0], radius: 0.3 }]; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, coarse.model, coarse.params)).toBe(xpbd & ~(1 << PHASE.carry) & ~(1 << PHASE.bending));
    // with a stencil model, bending too
    for (const bending of ['hinges', 'laplacian'] as const) {
      const bent = new Simulation(windyScene((s) => { s.solver.bending = bending; }), { kernel: 'ts' });
      expect(assignPhases(GPU_PHASES, bent.model, bent.params))
        .toBe(xpbd & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles));
    }
    // the springs solved together: by the GPU, in place of the springs one at a time, the tethers and the stretch limit
    const global = new Simulation(windyScene((s) => { s.solver.stretch = 'global'; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, global.model, global.params))
      .toBe((xpbd | (1 << PHASE.globalStretch)) & ~rare & ~(1 << PHASE.distance) & ~(1 << PHASE.tethers) & ~(1 << PHASE.stretchLimit));
    // the springs' coarse correction: by the GPU, before the springs one at a time
    const twoLevel = new Simulation(windyScene((s) => { s.solver.stretch = 'two-level'; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, twoLevel.model, twoLevel.params)).toBe((xpbd | (1 << PHASE.coarseStretch)) & ~rare);
    // the stencils solved together: by the GPU, in place of the stencils one at a time
    const together = new Simulation(windyScene((s) => { s.solver.bending = 'hinges'; s.solver.bendingSolve = 'global'; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, together.model, together.params))
      .toBe((xpbd | (1 << PHASE.globalBending)) & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles) & ~(1 << PHASE.bending));
    // self-contact: by the GPU too
    const selfy = new Simulation(windyScene((s) => { s.solver.selfContact = true; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, selfy.model, selfy.params)).toBe((xpbd | (1 << PHASE.selfContact)) & ~rare);
    // with carried pins, carry too, whatever the collider and its motion
    const carried = new Simulation(windyScene((s) => { s.colliders = [carrier]; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, carried.model, carried.params) & (1 << PHASE.carry)).toBe(1 << PHASE.carry);
    // a mesh collider (a cube mesh: sharp edges), moving: contact and triangle contact, by the GPU
    const mesh = new Simulation(windyScene((s) => { s.colliders = [meshCarrier]; }), { kernel: 'ts', meshes: () => cubeMesh() });
    expect(assignPhases(GPU_PHASES, mesh.model, mesh.params)).toBe(xpbd & ~(1 << PHASE.bending));
  });

  test('what it lacks it cannot leave to the reference (its cloth is in GPU memory): refused, saying why', () => {
    const sim = new Simulation(windyScene((s) => { s.solver.type = 'mass-spring'; }), { kernel: 'ts' });
    expect(() => assignPhases(GPU_PHASES, sim.model, sim.params)).toThrow(/GPU solver: only the xpbd solver runs on the GPU/);
  });
});

const solvers: GpuClothSolver[] = [];
afterAll(() => {
  for (const s of solvers) s.destroy();
});

describe.skipIf(!gpu)('the GPU encodes the schedule', () => {
  test.each([[true, true], [false, false], [true, false]])('wind %s, a grab %s: every phase, in order, by the GPU', async (wind, grabbed) => {
    const sim = new Simulation(windyScene((s) => { s.wind.enabled = wind; }), { kernel: 'ts' });
    const state = createState(sim.model);
    copyState(sim.state, state);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.setParams(sim.params);
    solver.upload(state);
    if (grabbed) grab(state, 5, [0.1, 2.2, 0.3]);
    for (let f = 0; f < 2; f++) {
      const log = new PhaseLog();
      solver.step(state, sim.params, FRAME_DT, undefined, log);
      expect(log.names()).toEqual(expected(3, wind, grabbed));
    }
    await solver.read(state);
    expect(state.positions.every(Number.isFinite)).toBe(true);
  });

  test('pins a moving collider carries: carry, by the GPU, after integrate in every substep', async () => {
    const sim = new Simulation(windyScene((s) => { s.colliders = [carrier]; }), { kernel: 'ts' });
    const state = createState(sim.model);
    copyState(sim.state, state);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.upload(state);
    const log = new PhaseLog();
    solver.step(state, sim.params, FRAME_DT, undefined, log);
    // the small box has sharp edges: triangle contact too
    expect(log.names()).toEqual(expected(3, true, false, true, true));
  });

  test('a moving mesh collider that carries pins: carry, contact and triangle contact, by the GPU, in every substep', async () => {
    const sim = new Simulation(windyScene((s) => { s.colliders = [meshCarrier]; }), { kernel: 'ts', meshes: () => cubeMesh() });
    const state = createState(sim.model);
    copyState(sim.state, state);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.upload(state);
    const log = new PhaseLog();
    solver.step(state, sim.params, FRAME_DT, undefined, log);
    expect(log.names()).toEqual(expected(3, true, false, true, true));
    await solver.read(state);
    expect(state.positions.every(Number.isFinite)).toBe(true);
  });

  test('self-contact: selfContact, by the GPU, after the stretch limit and before contact in every substep', async () => {
    // the scene's 3 substeps as they are (selfContactSpeed 0: none added for self-contact)
    const sim = new Simulation(windyScene((s) => { s.solver.selfContact = true; s.solver.selfContactSpeed = 0; }), { kernel: 'ts' });
    const state = createState(sim.model);
    copyState(sim.state, state);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.upload(state);
    const log = new PhaseLog();
    solver.step(state, sim.params, FRAME_DT, undefined, log);
    expect(log.names()).toEqual(expected(3, true, false, false, false, false, true));
    expect(Array.from(log.byReference.subarray(0, log.length)).every((r) => !r)).toBe(true);
    await solver.read(state);
    expect(state.positions.every(Number.isFinite)).toBe(true);
  });

  test.each(['hinges', 'laplacian'] as const)('the %s bending model: bending, by the GPU, after distance in every substep', async (bending) => {
    const sim = new Simulation(windyScene((s) => { s.solver.bending = bending; }), { kernel: 'ts' });
    const state = createState(sim.model);
    copyState(sim.state, state);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.upload(state);
    const log = new PhaseLog();
    solver.step(state, sim.params, FRAME_DT, undefined, log);
    expect(log.names()).toEqual(expected(3, true, false, false, false, true));
    await solver.read(state);
    expect(state.positions.every(Number.isFinite)).toBe(true);
  });
});
