/**
 * The hanging sheet, the free fall and the kernels' agreement the stretch solves' tests share (test-only: not built into the package,
 * tsconfig.build.json): global-stretch.test.ts, coarse-stretch.test.ts (and the GPU's).
 */
import { builtinScene } from '../scenes.js';
import { validateScene, type Scene } from '../scene.js';
import { Simulation, type CpuKernel } from '../simulation.js';

/** A fabric by its measured values (the scene's material fields). */
export interface SheetFabric { arealDensity: number; structuralStiffness: number; shearStiffness: number }

/** A 1 m sheet hanging from its top row (docs/physics.md "Converged stretch"), damping 0.2, the given solver fields. */
export function hangingSheet(fabric: SheetFabric, faces: number, solver: Partial<Scene['solver']>): Scene {
  return validateScene({
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: { ...fabric, damping: 0.2 },
    solver: { type: 'xpbd', ...solver },
    colliders: [],
    pins: ['top-edge'],
  });
}

/** Elongation of the middle half of the columns below their pinned tops [m] (rest height 1 m). */
export function elongation(sim: Simulation, faces: number): number {
  const x = sim.state.positions, nx = faces + 1;
  let sum = 0, count = 0;
  for (let i = Math.round(faces / 4); i <= Math.round((3 * faces) / 4); i++, count++) sum += x[3 * i + 1] - x[3 * (faces * nx + i) + 1] - 1;
  return sum / count;
}

/**
 * The sheet of `scene` (hangingSheet) after `frames` frames: its elongation over theory, ρ_A·g·L²/(2k), and its
 * kinetic energy over its weight times a metre [-] (near zero once settled).
 */
export function hangingRatio(scene: Scene, kernel: CpuKernel, frames = 240): { ratio: number; kinetic: number } {
  const sim = new Simulation(scene, { kernel });
  sim.advance(frames);
  const m = scene.material, weight = (m.arealDensity ?? NaN) * 9.81;
  const result = { ratio: elongation(sim, scene.cloth.resolution) / (weight / (2 * m.structuralStiffness)), kinetic: sim.report().energy.kinetic / weight };
  sim.dispose();
  return result;
}

/**
 * How far a free 4-face cloth falls in 30 frames with `solver`, as a share of ½gt², off by at most: near the origin
 * at 20 substeps and 300 m up at 200 (issue 10's precision cases).
 */
export function freeFallError(solver: Partial<Scene['solver']>, kernel: CpuKernel): number {
  let worst = 0;
  for (const [y, substeps] of [[1.2, 20], [300, 200]]) {
    const sim = new Simulation(validateScene({ cloth: { resolution: 4, position: [0, y, 0] }, colliders: [], solver: { ...solver, substeps } }), { kernel });
    const x = sim.state.positions, r = sim.state.residuals, y0 = x[1] + r[1];
    sim.advance(30);
    const t = sim.state.time;
    worst = Math.max(worst, Math.abs((y0 - (x[1] + r[1])) / (0.5 * 9.81 * t * t) - 1));
    sim.dispose();
  }
  return worst;
}

/** `scene` stepped `frames` frames on both CPU kernels: the largest difference of a position coordinate [m]. */
export function kernelsApart(scene: Scene, frames: number): number {
  const ts = new Simulation(scene, { kernel: 'ts' }), wasm = new Simulation(scene, { kernel: 'wasm' });
  ts.advance(frames);
  wasm.advance(frames);
  let worst = 0;
  for (let j = 0; j < ts.state.positions.length; j++) worst = Math.max(worst, Math.abs(ts.state.positions[j] - wasm.state.positions[j]));
  ts.dispose();
  wasm.dispose();
  return worst;
}

/**
 * A light (0.8 g), very stiff (290 kN/m) tablecloth at 6² blown off its table at 39 substeps, the springs after the
 * coarse correction: it crumples within a frame (trial 18 of physics.test.ts's random parameters), where a factor
 * kept through the frame overshot and the cloth flew off (coarse-stretch.test.ts, here and on the GPU).
 */
export function crumplingTablecloth(): Scene {
  const sc = builtinScene('tablecloth');
  sc.cloth.resolution = 6;
  sc.gravity = [-9.65, 9.62, -1.47];
  sc.wind = { ...sc.wind, enabled: true, strength: 24.85, direction: [0.406, -0.609, 0.758] };
  sc.material = {
    structuralStiffness: 289760, shearStiffness: 375.3, bendingRigidity: 0.5347, damping: 1.168, mass: 7.966e-4,
    stretchFactor: 1.715, friction: 2.59e-4, staticFriction: 0.903, scaleWithResolution: false,
  };
  sc.solver = { ...sc.solver, substeps: 39, iterations: 1, selfContact: false, stretch: 'two-level', bending: 'springs' };
  return validateScene(sc);
}
