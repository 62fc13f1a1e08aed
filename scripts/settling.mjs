#!/usr/bin/env node
// How a built-in scene comes to rest, second by second (docs/physics.md, "The Laplacian as the default: tried, not
// kept"): the wall time per frame, the kinetic energy at the second's end and how many times self-contact searched
// its candidates again in that second, for a bending model. The WebAssembly kernel on one thread, as `drape run --threads 1`.
//
//   npx tsc -p tsconfig.build.json && node scripts/settling.mjs
//   options: --scene cotton-basic  --bending springs,laplacian  --bending-solve gauss-seidel|global  --seconds 10
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';
import { selfContactBuilds } from '../dist/core/self-contact.js';
import { arg } from './solver-study-common.mjs';

const name = arg('scene', 'cotton-basic'), seconds = Number(arg('seconds', '10')), bendingSolve = arg('bending-solve', 'gauss-seidel');
for (const bending of arg('bending', 'springs,laplacian').split(',')) {
  const doc = builtinScene(name);
  doc.solver = { ...doc.solver, bending, ...(bending === 'springs' ? {} : { bendingSolve }) };
  const sim = new Simulation(validateScene(doc), { kernel: 'wasm', threads: 1 });
  const rows = [];
  let searched = selfContactBuilds(sim.model);
  for (let s = 1; s <= seconds; s++) {
    const t = performance.now();
    sim.advance(60);
    const ms = (performance.now() - t) / 60, builds = selfContactBuilds(sim.model);
    rows.push(`| ${s} | ${ms.toFixed(1)} | ${sim.report().energy.kinetic.toExponential(1)} | ${builds - searched} |`);
    searched = builds;
  }
  console.log(`${name}, solver.bending ${bending}${bending === 'springs' ? '' : ` (${bendingSolve})`}, self-contact ${sim.params.selfContact ? 'on' : 'off'}`);
  console.log('| second | ms/frame | kinetic energy at its end [J] | self-contact searches in it |\n|---|---|---|---|');
  console.log(rows.join('\n'));
  sim.dispose();
}
