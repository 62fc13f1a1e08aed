// Shared by scripts/cusick-specimens.mjs and scripts/cusick-measured.mjs: one Cusick specimen read as the scene reads
// it, and a mean. Not a script of its own.
import { Simulation } from '../dist/core/index.js';

/** The `cusick` scene document `scene` run to its duration (the WebAssembly kernel where it can): its test's reading. */
export function readSpecimen(scene) {
  const sim = new Simulation(scene);
  sim.advance(Math.round(scene.duration * 60));
  const t = sim.report().test;
  sim.dispose();
  return t;
}

export const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;
