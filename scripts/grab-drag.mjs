#!/usr/bin/env node
// A fast drag across the flag (docs/physics.md, "A fast grab"): the `wind` scene with a sphere 2 cm behind the flag
// (src/cli/threads.test.ts's), its lower free corner grabbed after 10 frames and pulled at once to [0.2, 2.2, 0.3] m,
// up past the flag's front, about a metre away. Per frame: the wall time, how far the grabbed particle went, and the
// triangle pairs crossing each other. With self-contact the grab goes at solver.selfContactSpeed (--speed sets it).
//
//   npx tsc -p tsconfig.build.json && node scripts/grab-drag.mjs
//   options: --faces 40  --kernel wasm|ts|gpu (gpu: the WebGPU solver on the adapter Node finds)  --speed 6  --frames 30
import { Simulation, builtinScene, grab, validateScene } from '../dist/core/index.js';
import { arg } from './solver-study-common.mjs';

const faces = Number(arg('faces', '40')), kernel = arg('kernel', 'wasm'), frames = Number(arg('frames', '30'));
const doc = builtinScene('wind');
doc.cloth.resolution = faces;
doc.colliders = [{ type: 'sphere', center: [0.2, 1.6, 0.62], radius: 0.6 }, { type: 'floor', height: 0 }];
if (arg('speed', '') !== '') doc.solver.selfContactSpeed = Number(arg('speed', ''));
const sim = new Simulation(validateScene(doc), { kernel: kernel === 'gpu' ? 'ts' : kernel, threads: 1 });
if (kernel === 'gpu') {
  const { createNodeDevice } = await import('../dist/gpu/node.js');
  const { GpuBackend } = await import('../dist/gpu/backend.js');
  sim.useBackend(await GpuBackend.create((await createNodeDevice()).device, sim.model));
}
const p = (faces + 1) * (faces + 1) - 1, x = sim.state.positions, to = [0.2, 2.2, 0.3];
sim.advance(10);
await sim.sync();
grab(sim.state, p, to);
console.log(`wind at ${faces}², ${kernel}, self-contact at ${sim.params.selfContact ? `${doc.solver.selfContactSpeed} m/s` : 'off'}, ${sim.params.substeps} substeps`);
console.log('| frame | ms | grabbed particle moved [m] | crossing pairs |\n|---|---|---|---|');
for (let f = 11; f <= 10 + frames; f++) {
  const from = [x[3 * p], x[3 * p + 1], x[3 * p + 2]], t = performance.now();
  sim.advance(1);
  await sim.sync();
  const moved = Math.hypot(x[3 * p] - from[0], x[3 * p + 1] - from[1], x[3 * p + 2] - from[2]);
  console.log(`| ${f} | ${(performance.now() - t).toFixed(0)} | ${moved.toFixed(4)} | ${sim.report().intersections} |`);
}
if (kernel === 'gpu' && sim.backend.notes.length) console.log(`notes: ${sim.backend.notes.join('; ')}`);
sim.dispose();
process.exit(0);
