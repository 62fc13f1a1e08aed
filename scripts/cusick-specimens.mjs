#!/usr/bin/env node
// The Cusick test as BS 5058 runs it: three specimens of each fabric, their drape coefficients and folds, and the
// mean, at two mesh densities (issue 10's resolution independence: the mean drape coefficient within ±0.05 and the
// mean fold count within ±1 between densities a factor 2 apart). Each specimen is the built-in `cusick` scene at
// its default settings with `cloth.perturbation.seed` set (the scene's 1 mm RMS waviness, perturbation.ts).
// Needs `npx tsc -p tsconfig.build.json` (it reads dist/).
//   node scripts/cusick-specimens.mjs [--fabrics cotton,silk,…] [--resolutions 48,96] [--seeds 1,2,3]
//       [--amplitude A (cloth.perturbation.amplitude [m], instead of the scene's)]
import { FABRIC_NAMES, builtinScene, setScenePath } from '../dist/core/index.js';
import { mean, readSpecimen } from './cusick-common.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return (i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback).split(',');
};
const fabrics = arg('fabrics', FABRIC_NAMES.join(','));
const resolutions = arg('resolutions', '48,96').map(Number);
const seeds = arg('seeds', '1,2,3').map(Number);
const amplitude = process.argv.includes('--amplitude') ? Number(arg('amplitude', 'none')[0]) : null;
if (amplitude !== null && !(amplitude >= 0)) throw new Error('--amplitude: give the waviness in metres, e.g. --amplitude 0.0002');

const specimen = (fabric, resolution, seed) => {
  let scene = setScenePath(builtinScene('cusick'), 'material.fabric', fabric);
  scene = setScenePath(scene, 'cloth.resolution', resolution);
  scene = setScenePath(scene, 'cloth.perturbation.seed', seed);
  if (amplitude !== null) scene = setScenePath(scene, 'cloth.perturbation.amplitude', amplitude);
  return readSpecimen(scene);
};

console.log(`seeds ${seeds.join(', ')}${amplitude !== null ? `, amplitude ${amplitude} m` : ''}; each cell: drape coefficient, folds per specimen → their mean`);
console.log(`| fabric | ${resolutions.map((r) => `${r} cells across`).join(' | ')} | mean differs by (coefficient, folds) |`);
console.log(`|---|${resolutions.map(() => '---|').join('')}---|`);
for (const fabric of fabrics) {
  const means = [];
  const cells = resolutions.map((resolution) => {
    const runs = seeds.map((seed) => specimen(fabric, resolution, seed));
    const dc = mean(runs.map((t) => t.drapeCoefficient)), folds = mean(runs.map((t) => t.folds));
    means.push([dc, folds]);
    return `${runs.map((t) => `${t.drapeCoefficient.toFixed(3)}, ${t.folds}`).join('; ')} → ${dc.toFixed(3)}, ${folds.toFixed(2)}`;
  });
  const spread = means.length > 1
    ? `${(means.at(-1)[0] - means[0][0]).toFixed(3)}, ${(means.at(-1)[1] - means[0][1]).toFixed(2)}`
    : '—';
  console.log(`| ${fabric} | ${cells.join(' | ')} | ${spread} |`);
}
