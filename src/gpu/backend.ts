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
  readonly state: ClothState;
  /** the solver, for what only the GPU has (timings, traffic, normals) */
  readonly solver: GpuClothSolver;
  private stale = true;

  private constructor(solver: GpuClothSolver, model: ClothModel) {
    this.solver = solver;
    this.state = createState(model);
  }

  /** A GPU backend for `model` on `device` (kernels compiled once per device); rejects naming the GPU's error. */
  static async create(device: GPUDevice, model: ClothModel): Promise<GpuBackend> {
    return new GpuBackend(await GpuClothSolver.create(device, model), model);
  }

  frame(_model: ClothModel, params: SimParams, dt: number): void {
    if (this.stale) {
      this.solver.setParams(params);
      this.solver.upload(this.state);
      this.stale = false;
    }
    this.solver.step(this.state, params, dt);
  }

  sync(): Promise<void> {
    return this.solver.read(this.state);
  }

  stateChanged(): void {
    this.stale = true;
  }

  whenReady(): Promise<void> {
    return Promise.resolve();
  }

  dispose(): void {
    this.solver.destroy();
  }
}
