#!/usr/bin/env node
// Could the bending stencils solved together (solver.bendingSolve 'global') be solved iteratively, as a GPU would
// have to (docs/physics.md, "Bending solved together", "On the GPU")? For a scene, a mesh and a fabric with the hinges
// solved together: after `frames` frames, the next substep's system of the global bending step (its matrix and
// right-hand side as solvers/global-bending.ts makes them) is solved by its factor and by Jacobi-preconditioned
// conjugate gradients (one run per coordinate) from the positions before the step, x*; printed: how far the step
// moves the cloth, and the iterations after which the CG solution is within 1e-2, 1e-3 and 1e-4 of that of the exact
// solution (the largest error over the particles). The TypeScript kernel; self-contact off.
//
//   npx tsc -p tsconfig.build.json && node scripts/iterative-bending.mjs [scene] [faces] [fabric] [frames]
//   defaults: cotton-basic 32 cotton 60
import { Simulation, builtinScene, setScenePath } from '../dist/core/index.js';
import { SparseCholesky } from '../dist/core/solvers/sparse.js';
import { PrefactoredSystem } from '../dist/core/solvers/prefactored.js';

const [scene = 'cotton-basic', faces = '32', fabric = 'cotton', frames = '60'] = process.argv.slice(2);
const TARGETS = [1e-2, 1e-3, 1e-4];
const MOST = 20000;

// the system the step solves: its PrefactoredSystem (for the rows' order) and the right-hand side it hands the factor
let sim, system = null, captured = null, armed = false;
const grabbed = PrefactoredSystem.prototype.grabbed;
PrefactoredSystem.prototype.grabbed = function (state) { system = this; return grabbed.call(this, state); };
const solve3 = SparseCholesky.prototype.solve3;
SparseCholesky.prototype.solve3 = function (b) {
  if (armed && !captured && system?.chol === this) {
    const st = sim.state, start = new Float64Array(3 * this.n);
    for (let i = 0; i < this.n; i++) for (let c = 0; c < 3; c++) start[3 * system.row[i] + c] = st.positions[3 * i + c] + st.residuals[3 * i + c];
    captured = { chol: this, b: b.slice(), start };
  }
  return solve3.call(this, b);
};

let doc = builtinScene(scene);
for (const [path, value] of [['cloth.resolution', Number(faces)], ['material.fabric', fabric], ['solver.bending', 'hinges'],
  ['solver.bendingSolve', 'global'], ['solver.selfContact', false]]) doc = setScenePath(doc, path, value);
sim = new Simulation(doc, { kernel: 'ts' });
sim.advance(Number(frames));
armed = true;
sim.advance(1);
const { chol, b, start } = captured, n = chol.n;
const exact = b.slice();
chol.solve3(exact);

// A·v for one coordinate, from A's lower triangle (SparseCholesky's aStart / aCols / aValues: row i's columns
// ascending, its diagonal last); Jacobi's preconditioner is its diagonal
const { aStart, aCols, aValues } = chol;
const diagonal = Float64Array.from({ length: n }, (_, i) => aValues[aStart[i + 1] - 1]);
const multiply = (v, c, out) => {
  out.fill(0);
  for (let i = 0; i < n; i++) {
    for (let p = aStart[i]; p < aStart[i + 1]; p++) {
      const j = aCols[p], a = aValues[p];
      out[i] += a * v[3 * j + c];
      if (j !== i) out[j] += a * v[3 * i + c];
    }
  }
};
let moves = 0;
for (let k = 0; k < 3 * n; k++) moves = Math.max(moves, Math.abs(exact[k] - start[k]));

const x = start.slice(), r = new Float64Array(3 * n), z = new Float64Array(3 * n), p = new Float64Array(3 * n);
const Ap = new Float64Array(n), rz = [0, 0, 0], reached = TARGETS.map(() => -1);
for (let c = 0; c < 3; c++) {
  multiply(x, c, Ap);
  for (let i = 0; i < n; i++) {
    const j = 3 * i + c;
    r[j] = b[j] - Ap[i]; z[j] = r[j] / diagonal[i]; p[j] = z[j];
    rz[c] += r[j] * z[j];
  }
}
for (let it = 0; it <= MOST && reached.includes(-1); it++) {
  let error = 0;
  for (let k = 0; k < 3 * n; k++) error = Math.max(error, Math.abs(x[k] - exact[k]));
  TARGETS.forEach((t, q) => { if (reached[q] < 0 && error <= t * moves) reached[q] = it; });
  for (let c = 0; c < 3; c++) {
    if (rz[c] === 0) continue;
    multiply(p, c, Ap);
    let pAp = 0;
    for (let i = 0; i < n; i++) pAp += p[3 * i + c] * Ap[i];
    const alpha = rz[c] / pAp;
    let next = 0;
    for (let i = 0; i < n; i++) {
      const j = 3 * i + c;
      x[j] += alpha * p[j]; r[j] -= alpha * Ap[i]; z[j] = r[j] / diagonal[i];
      next += r[j] * z[j];
    }
    const beta = next / rz[c];
    rz[c] = next;
    for (let i = 0; i < n; i++) p[3 * i + c] = z[3 * i + c] + beta * p[3 * i + c];
  }
}
const shown = reached.map((v) => (v < 0 ? `more than ${MOST}` : String(v))).join(' / ');
console.log(`${scene} at ${faces} faces, ${fabric}, frame ${Number(frames) + 1}: ${n} particles; the step moves the cloth by up to ` +
  `${(moves * 1e3).toFixed(3)} mm; Jacobi-preconditioned CG within ${TARGETS.join(' / ')} of that after ${shown} iterations`);
