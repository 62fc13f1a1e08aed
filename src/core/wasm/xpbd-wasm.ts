/**
 * The XPBD solver's substep in WebAssembly (SIMD, optionally threads): a ClothState whose arrays live in the
 * kernel's memory, so the TypeScript reference (reference.ts) and the kernel work on the same arrays with no copy.
 * The kernel is a backend of the frame loop (frame.ts): it declares the phases of the schedule it implements
 * (KERNEL_PHASES: the wind, integration, the grab, the distance constraints, the bending stencils, tethers, stretch limiting, self-contact — its
 * candidate search and passes, self-contact-wasm.ts — the global stretch and bending steps — their triangular solves,
 * factored-wasm.ts — and particle and triangle contact against every analytic collider, moving or not) and runs
 * each substep's run of them in one call (more, around self-contact and the global steps, which the host drives);
 * the phases it lacks or refuses (the start and end of a frame, carried pins, a mesh collider's contact) run in
 * TypeScript in their place in the schedule.
 *
 * Threads: with `threads` > 1 (at most 16) the memory is shared and the caller's front end starts `threads − 1` helpers
 * (a Web Worker or a Node worker thread each) with helperInit(); until every helper has checked in, substeps run
 * on the calling thread alone, so a slow start never blocks. Then each frame runs with the helpers or alone,
 * whichever its measured frame times say is faster (thread-mode.ts: on a busy machine, alone can be). The cloth is
 * the same bit for bit either way.
 */
import { runFrame, type FrameVars, type PhaseBackend } from '../frame.js';
import type { ClothModel } from '../model.js';
import { perClothRefusal, type SimParams } from '../params.js';
import { airFactor, needsTriangleContact } from '../phases.js';
import { PHASE, phasePasses, type BackendPhases, type PhaseId, type PhaseLog } from '../schedule.js';
import { SceneError } from '../scene.js';
import { collideSelf } from '../self-contact.js';
import { solveGlobalBending } from '../solvers/global-bending.js';
import { solveGlobalStretch } from '../solvers/global-stretch.js';
import { createState, type ClothState } from '../state.js';
import {
  CTRL, CTRL_BYTES, KERNEL_FLAG_ACCUMULATE, KERNEL_FLAG_FORCES, KERNEL_FLAG_STORE_LAMBDA, KERNEL_FLAG_TRACE,
  KERNEL_MAX_ITERATIONS, KERNEL_MAX_THREADS, MAX_COLLIDERS, COLLIDER_RECORD_FLOATS, COLLIDER_BOX, COLLIDER_CAPSULE,
  COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_PLANE, COLLIDER_SPHERE,
} from '../layout.generated.js';
import { WasmCoarseStretch } from './coarse-wasm.js';
import { WasmFactorSolver } from './factored-wasm.js';
import { KernelSelfContact, layoutSelfContact, type ListedPairs, type SelfContactExports } from './self-contact-wasm.js';
import { shownValue } from '../text.js';
import { ThreadModeChooser } from './thread-mode.js';
import { windVelocity } from '../wind.js';
import { XPBD_WASM_SINGLE, XPBD_WASM_THREADS } from './xpbd-kernel.generated.js';

/** The collider types the kernel's localDistance knows (contact.as.ts): every analytic shape, not a mesh. */
const KERNEL_TYPES: readonly number[] = [COLLIDER_SPHERE, COLLIDER_FLOOR, COLLIDER_PLANE, COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER];

/**
 * Why the kernel cannot do particle contact against these colliders, or null: it knows every analytic shape
 * (PosedCollider.typeId, the COLLIDER_* ids), moving or not, up to MAX_COLLIDERS of them; a mesh's contact runs in
 * TypeScript. The same holds for triangle contact, the next phase, contactTriangles (triangle-contact.as.ts: every
 * analytic shape's, on one thread).
 */
function contactRefusal(params: SimParams): string | null {
  const shapes = params.colliders;
  if (shapes.length > MAX_COLLIDERS) return 'more colliders than the control block holds';
  for (let k = 0; k < shapes.length; k++) {
    if (!KERNEL_TYPES.includes(shapes[k].typeId)) return `collider type '${shapes[k].type}' has no kernel code`;
  }
  return null;
}

/**
 * The phases of the schedule the kernel implements (XPBD's substep but its wind, a per-triangle scatter; the bending
 * stencils as well, bit for bit as the reference: bending.as.ts; self-contact's candidate search and narrow phase, with the TypeScript search as the fallback where
 * a window overflows: self-contact-wasm.ts; the global steps, the reference's assembly around the kernel's
 * triangular solves, bit for bit as the reference: factored-wasm.ts; the springs' coarse correction, bit for bit as
 * the reference: coarse-wasm.ts).
 */
export const KERNEL_PHASES: BackendPhases = {
  name: 'WebAssembly kernel',
  where: 'in the WebAssembly kernel',
  sharesMemory: true,
  solvers: ['xpbd'],
  phases: (1 << PHASE.wind) | (1 << PHASE.integrate) | (1 << PHASE.grab) | (1 << PHASE.globalStretch) | (1 << PHASE.coarseStretch) | (1 << PHASE.distance) | (1 << PHASE.bending) |
    (1 << PHASE.globalBending) | (1 << PHASE.tethers) | (1 << PHASE.stretchLimit) | (1 << PHASE.selfContact) | (1 << PHASE.contact) |
    (1 << PHASE.contactTriangles),
  // the kernel reads one thickness, friction, damping and stretch limit: cloths that differ in one leave the phases
  // that read it to the reference (self-contact reads each particle's cloth: it takes any)
  refusal: (id: PhaseId, model: ClothModel, params: SimParams) =>
    (id === PHASE.contact || id === PHASE.contactTriangles ? contactRefusal(params) : null) ??
    perClothRefusal(id, params),
};

/**
 * The kernel's phases the host drives on the calling thread between two substep() calls: self-contact, the global
 * steps (their assembly in TypeScript, their triangular solves in the kernel's code) and the springs' coarse
 * correction (in the kernel's code over a memory of its own).
 */
const HOSTED = (1 << PHASE.selfContact) | (1 << PHASE.globalStretch) | (1 << PHASE.globalBending) | (1 << PHASE.coarseStretch);

/** polls of a word before a kernel thread that waits sleeps (a phase usually opens sooner) */
const SPIN_LIMIT = 1 << 15;

interface KernelExports extends SelfContactExports {
  configure(...layout: number[]): void;
  substep(): void;
  helperLoop(thread: number): void;
  stopHelpers(): void;
}

/** What a helper thread needs to join a kernel: the compiled module, the shared memory, the layout, its index. */
export interface KernelHelperInit {
  module: WebAssembly.Module;
  memory: WebAssembly.Memory;
  layout: number[];
  thread: number;
}

/**
 * Starts one helper thread (front-end specific: Node worker_threads, Web Workers) and returns how to stop it;
 * calls `onError` if the thread fails (then whenHelpersReady() rejects with that error). `cores` says how many
 * threads the machine can run at once: a kernel never gets more threads than that.
 */
export interface HelperSpawner {
  (init: KernelHelperInit, onError: (error: Error) => void): { terminate(): void };
  /** logical cores available to the kernel's threads, the caller's included [-] */
  readonly cores: number;
}

const modules: { single?: WebAssembly.Module | null; threads?: WebAssembly.Module | null } = {};

function decode(base64: string): Uint8Array {
  const bin = atob(base64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes;
}

/** The compiled kernel, or null where WebAssembly SIMD (or, for threads, shared memory) is not available. */
function kernelModule(threads: boolean): WebAssembly.Module | null {
  const key = threads ? 'threads' : 'single';
  if (modules[key] === undefined) {
    try {
      if (typeof WebAssembly !== 'object') throw new Error('no WebAssembly');
      if (threads) new WebAssembly.Memory({ initial: 1, maximum: 1, shared: true });
      modules[key] = new WebAssembly.Module(decode(threads ? XPBD_WASM_THREADS : XPBD_WASM_SINGLE) as BufferSource);
    } catch {
      modules[key] = null;
    }
  }
  return modules[key]!;
}

/** Whether this runtime can run the WebAssembly kernel (with `threads`: over a shared memory). */
export function wasmKernelAvailable(threads = false): boolean {
  return kernelModule(threads) !== null;
}

/** The most 64 KiB pages one WebAssembly memory can have (4 GiB: wasm32's address space). */
const MAX_PAGES = 65536;

/** A cloth whose kernel memory would be more than one WebAssembly memory can hold (MAX_PAGES). */
class KernelMemoryError extends SceneError {
  constructor(particles: number, bytes: number, readonly withSelfContact: boolean) {
    super(`the WebAssembly kernel would need ${(bytes / 2 ** 30).toFixed(1)} GiB of memory for ${particles} particles${withSelfContact ? ' with self-contact' : ''}, ` +
      'more than the 4 GiB a WebAssembly memory holds: a smaller cloth, or the TypeScript kernel');
  }
}

/**
 * What the kernel imports: its memory, and for threads the host's wait and notify on a word of it (Atomics: a
 * thread that must wait sleeps instead of spinning). Where a thread may not block (a browser's main thread),
 * wait returns at once and the kernel polls again.
 */
export function kernelImports(memory: WebAssembly.Memory): WebAssembly.Imports {
  // only a shared memory has waiters; pages that are not cross-origin isolated have no SharedArrayBuffer at all
  const words = typeof SharedArrayBuffer !== 'undefined' && memory.buffer instanceof SharedArrayBuffer ? new Int32Array(memory.buffer) : null;
  return {
    env: {
      memory,
      abort: () => { throw new Error('xpbd kernel abort'); },
      wait: (address: number, expected: number, timeoutMs: number) => {
        try { Atomics.wait(words!, address >>> 2, expected, timeoutMs); } catch { /* this thread may not block */ }
      },
      notify: (address: number) => { Atomics.notify(words!, address >>> 2); },
    },
  };
}

/** Instantiates the kernel module over `memory` and configures it with `layout`. */
function instantiateKernel(module: WebAssembly.Module, memory: WebAssembly.Memory, layout: number[]): KernelExports {
  const instance = new WebAssembly.Instance(module, kernelImports(memory));
  const exports = instance.exports as unknown as KernelExports;
  exports.configure(...layout);
  return exports;
}

/** The kernel over one model's arrays: its memory, helper threads and the backend of the frame loop. */
export class XpbdKernel implements PhaseBackend {
  /** the phases it implements */
  readonly phases = KERNEL_PHASES;
  /** threads that share each substep (1: this thread only) */
  readonly threads: number;
  private readonly module: WebAssembly.Module;
  private readonly memory: WebAssembly.Memory;
  private readonly layout: number[];
  private readonly exports: KernelExports;
  private readonly ctrlI32: Int32Array;
  private readonly ctrlF64: Float64Array;
  private readonly alpha: Float32Array;
  private readonly stencilAlpha: Float32Array;
  /** each particle's inverse mass when free (params.particleInvMass: the wind's cap) */
  private readonly baseInvMass: Float32Array;
  /** the wind's velocity of a substep [m/s] (windVelocity's scratch) */
  private readonly wind = new Float64Array(3);
  /** self-contact's memory and passes in the kernel; null for a kernel made without (its phase then runs in the reference) */
  private readonly selfContact: KernelSelfContact | null;
  /** the global steps' triangular solves (made when a step first runs), one each: each keeps its factor in its memory */
  private stretchSolver: WasmFactorSolver | undefined;
  private bendingSolver: WasmFactorSolver | undefined;
  /** the springs' coarse correction (solver.stretch 'two-level'), over a memory of its own (coarse-wasm.ts) */
  private coarse: WasmCoarseStretch | undefined;
  private readonly helpers: { terminate(): void }[] = [];
  private paramsSeen: SimParams | undefined;
  /** with helpers: whether a frame runs with them (thread-mode.ts) */
  readonly mode = new ThreadModeChooser();
  private helpersJoined = false;
  private helperError: Error | undefined;
  private disposed = false;

  private constructor(model: ClothModel, threads: number, module: WebAssembly.Module, withSelfContact: boolean, selfWindow?: number) {
    this.threads = threads;
    this.module = module;
    const n = model.particleCount, m = model.restLengths.length, nb = model.batches.length;
    let at = CTRL_BYTES;
    const take = (bytes: number) => { const p = at; at += Math.ceil(bytes / 16) * 16; return p; };
    const X = take(12 * n), XP = take(12 * n), XR = take(12 * n), XPR = take(12 * n), V = take(12 * n), W = take(4 * n), F = take(12 * n);
    const LAMBDA = take(4 * m), ANCHOR = take(4 * n), TLEN = take(4 * n);
    const SPRINGS = take(8 * m), REST = take(4 * m), ALPHA = take(4 * m), BATCHES = take(12 * nb);
    // both bending stencil models (params.bending chooses one, and may change between frames), their compliances and λ
    const { hinges, laplacian } = model.stencils, stencilMost = Math.max(hinges.areas.length, laplacian.areas.length);
    const stencilArrays = [hinges, laplacian].map((st) => ({
      st, offsets: take(4 * st.offsets.length), vertices: take(4 * st.vertices.length), weights: take(4 * st.weights.length),
      batches: take(8 * st.batches.length),
    }));
    const SALPHA = take(4 * stencilMost), SLAMBDA = take(12 * stencilMost);
    const nt = model.triangles.length / 3, TRIANGLES = take(12 * nt), BASE_W = take(4 * n);
    const self = withSelfContact ? layoutSelfContact(model, take, selfWindow) : null;
    const pages = Math.ceil(at / 65536);
    if (pages > MAX_PAGES) throw new KernelMemoryError(n, at, withSelfContact);
    this.memory = threads > 1
      ? new WebAssembly.Memory({ initial: pages, maximum: pages, shared: true })
      : new WebAssembly.Memory({ initial: pages });
    const buf = this.memory.buffer;
    this.layout = [X, XP, XR, XPR, W, F, LAMBDA, ANCHOR, TLEN, SPRINGS, REST, ALPHA, BATCHES, nb, n,
      ...stencilArrays.flatMap((a) => [a.offsets, a.vertices, a.weights, a.batches, a.st.batches.length]), SALPHA, SLAMBDA, TRIANGLES, nt, BASE_W];
    this.exports = instantiateKernel(module, this.memory, this.layout);
    this.ctrlI32 = new Int32Array(buf, 0, CTRL_BYTES / 4);
    this.ctrlF64 = new Float64Array(buf, 0, CTRL_BYTES / 8);
    new Uint32Array(buf, SPRINGS, 2 * m).set(model.springs);
    new Float32Array(buf, REST, m).set(model.restLengths);
    new Uint32Array(buf, TRIANGLES, 3 * nt).set(model.triangles);
    const batches = new Int32Array(buf, BATCHES, 3 * nb);
    model.batches.forEach((b, k) => { batches[3 * k] = b.start; batches[3 * k + 1] = b.end; batches[3 * k + 2] = b.kind; });
    this.alpha = new Float32Array(buf, ALPHA, m);
    for (const a of stencilArrays) {
      new Uint32Array(buf, a.offsets, a.st.offsets.length).set(a.st.offsets);
      new Uint32Array(buf, a.vertices, a.st.vertices.length).set(a.st.vertices);
      new Float32Array(buf, a.weights, a.st.weights.length).set(a.st.weights);
      const b = new Int32Array(buf, a.batches, 2 * a.st.batches.length);
      a.st.batches.forEach((r, k) => { b[2 * k] = r.start; b[2 * k + 1] = r.end; });
    }
    this.stencilAlpha = new Float32Array(buf, SALPHA, stencilMost);
    this.baseInvMass = new Float32Array(buf, BASE_W, n);
    this.selfContact = self ? new KernelSelfContact(model, buf, self, this.exports) : null;
    this.ctrlI32[CTRL.THREADS / 4] = 1;
    this.ctrlI32[CTRL.SPIN_LIMIT / 4] = SPIN_LIMIT;
    this.state = createState(model, {
      positions: new Float32Array(buf, X, 3 * n),
      previousPositions: new Float32Array(buf, XP, 3 * n),
      residuals: new Float32Array(buf, XR, 3 * n),
      previousResiduals: new Float32Array(buf, XPR, 3 * n),
      velocities: new Float32Array(buf, V, 3 * n),
      invMass: new Float32Array(buf, W, n),
      forces: new Float32Array(buf, F, 3 * n),
      lambdas: new Float32Array(buf, LAMBDA, m),
      tetherAnchors: new Int32Array(buf, ANCHOR, n),
      tetherLengths: new Float32Array(buf, TLEN, n),
      bendingLambdas: new Float32Array(buf, SLAMBDA, 3 * stencilMost),
    });
  }

  /** the state whose arrays live in this kernel's memory */
  readonly state: ClothState;

  /**
   * A kernel and its state for `model`, or null where the runtime has no WebAssembly SIMD (or, with threads > 1,
   * no shared memory: then the caller may ask again with 1 thread). `selfWindow` [pairs]: the size of
   * self-contact's pair windows (tests: a small one; by default they grow with the cloth, self-contact-wasm.ts).
   * `selfContact` false: no memory for self-contact's passes (about 4.0 kB a particle: a 256² cloth's kernel takes
   * 28.1 MB instead of 291 MB); the phase, if asked for, then runs in the TypeScript reference (the same cloth, bit
   * for bit). A cloth whose kernel with that memory would pass the 4 GiB one WebAssembly memory holds (about a million
   * particles) gets one without it; one too big even so is refused (a SceneError naming the TypeScript kernel).
   */
  static create(model: ClothModel, threads = 1, selfWindow?: number, selfContact = true): XpbdKernel | null {
    const t = Math.min(KERNEL_MAX_THREADS, Math.max(1, Math.floor(threads)));
    const module = kernelModule(t > 1);
    if (!module) return null;
    try {
      return new XpbdKernel(model, t, module, selfContact, selfWindow);
    } catch (e) {
      // too big for one WebAssembly memory with self-contact's: without it (the phase then runs in the reference)
      if (e instanceof KernelMemoryError && e.withSelfContact) return new XpbdKernel(model, t, module, false, selfWindow);
      throw e;
    }
  }

  /** whether self-contact's passes run in the kernel (it was made with their memory) */
  get hasSelfContact(): boolean {
    return this.selfContact !== null;
  }

  /** self-contact's candidate pairs as the last search left them, and who searched (null: none yet, or no self-contact) */
  selfCandidates(): ListedPairs | null {
    return this.selfContact?.listed() ?? null;
  }

  /** Self-contact's edge records: how many of the last edge pass's are not current, and how many it made (self-contact-wasm.ts edgeRecords); null without self-contact. */
  selfEdgeRecords(): { stale: number; made: number } | null {
    return this.selfContact?.edgeRecords() ?? null;
  }

  /** the kernel's memory [bytes] */
  get bytes(): number {
    return this.memory.buffer.byteLength;
  }

  /** Starts the helper threads with `spawn` (threads − 1 of them); substeps use them once all have checked in. */
  startHelpers(spawn: HelperSpawner): void {
    if (this.disposed) throw new Error('XpbdKernel.startHelpers: the kernel was disposed');
    const onError = (e: Error) => { this.helperError ??= e; };
    for (let t = this.helpers.length + 1; t < this.threads; t++) {
      const helper: unknown = spawn({ module: this.module, memory: this.memory, layout: this.layout, thread: t }, onError);
      if (typeof (helper as { terminate?: unknown } | null)?.terminate !== 'function') {
        this.dispose(); // stops the helpers started so far
        throw new TypeError(`the helper spawner (options.spawnHelper) must return { terminate() } for each thread it starts, got ${shownValue(helper)}`);
      }
      this.helpers.push(helper as { terminate(): void });
    }
  }

  /**
   * Resolves once every helper has joined (at once with one thread or after dispose); rejects if a helper failed
   * or after `timeoutMs`.
   */
  async whenHelpersReady(timeoutMs = 10000): Promise<void> {
    const t0 = Date.now();
    while (!this.joinHelpers() && !this.disposed) {
      if (this.helperError) throw new Error(`kernel helper thread failed: ${this.helperError.message}`);
      if (Date.now() - t0 > timeoutMs) throw new Error(`kernel helper threads did not start within ${timeoutMs} ms`);
      await new Promise((r) => setTimeout(r, 2));
    }
  }

  /**
   * Polls before a waiting thread sleeps (default 32 768). Tests set 0, so that every wait sleeps through the host's
   * Atomics.wait inside the substep, the path a busy machine takes.
   */
  set spinLimit(polls: number) {
    Atomics.store(this.ctrlI32, CTRL.SPIN_LIMIT / 4, Math.max(0, Math.floor(polls)));
  }

  /** threads working on the substeps now (helpers count once they have checked in) */
  get activeThreads(): number {
    return this.helpersJoined ? this.threads : 1;
  }

  private joinHelpers(): boolean {
    if (!this.helpersJoined && !this.disposed && !this.helperError && this.threads > 1 && this.helpers.length === this.threads - 1 &&
        Atomics.load(this.ctrlI32, CTRL.READY / 4) === this.threads - 1) {
      this.helpersJoined = true;
    }
    return this.helpersJoined || this.threads === 1;
  }

  /** Stops the helper threads; the state stays readable, and later frames run on this thread. */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    this.exports.stopHelpers();
    this.ctrlI32[CTRL.THREADS / 4] = 1;
    this.helpersJoined = false;
    for (const h of this.helpers) h.terminate();
    this.helpers.length = 0;
  }

  /** Per-frame scalars and (new params) the compliances. */
  private upload(state: ClothState, params: SimParams, h: number): void {
    if (params !== this.paramsSeen) {
      this.alpha.set(params.compliance);
      this.stencilAlpha.set(params.stencilCompliance);
      this.baseInvMass.set(params.particleInvMass);
      this.ctrlI32[CTRL.STENCILS / 4] = params.bending === 'hinges' ? 1 : params.bending === 'laplacian' ? 2 : 0;
      this.paramsSeen = params;
    }
    const f = this.ctrlF64, i = this.ctrlI32;
    f[CTRL.H / 8] = h;
    f[CTRL.GRAVITY / 8] = params.gravity[0];
    f[CTRL.GRAVITY / 8 + 1] = params.gravity[1];
    f[CTRL.GRAVITY / 8 + 2] = params.gravity[2];
    f[CTRL.STRETCH / 8] = params.stretchFactor;
    f[CTRL.DAMPING / 8] = params.damping;
    f[CTRL.THICKNESS / 8] = params.thickness;
    f[CTRL.FRICTION / 8] = params.friction;
    f[CTRL.STATIC_FRICTION / 8] = params.staticFriction;
    f[CTRL.DEPENETRATION / 8] = params.depenetrationSpeed;
    i[CTRL.GRABBED / 4] = state.grabbed;
    // the schema's iterations (≤ 20) fit the substep descriptor's field
    i[CTRL.ITERATIONS / 4] = Math.min(KERNEL_MAX_ITERATIONS, phasePasses(PHASE.distance, params));
  }

  /**
   * One frame of dt [s] in params.substeps substeps: the frame loop (frame.ts) with this kernel as its backend.
   * `log` (tests) receives the phases run, the kernel's as the kernel reports them.
   */
  frame(model: ClothModel, state: ClothState, params: SimParams, dt: number, log?: PhaseLog): void {
    // with helpers, each frame runs with them or alone, whichever the measured frame times say is faster
    this.joinHelpers();
    const timed = this.helpersJoined;
    const parallel = timed && this.mode.next();
    this.ctrlI32[CTRL.THREADS / 4] = parallel ? this.threads : 1;
    const t0 = timed ? performance.now() : 0;
    this.upload(state, params, dt / params.substeps);
    runFrame(model, state, params, dt, this, log);
    if (timed) this.mode.record((performance.now() - t0) / params.substeps);
  }

  /**
   * The kernel's phases of `mask` (of one substep: frame.sub, starting at state.time): each run of them between the
   * phases the host drives in one substep() call, and those on this thread in their place — self-contact
   * (self-contact-wasm.ts: its search and passes in the kernel, called from here), the global steps (the
   * reference's code with the kernel's triangular solves, factored-wasm.ts) and the coarse correction (coarse-wasm.ts);
   * it lists what it ran for `log`.
   */
  run(mask: number, model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars, log: PhaseLog | undefined): void {
    let rest = mask;
    while (rest !== 0) {
      const hosted = rest & HOSTED;
      if (hosted === 0) {
        this.substep(rest, model, state, params, frame, log);
        return;
      }
      const bit = hosted & -hosted;
      if ((rest & (bit - 1)) !== 0) this.substep(rest & (bit - 1), model, state, params, frame, log);
      this.hosted(bit, model, state, params, frame, log);
      rest &= ~(2 * bit - 1);
    }
  }

  /** One of the phases the host drives on this thread (HOSTED): `bit` is its mask bit. */
  private hosted(bit: number, model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars, log: PhaseLog | undefined): void {
    if (bit === 1 << PHASE.selfContact) {
      if (this.selfContact) this.selfContact.run(model, state, params, frame.h, frame.substeps - frame.sub);
      else collideSelf(model, state, params, frame.h, frame.substeps - frame.sub);
      log?.push(PHASE.selfContact, this.selfContact === null);
    } else if (bit === 1 << PHASE.coarseStretch) {
      this.coarse ??= new WasmCoarseStretch(this.instantiateSingle);
      this.coarse.run(model, state, params, frame.h, frame.sub === 0);
      log?.push(PHASE.coarseStretch, false);
    } else if (bit === 1 << PHASE.globalStretch) {
      this.stretchSolver ??= new WasmFactorSolver(this.instantiateSingle);
      solveGlobalStretch(model, state, params, frame.h, phasePasses(PHASE.globalStretch, params), this.stretchSolver);
      log?.push(PHASE.globalStretch, false);
    } else {
      this.bendingSolver ??= new WasmFactorSolver(this.instantiateSingle);
      solveGlobalBending(model, state, params, frame.h, this.bendingSolver);
      log?.push(PHASE.globalBending, false);
    }
  }

  /** The kernel's single-thread module over another memory (the global steps' solves, factored-wasm.ts). */
  private readonly instantiateSingle = (memory: WebAssembly.Memory) => new WebAssembly.Instance(kernelModule(false)!, kernelImports(memory));

  /**
   * The kernel's phases of `mask` (none of HOSTED) in one substep() call, with the colliders' records of this
   * substep when it has contact; it lists what it ran for `log`.
   */
  private substep(mask: number, model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars, log: PhaseLog | undefined): void {
    const f = this.ctrlF64, i = this.ctrlI32;
    // (the distance and bending phases make as many passes: solver.iterations; KERNEL_FLAG_ACCUMULATE is both's)
    // (with the coarse correction, solver.stretch 'two-level', the distance pass goes on from the λ it set)
    const coarse = params.stretch === 'two-level', accumulate = phasePasses(PHASE.distance, params) > 1 || coarse;
    // λ starts from zero in every substep where it accumulates across passes
    if (accumulate && !coarse && (mask & (1 << PHASE.distance)) !== 0) state.lambdas.fill(0);
    if (accumulate && (mask & (1 << PHASE.bending)) !== 0) state.bendingLambdas.fill(0);
    if ((mask & (1 << PHASE.wind)) !== 0) {
      // the air this substep (phases.ts accumulateWind's scalars); integrate then reads the forces
      windVelocity(params, state.time, this.wind);
      f[CTRL.WIND / 8] = this.wind[0];
      f[CTRL.WIND / 8 + 1] = this.wind[1];
      f[CTRL.WIND / 8 + 2] = this.wind[2];
      f[CTRL.AIR_K / 8] = airFactor(params);
      frame.forced = true;
    }
    // λ is kept only where it is read: across iterations, and after the frame (energy) from its last substep
    i[CTRL.FLAGS / 4] = (frame.forced ? KERNEL_FLAG_FORCES : 0) | (accumulate ? KERNEL_FLAG_ACCUMULATE | KERNEL_FLAG_STORE_LAMBDA : 0) |
      (frame.sub === frame.substeps - 1 ? KERNEL_FLAG_STORE_LAMBDA : 0) | (log ? KERNEL_FLAG_TRACE : 0);
    f[CTRL.TAYLOR / 8] = state.substeps === 0 ? 0.5 : 1;
    if ((mask & (1 << PHASE.grab)) !== 0) {
      const frac = (frame.sub + 1) / frame.substeps, t = frame.grabTo, from = frame.grabFrom;
      f[CTRL.GRAB_AT / 8] = from[0] + (t[0] - from[0]) * frac;
      f[CTRL.GRAB_AT / 8 + 1] = from[1] + (t[1] - from[1]) * frac;
      f[CTRL.GRAB_AT / 8 + 2] = from[2] + (t[2] - from[2]) * frac;
    }
    if ((mask & (1 << PHASE.contactTriangles)) !== 0) {
      // (phases.ts collideTriangles' reach and recovery)
      f[CTRL.TRIANGLE_REACH / 8] = params.thickness + 2 * model.maxTriangleEdge;
      f[CTRL.TRIANGLE_RECOVER / 8] = (params.depenetrationSpeed * frame.h) / Math.max(1, model.maxTriangleValence);
    }
    if ((mask & ((1 << PHASE.contact) | (1 << PHASE.contactTriangles))) !== 0) {
      // each collider where it is at the substep's end, and its surface motion over the substep
      const shapes = params.colliders;
      for (let k = 0; k < shapes.length; k++) {
        shapes[k].moveTo(state.time, state.time + frame.h);
        shapes[k].writeRecord(f, CTRL.COLLIDER_RECORDS / 8 + k * COLLIDER_RECORD_FLOATS, needsTriangleContact(model, shapes[k], params.thickness));
      }
      i[CTRL.COLLIDERS / 4] = shapes.length;
    }
    i[CTRL.SUBSTEP_PHASES / 4] = mask;
    this.exports.substep();
    if (log) for (let k = 0; k < i[CTRL.TRACE_COUNT / 4]; k++) log.push(i[CTRL.TRACE / 4 + k], false);
  }
}

