#!/usr/bin/env node
// The strain table of docs/physics.md (XPBD, "one Gauss–Seidel pass per substep"): cotton dropped on the sphere,
// the largest structural strain over the first 4 s (sampled every frame) and at the end of them, per mesh size and
// substep count. Needs `npm run build` (it reads dist/).   node scripts/strain-table.mjs [--bending springs|hinges|laplacian]
import { Simulation, builtinScene } from '../dist/core/index.js';
import { arg } from './solver-study-common.mjs';

const bending = arg('bending', undefined);

const substeps = [10, 20, 40];
console.log(`| faces | ${substeps.map((n) => `${n} substeps`).join(' | ')} |`);
console.log(`|---|${substeps.map(() => '---').join('|')}|`);
for (const faces of [32, 64]) {
  const cells = substeps.map((n) => {
    const scene = builtinScene('cotton-basic');
    scene.cloth.resolution = faces;
    scene.solver.substeps = n;
    // self-contact off: with it a run takes at least the substeps its rule asks (20 at these sizes), not n
    scene.solver.selfContact = false;
    if (bending) scene.solver.bending = bending;
    const sim = new Simulation(scene);
    let worst = 0;
    for (let f = 0; f < 240; f++) {
      sim.advance(1);
      worst = Math.max(worst, sim.report().maxStrain);
    }
    const pct = (v) => `${(100 * v).toFixed(1)} %`;
    return `${pct(worst)} / ${pct(sim.report().maxStrain)}`;
  });
  console.log(`| ${faces}² | ${cells.join(' | ')} |`);
}
