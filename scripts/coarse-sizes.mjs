#!/usr/bin/env node
// The springs' coarse correction as the GPU holds it (docs/gpu.md, "The springs' coarse correction"): for
// cotton-basic at 33², 65², 129² and 257² particles (the model holds its skip-one springs whatever bends it, so the tables
// are the same for every bending model), the aggregates, the band's half width, the (particle, aggregate) pairs and their pairs, and the GPU memory of its tables
// (gpu/coarse-stretch.ts coarseTables), with the time the CPU takes to make them.
//   npx tsc -p tsconfig.build.json && node scripts/coarse-sizes.mjs
import { builtinScene, modelFor, setScenePath } from '../dist/core/index.js';
import { coarseTables } from '../dist/gpu/coarse-stretch.js';
import { BUFFERS } from '../dist/gpu/layout.js';

for (const r of [32, 64, 128, 256]) {
  const scene = setScenePath(setScenePath(builtinScene('cotton-basic'), 'cloth.resolution', r), 'solver.stretch', 'two-level');
  const model = modelFor(scene), n = model.particleCount;
  const t0 = performance.now();
  const t = coarseTables(model);
  const ms = performance.now() - t0;
  let bytes = 0;
  for (const [name, size] of Object.entries(t.sizes)) bytes += size * BUFFERS[name].bytes;
  const band = t.data.coarseBlocks[2];
  console.log(`${r + 1}²: ${t.aggregates} aggregates, band ${band}, ${t.pairs} pairs (${(t.pairs / n).toFixed(1)} a particle), ` +
    `${t.couples} pairs of pairs (${(t.couples / n).toFixed(1)}), ${(bytes / 1e6).toFixed(2)} MB (${(bytes / n).toFixed(0)} B a particle), made in ${ms.toFixed(0)} ms`);
}
