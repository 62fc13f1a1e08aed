#!/usr/bin/env node
// Issue 10 (the Cusick reading at the default settings): does a solver setting keep the rest another setting
// reached? The built-in `cusick` scene (cotton, specimen 1) runs FIRST's substeps × passes for 6 s; its state is
// then copied into the same scene at SECOND's and run on, the drape coefficient read every 2 s. A setting whose
// rest is the same as the other's keeps its reading; one that drifts has a rest of its own (docs/physics.md, "Not
// the threads' strain, it turns out"). Needs `npx tsc -p tsconfig.build.json` (it reads dist/).
//   node scripts/cusick-rest-swap.mjs [--first 40x16] [--second 20x1] [--fabric cotton]
import { Simulation, builtinScene, copyState, measureTest, setScenePath, validateScene } from '../dist/core/index.js';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
/** The scene at `setting` ("SUBSTEPS x PASSES"). */
function at(setting) {
  const m = /^(\d+)x(\d+)$/.exec(setting);
  if (!m) throw new Error(`"${setting}": give the setting as SUBSTEPSxPASSES, e.g. 40x16`);
  let scene = setScenePath(builtinScene('cusick'), 'material.fabric', arg('fabric', 'cotton'));
  scene = setScenePath(scene, 'solver.substeps', Number(m[1]));
  scene = validateScene(setScenePath(scene, 'solver.iterations', Number(m[2])));
  return { scene, sim: new Simulation(scene) };
}
const reading = ({ scene, sim }) => measureTest(sim.model, sim.state, scene).drapeCoefficient.toFixed(3);

const firstSetting = arg('first', '40x16'), secondSetting = arg('second', '20x1');
const first = at(firstSetting), second = at(secondSetting);
first.sim.advance(360);
console.log(`${firstSetting}, 6 s: drape coefficient ${reading(first)}`);
copyState(first.sim.state, second.sim.state);
for (let s = 2; s <= 6; s += 2) {
  second.sim.advance(120);
  console.log(`then ${secondSetting}, +${s} s: ${reading(second)}`);
}
first.sim.dispose();
second.sim.dispose();
