#!/usr/bin/env node
// "No allocation inside a step": what a built-in scene's frames leave for the garbage collector. After 60 frames
// (`--warm`: the code warm), 100 frames under V8's sampling heap profiler (every allocation sampled, kept or collected) give
// the bytes allocated per frame and the three innermost functions of the call stacks that allocate most, and 300
// more frames the collections V8 made meanwhile and their milliseconds a frame.
//
//   npx tsc -p tsconfig.build.json && node scripts/step-garbage.mjs
//   options: --scenes cotton-basic,cape  --kernel wasm|ts  --warm 60 (frames before the 100 sampled: V8 may still
//            optimise a function again after its first rare branch, and allocate meanwhile)
//            --scenes mesh-cube,mesh-ball: a 24² cloth dropped on a mesh collider (mesh-drop.test.ts's cube, icosphere)
import inspector from 'node:inspector/promises';
import { PerformanceObserver } from 'node:perf_hooks';
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';
import { cubeMesh, icosphereMesh } from '../dist/core/colliders/mesh-shapes.js';
import { arg } from './solver-study-common.mjs';

const kernel = arg('kernel', 'wasm'), warm = Number(arg('warm', '60'));
const session = new inspector.Session();
session.connect();
await session.post('HeapProfiler.enable');
for (const name of arg('scenes', 'cotton-basic,cape').split(',')) {
  const sim = name.startsWith('mesh-') ? meshDrop(name) : new Simulation(validateScene(builtinScene(name)), { kernel, threads: 1 });
  sim.advance(warm);
  await session.post('HeapProfiler.startSampling', { samplingInterval: 1024, includeObjectsCollectedByMajorGC: true, includeObjectsCollectedByMinorGC: true });
  sim.advance(100);
  const { profile } = await session.post('HeapProfiler.stopSampling');
  const sites = new Map();
  let total = 0;
  const walk = (node, stack) => {
    const f = node.callFrame;
    const here = [...stack, `${f.functionName || '(anonymous)'} ${(f.url || '').split('/').pop()}:${f.lineNumber + 1}`];
    if (node.selfSize) {
      total += node.selfSize;
      const key = here.slice(-3).join(' < ');
      sites.set(key, (sites.get(key) ?? 0) + node.selfSize);
    }
    for (const c of node.children ?? []) walk(c, here);
  };
  walk(profile.head, []);
  let collections = 0;
  const observer = new PerformanceObserver((list) => { collections += list.getEntries().length; });
  observer.observe({ entryTypes: ['gc'] });
  const started = performance.now();
  sim.advance(300);
  const ms = (performance.now() - started) / 300;
  await new Promise((resolve) => setTimeout(resolve, 50));
  observer.disconnect();
  console.log(`${name}, ${kernel}: ${(total / 100 / 1024).toFixed(1)} kB allocated a frame; ${collections} collections in 300 frames (${ms.toFixed(2)} ms a frame)`);
  for (const [key, bytes] of [...sites].sort((a, b) => b[1] - a[1]).slice(0, 5)) console.log(`  ${(bytes / 100 / 1024).toFixed(1)} kB/frame  ${key}`);
  sim.dispose();
}

/** A 24² cloth dropped on a mesh collider: mesh-cube (sharp edges, turned 30°) or mesh-ball (an icosphere). */
function meshDrop(name) {
  const files = { 'cube.obj': cubeMesh([0, 0, 0], 0.25), 'ball.obj': icosphereMesh(2, 0.3, [0, 0.35, 0]) };
  const collider = name === 'mesh-cube' ? { type: 'mesh', mesh: 'cube.obj', scale: 1, position: [0, 0.25, 0], rotation: [0, 30, 0] }
    : { type: 'mesh', mesh: 'ball.obj', scale: 1 };
  const scene = validateScene({ cloth: { resolution: 24, position: [0, 0.9, 0] }, colliders: [collider, { type: 'floor', height: 0 }] });
  return new Simulation(scene, { kernel, threads: 1, meshes: (path) => files[path] });
}
