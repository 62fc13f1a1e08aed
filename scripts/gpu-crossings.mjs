#!/usr/bin/env node
// Issue 12 on the GPU: the crossing triangle pairs (countIntersections, as `--json`'s `intersections`) at every 10th
// frame of issue 12's scenes run by the WebGPU solver with self-contact on, every cloth at --faces per side. The
// crossings are the solver's whatever the adapter (SwiftShader on a CPU counts the same; its milliseconds say
// nothing of a GPU's). A scene the GPU refuses is listed with the reason.
//
//   npx tsc -p tsconfig.build.json && node scripts/gpu-crossings.mjs [--faces 32] [--frames 300]
//        [--scenes fold,layers,wind,cotton-basic,silk-drape,leather-stiff,rubber-stretch]
import { builtinScene, countIntersections, validateScene } from '../dist/core/index.js';
import { openGpu } from '../dist/cli/gpu.js';
import { arg } from './solver-study-common.mjs';

const faces = Number(arg('faces', '32')), frames = Number(arg('frames', '300'));
const scenes = arg('scenes', 'fold,layers,wind,cotton-basic,silk-drape,leather-stiff,rubber-stretch').split(',');
const gpu = await openGpu();
console.log(`adapter: ${gpu.adapter}; ${faces} faces per side, ${frames} frames, self-contact on`);
console.log('| scene | particles | substeps | crossing pairs: most at a 10th frame (which) | at the last frame | ms per frame |');
console.log('|---|---|---|---|---|---|');
const kept = Array.from({ length: Math.floor(frames / 10) }, (_, k) => 10 * (k + 1));
for (const name of scenes) {
  const doc = builtinScene(name);
  for (const entry of doc.cloths ?? [doc]) entry.cloth.resolution = faces;
  doc.solver.selfContact = true;
  try {
    const { sim, msPerFrame, shapes } = await gpu.simulate(validateScene(doc), frames, undefined, kept);
    const counts = shapes.map((p) => countIntersections(sim.model.triangles, p));
    const most = Math.max(0, ...counts), at = counts.indexOf(most);
    console.log(`| ${name} | ${sim.model.particleCount} | ${sim.params.substeps} | ${most}${most > 0 ? ` (frame ${kept[at]})` : ''} | ` +
      `${counts.at(-1) ?? 0} | ${msPerFrame.toFixed(1)} |`);
  } catch (e) {
    console.log(`| ${name} | | | refused: ${e.message.split('\n')[0]} | | |`);
  }
}
