#!/usr/bin/env node
// How often the springs' coarse correction makes its matrix anew (docs/physics.md, "A factor that no longer fits"):
// every built-in scene with solver.stretch two-level, 180 frames in the TypeScript reference, the factors made per
// frame (1: only each frame's first substep; more: a step of the frame's factor overshot under the matrix now).
//   npx tsc -p tsconfig.build.json && node scripts/coarse-factors.mjs [scene ...]
import { SCENE_NAMES, Simulation, builtinScene, setScenePath } from '../dist/core/index.js';
import { coarseSystem } from '../dist/core/solvers/coarse-stretch.js';

const frames = 180;
for (const name of process.argv.length > 2 ? process.argv.slice(2) : SCENE_NAMES) {
  const sim = new Simulation(setScenePath(builtinScene(name), 'solver.stretch', 'two-level'), { kernel: 'ts' });
  const sys = coarseSystem(sim.model);
  let most = 0, before = sys.factors;
  for (let f = 0; f < frames; f++) {
    sim.advance(1);
    most = Math.max(most, sys.factors - before);
    before = sys.factors;
  }
  console.log(`${name}: ${(sys.factors / frames).toFixed(2)} factors a frame, at most ${most}`);
  sim.dispose();
}
