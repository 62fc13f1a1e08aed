/**
 * The coarse correction of the springs' multipliers (solver.stretch 'two-level', solvers/coarse-stretch.ts), on both
 * CPU kernels (the WebAssembly kernel runs the reference's phase on its memory, then its own sweep from the λ it set).
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type Scene } from '../scene.js';
import { mergeModels } from '../model.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { COARSE_DIRECTIONS, coarseAggregates, coarseCells } from './coarse-stretch.js';

/** A 1 m sheet pinned along its top edge, the scenes' bending (the hinges solved together), default substeps. */
function hanging(fabric: { arealDensity: number; structuralStiffness: number; shearStiffness: number }, faces: number, stretch: string): Scene {
  return validateScene({
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: { ...fabric, damping: 0.2 },
    solver: { type: 'xpbd', stretch, bending: 'hinges', bendingSolve: 'global' },
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

const RUBBER = { arealDensity: 0.38, structuralStiffness: 600, shearStiffness: 200 };
const COTTON = { arealDensity: 0.12, structuralStiffness: 8600, shearStiffness: 56 };

describe.each<CpuKernel>(['ts', 'wasm'])('solver.stretch "two-level" (xpbd), %s kernel', (kernel) => {
  it.each([16, 32])('a rubber sheet hanging from its top edge at %i faces a side, 20 substeps × 1 pass: its length grows by ρ_A·g·L²/(2k), within 5 percent (the issue asks 25)', (faces) => {
    const sim = new Simulation(hanging(RUBBER, faces, 'two-level'), { kernel });
    sim.advance(240);
    const theory = (0.38 * 9.81) / (2 * 600);
    // measured 0.96 at 16², 0.99 at 32²; the sweep alone at the same settings 1.26 and 2.26 (below)
    const ratio = elongation(sim, faces) / theory;
    expect(ratio).toBeGreaterThan(0.95);
    expect(ratio).toBeLessThan(1.05);
    expect(sim.report().energy.kinetic).toBeLessThan(1e-6 * 0.38 * 9.81);
  });

  it('the same sheet swept alone (gauss-seidel) is twice too long at 32²: what the correction removes', () => {
    const sim = new Simulation(hanging(RUBBER, 32, 'gauss-seidel'), { kernel });
    sim.advance(240);
    // measured 2.2 (docs/physics.md, "Converged stretch")
    expect(elongation(sim, 32) / ((0.38 * 9.81) / (2 * 600))).toBeGreaterThan(2);
  });

  it('a cotton sheet: its strain stays far below 0.5 % (the sweep alone: 1.6 %)', () => {
    for (const [stretch, bound] of [['two-level', 0.002], ['gauss-seidel', Infinity]] as const) {
      const sim = new Simulation(hanging(COTTON, 32, stretch), { kernel });
      sim.advance(180);
      const strain = sim.report().maxStrain;
      // measured 0.07 % (two-level) and 1.6 % (gauss-seidel); theory 0.014 % at the top
      if (bound < Infinity) expect(strain).toBeLessThan(bound);
      else expect(strain).toBeGreaterThan(0.005);
    }
  });

  it('free fall is exact: a cloth whose springs are at rest gets no correction, near the origin and far from it', () => {
    for (const [y, substeps] of [[1.2, 20], [300, 200]]) {
      const sim = new Simulation(validateScene({ cloth: { resolution: 4, position: [0, y, 0] }, colliders: [], solver: { stretch: 'two-level', substeps } }), { kernel });
      const x = sim.state.positions, r = sim.state.residuals, y0 = x[1] + r[1];
      sim.advance(30);
      const t = sim.state.time;
      expect(Math.abs((y0 - (x[1] + r[1])) / (0.5 * 9.81 * t * t) - 1)).toBeLessThan(1e-5);
    }
  });
});

it('both CPU kernels run the correction on the same cloth alike (the wind flag, 30 frames)', () => {
  const scene = validateScene({ ...hanging(RUBBER, 12, 'two-level'), wind: { enabled: true } });
  const ts = new Simulation(scene, { kernel: 'ts' }), wasm = new Simulation(scene, { kernel: 'wasm' });
  ts.advance(30);
  wasm.advance(30);
  let worst = 0;
  for (let j = 0; j < ts.state.positions.length; j++) worst = Math.max(worst, Math.abs(ts.state.positions[j] - wasm.state.positions[j]));
  expect(worst).toBeLessThan(1e-4);
  ts.dispose();
  wasm.dispose();
});

it('each cloth has its own aggregates: a cell of its grid and a direction, for the springs that are there', () => {
  // cells about 8 particles across, at least 4 a side: 4 at 8 and 32 faces, 8 at 64
  expect([9, 33, 65, 129].map((side) => coarseCells(side * side))).toEqual([4, 4, 8, 16]);
  const one = new Simulation(hanging(RUBBER, 8, 'two-level'));
  // a square grid's springs: the structural ones along u and v, the shear ones along both diagonals, in every cell
  expect(coarseAggregates(one.model)).toBe(4 * 4 * COARSE_DIRECTIONS);
  const two = mergeModels([one.model, one.model]);
  expect(coarseAggregates(two)).toBe(2 * 4 * 4 * COARSE_DIRECTIONS);
  one.dispose();
});
