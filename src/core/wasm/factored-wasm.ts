/**
 * The global steps' triangular solves in WebAssembly (factored.as.ts; SparseCholesky.solve3 in solvers/sparse.ts is
 * the reference): the WebAssembly kernel runs the globalStretch and globalBending phases with them. The factor's
 * size is known only once a step first factors (and differs between the two steps), while the kernel's memory is laid
 * out once and may not grow (the state's arrays are views of it), so the solves run over a memory of their own: the
 * kernel's module instantiated a second time, of which only solveFactored3 is called. The factor (L's columns, rows
 * and values) is copied in after each factorisation, the right-hand sides in and the solution out at each solve.
 * Solutions are the reference's bit for bit (the same operations in the same order).
 */
import type { FactorSolver, SparseCholesky } from '../solvers/sparse.js';

/** What the solves need of the kernel's exports. */
interface FactoredExports {
  solveFactored3(n: number, colStart: number, rows: number, values: number, b: number): void;
}

/** bytes of the memory left unused below the arrays (the module's own static data, if any, lies there) */
const BASE = 65536;

export class WasmFactorSolver implements FactorSolver {
  private readonly memory = new WebAssembly.Memory({ initial: 1 });
  private readonly exports: FactoredExports;
  /** the factor now in the memory (null: none yet), and its SparseCholesky.factors count when copied */
  private chol: SparseCholesky | null = null;
  private factors = -1;
  private colStart = 0;
  private rows = 0;
  private values = 0;
  private b = 0;
  private rhs = new Float64Array(0);

  /** `instantiate`: the kernel's single-thread module over a memory (xpbd-wasm.ts kernelImports). */
  constructor(instantiate: (memory: WebAssembly.Memory) => WebAssembly.Instance) {
    this.exports = instantiate(this.memory).exports as unknown as FactoredExports;
  }

  /** The memory's size [bytes]. */
  get bytes(): number {
    return this.memory.buffer.byteLength;
  }

  solve3(chol: SparseCholesky, b: Float64Array): void {
    if (chol !== this.chol || chol.factors !== this.factors) this.load(chol);
    this.rhs.set(b);
    this.exports.solveFactored3(chol.n, this.colStart, this.rows, this.values, this.b);
    b.set(this.rhs);
  }

  /** Copies the factor in (the memory grows to hold it; it never shrinks). */
  private load(chol: SparseCholesky): void {
    const n = chol.n, entries = chol.colStart[n];
    let at = BASE;
    const take = (bytes: number) => { const p = at; at += Math.ceil(bytes / 16) * 16; return p; };
    this.values = take(8 * entries);
    this.b = take(24 * n);
    this.colStart = take(4 * (n + 1));
    this.rows = take(4 * entries);
    const pages = Math.ceil(at / 65536) - this.memory.buffer.byteLength / 65536;
    if (pages > 0) this.memory.grow(pages);
    const buf = this.memory.buffer;
    new Float64Array(buf, this.values, entries).set(chol.values);
    new Int32Array(buf, this.colStart, n + 1).set(chol.colStart);
    new Int32Array(buf, this.rows, entries).set(chol.rows);
    this.rhs = new Float64Array(buf, this.b, 3 * n);
    this.chol = chol;
    this.factors = chol.factors;
  }
}
