/**
 * The coarse correction of the springs' multipliers (solver.stretch 'two-level', solvers/coarse-stretch.ts), on both
 * CPU kernels (the WebAssembly kernel runs the reference's phase on its memory, then its own sweep from the λ it set).
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type Scene } from '../scene.js';
import { FRAME_DT } from '../params.js';
import { copyState, createState } from '../state.js';
import { mergeModels } from '../model.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { COARSE_DIRECTIONS, coarseCells, coarseSystem, solveCoarseStretch } from './coarse-stretch.js';
import { crumplingTablecloth, elongation, freeFallError, hangingRatio, hangingSheet, kernelsApart, type SheetFabric } from './test-sheets.js';

/**
 * A 1 m sheet pinned along its top edge, default substeps; bending as the scenes have it (the hinges solved together)
 * or as the schema's default (the skip-one springs, which the correction holds in aggregates of their own).
 */
const hanging = (fabric: SheetFabric, faces: number, stretch: string, bending = 'hinges'): Scene =>
  hangingSheet(fabric, faces, { stretch, bending, ...(bending === 'hinges' ? { bendingSolve: 'global' } : {}) } as Partial<Scene['solver']>);

/** The largest difference of a coordinate of two position arrays [m]. */
const maxApart = (a: Float32Array, b: Float32Array) => a.reduce((m, v, j) => Math.max(m, Math.abs(v - b[j])), 0);

const RUBBER = { arealDensity: 0.38, structuralStiffness: 600, shearStiffness: 200 };
const COTTON = { arealDensity: 0.12, structuralStiffness: 8600, shearStiffness: 56 };

describe.each<CpuKernel>(['ts', 'wasm'])('solver.stretch "two-level" (xpbd), %s kernel', (kernel) => {
  it.each([[16, 'hinges'], [32, 'hinges'], [32, 'springs']])('a rubber sheet hanging from its top edge at %i faces a side, bending %s, 20 substeps × 1 pass: its length grows by ρ_A·g·L²/(2k), within 5 percent (the issue asks 25)', (faces, bending) => {
    const { ratio, kinetic } = hangingRatio(hanging(RUBBER, faces, 'two-level', bending), kernel);
    // measured 0.96 at 16², 0.99 at 32² (0.98 with the skip-one springs); the sweep alone at the same settings 1.26 and
    // 2.26 (below)
    expect(ratio).toBeGreaterThan(0.95);
    expect(ratio).toBeLessThan(1.05);
    expect(kinetic).toBeLessThan(1e-6);
  });

  it('the same sheet swept alone (gauss-seidel) is twice too long at 32²: what the correction removes', () => {
    // measured 2.2 (docs/physics.md, "Converged stretch")
    expect(hangingRatio(hanging(RUBBER, 32, 'gauss-seidel'), kernel).ratio).toBeGreaterThan(2);
  });

  it.each(['hinges', 'springs'])('a cotton sheet, bending %s: its strain stays far below 0.5 %, its length near theory (the sweep alone: about 53 times)', (bending) => {
    const theory = (0.12 * 9.81) / (2 * 8600);
    for (const stretch of ['two-level', 'gauss-seidel']) {
      const sim = new Simulation(hanging(COTTON, 32, stretch, bending), { kernel });
      sim.advance(180);
      const strain = sim.report().maxStrain, ratio = elongation(sim, 32) / theory;
      // measured (both bendings, the WebAssembly kernel): two-level 0.08 %, 1.56–1.57 times (the top rows,
      // docs/physics.md); gauss-seidel 1.1 %, 53 times; theory 0.014 % at the top
      if (stretch === 'two-level') {
        expect(strain).toBeLessThan(0.002);
        expect(ratio).toBeLessThan(2);
      } else expect(ratio).toBeGreaterThan(20);
    }
  });

  it('free fall is exact: a cloth whose springs are at rest gets no correction, near the origin and far from it', () => {
    expect(freeFallError({ stretch: 'two-level' }, kernel)).toBeLessThan(1e-5);
  });

  // A light, very stiff tablecloth blown off its table and crumpling within a frame (trial 18 of physics.test.ts's
  // random parameters): with the frame's factor kept through the frame its steps overshot and the cloth flew 470 km
  // off in 30 frames; the step checked against the matrix now, and the matrix made anew where it overshoots, it
  // stays where it was (seen 0.54 of its size from its start, both kernels).
  it('a cloth crumpling within a frame: the factor made anew where its step overshoots, the cloth stays', () => {
    const sim = new Simulation(crumplingTablecloth(), { kernel });
    const start = sim.report().centroid;
    sim.advance(30);
    const r = sim.report();
    expect(r.finite).toBe(true);
    for (const b of [r.bounds.min, r.bounds.max]) for (let k = 0; k < 3; k++) expect(Math.abs(b[k] - start[k])).toBeLessThan(2 * sim.model.size);
    sim.dispose();
  });
});

describe('a factor of an earlier substep', () => {
  /** A swinging 12² rubber sheet 10 frames in, what the correction reads of it copied into a fresh state. */
  const swinging = () => {
    const sim = new Simulation(validateScene({
      cloth: { orientation: 'hanging', resolution: 12, position: [0, 1.5, 0], rotation: [30, 0, 0] },
      material: { fabric: 'rubber' }, solver: { stretch: 'two-level' }, colliders: [], pins: ['top-edge'],
    }), { kernel: 'ts' });
    sim.advance(10);
    return sim;
  };
  const copyOf = (sim: Simulation, move: (x: Float32Array, j: number) => number) => {
    const s = createState(sim.model);
    copyState(sim.state, s);
    s.invMass.set(sim.state.invMass);
    for (let j = 0; j < s.positions.length; j++) if (s.invMass[(j / 3) | 0] > 0) s.positions[j] += move(s.positions, j);
    return s;
  };

  it('serves while its step does not overshoot, and is made anew (the step as from a fresh factor) where the cloth has crumpled', () => {
    const sim = swinging(), h = FRAME_DT / sim.params.substeps;
    // the factor from the sheet as it is
    solveCoarseStretch(sim.model, copyOf(sim, () => 0), sim.params, h, true);
    // moved a little (a substep's worth): the factor serves, so the step is not a fresh factor's
    const nudge = (_x: Float32Array, j: number) => 1e-4 * Math.sin(0.37 * j);
    const kept = copyOf(sim, nudge), fresh = copyOf(sim, nudge);
    solveCoarseStretch(sim.model, kept, sim.params, h, false);
    solveCoarseStretch(sim.model, fresh, sim.params, h, true);
    expect([...kept.positions]).not.toEqual([...fresh.positions]);
    expect(maxApart(kept.positions, fresh.positions)).toBeLessThan(1e-6);
    // crumpled: every other particle 10 cm out of the sheet (its springs 8.3 cm long), its chains of springs zigzagging: its
    // step's Rayleigh quotient under the matrix now over the factor's 1.57 (5 cm: 1.24; over the frames before, 1 ± 10⁻⁴)
    solveCoarseStretch(sim.model, copyOf(sim, () => 0), sim.params, h, true);
    const zigzag = (_x: Float32Array, j: number) => (j % 3 === 2 && ((j / 3) | 0) % 2 === 1 ? 0.1 : 0);
    const remade = copyOf(sim, zigzag), made = copyOf(sim, zigzag);
    solveCoarseStretch(sim.model, remade, sim.params, h, false);
    solveCoarseStretch(sim.model, made, sim.params, h, true);
    expect([...remade.positions]).toEqual([...made.positions]);
    expect([...remade.lambdas]).toEqual([...made.lambdas]);
    sim.dispose();
  });
});

it('both CPU kernels run the correction on the same cloth alike (the wind flag, 30 frames)', () => {
  expect(kernelsApart(validateScene({ ...hanging(RUBBER, 12, 'two-level'), wind: { enabled: true } }), 30)).toBeLessThan(1e-4);
});

it('each cloth has its own aggregates: a cell of its grid, a spring kind and a direction, for the springs that are there', () => {
  // cells about 8 particles across, at least 4 a side: 4 at 8 and 32 faces, 8 at 64
  expect([9, 33, 65, 129].map((side) => coarseCells(side * side))).toEqual([4, 4, 8, 16]);
  const one = new Simulation(hanging(RUBBER, 8, 'two-level'));
  // a square grid's springs in every cell: structural along u and v, shear along both diagonals, skip-one bend along
  // u and v (made with the model whatever the bending; without stiffness their aggregates take no part)
  const perCell = 2 + 2 + 2;
  expect(COARSE_DIRECTIONS).toBe(4);
  expect(coarseSystem(one.model).rhs.length).toBe(4 * 4 * perCell);
  const two = mergeModels([one.model, one.model]);
  expect(coarseSystem(two).rhs.length).toBe(2 * 4 * 4 * perCell);
  one.dispose();
});
