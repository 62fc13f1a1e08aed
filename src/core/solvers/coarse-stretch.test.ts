/**
 * The coarse correction of the springs' multipliers (solver.stretch 'two-level', solvers/coarse-stretch.ts), on both
 * CPU kernels (the WebAssembly kernel runs the reference's phase on its memory, then its own sweep from the λ it set).
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type Scene } from '../scene.js';
import { mergeModels } from '../model.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { COARSE_DIRECTIONS, coarseAggregates, coarseCells } from './coarse-stretch.js';

/**
 * A 1 m sheet pinned along its top edge, default substeps; bending as the scenes have it (the hinges solved together)
 * or as the schema's default (the skip-one springs, which the correction holds in aggregates of their own).
 */
function hanging(fabric: { arealDensity: number; structuralStiffness: number; shearStiffness: number }, faces: number, stretch: string, bending = 'hinges'): Scene {
  return validateScene({
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: { ...fabric, damping: 0.2 },
    solver: { type: 'xpbd', stretch, bending, ...(bending === 'hinges' ? { bendingSolve: 'global' } : {}) },
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
  it.each([[16, 'hinges'], [32, 'hinges'], [32, 'springs']])('a rubber sheet hanging from its top edge at %i faces a side, bending %s, 20 substeps × 1 pass: its length grows by ρ_A·g·L²/(2k), within 5 percent (the issue asks 25)', (faces, bending) => {
    const sim = new Simulation(hanging(RUBBER, faces, 'two-level', bending), { kernel });
    sim.advance(240);
    const theory = (0.38 * 9.81) / (2 * 600);
    // measured 0.96 at 16², 0.99 at 32² (0.98 with the skip-one springs); the sweep alone at the same settings 1.26 and
    // 2.26 (below)
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

  it.each(['hinges', 'springs'])('a cotton sheet, bending %s: its strain stays far below 0.5 %, its length near theory (the sweep alone: 45–50 times)', (bending) => {
    const theory = (0.12 * 9.81) / (2 * 8600);
    for (const stretch of ['two-level', 'gauss-seidel']) {
      const sim = new Simulation(hanging(COTTON, 32, stretch, bending), { kernel });
      sim.advance(180);
      const strain = sim.report().maxStrain, ratio = elongation(sim, 32) / theory;
      // measured (both bendings): two-level 0.07 %, 1.58 times (the top rows, docs/physics.md); gauss-seidel 45–50
      // times; theory 0.014 % at the top
      if (stretch === 'two-level') {
        expect(strain).toBeLessThan(0.002);
        expect(ratio).toBeLessThan(2);
      } else expect(ratio).toBeGreaterThan(20);
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

it('each cloth has its own aggregates: a cell of its grid, a spring kind and a direction, for the springs that are there', () => {
  // cells about 8 particles across, at least 4 a side: 4 at 8 and 32 faces, 8 at 64
  expect([9, 33, 65, 129].map((side) => coarseCells(side * side))).toEqual([4, 4, 8, 16]);
  const one = new Simulation(hanging(RUBBER, 8, 'two-level'));
  // a square grid's springs in every cell: structural along u and v, shear along both diagonals, skip-one bend along
  // u and v (made with the model whatever the bending; without stiffness their aggregates take no part)
  const perCell = 2 + 2 + 2;
  expect(COARSE_DIRECTIONS).toBe(4);
  expect(coarseAggregates(one.model)).toBe(4 * 4 * perCell);
  const two = mergeModels([one.model, one.model]);
  expect(coarseAggregates(two)).toBe(2 * 4 * 4 * perCell);
  one.dispose();
});
