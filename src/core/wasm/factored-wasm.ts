/**
 * The global steps' triangular solves in WebAssembly (factored.as.ts; SparseCholesky.solve3 in solvers/sparse.ts is
 * the reference): the WebAssembly kernel runs the globalStretch and globalBending phases with them. The factor's
 * size is known only once a step first factors (and differs between the two steps), while the kernel's memory is laid
 * out once and may not grow (the state's arrays are views of it), so the solves run over a memory of their own: the
 * kernel's module instantiated a second time, of which only solveFactored3 and productAdd3 are called. The factor (L's
 * columns, rows and values) and a product to add to the right-hand side (the bending step's damping, P·x_prev) are
 * copied in when they change, the right-hand sides and the product's vector in and the solution out at each solve.
 * Solutions are the reference's bit for bit (the same operations in the same order).
 */
import type { FactorSolver, SparseCholesky, SparseProduct } from '../solvers/sparse.js';

/** What the solves need of the kernel's exports. */
interface FactoredExports {
  solveFactored3(n: number, colStart: number, rows: number, values: number, b: number): void;
  productAdd3(n: number, diagonal: number, start: number, cols: number, values: number, row: number, v: number, b: number): void;
}

/** bytes of the memory left unused below the arrays (the module's own static data, if any, lies there) */
const BASE = 65536;

/** Where a factor's and a product's arrays lie in the memory (byte offsets). */
interface Layout {
  colStart: number; rows: number; values: number; b: number;
  /** the product's, when there is one */
  diagonal: number; start: number; cols: number; entries: number; row: number; v: number;
}

export class WasmFactorSolver implements FactorSolver {
  private readonly memory = new WebAssembly.Memory({ initial: 1 });
  private readonly exports: FactoredExports;
  /** the factor and the product the memory is laid out for (null: none yet / no product) */
  private chol: SparseCholesky | null = null;
  private product: SparseProduct | null = null;
  /** the factor's SparseCholesky.factors count and the product's version when their values were copied in */
  private factors = -1;
  private version = -1;
  private at: Layout | null = null;
  private rhs = new Float64Array(0);
  private vector = new Float64Array(0);

  /** `instantiate`: the kernel's single-thread module over a memory (xpbd-wasm.ts kernelImports). */
  constructor(instantiate: (memory: WebAssembly.Memory) => WebAssembly.Instance) {
    this.exports = instantiate(this.memory).exports as unknown as FactoredExports;
  }

  /** The memory's size [bytes]. */
  get bytes(): number {
    return this.memory.buffer.byteLength;
  }

  solve3(chol: SparseCholesky, b: Float64Array, product?: SparseProduct, v?: Float64Array): void {
    const pull = product && v ? product : null;
    if (chol !== this.chol || pull !== this.product) this.layout(chol, pull);
    const at = this.at!, buf = this.memory.buffer, n = chol.n;
    if (chol.factors !== this.factors) {
      new Float64Array(buf, at.values, chol.colStart[n]).set(chol.values);
      this.factors = chol.factors;
    }
    this.rhs.set(b);
    if (pull) {
      if (pull.version !== this.version) {
        new Float64Array(buf, at.diagonal, n).set(pull.diagonal);
        new Float64Array(buf, at.entries, pull.cols.length).set(pull.values);
        this.version = pull.version;
      }
      this.vector.set(v!);
      this.exports.productAdd3(n, at.diagonal, at.start, at.cols, at.entries, at.row, at.v, at.b);
    }
    this.exports.solveFactored3(n, at.colStart, at.rows, at.values, at.b);
    b.set(this.rhs);
  }

  /**
   * Lays the factor's arrays and the product's out (the memory grows to hold them; it never shrinks) and copies in
   * what does not change with a refactor: L's pattern and the product's structure; their values follow in solve3.
   */
  private layout(chol: SparseCholesky, product: SparseProduct | null): void {
    const n = chol.n, entries = chol.colStart[n], count = product ? product.cols.length : 0;
    let next = BASE;
    const take = (bytes: number) => { const p = next; next += Math.ceil(bytes / 16) * 16; return p; };
    const at: Layout = {
      values: take(8 * entries), b: take(24 * n), colStart: take(4 * (n + 1)), rows: take(4 * entries),
      diagonal: take(product ? 8 * n : 0), entries: take(8 * count), v: take(product ? 24 * n : 0),
      start: take(product ? 4 * (n + 1) : 0), cols: take(4 * count), row: take(product ? 4 * n : 0),
    };
    const pages = Math.ceil(next / 65536) - this.memory.buffer.byteLength / 65536;
    if (pages > 0) this.memory.grow(pages);
    const buf = this.memory.buffer;
    new Int32Array(buf, at.colStart, n + 1).set(chol.colStart);
    new Int32Array(buf, at.rows, entries).set(chol.rows);
    if (product) {
      new Int32Array(buf, at.start, n + 1).set(product.start);
      new Int32Array(buf, at.cols, count).set(product.cols);
      new Int32Array(buf, at.row, n).set(product.row);
    }
    this.rhs = new Float64Array(buf, at.b, 3 * n);
    this.vector = new Float64Array(buf, at.v, product ? 3 * n : 0);
    this.at = at;
    this.chol = chol;
    this.product = product;
    this.factors = -1;
    this.version = -1;
  }
}
