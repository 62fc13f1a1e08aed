/**
 * The WebGPU solver as a core Backend (core/backend.ts), so that a Simulation runs on it like on the CPU:
 * `sim.useBackend(await GpuBackend.create(device, sim.model))`. The state is a CPU mirror: frames are queued on the
 * GPU, `sync()` reads the cloth back, and a change made to the mirror is sent at once when `stateChanged()` says so
 * ('all': the whole cloth, e.g. a reset, so that views drawn from the GPU's buffers show it even while paused;
 * 'pins': only the pins, so an older mirror never brings back an older cloth). The grab is read from the mirror by
 * every frame.
 */
import { createState, type Backend, type ClothModel, type ClothState, type SimParams } from '../core/index.js';
import { GpuClothSolver, type GpuSolverOptions } from './solver.js';

export class GpuBackend implements Backend {
  readonly kind = 'gpu';
  readonly threads = 1;
  /** whether `state` holds the cloth as of the last frame (after sync(), until the next frame) */
  current = true;
  readonly state: ClothState;
  /** the solver, for what only the GPU has (timings, traffic, normals) */
  readonly solver: GpuClothSolver;
  /** the model the solver was made for: a backend steps no other */
  private readonly model: ClothModel;

  private constructor(solver: GpuClothSolver, model: ClothModel) {
    this.solver = solver;
    this.model = model;
    this.state = createState(model);
    solver.upload(this.state);
  }

  /** A GPU backend for `model` on `device` (kernels compiled once per device); rejects naming the GPU's error. */
  static async create(device: GPUDevice, model: ClothModel, options?: GpuSolverOptions): Promise<GpuBackend> {
    return new GpuBackend(await GpuClothSolver.create(device, model, options), model);
  }

  /**
   * Whether self-contact dropped pairs in some pass, over the syncs since the last upload
   * (GpuClothSolver.selfPairsOverflow), and how large the list is now, or that it can grow no more (the most the
   * device binds in one buffer: later passes may still find more than it holds).
   */
  get notes(): readonly string[] {
    const over = this.solver.selfPairsOverflow;
    if (!over) return [];
    const room = this.solver.selfPairCapacity;
    return [
      `GPU self-contact: a pass found ${over.found.toLocaleString('en')} candidate pairs, more than its list held ` +
      `(${over.held.toLocaleString('en')}); the ${(over.found - over.held).toLocaleString('en')} past it went unresolved in that substep, ` +
      'so the cloth may have passed through itself there — ' +
      (this.solver.selfPairsAtDeviceMost ? `the list holds ${room.toLocaleString('en')}, the most this device binds in one buffer` : `the list has grown to ${room.toLocaleString('en')} since`),
    ];
  }

  frame(model: ClothModel, params: SimParams, dt: number): void {
    if (model !== this.model) throw new Error('GPU solver: this backend was made for another model');
    this.solver.step(this.state, params, dt);
    this.current = false;
  }

  async sync(): Promise<void> {
    await this.solver.read(this.state);
    this.current = true;
  }

  stateChanged(what: 'pins' | 'all'): void {
    if (what === 'all') {
      this.solver.upload(this.state);
      this.current = true;
    } else {
      this.solver.uploadPins(this.state);
    }
  }

  whenReady(): Promise<void> {
    return Promise.resolve();
  }

  dispose(): void {
    this.solver.destroy();
  }
}
