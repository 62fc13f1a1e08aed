#!/usr/bin/env node
// The Cusick scene on six real fabrics whose areal density, stiffnesses and measured drape coefficient come from
// one source (docs/materials.md source 17: Petrak et al., Sustainability 17(4):1388, 2025, read second-hand, as
// transcribed from its tables 1, 2, 4 and 5 into `config/materials/kes-woven-fabrics-2025.v1.json` of the public
// repository KAFKA2306/image2outfit, commit 1e4a63f). The paper gives the fabrics' KES-FB values converted to CLO3D's
// inputs: stretch and shear in g/s² (×10⁻³ → N/m), bending in g·mm²/s² (×10⁻⁹ → N·m per unit width), warp and weft.
// Drape's bending and tensile stiffness are isotropic: each specimen takes the geometric mean of the warp's and the
// weft's bending rigidity (`--bending warp|weft|mean` for the others) and the mean of their tensile stiffness; every
// other material field is the scene's (cotton's damping and friction). Prints, per fabric, the drape coefficient
// and folds of each specimen (`cloth.perturbation.seed`) and their mean, beside the measured one and CLO3D's.
// Needs `npx tsc -p tsconfig.build.json` (it reads dist/).
//   node scripts/cusick-measured.mjs [--fabrics M1,…] [--seeds 1,2,3] [--resolution 48]
//       [--substeps S --iterations I (solver.substeps, solver.iterations: the defaults unless given)]
//       [--bending geometric|mean|warp|weft]
import { Simulation, builtinScene, setScenePath } from '../dist/core/index.js';

/** id, what it is, g/m², stretch warp and weft [g/s²], shear [g/s²], bending warp and weft [g·mm²/s²], measured DC, CLO3D's DC */
const FABRICS = [
  ['M1', 'polyester, twill 3/1', 135.17, 477226, 458614, 41000, 1950, 610, 0.223, 0.349],
  ['M2', 'polyester, plain', 83.66, 471944, 373515, 46000, 850, 330, 0.228, 0.313],
  ['M3', 'wool 75 %, PES 15 %, elastane 10 %, twill 2/1', 178.7, 449656, 439815, 50000, 2140, 2000, 0.349, 0.404],
  ['M4', 'PES 63 %, viscose 33 %, elastane 4 %, twill 2/1', 286.13, 403447, 401762, 61000, 2970, 2400, 0.286, 0.323],
  ['M5', 'PES 97 %, elastane 3 %, plain', 242, 407166, 415023, 57000, 3220, 3880, 0.443, 0.438],
  ['M6', 'cotton 65 %, PES 31 %, elastane 4 %, twill 2/1', 253.36, 473860, 404746, 126000, 7430, 3700, 0.549, 0.613],
];

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const chosen = arg('fabrics', FABRICS.map((f) => f[0]).join(',')).split(',');
const seeds = arg('seeds', '1,2,3').split(',').map(Number);
const resolution = Number(arg('resolution', '48'));
const substeps = arg('substeps', null), iterations = arg('iterations', null);
const bendingRule = arg('bending', 'geometric');
const rules = { geometric: (a, b) => Math.sqrt(a * b), mean: (a, b) => (a + b) / 2, warp: (a) => a, weft: (_a, b) => b };
if (!rules[bendingRule]) throw new Error(`--bending: geometric, mean, warp or weft, got '${bendingRule}'`);
for (const id of chosen) if (!FABRICS.some((f) => f[0] === id)) throw new Error(`--fabrics: unknown fabric '${id}' (M1…M6)`);

const specimen = (f, seed) => {
  const [, , gsm, stretchWarp, stretchWeft, shear, bendWarp, bendWeft] = f;
  let scene = builtinScene('cusick');
  const set = (path, value) => { scene = setScenePath(scene, path, value); };
  set('material.arealDensity', gsm * 1e-3);
  set('material.structuralStiffness', ((stretchWarp + stretchWeft) / 2) * 1e-3);
  set('material.shearStiffness', shear * 1e-3);
  set('material.bendingRigidity', rules[bendingRule](bendWarp, bendWeft) * 1e-9);
  set('cloth.resolution', resolution);
  set('cloth.perturbation.seed', seed);
  if (substeps !== null) set('solver.substeps', Number(substeps));
  if (iterations !== null) set('solver.iterations', Number(iterations));
  const sim = new Simulation(scene);
  sim.advance(Math.round(scene.duration * 60));
  const t = sim.report().test;
  sim.dispose();
  return t;
};
const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;

console.log(`the cusick scene at ${resolution} cells, ${substeps ?? 'the default'} substeps × ${iterations ?? 'the default'} passes, bending: ${bendingRule} of warp and weft; seeds ${seeds.join(', ')}`);
console.log('| fabric | g/m² | B used [µN·m] | c [cm] | specimens: drape coefficient, folds → mean | measured | Drape − measured | CLO3D |');
console.log('|---|---|---|---|---|---|---|---|');
for (const f of FABRICS.filter((x) => chosen.includes(x[0]))) {
  const [id, what, gsm, , , , bendWarp, bendWeft, measured, clo] = f;
  const B = rules[bendingRule](bendWarp, bendWeft) * 1e-9;
  const c = Math.cbrt(B / (gsm * 1e-3 * 9.81));
  const runs = seeds.map((seed) => specimen(f, seed));
  const dc = mean(runs.map((t) => t.drapeCoefficient)), folds = mean(runs.map((t) => t.folds));
  const cells = `${runs.map((t) => `${t.drapeCoefficient.toFixed(3)}, ${t.folds}`).join('; ')} → ${dc.toFixed(3)}, ${folds.toFixed(2)}`;
  console.log(`| ${id} (${what}) | ${gsm} | ${(B * 1e6).toFixed(2)} | ${(c * 100).toFixed(2)} | ${cells} | ${measured.toFixed(3)} | ${(dc - measured >= 0 ? '+' : '')}${(dc - measured).toFixed(3)} | ${clo.toFixed(3)} |`);
}
