#!/usr/bin/env node
// The numbers of docs/gpu.md "Parity" for the colliders: the scenes of src/gpu/moving-colliders.test.ts (and the
// built-in tablecloth) on the WebGPU solver and the CPU (TypeScript) solver side by side; over the frames the tests
// check, the largest particle distance and centroid distance, next to the CPU's own spread when its start positions
// are nudged by 1e-7 (relative), and the GPU cloth's deepest penetration into the exact shapes (maxPenetration).
// Needs `npm run build` (it reads dist/) and a WebGPU adapter (Dawn; SwiftShader from Debian's chromium will do).
//   node scripts/gpu-collider-parity.mjs
import {
  FRAME_DT, applyPins, builtinScene, centroid, copyState, createState, maxPenetration, modelFor, resolveParams,
  resolvePins, step, validateScene,
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
const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };
const floor = { type: 'floor', height: 0 };
const drop = (y, colliders) => ({ cloth: { resolution: 12, width: 0.6, height: 0.6, position: [0, y, 0] }, material: cotton, colliders });
const tablecloth = builtinScene('tablecloth');
tablecloth.cloth.resolution = 12;
// [name, scene, frames, check every]
const SCENES = [
  ['tilted plane', drop(0.5, [{ type: 'plane', point: [0, 0.3, 0], normal: [0.3, 1, 0.1] }]), 60, 15],
  ['box turned 30°', drop(0.55, [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.15, 0.2, 0.15], rotation: [0, 30, 0] }, floor]), 60, 15],
  ['slanted capsule', drop(0.5, [{ type: 'capsule', a: [-0.2, 0.3, 0.05], b: [0.2, 0.3, -0.05], radius: 0.08 }, floor]), 60, 15],
  ['upright cylinder', drop(0.5, [{ type: 'cylinder', center: [0, 0.2, 0], axis: [0, 1, 0], radius: 0.15, height: 0.4 }, floor]), 60, 15],
  ['cylinder on its side', drop(0.5, [{ type: 'cylinder', center: [0, 0.3, 0], axis: [1, 0, 0.2], radius: 0.1, height: 0.5 }, floor]), 60, 15],
  ['tablecloth (built-in, box)', tablecloth, 30, 30],
  ['box table moving 0.2 m (keyframes)', {
    cloth: { resolution: 12, width: 0.4, height: 0.4, position: [0, 0.45, 0] }, material: cotton,
    colliders: [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.3, 0.2, 0.3], motion: { keyframes: [{ time: 0.5 }, { time: 1.5, translation: [0.2, 0, 0] }] } }, floor],
  }, 105, 15],
  ['cape on a turning capsule (carry)', {
    cloth: { resolution: 12, width: 0.4, height: 0.5, orientation: 'hanging', position: [0, 0.95, -0.16] }, material: cotton,
    colliders: [{ type: 'capsule', a: [0, 0.6, 0], b: [0, 1.2, 0], radius: 0.12, pins: ['top-edge'], motion: { keyframes: [{ time: 0.25 }, { time: 1, rotation: [0, 90, 0] }] } }],
  }, 90, 5],
];
console.log(`adapter: ${adapter}`);
console.log('| scene | frames | GPU–CPU | centroid | CPU\'s own spread | its centroid | penetration (GPU) |');
console.log('|---|---|---|---|---|---|---|');
for (const [name, s, frames, every] of SCENES) {
  const scene = validateScene({ name: 'parity', ...s });
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
  const worst = [0, 0, 0, 0, 0];
  for (let f = 1; f <= frames; f++) {
    // the three share params: each puts the colliders where they are for its own substeps (moveTo) before use
    step(model, cpu, params, FRAME_DT);
    solver.step(gpu, params, FRAME_DT);
    step(model, nudged, params, FRAME_DT);
    if (f % every === 0) {
      await solver.read(gpu);
      const now = [maxDistance(gpu.positions, cpu.positions), centroidDistance(gpu, cpu), maxDistance(nudged.positions, cpu.positions),
        centroidDistance(nudged, cpu), maxPenetration(model, gpu, params)];
      now.forEach((v, k) => { worst[k] = Math.max(worst[k], v); });
    }
  }
  console.log(`| ${name} | ${frames} | ${worst.slice(0, 4).map(e).join(' | ')} | ${worst[4] === 0 ? '0' : e(worst[4])} |`);
  solver.destroy();
}
device.destroy();
