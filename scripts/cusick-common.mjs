// Shared by scripts/cusick-specimens.mjs, scripts/cusick-measured.mjs and scripts/bending-hysteresis.mjs: one Cusick
// specimen read as the scene reads it, the measured fabrics, and a mean. Not a script of its own.
import { builtinScene, setScenePath, Simulation } from '../dist/core/index.js';

/** The `cusick` scene document `scene` run to its duration (the WebAssembly kernel where it can): its test's reading. */
export function readSpecimen(scene) {
  const sim = new Simulation(scene);
  sim.advance(Math.round(scene.duration * 60));
  const t = sim.report().test;
  sim.dispose();
  return t;
}

/** KES-FB2's units: B [gf·cm²/cm] → N·m, 2HB [gf·cm/cm] → N (a moment per unit width) */
export const GF_CM2_PER_CM = 9.80665e-5, GF_CM_PER_CM = 9.80665e-3;
/**
 * id, what it is, areal density [kg/m²], tensile stiffness warp and weft [N/m] (null: the scene's), shear stiffness
 * [N/m] (null: the scene's), bending rigidity warp and weft [N·m], the measured drape coefficient, CLO3D's (null: none),
 * the bending hysteresis 2HB [N] (KES-FB2; null: not given), the folds the measured specimen drape made (null: not
 * given). Source 17's six (M1…M6) and source 16's four (A, B, C, F)
 * of docs/materials.md §3.6, as scripts/cusick-measured.mjs's header says where each was read.
 */
export const FABRICS = [
  ['M1', 'polyester, twill 3/1', 0.13517, [477.226, 458.614], 41, [1950e-9, 610e-9], 0.223, 0.349, null, null],
  ['M2', 'polyester, plain', 0.08366, [471.944, 373.515], 46, [850e-9, 330e-9], 0.228, 0.313, null, null],
  ['M3', 'wool 75 %, PES 15 %, elastane 10 %, twill 2/1', 0.1787, [449.656, 439.815], 50, [2140e-9, 2000e-9], 0.349, 0.404, null, null],
  ['M4', 'PES 63 %, viscose 33 %, elastane 4 %, twill 2/1', 0.28613, [403.447, 401.762], 61, [2970e-9, 2400e-9], 0.286, 0.323, null, null],
  ['M5', 'PES 97 %, elastane 3 %, plain', 0.242, [407.166, 415.023], 57, [3220e-9, 3880e-9], 0.443, 0.438, null, null],
  ['M6', 'cotton 65 %, PES 31 %, elastane 4 %, twill 2/1', 0.25336, [473.86, 404.746], 126, [7430e-9, 3700e-9], 0.549, 0.613, null, null],
  ['A', 'cotton broad, plain', 0.1238, null, null, [0.118 * GF_CM2_PER_CM, 0.118 * GF_CM2_PER_CM], 0.829, null, 0.124 * GF_CM_PER_CM, 2],
  ['B', 'wool tropical, plain', 0.1629, null, null, [0.067 * GF_CM2_PER_CM, 0.067 * GF_CM2_PER_CM], 0.498, null, 0.033 * GF_CM_PER_CM, 5],
  ['C', 'polyester tropical', 0.1165, null, null, [0.077 * GF_CM2_PER_CM, 0.077 * GF_CM2_PER_CM], 0.507, null, 0.029 * GF_CM_PER_CM, 5],
  ['F', 'polyester faille', 0.1043, null, null, [0.019 * GF_CM2_PER_CM, 0.019 * GF_CM2_PER_CM], 0.283, null, 0.007 * GF_CM_PER_CM, 7],
];

/**
 * The `cusick` scene for specimen `seed` (cloth.perturbation.seed) of fabric `f` (a row of FABRICS): its areal density,
 * the mean of its warp's and weft's tensile stiffness, its shear stiffness and `bending`(warp B, weft B), every field
 * the source does not give the scene's; `resolution` (cloth.resolution), `width` (cloth.width [m]), `substeps` and
 * `iterations` (solver.…) where not null.
 */
export function specimenScene(f, seed, { resolution = 48, width = null, substeps = null, iterations = null, bending = (a, b) => Math.sqrt(a * b) } = {}) {
  const [, , rho, tensile, shear, [bendWarp, bendWeft]] = f;
  let scene = builtinScene('cusick');
  const set = (path, value) => { scene = setScenePath(scene, path, value); };
  set('material.arealDensity', rho);
  if (tensile) set('material.structuralStiffness', (tensile[0] + tensile[1]) / 2);
  if (shear !== null) set('material.shearStiffness', shear);
  set('material.bendingRigidity', bending(bendWarp, bendWeft));
  set('cloth.resolution', resolution);
  if (width !== null) set('cloth.width', Number(width));
  set('cloth.perturbation.seed', seed);
  if (substeps !== null) set('solver.substeps', Number(substeps));
  if (iterations !== null) set('solver.iterations', Number(iterations));
  return scene;
}

export const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;
