/**
 * The springs' coarse correction on the WebAssembly kernel (coarse-wasm.ts, coarse.as.ts), which must give the
 * reference's positions and multipliers (solveCoarseStretch) bit for bit.
 */
import { describe, expect, it } from 'vitest';
import { FRAME_DT, Simulation, copyState, createState, validateScene, type ClothState } from '../index.js';
import { mergeModels } from '../model.js';
import { WasmBackend } from '../backend.js';
import { PhaseLog } from '../schedule.js';
import { solveCoarseStretch } from '../solvers/coarse-stretch.js';
import { WasmCoarseStretch } from './coarse-wasm.js';
import { kernelImports, wasmKernelAvailable } from './xpbd-wasm.js';
import { XPBD_WASM_SINGLE } from './xpbd-kernel.generated.js';

/** A copy of what the correction reads and writes. */
function copyOf(state: ClothState, sim: Simulation): ClothState {
  const copy = createState(sim.model);
  copyState(state, copy);
  copy.invMass.set(state.invMass);
  copy.lambdas.set(state.lambdas);
  return copy;
}

/** A sheet pinned along its top edge, let go turned 30° out of the vertical: moving, bent and strained. */
const swinging = (faces: number, bending: string) => validateScene({
  cloth: { orientation: 'hanging', resolution: faces, position: [0, 1.5, 0], rotation: [30, 0, 0] },
  material: { fabric: 'rubber' }, solver: { stretch: 'two-level', bending }, colliders: [], pins: ['top-edge'],
});

describe.runIf(wasmKernelAvailable())('the coarse correction in the WebAssembly kernel', () => {
  const module = new WebAssembly.Module(Uint8Array.from(atob(XPBD_WASM_SINGLE), (c) => c.charCodeAt(0)));
  const instantiate = (memory: WebAssembly.Memory) => new WebAssembly.Instance(module, kernelImports(memory));

  it.each([[12, 'springs'], [40, 'hinges']])('%i faces, bending %s: the reference\'s positions and multipliers bit for bit, refactored or not, over 20 substeps', (faces, bending) => {
    const sim = new Simulation(swinging(faces, bending), { kernel: 'ts' });
    sim.advance(10);
    const h = FRAME_DT / sim.params.substeps;
    const mine = copyOf(sim.state, sim), theirs = copyOf(sim.state, sim);
    const kernel = new WasmCoarseStretch(instantiate);
    for (let sub = 0; sub < 20; sub++) {
      // as a substep would leave them: the cloth moved by up to a millimetre from where the last correction put it
      for (const s of [mine, theirs]) for (let j = 0; j < s.positions.length; j++) if (s.invMass[(j / 3) | 0] > 0) s.positions[j] += 1e-3 * Math.sin(j * 0.37 + sub);
      kernel.run(sim.model, mine, sim.params, h, sub % 7 === 0);
      solveCoarseStretch(sim.model, theirs, sim.params, h, sub % 7 === 0);
      expect([...mine.positions]).toEqual([...theirs.positions]);
      expect([...mine.lambdas]).toEqual([...theirs.lambdas]);
    }
    expect(mine.lambdas.some((l) => l !== 0)).toBe(true);
    sim.dispose();
  });

  it('a factor whose step overshoots on a crumpled cloth is made anew, as in the reference: bit for bit', () => {
    const sim = new Simulation(swinging(12, 'springs'), { kernel: 'ts' });
    sim.advance(10);
    const h = FRAME_DT / sim.params.substeps;
    const mine = copyOf(sim.state, sim), theirs = copyOf(sim.state, sim);
    const kernel = new WasmCoarseStretch(instantiate);
    kernel.run(sim.model, mine, sim.params, h, true);
    solveCoarseStretch(sim.model, theirs, sim.params, h, true);
    // every other particle 10 cm out of the sheet (coarse-stretch.test.ts: the step's Rayleigh quotient 1.57)
    for (const s of [mine, theirs]) for (let i = 1; i < sim.model.particleCount; i += 2) if (s.invMass[i] > 0) s.positions[3 * i + 2] += 0.1;
    const before = Float32Array.from(mine.positions);
    kernel.run(sim.model, mine, sim.params, h, false);
    solveCoarseStretch(sim.model, theirs, sim.params, h, false);
    expect([...mine.positions]).toEqual([...theirs.positions]);
    expect([...mine.lambdas]).toEqual([...theirs.lambdas]);
    // and that is the step of a fresh factor
    const fresh = copyOf(sim.state, sim);
    fresh.positions.set(before);
    solveCoarseStretch(sim.model, fresh, sim.params, h, true);
    expect([...mine.positions]).toEqual([...fresh.positions]);
    sim.dispose();
  });

  it('several cloths: each its own block', () => {
    const sim = new Simulation(swinging(10, 'springs'), { kernel: 'ts' });
    sim.advance(5);
    const model = mergeModels([sim.model, sim.model]), h = FRAME_DT / sim.params.substeps;
    const two = (s: ClothState) => {
      const out = createState(model);
      for (const k of ['positions', 'previousPositions', 'invMass'] as const) { out[k].set(s[k]); out[k].set(s[k], s[k].length); }
      out.positions.forEach((_, j) => { if (j >= s.positions.length) out.positions[j] += 0.01; });
      return out;
    };
    const params = { ...sim.params, compliance: Float32Array.from([...sim.params.compliance, ...sim.params.compliance]) };
    const mine = two(sim.state), theirs = two(sim.state);
    new WasmCoarseStretch(instantiate).run(model, mine, params, h, true);
    solveCoarseStretch(model, theirs, params, h, true);
    expect([...mine.positions]).toEqual([...theirs.positions]);
    expect([...mine.lambdas]).toEqual([...theirs.lambdas]);
    sim.dispose();
  });

  it('the kernel runs the phase itself, every substep, before the sweep (the cloths of both kernels: coarse-stretch.test.ts)', () => {
    const wasm = new Simulation(swinging(16, 'hinges'), { kernel: 'wasm' });
    const log = new PhaseLog();
    (wasm.backend as WasmBackend).kernel.frame(wasm.model, wasm.state, wasm.params, FRAME_DT, log);
    const names = log.names();
    expect(names.filter((n) => n === 'coarseStretch')).toHaveLength(wasm.params.substeps);
    expect(names.indexOf('coarseStretch')).toBe(names.indexOf('distance') - 1);
    wasm.dispose();
  });
});
