/**
 * The global steps on the WebAssembly kernel (factored-wasm.ts): the reference's assembly around the kernel's
 * triangular solves (factored.as.ts), which must give the reference's solution bit for bit.
 */
import { describe, expect, it } from 'vitest';
import { FRAME_DT, Simulation, copyState, createState, setPinned, validateScene, type ClothState } from '../index.js';
import { PHASE, PhaseLog } from '../schedule.js';
import { REFERENCE } from '../reference.js';
import { WasmBackend } from '../backend.js';
import { REFERENCE_SOLVER, SparseCholesky, type SparseProduct } from '../solvers/sparse.js';
import { grid } from '../solvers/test-graphs.js';
import { WasmFactorSolver } from './factored-wasm.js';
import { kernelImports, wasmKernelAvailable } from './xpbd-wasm.js';
import { XPBD_WASM_SINGLE } from './xpbd-kernel.generated.js';

/** A copy of what the global steps read and write. */
function copyOf(sim: Simulation): ClothState {
  const copy = createState(sim.model);
  copyState(sim.state, copy);
  copy.invMass.set(sim.state.invMass);
  return copy;
}

/**
 * One substep of phase `id` by the kernel on sim's state and by the reference on a copy, from positions disturbed by
 * a few millimetres: the same positions, moved by the step.
 */
function sameAsReference(sim: Simulation, id: number, name: string): void {
  const frame = { h: FRAME_DT / sim.params.substeps, substeps: sim.params.substeps, sub: 0, forced: false, grabFrom: new Float64Array(3), grabTo: new Float64Array(3) };
  // a substep's predicted positions: the cloth moved off its solved shape by up to 2 mm, from a start that is bent
  // too (else the bending step's damping, which pulls towards the start's shape, would pull towards a flat one: 0)
  const x = sim.state.positions, xp = sim.state.previousPositions;
  for (let i = 0; i < x.length; i++) {
    x[i] += 2e-3 * Math.sin(1.3 * i);
    xp[i] += 1e-3 * Math.cos(0.7 * i);
  }
  const copy = copyOf(sim), before = Float32Array.from(x);
  const log = new PhaseLog();
  (sim.backend as WasmBackend).kernel.run(1 << id, sim.model, sim.state, sim.params, frame, log);
  REFERENCE[id](sim.model, copy, sim.params, frame);
  expect(log.names()).toEqual([name]); // run by the kernel, not left to the reference
  let moved = 0;
  for (let i = 0; i < before.length; i++) moved = Math.max(moved, Math.abs(before[i] - sim.state.positions[i]));
  expect(moved).toBeGreaterThan(2e-6); // some 30 f32 steps at 1 m
  expect([...sim.state.positions]).toEqual([...copy.positions]);
  expect([...sim.state.residuals]).toEqual([...copy.residuals]);
}

describe('the global steps on the WebAssembly kernel', () => {
  it('the springs and the stencils solved together give the reference\'s positions bit for bit, and again after a pin changes the factor', () => {
    expect(wasmKernelAvailable()).toBe(true);
    // a stiff sheet (B = 10⁻³ N·m), so that one bending step moves the disturbed cloth by more than rounding
    const sim = new Simulation(validateScene({
      cloth: { resolution: 10 }, material: { bendingRigidity: 1e-3 }, solver: { stretch: 'global', bending: 'hinges', bendingSolve: 'global' },
    }), { kernel: 'wasm' });
    sim.advance(15); // falling onto the sphere
    for (let round = 0; round < 2; round++) {
      sameAsReference(sim, PHASE.globalStretch, 'globalStretch');
      sameAsReference(sim, PHASE.globalBending, 'globalBending');
      sameAsReference(sim, PHASE.globalStretch, 'globalStretch');
      // a new pin: each step refactors its matrix, and the kernel's solves must take the new factor
      setPinned(sim.state, 60, true);
    }
  });

  it('a frame with both global steps runs them in the kernel', () => {
    const sim = new Simulation(validateScene({
      cloth: { resolution: 6 }, solver: { stretch: 'global', bending: 'hinges', bendingSolve: 'global' },
    }), { kernel: 'wasm' });
    const log = new PhaseLog();
    (sim.backend as WasmBackend).kernel.frame(sim.model, sim.state, sim.params, FRAME_DT, log);
    const names = log.names();
    expect(names.filter((n) => n === 'globalStretch')).toHaveLength(sim.params.substeps);
    expect(names.filter((n) => n === 'globalBending')).toHaveLength(sim.params.substeps);
    expect(names.some((n) => n.startsWith('global') && n.endsWith('(reference)'))).toBe(false);
  });

  it('solves as SparseCholesky.solve3 does, bit for bit, for two factors in turn and after a refactor, and with a product added as multiplyAdd3 adds it', () => {
    // two matrices on a 5 × 5 grid graph (diagonally dominant: at most six neighbours of −1.1), each factored; one
    // solver taking both in turn
    const { n, rowStart, cols } = grid(5, 3);
    const build = (shift: number) => {
      const chol = new SparseCholesky(rowStart, cols);
      for (let i = 0; i < n; i++) {
        chol.add(i, i, 8 + shift + Math.sin(i));
        for (let k = rowStart[i]; k < rowStart[i + 1]; k++) if (cols[k] < i) chol.add(i, cols[k], -1 - 0.1 * Math.cos(i * cols[k]));
      }
      chol.factor();
      return chol;
    };
    const a = build(0.3), b = build(7);
    const module = new WebAssembly.Module(Uint8Array.from(atob(XPBD_WASM_SINGLE), (c) => c.charCodeAt(0)));
    const solver = new WasmFactorSolver((memory) => new WebAssembly.Instance(module, kernelImports(memory)));
    const rhs = Float64Array.from({ length: 3 * n }, (_, k) => Math.cos(k * 1.7) / 3);
    const check = (chol: SparseCholesky) => {
      const mine = rhs.slice(), theirs = rhs.slice();
      solver.solve3(chol, mine);
      chol.solve3(theirs);
      expect([...mine]).toEqual([...theirs]);
      expect(mine).not.toEqual(rhs);
    };
    check(a); check(b); check(a);
    // the same factor object refactored with other values: the solver must not keep the old ones
    a.clear();
    for (let i = 0; i < n; i++) a.add(i, i, 2 + i);
    a.factor();
    check(a);

    // with a product added to the right-hand side (the bending step's damping): P on the grid's graph, its rows
    // permuted, as multiplyAdd3 and solve3 give it; again after its values change (a new version)
    const product: SparseProduct = {
      diagonal: Float64Array.from({ length: n }, (_, i) => 1 + 0.1 * i), start: rowStart, cols,
      values: Float64Array.from(cols, (c, k) => 0.3 * Math.sin(c + k)), row: Int32Array.from({ length: n }, (_, i) => (7 * i) % n), version: 0,
    };
    const v = Float64Array.from({ length: 3 * n }, (_, k) => Math.sin(k * 0.9) / 5);
    const withProduct = () => {
      const mine = rhs.slice(), theirs = rhs.slice(), without = rhs.slice();
      solver.solve3(b, mine, product, v);
      REFERENCE_SOLVER.solve3(b, theirs, product, v);
      b.solve3(without);
      expect([...mine]).toEqual([...theirs]);
      expect(mine).not.toEqual(without);
    };
    check(b); // the solver laid out for b alone: the product must make it lay out again
    withProduct();
    product.values.forEach((w, k) => { product.values[k] = -2 * w; });
    product.version++;
    withProduct();
    check(b); // and without it again
  });
});
