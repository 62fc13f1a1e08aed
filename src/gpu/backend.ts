/**
 * The WebGPU solver as a core Backend (core/backend.ts), so that a Simulation runs on it like on the CPU:
 * `sim.useBackend(await GpuBackend.create(device, sim.model))`. The state is a CPU mirror: frames are queued on the
 * GPU, `sync()` reads the cloth back, and a change made to the mirror (reset, pins, grab release, a state copied
 * in) is uploaded before the next frame once `stateChanged()` says so.
 */
import { createState, type Backend, type ClothModel, type ClothState, type SimParams } from '../core/index.js';
import { GpuClothSolver } from './solver.js';

export class GpuBackend implements Backend {
  readonly kind = 'gpu';
  readonly threads = 1;
  /** whether `state` holds the cloth as of the last frame (after sync(), until the next frame) */
  current = true;
  readonly state: ClothState;
  /** the solver, for what only the GPU has (timings, traffic, normals) */
  readonly solver: GpuClothSolver;
  /** what of `state` the GPU has not seen: 'all' (send the whole cloth), 'pins' (only the pins), or nothing */
  private unsent: 'all' | 'pins' | null = 'all';
  /** the model the solver was made for: a backend steps no other */
  private readonly model: ClothModel;

  private constructor(solver: GpuClothSolver, model: ClothModel) {
    this.solver = solver;
    this.model = model;
    this.state = createState(model);
  }

  /** A GPU backend for `model` on `device` (kernels compiled once per device); rejects naming the GPU's error. */
  static async create(device: GPUDevice, model: ClothModel): Promise<GpuBackend> {
    return new GpuBackend(await GpuClothSolver.create(device, model), model);
  }

  frame(model: ClothModel, params: SimParams, dt: number): void {
    if (model !== this.model) throw new Error('GPU solver: this backend was made for another model');
    if (this.unsent === 'all') {
      this.solver.setParams(params);
      this.solver.upload(this.state);
    } else if (this.unsent === 'pins') {
      this.solver.uploadPins(this.state);
    }
    this.unsent = null;
    this.solver.step(this.state, params, dt);
    this.current = false;
  }

  async sync(): Promise<void> {
    await this.solver.read(this.state);
    this.current = true;
  }

  stateChanged(what: 'pins' | 'all'): void {
    // a whole state replaces the cloth on the GPU; pins alone must not bring back an older cloth
    if (what === 'all' || this.unsent === null) this.unsent = what;
  }

  whenReady(): Promise<void> {
    return Promise.resolve();
  }

  dispose(): void {
    this.solver.destroy();
  }
}
