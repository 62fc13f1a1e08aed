#!/usr/bin/env node
// Where a scene's frame goes: V8's sampling profiler (node:inspector) over a block of frames of a built-in scene on
// the WebAssembly kernel, one thread, and the functions that took the most of it (self time), the kernel's by their
// AssemblyScript names (its text form built with the kernel's own flags: gen-wasm.mjs kernelFunctionNames).
//
//   npx tsc -p tsconfig.build.json && node scripts/frame-profile.mjs
//   options: --scene cotton-basic  --from 150 (frames stepped first)  --frames 150 (profiled)
//            --self-contact on|off (default: the scene's)  --faces N (every cloth's; default: the scene's)  --top 15
import { Session } from 'node:inspector/promises';
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';
import { kernelFunctionNames } from '../src/core/wasm/gen-wasm.mjs';
import { arg } from './solver-study-common.mjs';

const name = arg('scene', 'cotton-basic');
const from = Number(arg('from', '150')), frames = Number(arg('frames', '150')), top = Number(arg('top', '15'));
const scene = builtinScene(name);
const self = arg('self-contact', '');
if (self) scene.solver.selfContact = self === 'on';
const faces = arg('faces', '');
if (faces) for (const entry of scene.cloths ?? [scene]) entry.cloth.resolution = Number(faces);
const sim = new Simulation(validateScene(scene), { kernel: 'wasm', threads: 1 });
await sim.whenReady();
sim.advance(from);
const names = await kernelFunctionNames();

const session = new Session();
session.connect();
await session.post('Profiler.enable');
await session.post('Profiler.start');
const t0 = performance.now();
sim.advance(frames);
const ms = (performance.now() - t0) / frames;
const { profile } = await session.post('Profiler.stop');
session.disconnect();

const nodes = new Map(profile.nodes.map((n) => [n.id, n]));
const samples = new Map();
for (const id of profile.samples) {
  const f = nodes.get(id).callFrame;
  const wasm = /^wasm-function\[(\d+)\]$/.exec(f.functionName);
  const label = wasm ? `${names[Number(wasm[1])] ?? f.functionName} (kernel)` : `${f.functionName || '(anonymous)'} ${f.url.split('/').pop()}`;
  samples.set(label, (samples.get(label) ?? 0) + 1);
}
const total = profile.samples.length;
console.log(`${name}, frames ${from + 1}–${from + frames}, the kernel on one thread, self-contact ${scene.solver.selfContact ? 'on' : 'off'}: ${ms.toFixed(2)} ms a frame; self time:`);
console.log('| share | function |');
console.log('|---|---|');
for (const [label, n] of [...samples].sort((a, b) => b[1] - a[1]).slice(0, top)) console.log(`| ${((100 * n) / total).toFixed(1)} % | ${label} |`);
