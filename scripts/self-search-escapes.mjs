#!/usr/bin/env node
// Issue 12 (self-contact's cost): when self-contact's candidates are found again, how many particles made it
// necessary? The candidates hold while every particle's box over the substep lies inside its reach box; one outside
// is enough to search the whole cloth again. The `fold` scene at --faces per side on the TypeScript reference, the
// selfContact phase wrapped to count, at a substep's start, the particles outside the last search's reach boxes;
// per 15-frame block: searches so started per frame, and how many particles were out (mean, fewest–most). (The
// searches after the particle pass, for the edges, are not counted.)
//
//   npx tsc -p tsconfig.build.json && node scripts/self-search-escapes.mjs
//   options: --faces 64  --frames 120
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';
import { REFERENCE } from '../dist/core/reference.js';
import { PHASE } from '../dist/core/schedule.js';
import { lastSelfCandidates } from '../dist/core/self-contact.js';
import { arg } from './solver-study-common.mjs';

const faces = Number(arg('faces', '64')), frames = Number(arg('frames', '120'));
const scene = builtinScene(arg('scene', 'fold'));
scene.cloth.resolution = faces;
const sim = new Simulation(validateScene(scene), { kernel: 'ts' });
const n = sim.model.particleCount;
const own = REFERENCE[PHASE.selfContact];
let block = { searches: 0, out: 0, fewest: Infinity, most: 0 };
REFERENCE[PHASE.selfContact] = (model, state, params, frame) => {
  const c = lastSelfCandidates(model);
  if (c) {
    const x = state.positions, xp = state.previousPositions;
    let out = 0;
    for (let p = 0; p < n; p++) {
      for (let k = 0; k < 3; k++) {
        const lo = Math.min(x[3 * p + k], xp[3 * p + k]), hi = Math.max(x[3 * p + k], xp[3 * p + k]);
        if (!(lo >= c.reach[6 * p + k] && hi <= c.reach[6 * p + 3 + k])) { out++; break; }
      }
    }
    if (out) {
      block.searches++;
      block.out += out;
      block.fewest = Math.min(block.fewest, out);
      block.most = Math.max(block.most, out);
    }
  }
  own(model, state, params, frame);
};
for (let f = 1; f <= frames; f++) {
  sim.advance(1);
  if (f % 15) continue;
  const { searches, out, fewest, most } = block;
  console.log(`frames ${f - 14}–${f}: ${(searches / 15).toFixed(1)} searches a frame; particles out of their boxes then: mean ${searches ? Math.round(out / searches) : 0}, ${searches ? `${fewest}–${most}` : '–'} of ${n}`);
  block = { searches: 0, out: 0, fewest: Infinity, most: 0 };
}
sim.dispose();
