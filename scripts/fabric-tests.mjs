#!/usr/bin/env node
// The standard fabric tests for every named fabric (docs/physics.md, "The standard fabric tests"): the built-in
// `cantilever` and `cusick` scenes with material.fabric set, for each bending model, at the scenes' own resolution
// and duration and the default solver settings. Cantilever: the bending length the tip's chord gives against
// c = (B/(ρ_A·g))^(1/3). Cusick: drape coefficient and folds. Needs `npm run build` (it reads dist/).
//   node scripts/fabric-tests.mjs [--stretch gauss-seidel|global] [--models springs,hinges,laplacian]
import { FABRICS, FABRIC_NAMES, Simulation, builtinScene, setScenePath } from '../dist/core/index.js';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const stretch = arg('stretch', 'gauss-seidel');

const run = (name, fabric, bending) => {
  let scene = setScenePath(builtinScene(name), 'material.fabric', fabric);
  scene = setScenePath(scene, 'solver.bending', bending);
  scene = setScenePath(scene, 'solver.stretch', stretch);
  const sim = new Simulation(scene);
  sim.advance(Math.round(scene.duration * 60));
  const r = sim.report();
  sim.dispose();
  return r.test;
};

const MODELS = arg('models', 'springs,hinges,laplacian').split(',');
console.log(`solver.stretch ${stretch}`);
console.log(`| fabric | c theory [cm] | ${MODELS.map((m) => `${m}: chord → c / c_theory`).join(' | ')} | ${MODELS.map((m) => `Cusick ${m}: DC, folds`).join(' | ')} |`);
console.log(`|---|---|${MODELS.map(() => '---|---|').join('')}`);
for (const fabric of FABRIC_NAMES) {
  const f = FABRICS[fabric];
  const c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
  const cells = [];
  for (const bending of MODELS) {
    const t = run('cantilever', fabric, bending);
    cells.push(`${t.chordAngle.toFixed(1)}° → ${(t.bendingLength / c).toFixed(2)}`);
  }
  for (const bending of MODELS) {
    const t = run('cusick', fabric, bending);
    cells.push(`${t.drapeCoefficient.toFixed(2)}, ${t.folds}`);
  }
  console.log(`| ${fabric} | ${(100 * c).toFixed(2)} | ${cells.join(' | ')} |`);
}
