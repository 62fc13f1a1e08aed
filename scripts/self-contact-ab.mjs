#!/usr/bin/env node
// Issue 12 (self-contact's cost): two builds of the library timed against each other in one process, for changes
// too small to see in separate runs on a machine whose speed drifts from run to run (here ±10 % between two runs of
// the same code; ±2 % between the two builds of one run of this script when they are the same code). Each build
// runs the same scene with self-contact on the WebAssembly kernel (one thread); their frames alternate (A then B,
// then B then A, …), so both meet the machine as it is. Per block of frames it prints, for each build, the frame,
// self-contact's whole phase, its whole searches and its two passes over the listed pairs [ms a frame], as
// scripts/self-contact-phases.mjs does for one build.
//
//   node scripts/self-contact-ab.mjs BUILD_A BUILD_B  [--scene fold] [--faces 64] [--blocks 0,60,180]
//
// BUILD_A and BUILD_B are `dist` folders made by `npx tsc -p tsconfig.build.json` (the other one, e.g. of the code
// before a change: `git stash; node src/core/wasm/gen-wasm.mjs; npx tsc -p tsconfig.build.json --outDir /tmp/before/dist;
// git stash pop; node src/core/wasm/gen-wasm.mjs`, with /tmp/before/package.json and /tmp/before/node_modules
// copied or linked from here so that its imports resolve).
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { arg } from './solver-study-common.mjs';

const [first, second] = process.argv.slice(2).filter((a, i, all) => !a.startsWith('--') && !(all[i - 1] ?? '').startsWith('--'));
if (!first || !second) throw new Error('usage: node scripts/self-contact-ab.mjs BUILD_A BUILD_B [--scene fold] [--faces 64] [--blocks 0,60,180]');
const faces = Number(arg('faces', '64'));
const blocks = arg('blocks', '0,60,180').split(',').map(Number);
const sceneName = arg('scene', 'fold');

async function make(dist) {
  const { Simulation, builtinScene, validateScene } = await import(pathToFileURL(resolve(dist, 'core/index.js')).href);
  const scene = builtinScene(sceneName);
  for (const entry of scene.cloths ?? [scene]) entry.cloth.resolution = faces;
  scene.solver.selfContact = true;
  const sim = new Simulation(validateScene(scene), { kernel: 'wasm', threads: 1 });
  await sim.whenReady();
  // the kernel's self-contact: a private field of the backend's kernel, reached here only to time it
  const self = sim.backendNow?.kernel?.selfContact;
  if (!self) throw new Error(`${dist}: no WebAssembly kernel with self-contact here (it needs WebAssembly SIMD)`);
  const t = { frame: 0, phase: 0, search: 0, particles: 0, edges: 0 };
  const timed = (key, f) => function (...args) {
    const t0 = performance.now();
    const done = f.apply(this, args);
    t[key] += performance.now() - t0;
    return done;
  };
  const proto = Object.getPrototypeOf(self);
  self.run = timed('phase', proto.run);
  self.find = timed('search', proto.find);
  self.particles = timed('particles', self.particles);
  self.edges = timed('edges', self.edges);
  return { sim, t };
}

const a = await make(first), b = await make(second);
console.log(`${sceneName} at ${faces} faces per side, self-contact on, the WebAssembly kernel (1 thread); ms a frame; A = ${first}, B = ${second}`);
console.log('| frames | build | frame | self-contact | whole searches | particle pass | edge pass |');
console.log('|---|---|---|---|---|---|---|');
for (let k = 0; k + 1 < blocks.length; k++) {
  for (const run of [a, b]) for (const key of Object.keys(run.t)) run.t[key] = 0;
  const n = blocks[k + 1] - blocks[k];
  for (let f = 0; f < n; f++) {
    for (const run of f % 2 ? [b, a] : [a, b]) {
      const t0 = performance.now();
      run.sim.advance(1);
      run.t.frame += performance.now() - t0;
    }
  }
  for (const [name, run] of [['A', a], ['B', b]]) {
    const t = run.t, ms = (v) => (v / n).toFixed(1);
    console.log(`| ${blocks[k] + 1}–${blocks[k + 1]} | ${name} | ${ms(t.frame)} | ${ms(t.phase)} | ${ms(t.search)} | ${ms(t.particles)} | ${ms(t.edges)} |`);
  }
}
