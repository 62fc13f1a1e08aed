#!/usr/bin/env node
// Issue 12 (self-contact's cost): where a frame's self-contact time goes in the WebAssembly kernel, block by block of
// frames. The kernel's self-contact (wasm/self-contact-wasm.ts KernelSelfContact) is wrapped to time, in each block,
// its whole phase, the whole searches (find) and the updates for a few escaped particles (update: how many a frame,
// and how many particles each took), and the particle–triangle and edge–edge passes over the listed pairs; the
// rest of the phase (the particles' boxes against their reach boxes, the triangles' and edges' boxes) is the
// difference; and the pairs each pass visits a substep. One thread; the timer wraps each call, so the numbers are a
// little above an unwrapped run's.
//
//   npx tsc -p tsconfig.build.json && node scripts/self-contact-phases.mjs
//   options: --scene fold  --faces 64  --blocks 0,30,60,90,180  (frame numbers where the blocks start and end)
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';
import { arg } from './solver-study-common.mjs';

const faces = Number(arg('faces', '64'));
const blocks = arg('blocks', '0,30,60,90,180').split(',').map(Number);
const scene = builtinScene(arg('scene', 'fold'));
for (const entry of scene.cloths ?? [scene]) entry.cloth.resolution = faces;
scene.solver.selfContact = true;
const sim = new Simulation(validateScene(scene), { kernel: 'wasm', threads: 1 });
await sim.whenReady();
// the kernel's self-contact: a private field of the backend's kernel, reached here only to time it
const self = sim.backendNow?.kernel?.selfContact;
if (!self) throw new Error('no WebAssembly kernel with self-contact here (it needs WebAssembly SIMD)');

let t = {};
const timed = (key, f, count) => function (...args) {
  const t0 = performance.now();
  const done = f.apply(this, args);
  t[key] = (t[key] ?? 0) + performance.now() - t0;
  if (count) count(args, done);
  return done;
};
const proto = Object.getPrototypeOf(self);
self.run = timed('phase', proto.run);
self.find = timed('search', proto.find, () => { t.searches = (t.searches ?? 0) + 1; });
self.update = timed('update', proto.update, (a, done) => {
  // update(model, params, out, …): `out` particles out of their boxes; it declines (and a search follows) above its limit
  if (!done) return;
  t.updates = (t.updates ?? 0) + 1;
  t.escaped = (t.escaped ?? 0) + a[2];
});
// each pass's first argument: the pairs it visits (all of the list, or a window of it)
self.particles = timed('particles', self.particles, (a) => { t.particlePairs = (t.particlePairs ?? 0) + a[0]; });
self.edges = timed('edges', self.edges, (a) => { t.edgePairs = (t.edgePairs ?? 0) + a[0]; });

const ms = (v, f) => ((v ?? 0) / f).toFixed(1);
const substeps = sim.params.substeps;
const pairs = (v, f) => {
  const n = (v ?? 0) / (f * substeps);
  return n < 1000 ? n.toFixed(0) : `${(n / 1000).toFixed(1)} k`;
};
console.log(`self-contact's time in the WebAssembly kernel (1 thread), ${arg('scene', 'fold')} at ${faces} faces per side, ${sim.model.particleCount} particles, ${substeps} substeps; ms per frame (and per frame: whole searches; updates made, and the particles out of their boxes that each took; per substep: the pairs each pass visited)`);
console.log('| frames | frame | self-contact | whole searches | updates | particle pass | edge pass | the rest |');
console.log('|---|---|---|---|---|---|---|---|');
for (let b = 0; b + 1 < blocks.length; b++) {
  const f = blocks[b + 1] - blocks[b];
  t = {};
  const t0 = performance.now();
  sim.advance(f);
  const frame = performance.now() - t0;
  const rest = (t.phase ?? 0) - (t.search ?? 0) - (t.update ?? 0) - (t.particles ?? 0) - (t.edges ?? 0);
  console.log(`| ${blocks[b] + 1}–${blocks[b + 1]} | ${ms(frame, f)} | ${ms(t.phase, f)} | ${ms(t.search, f)} (${((t.searches ?? 0) / f).toFixed(2)}) | ${ms(t.update, f)} (${((t.updates ?? 0) / f).toFixed(1)}, ${((t.escaped ?? 0) / Math.max(1, t.updates ?? 0)).toFixed(0)}) | ${ms(t.particles, f)} (${pairs(t.particlePairs, f)}) | ${ms(t.edges, f)} (${pairs(t.edgePairs, f)}) | ${ms(rest, f)} |`);
}
sim.dispose();
