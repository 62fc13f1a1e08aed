/**
 * The global stretch step (solver.stretch 'global', solvers/global-stretch.ts) and its direct solver (sparse.ts), on
 * both CPU kernels (the WebAssembly kernel runs the reference's assembly with its own triangular solves,
 * wasm/factored-wasm.ts).
 */
import { describe, expect, it } from 'vitest';
import { FRAME_DT } from '../params.js';
import { validateScene, type Scene } from '../scene.js';
import { builtinScene } from '../scenes.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { grab, release, setPinned } from '../state.js';
import { EnvelopeCholesky, SparseCholesky, nestedDissection, orderedGraph, reverseCuthillMcKee } from './sparse.js';
import { grid } from './test-graphs.js';
import { elongation, freeFallError, hangingRatio, hangingSheet, kernelsApart, type SheetFabric } from './test-sheets.js';

describe('the envelope Cholesky solver in reverse Cuthill–McKee order', () => {
  const envelopeOf = (first: Int32Array) => first.reduce((sum, f, i) => sum + i - f + 1, 0);

  it('orders a shuffled grid into a narrow band (a permutation), and solves M/h² + Σk·SᵀS to round-off', () => {
    const m = 20;
    const { n, edges, rowStart, cols } = grid(m, 7);
    const order = reverseCuthillMcKee(rowStart, cols);
    expect([...order].sort((a, b) => a - b)).toEqual([...Array(n).keys()]);
    const row = new Int32Array(n);
    order.forEach((v, r) => { row[v] = r; });
    const firstFor = (rank: (v: number) => number) => {
      const first = new Int32Array(n).map((_, r) => r);
      for (const [a, b] of edges) { const ra = rank(a), rb = rank(b); first[Math.max(ra, rb)] = Math.min(first[Math.max(ra, rb)], Math.min(ra, rb)); }
      return first;
    };
    const first = firstFor((v) => row[v]);
    // an m × m grid with one diagonal has a band of m + 1 at best; the shuffled numbering's is near n
    expect(envelopeOf(first) / n).toBeLessThan(1.6 * (m + 1));
    expect(envelopeOf(firstFor((v) => v)) / n).toBeGreaterThan(5 * (m + 1));
    const chol = new EnvelopeCholesky(first);
    const diag = 0.3, k = 1000;
    for (let v = 0; v < n; v++) chol.add(row[v], row[v], diag);
    for (const [a, b] of edges) { chol.add(row[a], row[a], k); chol.add(row[b], row[b], k); chol.add(row[a], row[b], -k); }
    chol.factor();
    const x = Float64Array.from({ length: 3 * n }, (_, j) => Math.sin(j));
    // b = A·x by rows, solved back
    const b = new Float64Array(3 * n);
    const apply = (src: Float64Array, dst: Float64Array) => {
      for (let v = 0; v < n; v++) for (let c = 0; c < 3; c++) dst[3 * row[v] + c] += diag * src[3 * row[v] + c];
      for (const [a, b2] of edges) for (let c = 0; c < 3; c++) {
        const d = src[3 * row[a] + c] - src[3 * row[b2] + c];
        dst[3 * row[a] + c] += k * d; dst[3 * row[b2] + c] -= k * d;
      }
    };
    apply(x, b);
    chol.solve3(b);
    for (let j = 0; j < 3 * n; j++) expect(Math.abs(b[j] - x[j])).toBeLessThan(1e-8);
    const one = Float64Array.from({ length: n }, (_, r) => x[3 * r]), rhs = new Float64Array(3 * n);
    apply(x, rhs);
    const single = Float64Array.from({ length: n }, (_, r) => rhs[3 * r]);
    chol.solve(single);
    for (let r = 0; r < n; r++) expect(Math.abs(single[r] - one[r])).toBeLessThan(1e-8);
  });

  it('refuses a matrix that is not positive definite, naming the row', () => {
    const chol = new EnvelopeCholesky(Int32Array.from([0, 0]));
    chol.add(0, 0, 1); chol.add(1, 1, 1); chol.add(1, 0, 2);
    expect(() => chol.factor()).toThrow(/not positive definite \(row 1\)/);
    expect(() => new EnvelopeCholesky(Int32Array.from([0, 2]))).toThrow(/first\[1\] = 2/);
  });
});

describe('the sparse Cholesky solver in nested dissection order (what the global stretch step uses)', () => {
  /** the graph of `g` in the order `order` (order[k]: the vertex placed k-th), and each vertex's row */
  function ordered(g: { rowStart: Int32Array; cols: Int32Array }, order: Int32Array) {
    const { row, rowStart: start, cols: list } = orderedGraph(g.rowStart, g.cols, order);
    return { row, start, list };
  }
  /** D + Σ k·SᵀS over `edges` (D: 0.3 on the diagonal, k = 1000) into the solver, by row */
  function assemble(chol: { add(i: number, j: number, v: number): void; clear(): void }, n: number, edges: [number, number][], row: Int32Array) {
    chol.clear();
    for (let v = 0; v < n; v++) chol.add(row[v], row[v], 0.3);
    for (const [a, b] of edges) { chol.add(row[a], row[a], 1000); chol.add(row[b], row[b], 1000); chol.add(row[a], row[b], -1000); }
  }
  /** A·x by rows for that matrix */
  function apply(n: number, edges: [number, number][], row: Int32Array, x: Float64Array, width: number): Float64Array {
    const b = new Float64Array(width * n);
    for (let v = 0; v < n; v++) for (let c = 0; c < width; c++) b[width * row[v] + c] += 0.3 * x[width * row[v] + c];
    for (const [a, e] of edges) for (let c = 0; c < width; c++) {
      const d = x[width * row[a] + c] - x[width * row[e] + c];
      b[width * row[a] + c] += 1000 * d; b[width * row[e] + c] -= 1000 * d;
    }
    return b;
  }

  it('orders a shuffled grid (a permutation) with less fill than the envelope (0.59 of it at 64²), and solves to round-off', () => {
    const m = 64, g = grid(m, 11);
    const order = nestedDissection(g.rowStart, g.cols);
    expect([...order].sort((a, b) => a - b)).toEqual([...Array(g.n).keys()]);
    const { row, start, list } = ordered(g, order);
    const chol = new SparseCholesky(start, list);
    // the same matrix's envelope in reverse Cuthill–McKee order, which the global step used before
    const rcm = ordered(g, reverseCuthillMcKee(g.rowStart, g.cols)).row;
    const first = new Int32Array(g.n).map((_, r) => r);
    for (const [a, b] of g.edges) { const hi = Math.max(rcm[a], rcm[b]); first[hi] = Math.min(first[hi], Math.min(rcm[a], rcm[b])); }
    const envelope = first.reduce((sum, f, i) => sum + i - f + 1, 0);
    expect(chol.entries / envelope).toBeLessThan(0.65);
    // in the shuffled numbering itself, the fill is most of the dense triangle
    const natural = new SparseCholesky(g.rowStart, g.cols);
    expect(natural.entries / chol.entries).toBeGreaterThan(10);
    assemble(chol, g.n, g.edges, row);
    chol.factor();
    const x = Float64Array.from({ length: 3 * g.n }, (_, j) => Math.sin(j));
    const b = apply(g.n, g.edges, row, x, 3);
    chol.solve3(b);
    for (let j = 0; j < 3 * g.n; j++) expect(Math.abs(b[j] - x[j])).toBeLessThan(1e-8);
    const one = Float64Array.from({ length: g.n }, (_, r) => Math.cos(r));
    const single = apply(g.n, g.edges, row, one, 1);
    chol.solve(single);
    for (let r = 0; r < g.n; r++) expect(Math.abs(single[r] - one[r])).toBeLessThan(1e-8);
  });

  it('takes a graph in pieces, with an edge listed twice, and a matrix assembled again', () => {
    const a = grid(9, 3), b = grid(5, 4);
    // the two grids side by side (b's vertices after a's), and a's first edge twice
    const n = a.n + b.n;
    const edges: [number, number][] = [...a.edges, a.edges[0], ...b.edges.map(([u, v]) => [u + a.n, v + a.n] as [number, number])];
    const lists = Array.from({ length: n }, () => [] as number[]);
    for (const [u, v] of edges) { lists[u].push(v); lists[v].push(u); }
    const rowStart = new Int32Array(n + 1);
    for (let i = 0; i < n; i++) rowStart[i + 1] = rowStart[i] + lists[i].length;
    const g = { n, rowStart, cols: Int32Array.from(lists.flat()) };
    const { row, start, list } = ordered(g, nestedDissection(g.rowStart, g.cols));
    const chol = new SparseCholesky(start, list);
    for (let round = 0; round < 2; round++) {
      assemble(chol, n, edges, row);
      chol.factor();
      const x = Float64Array.from({ length: 3 * n }, (_, j) => Math.sin(j + round));
      const rhs = apply(n, edges, row, x, 3);
      chol.solve3(rhs);
      for (let j = 0; j < 3 * n; j++) expect(Math.abs(rhs[j] - x[j])).toBeLessThan(1e-8);
    }
  });

  it('refuses a matrix that is not positive definite, an entry outside the graph and a graph that lists no row', () => {
    const chol = new SparseCholesky(Int32Array.from([0, 1, 2, 2]), Int32Array.from([1, 0]));
    chol.add(0, 0, 1); chol.add(1, 1, 1); chol.add(2, 2, 1); chol.add(1, 0, 2);
    expect(() => chol.factor()).toThrow(/^SparseCholesky: the matrix is not positive definite \(row 1\)$/);
    expect(() => chol.add(2, 0, 1)).toThrow(/^SparseCholesky\.add: \(2, 0\) is not in the matrix's graph$/);
    expect(() => new SparseCholesky(Int32Array.from([0, 1, 1]), Int32Array.from([5]))).toThrow(/^SparseCholesky: row 0 lists 5, not another row in 0…1$/);
  });
});

/** A 1 m sheet hanging from its top row, the springs solved together. */
const hanging = (fabric: SheetFabric, faces: number): Scene => hangingSheet(fabric, faces, { stretch: 'global' });

describe.each<CpuKernel>(['ts', 'wasm'])('solver.stretch "global" (xpbd), %s kernel', (kernel) => {
  it.each([16, 32])('a rubber sheet hanging from its top edge at %i faces a side, default substeps: its length grows by ρ_A·g·L²/(2k), within 5 percent (the issue asks 25)', (faces) => {
    // XPBD's sweep at the same settings: 1.06× at 16², 1.99× at 32², 5.9× at 64², 8.2× at 128² (docs/physics.md)
    const rubber = { arealDensity: 0.38, structuralStiffness: 600, shearStiffness: 200 };
    const { ratio, kinetic } = hangingRatio(hanging(rubber, faces), kernel);
    // measured 0.97 at 16², 0.99 at 32² (the pinned top row cannot contract sideways, which stiffens the top a little)
    expect(ratio).toBeGreaterThan(0.95);
    expect(ratio).toBeLessThan(1.05);
    expect(kinetic).toBeLessThan(1e-6);
  });

  it('a cotton sheet hanging from its top edge: elongation as its stiffness says (within 5 %), strain far below 0.5 %', () => {
    const cotton = { arealDensity: 0.12, structuralStiffness: 8600, shearStiffness: 56 };
    const sim = new Simulation(hanging(cotton, 32), { kernel });
    sim.advance(180);
    const theory = (0.12 * 9.81) / (2 * 8600);
    expect(Math.abs(elongation(sim, 32) / theory - 1)).toBeLessThan(0.05);
    expect(sim.report().maxStrain).toBeLessThan(0.005);
  });

  it('free fall is exact: the step leaves a cloth whose springs are at rest where the prediction put it', () => {
    expect(freeFallError({ stretch: 'global' }, kernel)).toBeLessThan(1e-5);
  });

  it('pinned particles stay; a pin set mid-run holds from the next frame, and lets go when unset (the system is refactored)', () => {
    const sim = new Simulation(validateScene({ cloth: { resolution: 8, position: [0, 1, 0] }, colliders: [], pins: ['top-left', 'top-right'], solver: { stretch: 'global' } }), { kernel });
    const at = (i: number) => [...sim.state.positions.subarray(3 * i, 3 * i + 3)];
    const corner = 0, pinnedBefore = [...sim.state.pinned.keys()].filter((i) => sim.state.pinned[i]);
    const held = pinnedBefore.map(at);
    sim.advance(30);
    pinnedBefore.forEach((i, k) => expect(at(i)).toEqual(held[k]));
    const middle = 40;
    setPinned(sim.state, middle, true);
    const there = at(middle);
    sim.advance(20);
    expect(at(middle)).toEqual(there);
    setPinned(sim.state, middle, false);
    sim.advance(20);
    expect(Math.hypot(at(middle)[0] - there[0], at(middle)[1] - there[1], at(middle)[2] - there[2])).toBeGreaterThan(1e-3);
    expect(sim.state.pinned[corner]).toBe(pinnedBefore.includes(corner) ? 1 : 0);
  });

  it('a grabbed particle is where the grab puts it (held exactly in the solve), and the cloth keeps its momentum when released', () => {
    const sim = new Simulation(validateScene({ cloth: { resolution: 8 }, gravity: [0, 0, 0], colliders: [], solver: { stretch: 'global' } }), { kernel });
    const p = 40;
    const target = [...sim.state.positions.subarray(3 * p, 3 * p + 3)] as [number, number, number];
    for (let f = 0; f < 10; f++) {
      target[1] += 0.02;
      grab(sim.state, p, target);
      sim.advance(1);
      [0, 1, 2].forEach((k) => expect(sim.state.positions[3 * p + k]).toBeCloseTo(target[k], 5));
    }
    expect(sim.state.velocities[3 * p + 1]).toBeCloseTo(0.02 / FRAME_DT, 1);
    release(sim.state);
    const y0 = sim.report().centroid[1];
    sim.advance(10);
    expect(sim.report().centroid[1] - y0).toBeGreaterThan(0.05);
  });

  it('a hammock pinned at four corners, no contact: total energy falls, and rises in no frame by more than 1 % (the sweep: 17 %)', () => {
    const s = builtinScene('pins');
    s.cloth.resolution = 16;
    s.colliders = [];
    s.solver.stretch = 'global';
    const sim = new Simulation(s, { kernel });
    const total = () => { const e = sim.report().energy; return e.kinetic + e.gravitational + e.elastic; };
    const e0 = total();
    let prev = e0, rise = 0;
    for (let f = 0; f < 180; f++) {
      sim.advance(1);
      const e = total();
      rise = Math.max(rise, e - prev);
      prev = e;
    }
    // one local/global pass per substep is not the converged implicit step, so a frame can gain a little: measured
    // 0.3 % of E0 (at 1 or 3 passes), against 17 % for XPBD's sweep in the same frames (docs/physics.md, "The
    // global stretch step")
    expect(rise).toBeLessThanOrEqual(0.01 * Math.abs(e0));
    expect(prev).toBeLessThan(e0 - 0.01 * Math.abs(e0));
    expect(sim.report().energy.kinetic).toBeLessThan(1e-3 * Math.abs(e0));
  });
});

it('both CPU kernels run the global step on the same cloth alike', () => {
  const scene = (() => { const s = builtinScene('wind'); s.cloth.resolution = 10; s.solver.stretch = 'global'; return s; })();
  expect(kernelsApart(scene, 30)).toBeLessThan(1e-4);
});
