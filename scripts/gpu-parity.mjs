#!/usr/bin/env node
// The numbers of docs/gpu.md "Parity": per built-in scene at 12 faces per side, the largest particle distance
// between the WebGPU solver and the CPU (TypeScript) solver at frames 16, 22 and 30 and their centroids' distance at
// frame 30, next to the CPU's own spread at frame 30 when its start positions are nudged by 1e-7 (relative).
// Needs `npm run build` (it reads dist/) and a WebGPU adapter (Dawn; SwiftShader from Debian's chromium will do).
//   node scripts/gpu-parity.mjs
import {
  FRAME_DT, applyPins, builtinScene, centroid, copyState, createState, modelFor, resolveParams, resolvePins, step, validateScene,
} from '../dist/core/index.js';
import { createNodeDevice } from '../dist/gpu/node.js';
import { GpuClothSolver } from '../dist/gpu/solver.js';

const { device, adapter } = await createNodeDevice();
const maxDistance = (p, q) => {
  let m = 0;
  for (let i = 0; i < p.length; i += 3) m = Math.max(m, Math.hypot(p[i] - q[i], p[i + 1] - q[i + 1], p[i + 2] - q[i + 2]));
  return m;
};
const centroidDistance = (a, b) => Math.hypot(...centroid(a).map((v, k) => v - centroid(b)[k]));
const e = (v) => v.toExponential(1);
console.log(`adapter: ${adapter}`);
console.log('| scene | frame 16 | frame 22 | frame 30 | centroid, frame 30 | CPU\'s own spread, frame 30 | its centroid |');
console.log('|---|---|---|---|---|---|---|');
for (const name of ['cotton-basic', 'silk-drape', 'leather-stiff', 'rubber-stretch', 'wind', 'pins']) {
  const s = builtinScene(name);
  s.cloth.resolution = 12;
  const scene = validateScene(s);
  const model = modelFor(scene), params = resolveParams(model, scene);
  const cpu = createState(model);
  applyPins(cpu, resolvePins(model, scene.pins));
  const nudged = createState(model);
  copyState(cpu, nudged);
  for (let i = 0; i < nudged.positions.length; i++) {
    nudged.positions[i] *= 1 + 1e-7 * Math.sin(7 * i);
    nudged.previousPositions[i] = nudged.positions[i];
  }
  const gpu = createState(model);
  copyState(cpu, gpu);
  const solver = await GpuClothSolver.create(device, model);
  solver.setParams(params);
  solver.upload(gpu);
  const cells = [];
  for (let f = 1; f <= 30; f++) {
    step(model, cpu, params, FRAME_DT);
    step(model, nudged, params, FRAME_DT);
    solver.step(gpu, params, FRAME_DT);
    if (f === 16 || f === 22 || f === 30) {
      await solver.read(gpu);
      cells.push(e(maxDistance(gpu.positions, cpu.positions)));
    }
  }
  console.log(`| ${name} | ${cells.join(' | ')} | ${e(centroidDistance(gpu, cpu))} | ${e(maxDistance(nudged.positions, cpu.positions))} | ${e(centroidDistance(nudged, cpu))} |`);
  solver.destroy();
}
device.destroy();
