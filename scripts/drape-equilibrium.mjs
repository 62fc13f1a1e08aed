#!/usr/bin/env node
// Is where a solver leaves the Cusick disc an equilibrium of the model? Runs the `cusick` scene with the springs swept
// (the scene's) or solved together, then Newton's method on the static energy of the same discrete model (springs,
// hinges with the clamp's held hinges on their free side, gravity; the clamp fixed; no contact:
// scripts/pd-solver.mjs newtonStatic) from where the run left the cloth: the nearest equilibrium. Prints the drape
// coefficient and folds before and after, how far Newton moved the particles, the energies, and the particles that
// end up inside the pedestal or within the cloth's thickness of it (where contact, left out, would have acted).
//   npx tsc -p tsconfig.build.json && node scripts/drape-equilibrium.mjs [--stretch gauss-seidel|global]
//     [--fabric F] [--resolution R] [--newton N (the most Newton iterations, 400)]
import { builtinScene, measureTest, resolveParams, scenePins, setScenePath, Simulation, validateScene } from '../dist/core/index.js';
import { PDSolver, newtonStatic, withHeldHinges } from './pd-solver.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
let scene = setScenePath(builtinScene('cusick'), 'solver.stretch', arg('stretch', 'gauss-seidel'));
scene = setScenePath(scene, 'material.fabric', arg('fabric', 'cotton'));
if (arg('resolution')) scene = setScenePath(scene, 'cloth.resolution', Number(arg('resolution')));
scene = validateScene(scene);
const sim = new Simulation(scene);
sim.advance(Math.round(scene.duration * 60));
const model = sim.model, n = model.particleCount;
const before = sim.report();
const params = resolveParams(model, scene);
const pinned = new Uint8Array(n);
for (const i of scenePins(model, scene)) pinned[i] = 1;
const pd = new PDSolver(model, withHeldHinges(model, params, pinned), pinned, sim.state.positions, { substeps: 1, iterations: 1 });
const start = Float64Array.from(pd.x);
const r = newtonStatic(pd, Number(arg('newton', '400')));
const after = measureTest(model, { positions: pd.x, pinned }, scene);
let moved = 0, inside = 0, near = 0;
const pedestal = scene.colliders.find((c) => c.type === 'cylinder');
for (let i = 0; i < n; i++) {
  const j = 3 * i;
  moved = Math.max(moved, Math.hypot(pd.x[j] - start[j], pd.x[j + 1] - start[j + 1], pd.x[j + 2] - start[j + 2]));
  if (pedestal) {
    const [cx, cy, cz] = pedestal.center, radial = Math.hypot(pd.x[j] - cx, pd.x[j + 2] - cz);
    if (radial < pedestal.radius - 1e-3 && Math.abs(pd.x[j + 1] - cy) < pedestal.height / 2 - 1e-3) inside++;
    // within the cloth's thickness of the pedestal (its side, its top or the rim between), where contact would push
    const out = Math.max(radial - pedestal.radius, 0), above = Math.max(Math.abs(pd.x[j + 1] - cy) - pedestal.height / 2, 0);
    if (!pinned[i] && Math.hypot(out, above) < scene.cloth.thickness) near++;
  }
}
const shown = (t) => `drape coefficient ${t.drapeCoefficient.toFixed(3)}, folds ${t.folds}`;
console.log(`${arg('fabric', 'cotton')}, ${scene.cloth.resolution} cells, stretch ${scene.solver.stretch}: ` +
  `after the run ${shown(before.test)} (elastic ${before.energy.elastic.toExponential(3)} J, gravitational ${before.energy.gravitational.toExponential(5)} J); ` +
  `Newton (${r.iterations} iterations, energy ${r.energy.toExponential(5)} J, gradient ${r.gnorm.toExponential(1)}): ${shown(after)}, ` +
  `the particles moved by up to ${(1000 * moved).toFixed(1)} mm, ${inside} inside the pedestal, ${near} free ones within the cloth's thickness (${(1000 * scene.cloth.thickness).toFixed(1)} mm) of it`);
sim.dispose();
