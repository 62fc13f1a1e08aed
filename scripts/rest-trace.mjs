#!/usr/bin/env node
// Issue 12 (the resting jitter): what moves the particles of a pile that should be at rest? The `fold` scene at
// --faces per side runs to --frame on --kernel (the defaults otherwise). Then:
// 1. the fastest particle's motion (v = (x − x_prev)/h) is traced over one frame, phase by phase: the state moves
//    onto the TypeScript reference (TsBackend), whose phases are wrapped to print the particle's displacement in
//    each [µm, x y z] and the substep's net; and, over that frame, how far each phase moved the whole cloth;
// 2. the next --frames frames: the particles over 1 cm/s at every 5th frame (with the fastest speed), and how many
//    moved more than 1 mm from where they were at --frame (a pile still settling moves; one that jitters does not).
//
//   npx tsc -p tsconfig.build.json && node scripts/rest-trace.mjs
//   options: --faces 64  --frame 255  --kernel wasm|ts  --frames 45
import { Simulation, TsBackend, builtinScene, validateScene } from '../dist/core/index.js';
import { REFERENCE } from '../dist/core/reference.js';
import { PHASES } from '../dist/core/schedule.js';
import { arg } from './solver-study-common.mjs';

const faces = Number(arg('faces', '64')), at = Number(arg('frame', '255')), kernel = arg('kernel', 'wasm'), frames = Number(arg('frames', '45'));
const scene = builtinScene('fold');
scene.cloth.resolution = faces;
const make = () => {
  const sim = new Simulation(validateScene(scene), { kernel, threads: 1 });
  sim.advance(at);
  return sim;
};
const speeds = (sim) => {
  const { positions: x, previousPositions: xp } = sim.state, h = 1 / 60 / sim.params.substeps;
  return Array.from({ length: sim.model.particleCount }, (_, i) => Math.hypot(x[3 * i] - xp[3 * i], x[3 * i + 1] - xp[3 * i + 1], x[3 * i + 2] - xp[3 * i + 2]) / h);
};

// 1. one frame of the fastest particle, phase by phase
const traced = make();
const v = speeds(traced);
const p = v.indexOf(Math.max(...v));
const y = traced.state.positions[3 * p + 1];
console.log(`fold ${faces}², ${kernel}, frame ${at}: particle ${p} at ${(v[p] * 100).toFixed(2)} cm/s, ${(1000 * y).toFixed(2)} mm above the floor (thickness ${(1000 * traced.params.thickness).toFixed(1)} mm)`);
// its springs, most stretched first: strain now, and the partner's height relative to it
const { springs, restLengths } = traced.model, X = traced.state.positions;
const mine = [];
for (let k = 0; k < restLengths.length; k++) {
  const a = springs[2 * k], b = springs[2 * k + 1];
  if (a !== p && b !== p) continue;
  const q = a === p ? b : a, len = Math.hypot(X[3 * q] - X[3 * p], X[3 * q + 1] - X[3 * p + 1], X[3 * q + 2] - X[3 * p + 2]);
  mine.push({ q, strain: len / restLengths[k] - 1, dy: X[3 * q + 1] - X[3 * p + 1] });
}
mine.sort((m, n) => n.strain - m.strain);
console.log(`its springs: ${mine.map((m) => `→${m.q} ${(100 * m.strain).toFixed(1)} % (partner ${(1000 * m.dy).toFixed(1)} mm above)`).join(', ')}`);
traced.useBackend(new TsBackend(traced.model));
const names = PHASES.map((ph) => ph.name), own = REFERENCE.slice(), shown = ['integrate', 'coarseStretch', 'distance', 'stretchLimit', 'selfContact', 'contact'];
// and the whole cloth's moves in each phase: how many particles it moved more than 10 µm, the mean move of all, the most
const n = traced.model.particleCount, before = new Float32Array(3 * n), cloth = {};
const um = (d) => d.map((q) => (q * 1e6).toFixed(1).padStart(7)).join('');
let row = {};
REFERENCE.forEach((_, id) => {
  REFERENCE[id] = (model, state, params, frame) => {
    const x = state.positions, b = [x[3 * p], x[3 * p + 1], x[3 * p + 2]];
    before.set(x);
    own[id](model, state, params, frame);
    const moves = (cloth[names[id]] ??= { runs: 0, over: 0, sum: 0, most: 0 });
    moves.runs++;
    for (let i = 0; i < n; i++) {
      const d = Math.hypot(x[3 * i] - before[3 * i], x[3 * i + 1] - before[3 * i + 1], x[3 * i + 2] - before[3 * i + 2]);
      moves.sum += d;
      if (d > 1e-5) moves.over++;
      if (d > moves.most) moves.most = d;
    }
    if (names[id] === shown[0]) row = { sub: frame.sub };
    row[names[id]] = [0, 1, 2].map((c) => x[3 * p + c] - b[c]);
    if (names[id] !== shown[shown.length - 1]) return;
    const net = [0, 1, 2].map((c) => shown.reduce((s, k) => s + (row[k]?.[c] ?? 0), 0));
    console.log(`${String(row.sub).padStart(2)} ${shown.map((k) => `${k} ${um(row[k] ?? [0, 0, 0])}`).join(' | ')} | net ${um(net)}`);
  };
});
traced.advance(1);
own.forEach((f, id) => { REFERENCE[id] = f; });
console.log('the whole cloth in each phase that moved it, per run (a substep\'s): particles moved more than 10 µm, the mean move of all [µm], the most [µm]');
for (const [name, c] of Object.entries(cloth)) {
  if (c.sum === 0) continue;
  console.log(`  ${name.padEnd(14)} ${String(Math.round(c.over / c.runs)).padStart(5)} ${(1e6 * c.sum / (c.runs * n)).toFixed(1).padStart(7)} ${(1e6 * c.most).toFixed(0).padStart(6)}`);
}
traced.dispose();

// 2. the next frames on the kernel asked for
const sim = make();
const from = sim.state.positions.slice(), counts = [];
for (let f = 1; f <= frames; f++) {
  sim.advance(1);
  if (f % 5) continue;
  const s = speeds(sim);
  counts.push(`${s.filter((q) => q > 0.01).length} (${(Math.max(...s) * 100).toFixed(1)} cm/s)`);
}
const x = sim.state.positions;
let moved = 0, most = 0;
for (let i = 0; i < sim.model.particleCount; i++) {
  const d = Math.hypot(x[3 * i] - from[3 * i], x[3 * i + 1] - from[3 * i + 1], x[3 * i + 2] - from[3 * i + 2]);
  if (d > 1e-3) moved++;
  most = Math.max(most, d);
}
console.log(`over 1 cm/s at every 5th frame after ${at}: ${counts.join(', ')}`);
console.log(`moved more than 1 mm over those ${frames} frames: ${moved} particles (the most ${(most * 1000).toFixed(2)} mm)`);
sim.dispose();
process.exit(0);
