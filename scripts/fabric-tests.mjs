#!/usr/bin/env node
// The standard fabric tests for every named fabric (docs/physics.md, "The standard fabric tests"): the built-in
// `cantilever` and `cusick` scenes with material.fabric set, for each bending model, at the scenes' own resolution
// and duration and the default solver settings. Cantilever: the bending length the tip's chord gives against
// c = (B/(ρ_A·g))^(1/3), and how far the chord still swings over the last second before the reading. Cusick: drape
// coefficient and folds, and the coefficient's range over that second. Needs `npm run build` (it reads dist/).
//   node scripts/fabric-tests.mjs [--stretch gauss-seidel|global] [--bending-solve gauss-seidel|global]
//       [--models springs,hinges,laplacian] [--fabrics cotton,silk,…] [--tests cantilever,cusick]
//       [--air none (no air: the scenes' still air switched off)] [--kernel wasm|ts]
//       [--set path=JSON (more scene paths, e.g. solver.substeps=5 or cloth.resolution=16; repeatable)]
import { FABRICS, FABRIC_NAMES, Simulation, builtinScene, measureTest, setScenePath } from '../dist/core/index.js';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const stretch = arg('stretch', 'gauss-seidel');
const noAir = arg('air', 'still') === 'none';
const bendingSolve = arg('bending-solve', 'gauss-seidel');
const kernel = arg('kernel', 'wasm');
const TESTS = arg('tests', 'cantilever,cusick').split(',');
const sets = process.argv.flatMap((a, i) => (a === '--set' && i + 1 < process.argv.length ? [process.argv[i + 1]] : []))
  .map((kv) => { const at = kv.indexOf('='); return [kv.slice(0, at), JSON.parse(kv.slice(at + 1))]; });

const run = (name, fabric, bending) => {
  let scene = setScenePath(builtinScene(name), 'material.fabric', fabric);
  scene = setScenePath(scene, 'solver.bending', bending);
  scene = setScenePath(scene, 'solver.stretch', stretch);
  scene = setScenePath(scene, 'solver.bendingSolve', bendingSolve);
  if (noAir) scene = setScenePath(scene, 'wind.enabled', false);
  for (const [path, value] of sets) scene = setScenePath(scene, path, value);
  const sim = new Simulation(scene, { kernel });
  const frames = Math.round(scene.duration * 60);
  sim.advance(frames - 60);
  // the last second frame by frame: the reading's range over it (how settled the specimen is when it is read)
  let lo = Infinity, hi = -Infinity;
  for (let f = 0; f < 60; f++) {
    sim.advance(1);
    const t = measureTest(sim.model, sim.state, sim.scene);
    const v = t.type === 'cantilever' ? t.chordAngle : t.drapeCoefficient;
    lo = Math.min(lo, v); hi = Math.max(hi, v);
  }
  const r = sim.report();
  sim.dispose();
  return { ...r.test, lo, hi };
};

const MODELS = arg('models', 'springs,hinges,laplacian').split(',');
const columns = [
  ...(TESTS.includes('cantilever') ? MODELS.map((m) => `${m}: chord → c / c_theory`) : []),
  ...(TESTS.includes('cusick') ? MODELS.map((m) => `Cusick ${m}: DC, folds`) : []),
];
console.log(`solver.stretch ${stretch}, solver.bendingSolve ${bendingSolve}, kernel ${kernel}${noAir ? ', no air' : ''}${sets.map(([p, v]) => `, ${p} ${JSON.stringify(v)}`).join('')}`);
console.log('(in brackets: the chord or the coefficient over the last second before the reading)');
console.log(`| fabric | c theory [cm] | ${columns.join(' | ')} |`);
console.log(`|---|---|${columns.map(() => '---|').join('')}`);
for (const fabric of arg('fabrics', FABRIC_NAMES.join(',')).split(',')) {
  const f = FABRICS[fabric];
  const c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
  const cells = [];
  for (const bending of TESTS.includes('cantilever') ? MODELS : []) {
    const t = run('cantilever', fabric, bending);
    cells.push(`${t.chordAngle.toFixed(1)}° → ${(t.bendingLength / c).toFixed(2)} (${t.lo.toFixed(0)}–${t.hi.toFixed(0)}°)`);
  }
  for (const bending of TESTS.includes('cusick') ? MODELS : []) {
    const t = run('cusick', fabric, bending);
    cells.push(`${t.drapeCoefficient.toFixed(2)}, ${t.folds} (${t.lo.toFixed(2)}–${t.hi.toFixed(2)})`);
  }
  console.log(`| ${fabric} | ${(100 * c).toFixed(2)} | ${cells.join(' | ')} |`);
}
