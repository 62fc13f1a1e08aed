#!/usr/bin/env node
// The global stretch step's factor as the GPU holds it (docs/gpu.md, "The springs solved together"): for cotton-basic
// at 33², 65² and 129² particles, the levels of its triangular solves, L's entries outside the blocks and the values of
// the blocks' inverses (gpu/global-bending.ts FactorLayout), the GPU memory of the step (the factor's tables and values,
// each spring's coefficients and force term, its incidence, each particle's y, rows of b and t, and z) and how long the
// CPU takes to order and factor it.
//   npx tsc -p tsconfig.build.json && node scripts/factor-sizes.mjs
import { applyPins, builtinScene, createState, modelFor, resolveParams, scenePins, setScenePath } from '../dist/core/index.js';
import { globalStretchSystem } from '../dist/core/solvers/global-stretch.js';
import { FactorLayout } from '../dist/gpu/global-bending.js';

for (const r of [32, 64, 128]) {
  const scene = setScenePath(setScenePath(builtinScene('cotton-basic'), 'cloth.resolution', r), 'solver.stretch', 'global');
  const model = modelFor(scene), params = resolveParams(model, scene), state = createState(model);
  applyPins(state, scenePins(model, scene));
  const t0 = performance.now();
  const system = globalStretchSystem(model, params, state.pinned, 1 / (60 * scene.solver.substeps));
  const ms = performance.now() - t0;
  const layout = new FactorLayout(system.chol, system.row);
  const n = model.particleCount, S = model.restLengths.length;
  const bytes = 4 * layout.index.length + 4 * layout.valueCount + S * (16 + 16) + 4 * (n + 1 + 2 * S) + n * (16 + 16 + 16 + 4);
  console.log(`${r + 1}²: ${layout.forwardLevels} levels, ${layout.outside} entries outside the blocks, ${layout.inverseValues} values of their inverses, ` +
    `${(bytes / 1e6).toFixed(2)} MB (${(bytes / n).toFixed(0)} B a particle), ordered and factored in ${ms.toFixed(0)} ms`);
}
