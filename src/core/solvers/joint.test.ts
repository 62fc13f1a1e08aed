/**
 * solver.stretch 'hybrid' (solvers/joint.ts): the sweep, the bending, then one pass of the springs and the stencils in
 * one matrix. On both CPU kernels (the WebAssembly kernel sweeps in its own code and runs the pass with its own
 * triangular solves: the same cloth bit for bit).
 */
import { describe, expect, it } from 'vitest';
import { FABRICS } from '../fabrics.js';
import { setScenePath, validateScene, type Scene } from '../scene.js';
import { builtinScene } from '../scenes.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { grab } from '../state.js';

/** The cantilever scene (cotton, 32 faces, the hinges solved together), its springs 'hybrid', at `substeps`. */
function cantilever(substeps: number, stretch = 'hybrid'): Scene {
  let s = setScenePath(builtinScene('cantilever'), 'solver.stretch', stretch);
  s = setScenePath(s, 'solver.substeps', substeps);
  return validateScene(s);
}

const cotton = FABRICS.cotton, C_COTTON = Math.cbrt(cotton.bendingRigidity / (cotton.arealDensity * 9.81));
const bendingLength = (sim: Simulation) => (sim.report().test as { bendingLength: number }).bendingLength;

/** A 1 m sheet hanging from its top row, its springs 'hybrid', bending as `bending` says. */
function hanging(fabric: { arealDensity: number; structuralStiffness: number; shearStiffness: number }, faces: number, bending: 'springs' | 'hinges', substeps = 20): Scene {
  return validateScene({
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: { ...fabric, damping: 0.2 },
    solver: { type: 'xpbd', stretch: 'hybrid', bending, bendingSolve: 'global', substeps },
    colliders: [],
    pins: ['top-edge'],
  });
}

/** Elongation of the middle half of the columns below their pinned tops [m] (rest height 1 m). */
function elongation(sim: Simulation, faces: number): number {
  const x = sim.state.positions, nx = faces + 1;
  let sum = 0, count = 0;
  for (let i = Math.round(faces / 4); i <= Math.round((3 * faces) / 4); i++, count++) sum += x[3 * i + 1] - x[3 * (faces * nx + i) + 1] - 1;
  return sum / count;
}

describe('solver.stretch "hybrid": the cantilever reads its bending length', () => {
  it('at 5 substeps within 2 % of the model\'s own answer (0.996 of (B/(ρ_A·g))^⅓), where the springs solved together read 1.15', () => {
    // measured 1.004; solver.stretch 'global' (the two global steps one after the other) 1.15 at 5 substeps; the
    // static equilibrium of the same discrete energy 0.996 (scripts/pd-study.mjs --part fabrics)
    const sim = new Simulation(cantilever(5), { kernel: 'wasm' });
    sim.advance(180);
    const ratio = bendingLength(sim) / C_COTTON;
    expect(ratio).toBeGreaterThan(0.99);
    expect(ratio).toBeLessThan(1.02);
    expect(sim.report().energy.kinetic).toBeLessThan(1e-12);
    sim.dispose();
  });

  it('at the scene\'s 20 substeps within the issue\'s 10 % (measured 1.056; the global steps 1.23)', () => {
    const sim = new Simulation(cantilever(20), { kernel: 'wasm' });
    sim.advance(180);
    const ratio = bendingLength(sim) / C_COTTON;
    expect(ratio).toBeGreaterThan(1.0);
    expect(ratio).toBeLessThan(1.1);
    sim.dispose();
  });

  it('runs on the WebAssembly kernel as in TypeScript (the kernel\'s sweep rounds in float32 lanes: within a micrometre: 0.18 µm measured)', () => {
    const ts = new Simulation(cantilever(5), { kernel: 'ts' });
    const wasm = new Simulation(cantilever(5), { kernel: 'wasm' });
    let most = 0;
    for (let f = 0; f < 4; f++) {
      ts.advance(15);
      wasm.advance(15);
      for (let j = 0; j < ts.state.positions.length; j++) {
        most = Math.max(most, Math.abs(ts.state.positions[j] + ts.state.residuals[j] - wasm.state.positions[j] - wasm.state.residuals[j]));
      }
    }
    expect(most).toBeLessThan(1e-6);
    wasm.dispose();
  });
});

describe.each<CpuKernel>(['ts', 'wasm'])('solver.stretch "hybrid", %s kernel', (kernel) => {
  it('a rubber sheet hanging from its top edge at 32 faces: its length grows by ρ_A·g·L²/(2k) within 5 %, with the hinges solved together and with the skip-one springs', () => {
    // measured 0.99 and 0.97 (XPBD's sweep alone: 1.99)
    const rubber = { arealDensity: 0.38, structuralStiffness: 600, shearStiffness: 200 };
    for (const bending of ['hinges', 'springs'] as const) {
      const sim = new Simulation(hanging(rubber, 32, bending), { kernel });
      sim.advance(180);
      const ratio = elongation(sim, 32) / ((0.38 * 9.81) / (2 * 600));
      expect(ratio, bending).toBeGreaterThan(0.95);
      expect(ratio, bending).toBeLessThan(1.05);
      sim.dispose();
    }
  });

  it('free fall is exact: nothing strains, so the pass returns the prediction', () => {
    for (const [y, substeps] of [[1.2, 20], [300, 200]]) {
      const sim = new Simulation(validateScene({
        cloth: { resolution: 4, position: [0, y, 0] }, colliders: [], solver: { stretch: 'hybrid', bending: 'hinges', bendingSolve: 'global', substeps },
      }), { kernel });
      const x = sim.state.positions, r = sim.state.residuals, y0 = x[1] + r[1];
      sim.advance(30);
      const t = sim.state.time;
      expect(Math.abs((y0 - (x[1] + r[1])) / (0.5 * 9.81 * t * t) - 1)).toBeLessThan(1e-5);
      sim.dispose();
    }
  });

  it('holds the pinned particles where they are and the grabbed one where the grab puts it', () => {
    const sim = new Simulation(hanging({ arealDensity: 0.12, structuralStiffness: 8600, shearStiffness: 56 }, 8, 'hinges'), { kernel });
    const top = Array.from(sim.state.positions.subarray(0, 3));
    const g = 8 * 9 + 4; // the bottom row's middle
    grab(sim.state, g, [0.2, 0.3, 0.4]);
    sim.advance(240);
    expect(Array.from(sim.state.positions.subarray(0, 3))).toEqual(top);
    const at = [0, 1, 2].map((c) => sim.state.positions[3 * g + c] + sim.state.residuals[3 * g + c]);
    expect(Math.hypot(at[0] - 0.2, at[1] - 0.3, at[2] - 0.4)).toBeLessThan(1e-3);
    sim.dispose();
  });
});
