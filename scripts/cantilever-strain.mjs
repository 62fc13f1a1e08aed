#!/usr/bin/env node
// The cantilever scene (docs/physics.md, "The standard fabric tests") at rest after its 6 s, with the springs swept one
// at a time (the scene's) and solved together: the bending length it reads over the theory's c, the strain of its
// free structural and shear springs (mean, largest, least) and where the largest is, and the energies; then the same
// discrete energy's static equilibrium (Newton from the flat strip: scripts/pd-solver.mjs newtonStatic), with the
// hinges beside the clamp counted on their free side as the global bending step counts them, and counted whole as the
// sweep counts them; energies as the library counts them for the scene (`elastic` includes the bending, the clamp's
// hinges on their free side).
//   npx tsc -p tsconfig.build.json && node scripts/cantilever-strain.mjs [--fabric F] [--resolution R]
import {
  applyPins, builtinScene, createState, energy as energyOf, FABRICS, measureTest, modelFor, resolveParams, scenePins, setScenePath, Simulation,
  validateScene,
} from '../dist/core/index.js';
import { PDSolver, newtonStatic, withHeldHinges } from './pd-solver.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const fabric = arg('fabric', 'cotton'), f = FABRICS[fabric];
const c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
const shown = (e) => `energy [J] elastic ${e.elastic.toExponential(2)}, bending ${e.bending.toExponential(2)}, gravitational ${e.gravitational.toExponential(5)}, ` +
  `kinetic ${e.kinetic.toExponential(1)}`;
for (const stretch of ['gauss-seidel', 'global']) {
  let scene = setScenePath(builtinScene('cantilever'), 'solver.stretch', stretch);
  scene = setScenePath(setScenePath(scene, 'material.fabric', fabric), 'cloth.resolution', Number(arg('resolution', '32')));
  const sim = new Simulation(validateScene(scene));
  sim.advance(Math.round(scene.duration * 60));
  const m = sim.model, x = sim.state.positions, pinned = sim.state.pinned;
  const kinds = [0, 1].map(() => ({ sum: 0, count: 0, most: -Infinity, least: Infinity }));
  let worst = 0, at = -1;
  for (let s = 0; s < m.restLengths.length; s++) {
    const k = m.springKinds[s], a = m.springs[2 * s], b = m.springs[2 * s + 1];
    if (k > 1 || (pinned[a] && pinned[b])) continue;
    const e = Math.hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]) / m.restLengths[s] - 1;
    const r = kinds[k];
    r.sum += e; r.count++; r.most = Math.max(r.most, e); r.least = Math.min(r.least, e);
    if (Math.abs(e) > Math.abs(worst)) { worst = e; at = a; }
  }
  const { test, energy } = sim.report();
  const pct = (v) => `${(100 * v).toFixed(2)} %`;
  console.log(`${stretch}: c / c_theory ${(test.bendingLength / c).toFixed(3)}; ` +
    ['structural', 'shear'].map((name, k) => `${name} strain mean ${pct(kinds[k].sum / kinds[k].count)}, largest ${pct(kinds[k].most)}, least ${pct(kinds[k].least)}`).join('; ') +
    `; the largest at ${(100 * m.restPositions[3 * at + 2]).toFixed(2)} cm along the strip from its centre; ${shown(energy)}`);
  sim.dispose();
}
for (const held of [true, false]) {
  let scene = setScenePath(builtinScene('cantilever'), 'material.fabric', fabric);
  scene = validateScene(setScenePath(scene, 'cloth.resolution', Number(arg('resolution', '32'))));
  const model = modelFor(scene), params = resolveParams(model, scene), pins = scenePins(model, scene);
  const pinned = new Uint8Array(model.particleCount);
  for (const i of pins) pinned[i] = 1;
  const pd = new PDSolver(model, held ? withHeldHinges(model, params, pinned) : params, pinned, model.restPositions, { substeps: 1, iterations: 1 });
  const r = newtonStatic(pd, 300);
  const state = createState(model);
  applyPins(state, pins);
  state.positions.set(Float32Array.from(pd.x));
  state.previousPositions.set(state.positions);
  const test = measureTest(model, { positions: pd.x, pinned }, scene);
  console.log(`static Newton, the clamp's hinges ${held ? 'on their free side (as the global bending step and the energy count them)' : 'counted whole (as the sweep counts them)'} (${r.iterations} iterations): c / c_theory ${(test.bendingLength / c).toFixed(3)}; ${shown(energyOf(model, state, params))}`);
}
