/**
 * Where a cloth's frames run. One interface for every backend — the TypeScript reference, the WebAssembly SIMD
 * kernel (with threads) and, in src/gpu, WebGPU — so that the CLI, the app and the library drive them the same
 * way: a Simulation owns one, and the state it steps lives in the backend's memory (plain arrays, the kernel's
 * memory, or GPU buffers mirrored on the CPU).
 */
import type { ClothModel } from './model.js';
import type { SimParams } from './params.js';
import { step } from './solvers/index.js';
import { createState, type ClothState } from './state.js';
import { XpbdKernel } from './wasm/xpbd-wasm.js';
import type { HelperSpawner } from './wasm/xpbd-wasm.js';

/** What a backend is: 'ts' the TypeScript reference, 'wasm' the WebAssembly kernel, 'gpu' WebGPU. */
export type BackendKind = 'ts' | 'wasm' | 'gpu';

export interface Backend {
  readonly kind: BackendKind;
  /**
   * the cloth's state as the CPU sees it: pins, grab and resets are written here; on the GPU it is current after
   * sync(), and a change made to it is sent with the next frame once stateChanged() is called
   */
  readonly state: ClothState;
  /** threads sharing each substep now */
  readonly threads: number;
  /** whether `state` holds the cloth as of the last frame stepped (false on the GPU between a frame and sync()) */
  readonly current: boolean;
  /** Steps one frame of dt [s] with `params` (on the GPU: queued). */
  frame(model: ClothModel, params: SimParams, dt: number): void;
  /** Brings `state` up to date with the frames stepped (a no-op where the state is the backend's memory). */
  sync(): Promise<void>;
  /**
   * Says `state` was changed on the CPU: 'pins' (the pinned flags only: the cloth itself stays where the backend
   * has it) or 'all' (a reset, a state copied in: the next frame starts from `state` as it is).
   */
  stateChanged(what: 'pins' | 'all'): void;
  /** Resolves once the backend runs at full strength (a kernel's helper threads started). */
  whenReady(): Promise<void>;
  /** Releases threads and device memory; the state stays readable. */
  dispose(): void;
  /**
   * what the backend had to do differently from what the params ask, in words, over the syncs since the cloth was
   * last put anew (the GPU's self-contact list overflowing); none where absent. Simulation.notes adds them to the params' clamps.
   */
  readonly notes?: readonly string[];
}

/** The TypeScript reference: plain arrays, every phase in TypeScript (solvers/index.ts `step`). */
export class TsBackend implements Backend {
  readonly kind = 'ts';
  readonly threads = 1;
  readonly current = true;
  readonly state: ClothState;
  constructor(model: ClothModel) {
    this.state = createState(model);
  }
  frame(model: ClothModel, params: SimParams, dt: number): void {
    step(model, this.state, params, dt);
  }
  sync(): Promise<void> { return Promise.resolve(); }
  stateChanged(): void {}
  whenReady(): Promise<void> { return Promise.resolve(); }
  dispose(): void {}
}

/**
 * The WebAssembly SIMD kernel (wasm/xpbd-wasm.ts): the state lives in its memory; XPBD frames run the kernel's
 * phases there and the rest in TypeScript on the same arrays; a mass-spring frame runs in TypeScript on them.
 */
export class WasmBackend implements Backend {
  readonly kind = 'wasm';
  readonly current = true;
  /** the kernel, for its thread tuning (mode, spinLimit) */
  readonly kernel: XpbdKernel;
  private constructor(kernel: XpbdKernel) {
    this.kernel = kernel;
  }
  /**
   * A kernel backend for `model` on `threads` threads (helpers started with `spawn` when given and threads > 1),
   * or null where the runtime has no WebAssembly SIMD (or, with threads > 1, no shared memory). `selfContact`
   * false: a kernel without self-contact's memory (XpbdKernel.create), for a scene with it off.
   */
  static create(model: ClothModel, threads = 1, spawn?: HelperSpawner, selfContact = true): WasmBackend | null {
    const kernel = XpbdKernel.create(model, threads, undefined, selfContact);
    if (!kernel) return null;
    if (spawn && kernel.threads > 1) kernel.startHelpers(spawn);
    return new WasmBackend(kernel);
  }
  get state(): ClothState { return this.kernel.state; }
  get threads(): number { return this.kernel.activeThreads; }
  frame(model: ClothModel, params: SimParams, dt: number): void {
    if (params.solver === 'xpbd') this.kernel.frame(model, this.kernel.state, params, dt);
    else step(model, this.kernel.state, params, dt);
  }
  sync(): Promise<void> { return Promise.resolve(); }
  stateChanged(): void {}
  whenReady(): Promise<void> { return this.kernel.whenHelpersReady(); }
  dispose(): void { this.kernel.dispose(); }
}
