#!/usr/bin/env node
// The stretch XPBD leaves, seen as energy (docs/physics.md, "Energy"): the elastic energy is taken from the
// positions, so a constraint the solver has not converged counts. For cotton dropped on the sphere and the `pins`
// hammock (16 faces a side, 4 s), per solver and substep count: the largest rise of the total energy in one frame
// (relative to the starting total) and the largest elastic energy seen; a converged solver's total never rises. XPBD
// with the springs swept alone and after the coarse correction (solver.stretch gauss-seidel, two-level).
// Needs `npm run build` (it reads dist/).   node scripts/energy-lag.mjs
import { builtinScene, Simulation } from '../dist/core/index.js';

console.log('| scene | solver | stretch | substeps | largest rise in a frame / E₀ | largest elastic [J] | elastic at 4 s [J] |');
console.log('|---|---|---|---|---|---|---|');
for (const name of ['cotton-basic', 'pins']) {
  for (const [solver, stretch, substeps] of [['xpbd', 'gauss-seidel', 20], ['xpbd', 'gauss-seidel', 80], ['xpbd', 'two-level', 20], ['mass-spring', '—', 20]]) {
    const s = builtinScene(name);
    s.solver.type = solver; s.solver.substeps = substeps; s.cloth.resolution = 16;
    if (solver === 'xpbd') s.solver.stretch = stretch;
    const sim = new Simulation(s, { kernel: 'ts' });
    const total = () => { const e = sim.report().energy; return e.kinetic + e.gravitational + e.elastic; };
    const e0 = total();
    let prev = e0, rise = 0, most = 0;
    for (let f = 0; f < 240; f++) {
      sim.advance(1);
      const e = total();
      rise = Math.max(rise, e - prev);
      prev = e;
      most = Math.max(most, sim.report().energy.elastic);
    }
    const last = sim.report().energy.elastic;
    console.log(`| ${name} | ${solver} | ${stretch} | ${substeps} | ${(rise / Math.abs(e0)).toExponential(1)} | ${most.toFixed(3)} | ${last.toFixed(3)} |`);
  }
}
