/**
 * The springs' coarse correction in WebAssembly (coarse.as.ts; solveCoarseStretch in solvers/coarse-stretch.ts is the
 * reference): the WebAssembly kernel runs the coarseStretch phase with it. Its arrays' sizes are the model's
 * aggregates' and band's, known once the reference has made them, while the kernel's memory is laid out once and may
 * not grow, so it runs over a memory of its own: the kernel's module instantiated a second time, of which only
 * coarseStretch is called. The model's arrays (its springs and aggregates) are copied in once per model, the
 * compliances when the params change; each substep copies the positions and inverse masses in and the positions and
 * multipliers out. The factor stays in that memory from the frame's first substep to the next. Positions and
 * multipliers are the reference's bit for bit (the same operations in the same order).
 */
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import { coarseSystem } from '../solvers/coarse-stretch.js';
import type { ClothState } from '../state.js';

/** What the correction needs of the kernel's exports. */
interface CoarseExports {
  coarseStretch(header: number, h: number, factor: boolean): void;
}

/** bytes of the memory left unused below the arrays (the module's own static data, if any, lies there) */
const BASE = 65536;
/** the header's words (coarse.as.ts, H_ constants) */
const HEADER_WORDS = 27;

export class WasmCoarseStretch {
  private readonly memory = new WebAssembly.Memory({ initial: 1 });
  private readonly exports: CoarseExports;
  /** the model the memory is laid out for, the params its compliances are, and the params and h of its factor */
  private model: ClothModel | null = null;
  private params: SimParams | null = null;
  private factoredFor: SimParams | null = null;
  private factoredAt = 0;
  private x = new Float32Array(0);
  private w = new Float32Array(0);
  private lambdas = new Float32Array(0);
  private compliance = new Float32Array(0);

  /** `instantiate`: the kernel's single-thread module over a memory (xpbd-wasm.ts kernelImports). */
  constructor(instantiate: (memory: WebAssembly.Memory) => WebAssembly.Instance) {
    this.exports = instantiate(this.memory).exports as unknown as CoarseExports;
  }

  /** solveCoarseStretch(model, state, params, h, refactor), in the kernel (see the file's comment). */
  run(model: ClothModel, state: ClothState, params: SimParams, h: number, refactor: boolean): void {
    if (model !== this.model) this.layout(model);
    if (params !== this.params) {
      this.compliance.set(params.compliance);
      this.params = params;
    }
    const factor = refactor || this.factoredFor !== params || this.factoredAt !== h;
    this.x.set(state.positions);
    this.w.set(state.invMass);
    this.exports.coarseStretch(BASE, h, factor);
    if (factor) {
      this.factoredFor = params;
      this.factoredAt = h;
    }
    state.positions.set(this.x);
    state.lambdas.set(this.lambdas);
  }

  /** Lays the model's arrays out (the memory grows to hold them; it never shrinks) and copies in what they hold. */
  private layout(model: ClothModel): void {
    const sys = coarseSystem(model), n = model.particleCount, ns = model.restLengths.length;
    const cloths = sys.blockStart.length - 1, count = sys.rhs.length, most = sys.touched.length;
    let next = BASE + 4 * HEADER_WORDS;
    const take = (bytes: number) => { next = Math.ceil(next / 16) * 16; const p = next; next += bytes; return p; };
    // in the order of the header's words (coarse.as.ts)
    const offsets = [
      take(12 * n), take(4 * n), take(4 * ns), take(8 * ns), take(4 * ns), take(4 * ns), take(4 * ns), take(16 * ns), take(16 * ns),
      take(4 * (n + 1)), take(8 * ns), take(24 * n), take(4 * (cloths + 1)), take(4 * cloths), take(4 * (cloths + 1)), take(4 * count),
      take(8 * sys.matrix.length), take(8 * count), take(24 * ns), take(4 * most), take(24 * most), take(8 * count), take(24 * n),
    ];
    const pages = Math.ceil(next / 65536) - this.memory.buffer.byteLength / 65536;
    if (pages > 0) this.memory.grow(pages);
    const buf = this.memory.buffer;
    new Int32Array(buf, BASE, HEADER_WORDS).set([n, ns, cloths, count, ...offsets]);
    const [x, w, lambdas, springs, rest, compliance, aggregate, nearId, nearWeight, start, incidence, , blockStart, band, matrixStart, blockOf] = offsets;
    this.x = new Float32Array(buf, x, 3 * n);
    this.w = new Float32Array(buf, w, n);
    this.lambdas = new Float32Array(buf, lambdas, ns);
    this.compliance = new Float32Array(buf, compliance, ns);
    new Int32Array(buf, springs, 2 * ns).set(model.springs);
    new Float32Array(buf, rest, ns).set(model.restLengths);
    new Int32Array(buf, aggregate, ns).set(sys.aggregate);
    new Int32Array(buf, nearId, 4 * ns).set(sys.nearId);
    new Float32Array(buf, nearWeight, 4 * ns).set(sys.nearWeight);
    new Int32Array(buf, start, n + 1).set(sys.start);
    new Int32Array(buf, incidence, 2 * ns).set(sys.incidence);
    new Int32Array(buf, blockStart, cloths + 1).set(sys.blockStart);
    new Int32Array(buf, band, cloths).set(sys.band);
    new Int32Array(buf, matrixStart, cloths + 1).set(sys.matrixStart);
    new Int32Array(buf, blockOf, count).set(sys.blockOf);
    this.model = model;
    this.params = null;
    this.factoredFor = null;
  }
}
