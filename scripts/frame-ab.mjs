#!/usr/bin/env node
// Two builds of the library timed against each other in one process, on `drape bench`'s cloth: for a change to the
// solver's speed smaller than this machine's drift between runs (the same code's frame here varies by ±10–20 % from
// one run to the next, and by 2× between days). Each build steps the same scene on the WebAssembly kernel; their
// blocks of frames alternate (A then B, then B then A, …), so both meet the machine as it is. Prints each build's
// ms a frame and B/A.
//
//   node scripts/frame-ab.mjs BUILD_A BUILD_B  [--like] [--size 64] [--threads 1] [--blocks 24] [--frames 5]
//   node scripts/frame-ab.mjs BUILD_A BUILD_B  --scene NAME  [--threads 1] [--blocks 12] [--frames 10]
//
// --like: the bench's like-for-like settings (XPBD, 10 substeps, one pass, the skip-one springs swept alone,
// self-contact off: src/cli/bench.ts benchScene); without it, the scene's own default model with self-contact off
// (the bench's fabric-model rows). A build older than one of those settings gets only the settings its scene has.
// --size: particles per side (the bench's sizes: 64, 128). --scene: a built-in scene as it is (its resolution and
// settings, self-contact as it says), timed from its start rather than after 30 frames. BUILD_A and BUILD_B are `dist` folders made by
// `npx tsc -p tsconfig.build.json`, e.g. of a commit checked out with `git worktree add /tmp/before COMMIT` (link its
// node_modules to this one's).
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { arg } from './solver-study-common.mjs';

const builds = process.argv.slice(2).filter((a, i, all) => !a.startsWith('--') && !['--size', '--threads', '--blocks', '--frames', '--scene'].includes(all[i - 1]));
if (builds.length !== 2) throw new Error('usage: node scripts/frame-ab.mjs BUILD_A BUILD_B [--like] [--size 64] [--threads 1] [--blocks 24] [--frames 5]');
const like = process.argv.includes('--like');
const size = Number(arg('size', '64')), threads = Number(arg('threads', '1'));
const blocks = Number(arg('blocks', '24')), frames = Number(arg('frames', '5'));

const sceneName = arg('scene', '');

async function make(dist) {
  const { Simulation, builtinScene } = await import(pathToFileURL(resolve(dist, 'core/index.js')).href);
  if (sceneName) {
    const sim = new Simulation(builtinScene(sceneName), { kernel: 'wasm', threads });
    await sim.whenReady?.();
    if (sim.kernel !== 'wasm') throw new Error(`${dist}: the WebAssembly kernel did not start here (it needs WebAssembly SIMD)`);
    return sim;
  }
  const scene = builtinScene('cotton-basic');
  scene.cloth.resolution = size - 1;
  const want = like
    ? { type: 'xpbd', substeps: 10, iterations: 1, selfContact: false, bending: 'springs', stretch: 'gauss-seidel' }
    : { selfContact: false };
  for (const [key, value] of Object.entries(want)) if (key in scene.solver || ['type', 'substeps', 'iterations'].includes(key)) scene.solver[key] = value;
  const sim = new Simulation(scene, { kernel: 'wasm', threads });
  await sim.whenReady?.();
  if (sim.kernel !== 'wasm') throw new Error(`${dist}: the WebAssembly kernel did not start here (it needs WebAssembly SIMD)`);
  sim.advance(30);
  return sim;
}

const sims = [await make(builds[0]), await make(builds[1])];
const ms = [0, 0];
for (let b = 0; b < blocks; b++) {
  for (const i of b % 2 ? [1, 0] : [0, 1]) {
    const t0 = performance.now();
    sims[i].advance(frames);
    ms[i] += performance.now() - t0;
  }
}
const perFrame = ms.map((t) => t / (blocks * frames));
const what = sceneName ? `${sceneName} from its start` : `${like ? 'like for like' : 'default model'}, ${size}²`;
console.log(`${what}, ${threads} thread${threads === 1 ? '' : 's'}: ` +
  `A ${perFrame[0].toFixed(2)} ms a frame, B ${perFrame[1].toFixed(2)}, B/A ${(perFrame[1] / perFrame[0]).toFixed(3)}`);
