/**
 * The WebGPU XPBD solver: the phase schedule (core/schedule.ts) of src/core/solvers/xpbd.ts, in the same order and
 * with the same parameters, as compute kernels over the same ClothModel. One frame (all its substeps) is one
 * command buffer and one submit; the CPU keeps the bookkeeping (`state.time`, `state.substeps`, tethers, gust wind)
 * so that the Taylor start and the gusts match the CPU solver exactly. This class ties the parts together, one job
 * each: the kernels compiled per device (kernels.ts), the cloth's storage buffers (buffers.ts), the uniform tables
 * (uniforms.ts), the frame encoder that maps phases to dispatches (encoder.ts), the readback (readback.ts) and the
 * cost accounting (traffic.ts).
 */
import type {} from 'webgpu'; // WebGPU types (@webgpu/types through the webgpu package); erased at runtime
import type { ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import { keepGrabOutside } from '../core/phases.js';
import { PHASE, assignPhases, framePhases, type PhaseLog } from '../core/schedule.js';
import type { ClothState } from '../core/state.js';
import { ClothBuffers } from './buffers.js';
import { ColliderTables } from './colliders.js';
import { FrameEncoder, GPU_PHASES } from './encoder.js';
import { kernelsFor, type Kernels } from './kernels.js';
import { Readback } from './readback.js';
import { SELF_PAIRS_PER_PRIMITIVE } from './layout.js';
import { dispatchesPerFrame, substepTraffic, type SubstepTraffic } from './traffic.js';
import { UniformTables } from './uniforms.js';

export type { SubstepTraffic };

/** How a GPU solver is made (GpuClothSolver.create). */
export interface GpuSolverOptions {
  /**
   * room in the self-contact candidates' list per triangle or edge (the larger count) [-]; default
   * SELF_PAIRS_PER_PRIMITIVE (8, 4× the most measured). Fewer is for tests of what an overflow reports.
   */
  selfPairsPerPrimitive?: number;
}

/**
 * How much larger than the most candidate pairs a pass found the self-contact list is made when they did not fit
 * [-] (GpuClothSolver.selfPairsOverflow): room for a landing that goes on piling up, without growing every frame.
 */
const GROWTH = 1.5;

/** One cloth on the GPU: create, setParams, upload, then step every frame and read when the CPU needs the cloth. */
export class GpuClothSolver {
  /** the device it runs on */
  readonly device: GPUDevice;
  /** the cloth it was made for */
  readonly model: ClothModel;
  private readonly buffers: ClothBuffers;
  private readonly uniforms: UniformTables;
  private readonly colliders: ColliderTables;
  private readonly encoder: FrameEncoder;
  private readonly readback: Readback;
  private params: SimParams | undefined;
  private destroyed = false;

  /**
   * Creates the buffers for `model` (the kernels are compiled once per device and reused: they do not depend on
   * the model); the cloth starts at its rest pose, unpinned.
   */
  static async create(device: GPUDevice, model: ClothModel, options: GpuSolverOptions = {}): Promise<GpuClothSolver> {
    const kernels = await kernelsFor(device);
    // the scopes are pushed and popped with nothing awaited in between: a device's error scopes are one stack, and
    // two solvers made at once (the app's side-by-side sweep) would otherwise take each other's errors
    device.pushErrorScope('validation');
    device.pushErrorScope('out-of-memory');
    let solver: GpuClothSolver | undefined;
    let failure: unknown;
    try {
      solver = new GpuClothSolver(device, model, kernels, options.selfPairsPerPrimitive ?? SELF_PAIRS_PER_PRIMITIVE);
    } catch (e) {
      failure = e;
    }
    const popped = [device.popErrorScope(), device.popErrorScope()];
    const [oom, invalid] = await Promise.all(popped);
    if (failure) throw failure;
    if (oom) { solver?.destroy(); throw new Error(`GPU solver: out of GPU memory for ${model.particleCount} particles: ${oom.message}`); }
    if (invalid) { solver?.destroy(); throw new Error(`GPU solver: ${invalid.message.split('\n')[0]}`); }
    return solver!;
  }

  private constructor(device: GPUDevice, model: ClothModel, kernels: Kernels, pairsPerPrimitive: number) {
    this.device = device;
    this.model = model;
    this.buffers = new ClothBuffers(device, model, kernels.storageLayouts, pairsPerPrimitive);
    this.uniforms = new UniformTables(device, model, kernels.uniformLayout, pairsPerPrimitive);
    this.colliders = new ColliderTables(device, this.buffers);
    this.encoder = new FrameEncoder(device, model, kernels.pipelines, this.buffers, this.uniforms, this.colliders);
    this.readback = new Readback(device, model, this.buffers);
  }

  /**
   * The self-contact candidate pairs one pass's list holds now: layout.ts selfGridSize's `pairs` (0 until params
   * with self-contact make the list), more once a pass found more (selfPairsOverflow).
   */
  get selfPairCapacity(): number {
    return this.buffers.selfPairCapacity;
  }

  /** whether the self-contact candidates' list is as large as this device binds in one buffer: it grows no more */
  get selfPairsAtDeviceMost(): boolean {
    return this.buffers.selfPairCapacity >= this.buffers.selfPairMost;
  }

  /**
   * The most self-contact candidate pairs one pass found, over the readbacks since the last upload: more than selfPairCapacity
   * means pairs went unresolved in that pass (counted, not kept), and cloth may have passed through itself there.
   */
  get selfPairsMost(): number {
    return this.readback.selfPairsMost;
  }

  /**
   * Since the last upload, the pass that found the most candidate pairs past what its list held: `found` pairs,
   * `held` in the list then (the `found − held` past it went unresolved in that substep); undefined when none
   * did. The readback that shows it grows the list to half as much again as was found (GROWTH; at most what the
   * device binds in one buffer), so that the passes of the frames encoded after it hold them.
   */
  get selfPairsOverflow(): { readonly found: number; readonly held: number } | undefined {
    return this.overflow;
  }
  private overflow: { found: number; held: number } | undefined;

  /** Position buffer (`array<vec4f>`, x y z 0 per particle [m], usage VERTEX | STORAGE) for renderers. */
  get positionBuffer(): GPUBuffer { return this.buffers.buffers.positions; }
  /** Vertex normals (`array<vec4f>`, unit, usage VERTEX | STORAGE), updated at the end of every step. */
  get normalBuffer(): GPUBuffer { return this.buffers.buffers.normals; }
  /** Velocities (`array<vec4f>` [m/s]). */
  get velocityBuffer(): GPUBuffer { return this.buffers.buffers.velocities; }
  /** Triangle indices (u32, usage INDEX | STORAGE), the model's `triangles`. */
  get indexBuffer(): GPUBuffer { return this.buffers.buffers.triangles; }
  /** Triangle colours used by triangle contact. */
  get triangleColourCount(): number { return this.model.triangleBatches.length; }

  /**
   * Takes new parameters (stiffness, damping, mass, gravity, wind, colliders, substeps, iterations, the bending
   * model...) without rebuilding anything but the uniform tables (and, on the first params with a stencil bending
   * model or a switch to the other, the stencils' buffers). `step` calls it by itself when handed a different params object; call it after changing a
   * params object in place. Throws for what the GPU does not implement (GPU_PHASES: the mass-spring solver, a
   * collider type its kernels do not know) or cannot hold (self-contact's buffers past what the device binds). Colliders may move (keyframes, or a drive the library sets on
   * params.colliders: read every frame) and carry pins.
   */
  setParams(params: SimParams): void {
    this.checkAlive();
    assignPhases(GPU_PHASES, this.model, params);
    // what this device cannot hold is refused before anything changes (the colliders' tables are set first below)
    this.buffers.checkParams(params);
    this.watched("the new parameters (self-contact's lists, the bending stencils, mesh colliders)", () => {
      // first: it may refuse mesh colliders too big for this device
      this.colliders.setParams(params);
      this.buffers.writeParams(params);
      this.uniforms.setParams(params);
    });
    this.params = params;
  }

  /**
   * Runs `make`, which may make buffers, inside error scopes pushed and popped around it with nothing awaited in
   * between (a device's scopes are one stack): a buffer the device could not make (out of memory, over a limit) is
   * known a moment later, and the next `step` or `read` throws saying so, instead of a cloth left standing still on
   * buffers that do not exist.
   */
  private watched(what: string, make: () => void): void {
    this.device.pushErrorScope('validation');
    this.device.pushErrorScope('out-of-memory');
    try {
      make();
    } finally {
      const popped = [this.device.popErrorScope(), this.device.popErrorScope()];
      void Promise.all(popped).then(([oom, invalid]) => {
        const e = oom ?? invalid;
        if (e && !this.failure) this.failure = `GPU solver: ${oom ? 'out of GPU memory' : 'the device refused a buffer or a write'} for ${what} (${this.model.particleCount} particles): ${e.message.split('\n')[0]}`;
      }, () => undefined);
    }
  }

  /** what a watched allocation could not make ('' while all could) */
  private failure = '';

  /**
   * Copies the cloth from a CPU state: positions, previous positions, velocities, pins and tethers (recomputed
   * first when `state.tethersStale`). The grab is read by every `step`.
   */
  upload(state: ClothState): void {
    this.checkAlive();
    this.buffers.writeParticles(state);
    this.buffers.writePins(state);
    this.refreshNormals();
    // a cloth put anew (a reset, a state copied in): a read on its way reads again, and what self-contact dropped
    // before is no longer the cloth's
    this.readback.uploaded();
    this.overflow = undefined;
  }

  /**
   * Where a readback showed a pass that found more candidate pairs than the list holds: kept in `overflow` where it
   * left more unresolved than any pass before, and a larger list (see selfPairsOverflow).
   */
  private growSelfPairs(): void {
    const found = this.readback.selfPairsMost, held = this.buffers.selfPairCapacity;
    if (!this.buffers.hasSelfContact || found <= held) return;
    if (!this.overflow || found - held > this.overflow.found - this.overflow.held) this.overflow = { found, held };
    this.watched('a longer self-contact list', () => {
      const room = this.buffers.growSelfPairs(Math.ceil(GROWTH * found));
      if (room > held) this.uniforms.setSelfPairCapacity(room);
    });
  }

  /** Copies only the pins (and tethers, recomputed first when `state.tethersStale`) from a CPU state. */
  uploadPins(state: ClothState): void {
    this.checkAlive();
    this.buffers.writePins(state);
  }

  /** Recomputes the vertex normals from the current positions (step does this itself; upload calls it). */
  refreshNormals(): void {
    this.checkAlive();
    this.encoder.refreshNormals();
  }

  /**
   * Advances the GPU cloth by dt [s] in params.substeps substeps: one command buffer, one submit, no readback.
   * Updates state.time and state.substeps (and the tethers when the pins changed: `state.tethersStale`) on the
   * CPU; the particle arrays of `state` are left alone until `read`. `timestampWrites` (benchmarks) times the
   * frame's compute pass on devices with 'timestamp-query'; `log` (tests) receives the phases encoded.
   */
  step(state: ClothState, params: SimParams, dt: number, timestampWrites?: GPUComputePassTimestampWrites, log?: PhaseLog): void {
    this.checkAlive();
    if (params !== this.params) this.setParams(params);
    // the grab target out of the colliders, as runFrame does for the CPU backends (the frame writes it to the uniforms)
    keepGrabOutside(state, params, state.time, state.time + dt);
    // the global steps' factors for this frame's pins and substep, before the frame is encoded (their tables may be
    // made anew; a buffer the device cannot make is said by the next step or read, as the params' are)
    const phases = framePhases(this.model, state, params);
    // (made once per model: watched only on the frame that makes them)
    if ((phases & (1 << PHASE.coarseStretch)) !== 0 && !this.encoder.coarse.layout) {
      this.watched("the coarse correction's tables", () => this.encoder.coarse.prepare());
    }
    if ((phases & (1 << PHASE.globalStretch)) !== 0) {
      this.watched("the global stretch step's factor", () => this.encoder.globalStretch.prepare(state, params, dt / params.substeps));
    }
    if ((phases & (1 << PHASE.globalBending)) !== 0) {
      this.watched("the global bending step's factor", () => this.encoder.globalBending.prepare(state, params, dt / params.substeps));
    }
    this.encoder.frame(state, params, dt, timestampWrites, log);
  }

  /**
   * Copies the GPU cloth back into `state`: positions, previous positions, velocities and the springs' λ of the
   * last substep (what `energy` reads). Resolves once the data is in `state` (and the self-contact list has grown
   * where a pass found more pairs than it holds: selfPairsOverflow). Calls are serialised.
   */
  read(state: ClothState): Promise<void> {
    this.checkAlive();
    return this.readback.read(state).then(() => {
      if (!this.destroyed) this.growSelfPairs();
    });
  }

  /** Bytes one substep's kernels move with the current params (see docs/gpu.md, "Benchmark"). */
  substepTraffic(): SubstepTraffic {
    if (!this.params) throw new Error('GPU solver: setParams first');
    return substepTraffic(
      this.model, this.params, this.uniforms.collidePasses, this.uniforms.selfRecords, this.buffers.hasTethers, this.encoder.globalBending.factorSize,
      this.encoder.globalStretch.factorSize, this.encoder.coarse.layout,
    );
  }

  /** Dispatches one frame encodes (for reports). */
  dispatchesPerFrame(params: SimParams): number {
    const u = this.uniforms;
    return dispatchesPerFrame(params, u.batchRecords, u.stencilRecords, u.collidePasses, u.selfRecords, this.buffers.hasTethers);
  }

  /** Frees every GPU buffer. The solver cannot be used afterwards. */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    this.buffers.destroy();
    this.uniforms.destroy();
    this.readback.destroy();
  }

  private checkAlive(): void {
    if (this.destroyed) throw new Error('GPU solver: used after destroy()');
    if (this.failure) throw new Error(this.failure);
  }
}
