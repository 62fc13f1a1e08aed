#!/usr/bin/env node
// The Cusick scene on real fabrics whose areal density, bending rigidity and measured drape coefficient come from one
// source each (docs/materials.md §3.6), both read second-hand:
// - source 17, Petrak et al., Sustainability 17(4):1388, 2025, as transcribed from its tables 1, 2, 4 and 5 into
//   `config/materials/kes-woven-fabrics-2025.v1.json` of the public repository KAFKA2306/image2outfit (commit
//   1e4a63f): six fabrics, M1…M6, their KES-FB values as the paper converted them to CLO3D's inputs (stretch and
//   shear in g/s², ×10⁻³ → N/m; bending in g·mm²/s², ×10⁻⁹ → N·m per unit width, warp and weft), and the drape
//   coefficient CLO3D gave from them;
// - source 16, Matsudaira, Masuda, Wada, Yokura, J. Textile Eng. 61(6):69–73, 2015, tables 1 and 2, as transcribed
//   into `src/motion_engine/cloth/r6_setup.py` of the public repository antonbj3/3fold-motion-engine (commit
//   72e280a): four fabrics, A, B, C, F, their KES-FB2 B [gf·cm²/cm, ×9.80665·10⁻⁵ → N·m] and weight W [mg/cm²,
//   ×10⁻² → kg/m²]; no tensile or shear stiffness, so those are the scene's (cotton's).
// Drape's bending and tensile stiffness are isotropic: a specimen takes the geometric mean of the warp's and the
// weft's bending rigidity (`--bending warp|weft|mean` for the others) and the mean of their tensile stiffness; every
// field the source does not give is the scene's (cotton's damping and friction). Prints, per fabric, the drape
// coefficient and folds of each specimen (`cloth.perturbation.seed`) and their mean, beside the measured one and
// CLO3D's. Needs `npx tsc -p tsconfig.build.json` (it reads dist/).
//   node scripts/cusick-measured.mjs [--fabrics M1,…,A,B,C,F] [--seeds 1,2,3] [--resolution 48]
//       [--substeps S --iterations I (solver.substeps, solver.iterations: the defaults unless given)]
//       [--bending geometric|mean|warp|weft] [--width W (the specimen's diameter [m], cloth.width: the scene's 0.3 unless
//       given; the pedestal stays 18 cm)]
import { FABRICS, mean, readSpecimen, specimenScene } from './cusick-common.mjs';
import { arg } from './solver-study-common.mjs';

const chosen = arg('fabrics', FABRICS.map((f) => f[0]).join(',')).split(',');
const seeds = arg('seeds', '1,2,3').split(',').map(Number);
const resolution = Number(arg('resolution', '48'));
const substeps = arg('substeps', null), iterations = arg('iterations', null);
const bendingRule = arg('bending', 'geometric');
const width = arg('width', null);
const rules = { geometric: (a, b) => Math.sqrt(a * b), mean: (a, b) => (a + b) / 2, warp: (a) => a, weft: (_a, b) => b };
if (!rules[bendingRule]) throw new Error(`--bending: geometric, mean, warp or weft, got '${bendingRule}'`);
for (const id of chosen) if (!FABRICS.some((f) => f[0] === id)) throw new Error(`--fabrics: unknown fabric '${id}' (${FABRICS.map((f) => f[0]).join(', ')})`);

const specimen = (f, seed) => readSpecimen(specimenScene(f, seed, { resolution, substeps, iterations, bending: rules[bendingRule], width }));

console.log(`the cusick scene at ${resolution} cells${width !== null ? `, a ${width} m specimen` : ''}, ${substeps ?? 'the default'} substeps × ${iterations ?? 'the default'} passes, bending: ${bendingRule} of warp and weft; seeds ${seeds.join(', ')}`);
console.log('| fabric | g/m² | B used [µN·m] | c [cm] | specimens: drape coefficient, folds → mean | measured | Drape − measured | CLO3D |');
console.log('|---|---|---|---|---|---|---|---|');
const pairs = [];
for (const f of FABRICS.filter((x) => chosen.includes(x[0]))) {
  const [id, what, rho, , , [bendWarp, bendWeft], measured, clo] = f;
  const B = rules[bendingRule](bendWarp, bendWeft);
  const c = Math.cbrt(B / (rho * 9.81));
  const runs = seeds.map((seed) => specimen(f, seed));
  const dc = mean(runs.map((t) => t.drapeCoefficient)), folds = mean(runs.map((t) => t.folds));
  const cells = `${runs.map((t) => `${t.drapeCoefficient.toFixed(3)}, ${t.folds}`).join('; ')} → ${dc.toFixed(3)}, ${folds.toFixed(2)}`;
  pairs.push([measured, dc]);
  console.log(`| ${id} (${what}) | ${(rho * 1e3).toFixed(2)} | ${(B * 1e6).toFixed(2)} | ${(c * 100).toFixed(2)} | ${cells} | ${measured.toFixed(3)} | ${(dc - measured >= 0 ? '+' : '')}${(dc - measured).toFixed(3)} | ${clo === null ? '–' : clo.toFixed(3)} |`);
}
if (pairs.length > 2) {
  // how Drape's means follow the measured coefficients: their mean and RMS difference, the correlation, and the
  // least-squares slope of Drape's on the measured (1: Drape spreads the fabrics as far apart as they are)
  const n = pairs.length, mx = mean(pairs.map((p) => p[0])), my = mean(pairs.map((p) => p[1]));
  let sxx = 0, syy = 0, sxy = 0, sdd = 0;
  for (const [x, y] of pairs) { sxx += (x - mx) ** 2; syy += (y - my) ** 2; sxy += (x - mx) * (y - my); sdd += (y - x) ** 2; }
  console.log(`\n${n} fabrics: Drape − measured ${(my - mx).toFixed(3)} on average, RMS ${Math.sqrt(sdd / n).toFixed(3)}; correlation ${(sxy / Math.sqrt(sxx * syy)).toFixed(2)}; slope of Drape's on the measured ${(sxy / sxx).toFixed(2)}`);
}
