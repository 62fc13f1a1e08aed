#!/usr/bin/env node
// The Cusick disc (or a 30 cm square) on an 18 cm pedestal with the hinges solved together, for docs/physics.md "The
// global stretch step": whether it stays on the pedestal, and how far the one-at-a-time stretch overstretches its top.
//   npx tsc -p tsconfig.build.json && node scripts/converged-drape.mjs [--rings 48] [--substeps 20]
//       [--stretch gauss-seidel|global] [--square (a 30 cm square at 32 faces instead of the disc)] [--box (a box
//       pedestal instead of the cylinder)] [--damping β (material.damping, N·s/m: the stencils' damping time follows)]
//       [--lattice weave|rings (cloth.lattice; the scene's: weave)] [--fabric F] [--seconds S (how long)]
//       [--loose (unclamped on the pedestal) | --square-clamp] [--no-pedestal (the clamp alone)] [--all-bands]
// Prints, every second, the drape coefficient and folds, the cloth's centroid and highest point, and at the end the
// drape coefficient (the disc) and the mean, largest and least strain of the structural springs that start on the
// pedestal's top (with --all-bands: anywhere), by centimetre of radius.
import { builtinScene, centroid, setScenePath, Simulation, validateScene } from '../dist/core/index.js';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const has = (name) => process.argv.includes(`--${name}`);

let scene = builtinScene('cusick');
scene = setScenePath(scene, 'cloth.resolution', Number(arg('rings', '48')));
scene = setScenePath(scene, 'solver.substeps', Number(arg('substeps', '20')));
scene = setScenePath(scene, 'solver.stretch', arg('stretch', 'global'));
if (has('square')) scene = setScenePath(scene, 'cloth', { shape: 'rectangle', width: 0.3, height: 0.3, resolution: 32, orientation: 'horizontal', position: [0, 0.506, 0] });
if (has('damping')) scene = setScenePath(scene, 'material.damping', Number(arg('damping', '0.1')));
if (has('lattice')) scene = setScenePath(scene, 'cloth.lattice', arg('lattice', 'weave'));
if (has('fabric')) scene = setScenePath(scene, 'material.fabric', arg('fabric', 'cotton'));
if (has('seconds')) scene = setScenePath(scene, 'duration', Number(arg('seconds', '6')));
// the scene clamps the disc within the pedestal's radius; --loose lays it on the pedestal unclamped (as until
// 2026-12-06), --square-clamp clamps the square inscribed in the pedestal instead
if (has('loose')) scene = setScenePath(scene, 'pins', []);
if (has('square-clamp')) scene = setScenePath(scene, 'pins', [{ min: [-0.0636, 0, -0.0636], max: [0.0636, 1, 0.0636] }]);
if (has('no-pedestal')) scene = setScenePath(scene, 'colliders', [{ type: 'floor', height: 0 }]);
if (has('box')) scene = setScenePath(scene, 'colliders[0]', { type: 'box', center: [0, 0.25, 0], halfExtents: [0.09, 0.25, 0.09], rotation: [0, 0, 0] });
const sim = new Simulation(validateScene(scene));
const x = sim.state.positions;
for (let s = 1; s <= scene.duration; s++) {
  sim.advance(60);
  let top = -Infinity;
  for (let i = 1; i < x.length; i += 3) top = Math.max(top, x[i]);
  const t = sim.report().test;
  console.log(`${s} s: DC ${t ? t.drapeCoefficient.toFixed(3) + ' ' + t.folds : '-'} centroid ${centroid(sim.state).map((v) => v.toFixed(3)).join(', ')} m, highest ${top.toFixed(3)} m, kinetic ${sim.report().energy.kinetic.toExponential(1)} J`);
}
const test = sim.report().test;
if (!has('square')) console.log(`drape coefficient ${test.drapeCoefficient.toFixed(3)}, ${test.folds} folds`);
const { model } = sim, rest = model.restPositions, bands = new Map();
for (let k = 0; k < model.restLengths.length; k++) {
  if (model.springKinds[k] !== 0) continue;
  const a = model.springs[2 * k], b = model.springs[2 * k + 1];
  const r = Math.hypot(rest[3 * a], rest[3 * a + 2]);
  if (r >= 0.09 && !has('all-bands')) continue;
  const strain = Math.hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]) / model.restLengths[k] - 1;
  const band = bands.get(Math.floor(r * 100)) ?? { sum: 0, count: 0, most: -Infinity };
  band.sum += strain; band.count++; band.most = Math.max(band.most, strain); band.least = Math.min(band.least ?? Infinity, strain);
  bands.set(Math.floor(r * 100), band);
}
let sum = 0, count = 0;
for (const [cm, b] of [...bands].sort((p, q) => p[0] - q[0])) {
  console.log(`top, ${cm}–${cm + 1} cm: structural strain mean ${(100 * b.sum / b.count).toFixed(2)} %, largest ${(100 * b.most).toFixed(2)} %, least ${(100 * b.least).toFixed(2)} %`);
  sum += b.sum; count += b.count;
}
console.log(`top: mean structural strain ${(100 * sum / count).toFixed(2)} %`);
