#!/usr/bin/env node
// Numerical dissipation (docs/physics.md, "Energy"): a 1 m cotton cloth pinned along its top edge, started turned 40°
// out of the vertical, swings as a pendulum with no damping, no air and no colliders for 10 s. The swing's amplitude
// (half the range of the centroid's horizontal position within each 2 s, about two periods) is printed per 2 s; the
// energy of a swing goes as its amplitude², so (A_last / A_first)² is the share of its energy the integrator keeps
// over 8 s. Per solver and substep count. (Total energy cannot show it at the defaults: XPBD's unconverged stretch
// is itself stored energy of the same size.) Needs `npm run build` (it reads dist/).   node scripts/dissipation.mjs
import { Simulation, validateScene } from '../dist/core/index.js';

function amplitudes(solver, substeps) {
  const scene = validateScene({
    cloth: { orientation: 'hanging', resolution: 16, position: [0, 1.5, 0], rotation: [40, 0, 0] },
    material: { fabric: 'cotton', damping: 0 },
    solver: { type: solver, substeps },
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

console.log('| solver | substeps | swing amplitude in each 2 s [cm] | energy kept after 8 s |');
console.log('|---|---|---|---|');
for (const [solver, substeps] of [['xpbd', 10], ['xpbd', 20], ['xpbd', 80], ['mass-spring', 20], ['mass-spring', 80]]) {
  const a = amplitudes(solver, substeps);
  console.log(`| ${solver} | ${substeps} | ${a.map((v) => (100 * v).toFixed(2)).join(', ')} | ${(100 * (a[4] / a[0]) ** 2).toFixed(0)} % |`);
}
