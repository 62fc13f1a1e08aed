#!/usr/bin/env node
// Numerical dissipation (docs/physics.md, "Energy"): a 1 m cotton cloth pinned along its top edge, started turned 40°
// out of the vertical, swings as a pendulum with no damping, no air and no colliders for 10 s. The swing's amplitude
// (half the range of the centroid's horizontal position within each 2 s, about two periods) is printed per 2 s; the
// energy of a swing goes as its amplitude², so (A_last / A_first)² is the share of its energy the integrator keeps
// over 8 s. Per solver, substep count and, for xpbd, how the springs and the bending are solved (one at a time or
// together: solver.stretch, solver.bending, solver.bendingSolve). (Total energy cannot show it at the defaults:
// XPBD's unconverged stretch is itself stored energy of the same size.) Needs `npm run build` (it reads dist/).
//   node scripts/dissipation.mjs [--only TEXT (the rows whose springs' setting names it, e.g. --only coarse)]
import { Simulation, validateScene } from '../dist/core/index.js';

function amplitudes(solver, substeps, settings = {}) {
  const scene = validateScene({
    cloth: { orientation: 'hanging', resolution: 16, position: [0, 1.5, 0], rotation: [40, 0, 0] },
    material: { fabric: 'cotton', damping: 0 },
    solver: { type: solver, substeps, ...settings },
    colliders: [],
    pins: ['top-edge'],
  });
  const sim = new Simulation(scene, { kernel: 'ts' });
  const out = [];
  for (let w = 0; w < 5; w++) {
    let lo = Infinity, hi = -Infinity;
    for (let f = 0; f < 120; f++) {
      sim.advance(1);
      const z = sim.report().centroid[2];
      lo = Math.min(lo, z); hi = Math.max(hi, z);
    }
    out.push((hi - lo) / 2);
  }
  return out;
}

console.log('| solver | substeps | springs, bending | swing amplitude in each 2 s [cm] | energy kept after 8 s |');
console.log('|---|---|---|---|---|');
const SOLVES = [
  ['one at a time, skip-one springs', {}],
  ['together, skip-one springs', { stretch: 'global' }],
  ['one at a time, hinges together', { bending: 'hinges', bendingSolve: 'global' }],
  ['together, hinges together', { stretch: 'global', bending: 'hinges', bendingSolve: 'global' }],
  ['together (4 passes), skip-one springs', { stretch: 'global', iterations: 4 }],
  ['together (16 passes), skip-one springs', { stretch: 'global', iterations: 16 }],
  ['one at a time after the coarse correction, skip-one springs', { stretch: 'two-level' }],
  ['one at a time after the coarse correction, hinges together', { stretch: 'two-level', bending: 'hinges', bendingSolve: 'global' }],
];
const only = process.argv.includes('--only') ? process.argv[process.argv.indexOf('--only') + 1] : null;
for (const [solver, substeps, solves] of [['xpbd', 10, [0]], ['xpbd', 20, [0, 1, 4, 5, 2, 3, 6, 7]], ['xpbd', 80, [0, 1, 2, 3]], ['mass-spring', 20, [0]], ['mass-spring', 80, [0]]]) {
  for (const k of solves) {
    const [name, settings] = SOLVES[k];
    if (only && !(solver === 'xpbd' && name.includes(only))) continue;
    const a = amplitudes(solver, substeps, settings);
    console.log(`| ${solver} | ${substeps} | ${solver === 'xpbd' ? name : 'the seed\'s'} | ${a.map((v) => (100 * v).toFixed(2)).join(', ')} | ${(100 * (a[4] / a[0]) ** 2).toFixed(0)} % |`);
  }
}
