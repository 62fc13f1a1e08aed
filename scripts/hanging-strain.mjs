#!/usr/bin/env node
// Issue 10 (converged stretch): does XPBD at the scene defaults stretch a hanging sheet as much as the fabric says?
// A 1 m sheet pinned along its whole top row, no colliders, gravity (scripts/solver-study-common.mjs): after it
// settles, the bottom's drop (elongation) and the mean vertical strain of the middle region are compared with
// theory, ρ_A·g·L²/(2k) and ρ_A·g·L/(2k), k = structuralStiffness. The real solver (Simulation with scene
// overrides through validateScene, the WebAssembly kernel unless --kernel ts), per fabric (rubber: k = 600 N/m,
// ρ_A = 0.38 kg/m²; cotton: k = 8600, ρ_A = 0.12), mesh size and solver setting (substeps × iterations; with
// iterations > 1 XPBD accumulates λ across the passes).
//
// "Settled": frames run in chunks of 30 until the elongation changes by < 0.1 % over a chunk (at least 300 frames) and the kinetic
// energy is < 1e-6 of the sheet's m·g·L, or a per-case time budget runs out (then the row says "not settled", and
// the elongation is still moving, usually still growing). Columns: frames run, kinetic energy at the end, the
// drift of the elongation over the last chunk, elongation / theory, middle strain / theory, ms per frame.
//
// Note: the theory counts the structural springs only; the shear springs (rubber 200 N/m, cotton 56) make the
// grid's discrete sheet 10–30 % (rubber) or < 1 % (cotton) stiffer than k; scripts/pd-study.mjs prints the
// converged discrete equilibrium for the same model, which is the solver's true target.
//
//   npx tsc -p tsconfig.build.json && node scripts/hanging-strain.mjs
//   options: --fabrics rubber,cotton  --faces 16,32,64,128  --settings 20x1,20x5,100x1 (more: 20x20,100x4,200x1)
//            --budget 8 (seconds per case; the defaults run ~3 min)  --kernel wasm|ts  --bending springs|hinges
//            --stretch gauss-seidel|global (solver.stretch)
import { Simulation } from '../dist/core/index.js';
import { arg, hangingScene, hangingTheory, measureHanging, pct } from './solver-study-common.mjs';

const fabrics = arg('fabrics', 'rubber,cotton').split(',');
const facesList = arg('faces', '16,32,64,128').split(',').map(Number);
const settings = arg('settings', '20x1,20x5,100x1').split(',').map((s) => s.split('x').map(Number));
const budget = Number(arg('budget', '8')) * 1000;
const kernel = arg('kernel', 'wasm');
const bending = arg('bending', 'springs');
const stretch = arg('stretch', 'gauss-seidel');

console.log(`XPBD hanging sheet, kernel ${kernel}, bending ${bending}, stretch ${stretch}; ratios are measured / theory (1.00 = as the fabric says)`);
for (const fabric of fabrics) {
  const th = hangingTheory(fabric);
  console.log(`\n${fabric}: theory elongation ${(1000 * th.elongation).toFixed(3)} mm, middle strain ${pct(th.strainMid, 3)}, top strain ${pct(th.strainTop, 3)}`);
  console.log('| faces | substeps × iterations | frames | KE [J] | last-chunk drift | elongation [mm] | elongation ratio | middle strain ratio | max strain | ms/frame |');
  console.log('|---|---|---|---|---|---|---|---|---|---|');
  for (const faces of facesList) {
    for (const [substeps, iterations] of settings) {
      const scene = hangingScene(fabric, faces, substeps, iterations, bending, stretch);
      const sim = new Simulation(scene, { kernel });
      const mgl = scene.material.mass * 9.81 * 1;
      const t0 = performance.now();
      let prev = NaN, drift = NaN, settled = false, ke = NaN;
      while (performance.now() - t0 < budget) {
        sim.advance(30);
        const m = measureHanging(sim.state.positions, faces);
        ke = sim.report().energy.kinetic;
        drift = (m.elongation - prev) / m.elongation;
        prev = m.elongation;
        if (sim.frame >= 300 && Math.abs(drift) < 0.001 && ke < 1e-6 * mgl) { settled = true; break; }
      }
      const ms = (performance.now() - t0) / sim.frame;
      const m = measureHanging(sim.state.positions, faces);
      const rep = sim.report();
      console.log(`| ${faces}² | ${substeps} × ${iterations} | ${sim.frame}${settled ? '' : ' (not settled)'} | ${ke.toExponential(1)} | ${pct(drift, 2)} | ` +
        `${(1000 * m.elongation).toFixed(3)} | ${(m.elongation / th.elongation).toFixed(2)} | ${(m.strainMid / th.strainMid).toFixed(2)} | ${pct(rep.maxStrain)} | ${ms.toFixed(1)} |`);
      sim.dispose();
    }
  }
}
