/**
 * The CLI's WebGPU backend: Dawn in Node through the optional `webgpu` package (src/gpu/node.ts), the same scenes
 * and models as the CPU. Loaded only when `--backend gpu` is asked for.
 */
import { FRAME_DT, Simulation, type MeshResolver, type Scene } from '../core/index.js';
import type { GpuBenchResult } from '../gpu/index.js';
import { UsageError } from './errors.js';

export interface Gpu {
  device: GPUDevice;
  adapter: string;
  /** steps `scene` for `frames` frames on the GPU; the returned Simulation holds the read-back state */
  simulate(scene: Scene, frames: number, meshes?: MeshResolver): Promise<{ sim: Simulation; msPerFrame: number }>;
  bench(sizes: number[], substeps: number, frames: number): Promise<GpuBenchResult[]>;
}

export async function openGpu(): Promise<Gpu> {
  let node: typeof import('../gpu/node.js'), gpu: typeof import('../gpu/index.js');
  try {
    [node, gpu] = await Promise.all([import('../gpu/node.js'), import('../gpu/index.js')]);
  } catch (e) {
    throw new UsageError(`--backend gpu: the WebGPU backend does not load (${(e as Error).message.split('\n')[0]})`);
  }
  let device: GPUDevice, adapter: string;
  try {
    ({ device, adapter } = await node.createNodeDevice());
  } catch (e) {
    throw new UsageError(`--backend gpu: ${(e as Error).message.split('\n')[0]}`);
  }
  return {
    device,
    adapter,
    async simulate(scene, frames, meshes) {
      const sim = new Simulation(scene, { kernel: 'ts', meshes });
      const solver = await gpu.GpuClothSolver.create(device, sim.model);
      try {
        try {
          solver.setParams(sim.params);
        } catch (e) {
          throw new UsageError(`--backend gpu: ${(e as Error).message.split('\n')[0]}`);
        }
        solver.upload(sim.state);
        const t0 = performance.now();
        for (let f = 0; f < frames; f++) solver.step(sim.state, sim.params, FRAME_DT);
        await device.queue.onSubmittedWorkDone();
        const msPerFrame = frames > 0 ? (performance.now() - t0) / frames : 0;
        await solver.read(sim.state);
        sim.frame = frames;
        return { sim, msPerFrame };
      } finally {
        solver.destroy();
      }
    },
    bench: (sizes, substeps, frames) => gpu.benchGpu(device, sizes, substeps, frames),
  };
}
