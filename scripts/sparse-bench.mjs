#!/usr/bin/env node
// The global stretch step's direct solver (src/core/solvers/sparse.ts): on the spring graph of the hanging rubber sheet
// (scripts/solver-study-common.mjs, solver.bending hinges, so the springs are the structural and shear ones) at each
// --faces, the matrix M/h² + Σ k·SᵀS (h = 1/300 s) ordered and factored two ways — nested dissection and the sparse
// Cholesky the step uses, and reverse Cuthill–McKee with the envelope Cholesky it used before — with the entries of
// each factor, the time to order and set up, to factor (the cost of a pin change) and to solve three right-hand sides
// (once per pass), the median of --repeats, and the largest difference of the two solutions.
//
//   npx tsc -p tsconfig.build.json && node scripts/sparse-bench.mjs
//   options: --faces 32,64,128,256  --repeats 5
import { Simulation } from '../dist/core/index.js';
import { EnvelopeCholesky, SparseCholesky, nestedDissection, orderedGraph, reverseCuthillMcKee } from '../dist/core/solvers/sparse.js';
import { arg, hangingScene } from './solver-study-common.mjs';

const facesList = arg('faces', '32,64,128,256').split(',').map(Number);
const repeats = Number(arg('repeats', '5'));
/** the median time of f() over --repeats [ms], `before` run untimed before each */
const median = (f, before = () => {}) => {
  const t = [];
  for (let r = 0; r < repeats; r++) { before(); const t0 = performance.now(); f(); t.push(performance.now() - t0); }
  return t.sort((a, b) => a - b)[repeats >> 1];
};

console.log('| faces | particles | order | factor entries | order + set up [ms] | factor [ms] | solve, 3 right-hand sides [ms] | largest difference |');
console.log('|---|---|---|---|---|---|---|---|');
for (const faces of facesList) {
  const sim = new Simulation(hangingScene('rubber', faces, 5, 1, 'hinges', 'global'), { kernel: 'ts' });
  const { model, params } = sim;
  const n = model.particleCount, h = 1 / 300;
  const edges = [], k = [];
  for (let s = 0; s < model.restLengths.length; s++) {
    if (!(params.stiffness[s] > 0)) continue;
    edges.push([model.springs[2 * s], model.springs[2 * s + 1]]);
    k.push(params.stiffness[s]);
  }
  const lists = Array.from({ length: n }, () => []);
  for (const [a, b] of edges) { lists[a].push(b); lists[b].push(a); }
  const rowStart = new Int32Array(n + 1);
  for (let i = 0; i < n; i++) rowStart[i + 1] = rowStart[i] + lists[i].length;
  const cols = Int32Array.from(lists.flat());
  const assemble = (chol, row) => {
    chol.clear();
    for (let i = 0; i < n; i++) chol.add(row[i], row[i], params.particleMass[i] / (h * h));
    edges.forEach(([a, b], s) => { chol.add(row[a], row[a], k[s]); chol.add(row[b], row[b], k[s]); chol.add(row[a], row[b], -k[s]); });
  };
  const rhs = Float64Array.from({ length: 3 * n }, (_, j) => Math.sin(j));
  const ways = {
    'nested dissection, sparse': () => {
      const g = orderedGraph(rowStart, cols, nestedDissection(rowStart, cols)), row = g.row;
      const chol = new SparseCholesky(g.rowStart, g.cols);
      return { chol, row, entries: chol.entries };
    },
    'reverse Cuthill–McKee, envelope': () => {
      const row = orderedGraph(rowStart, cols, reverseCuthillMcKee(rowStart, cols)).row;
      const first = new Int32Array(n).map((_, r) => r);
      for (const [a, b] of edges) { const hi = Math.max(row[a], row[b]); first[hi] = Math.min(first[hi], row[a], row[b]); }
      const chol = new EnvelopeCholesky(first);
      return { chol, row, entries: chol.values.length };
    },
  };
  const solutions = [];
  for (const [name, make] of Object.entries(ways)) {
    let made;
    const setup = median(() => { made = make(); });
    const { chol, row, entries } = made;
    const factor = median(() => chol.factor(), () => assemble(chol, row)); // the envelope factors in place
    const b = new Float64Array(3 * n);
    const solve = median(() => { for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) b[3 * row[i] + c] = rhs[3 * i + c]; chol.solve3(b); });
    solutions.push(Float64Array.from({ length: 3 * n }, (_, j) => b[3 * row[Math.floor(j / 3)] + (j % 3)]));
    const diff = solutions.length === 2 ? solutions[0].reduce((m, v, j) => Math.max(m, Math.abs(v - solutions[1][j])), 0).toExponential(1) : '';
    console.log(`| ${faces}² | ${n} | ${name} | ${entries} | ${setup.toFixed(1)} | ${factor.toFixed(1)} | ${solve.toFixed(2)} | ${diff} |`);
  }
}
