/**
 * The GPU solver held to the phase schedule: what it implements (no GPU needed), and, on whatever adapter
 * `createNodeDevice` finds, that its encoder dispatches exactly the schedule's phases of a frame in order. No
 * adapter: as in gpu.test.ts, the device tests fail in CI and are skipped (saying why) elsewhere.
 */
import { afterAll, describe, expect, test } from 'vitest';
import type {} from 'webgpu';
import { FRAME_DT, Simulation, builtinScene, copyState, createState, grab, type Scene } from '../core/index.js';
import { PHASE, PHASES, PhaseLog, assignPhases, solverPhases, type PhaseName } from '../core/schedule.js';
import { createColliders } from '../core/colliders/index.js';
import { GPU_PHASES } from './encoder.js';
import { testDevice } from './test-device.js';
import { GpuClothSolver } from './solver.js';

const gpu = await testDevice('src/gpu/schedule.test.ts');

/** The hanging flag in gusts, pinned along one edge (tethers), over a floor: 3 substeps of 2 iterations. */
function windyScene(edit: (s: Scene) => void = () => {}): Scene {
  const s = builtinScene('wind');
  s.cloth.resolution = 6;
  s.solver = { ...s.solver, substeps: 3, iterations: 2 };
  edit(s);
  return s;
}

/** The phases an XPBD frame must run, straight from the table. */
function expected(substeps: number, wind: boolean, grabbed: boolean): PhaseName[] {
  const runs = (name: PhaseName) => {
    const p = PHASES[PHASE[name]];
    return p.solvers.includes('xpbd') && (p.when === 'always' || (p.when === 'wind' && wind) || (p.when === 'grab' && grabbed));
  };
  const of = (scope: string) => PHASES.filter((p) => p.scope === scope && runs(p.name)).map((p) => p.name);
  return [...of('frame-start'), ...Array.from({ length: substeps }, () => of('substep')).flat(), ...of('frame-end')];
}

describe('what the GPU implements of the schedule', () => {
  test('every phase of an XPBD frame: none is left to the TypeScript reference', () => {
    const sim = new Simulation(windyScene(), { kernel: 'ts' });
    // but carry, which a frame runs only for pins a collider carries (none here), and triangle contact, only for a
    // collider that needs it at this mesh size (none here; with one, the GPU runs it)
    expect(assignPhases(GPU_PHASES, sim.model, sim.params)).toBe(solverPhases('xpbd') & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles));
    const coarse = new Simulation(windyScene((s) => { s.cloth.resolution = 1; s.colliders = [{ type: 'sphere', center: [0, 0, 0], radius: 0.3 }]; }), { kernel: 'ts' });
    expect(assignPhases(GPU_PHASES, coarse.model, coarse.params)).toBe(solverPhases('xpbd') & ~(1 << PHASE.carry));
  });

  test('pins a collider carries: refused by name (the GPU has no carry phase)', () => {
    const sim = new Simulation(windyScene((s) => { s.colliders = [{ type: 'floor', height: -1, pins: ['top-left'] }]; }), { kernel: 'ts' });
    expect(() => assignPhases(GPU_PHASES, sim.model, sim.params)).toThrow(/GPU solver: it does not implement phase 'carry'/);
  });

  test('what it lacks it cannot leave to the reference (its cloth is in GPU memory): refused, saying why', () => {
    const sim = new Simulation(windyScene((s) => { s.solver.type = 'mass-spring'; }), { kernel: 'ts' });
    expect(() => assignPhases(GPU_PHASES, sim.model, sim.params)).toThrow(/GPU solver: only the xpbd solver runs on the GPU/);
    const xpbd = new Simulation(windyScene(), { kernel: 'ts' });
    const [box] = createColliders([{ type: 'box', center: [0, 3, 0], halfExtents: [0.1, 0.1, 0.1], rotation: [0, 0, 0] }]);
    const params = { ...xpbd.params, colliders: [...xpbd.params.colliders, box] };
    expect(() => assignPhases(GPU_PHASES, xpbd.model, params)).toThrow(/collider type 'box' is not supported on the GPU/);
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
});
