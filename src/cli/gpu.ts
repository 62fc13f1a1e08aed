/**
 * The CLI's WebGPU backend: Dawn in Node through the optional `webgpu` package (src/gpu/node.ts), the same scenes
 * and models as the CPU. Loaded only when `--backend gpu` is asked for.
 */
import { Simulation, type MeshResolver, type Scene } from '../core/index.js';
import type { GpuBenchResult } from '../gpu/index.js';
import { UsageError } from './errors.js';

export interface Gpu {
  device: GPUDevice;
  adapter: string;
  /**
   * Runs `scene` for `frames` frames on the GPU; `kept` (ascending, each ≤ frames): the frames whose positions are
   * read back on the way, for a bake (each read waits for the GPU); `before` sees the Simulation before its first
   * frame (and may throw to refuse the run). The Simulation is disposed, its state read back.
   */
  simulate(scene: Scene, frames: number, meshes?: MeshResolver, kept?: readonly number[], before?: (sim: Simulation) => void): Promise<{ sim: Simulation; msPerFrame: number; shapes: Float32Array[] }>;
  /** benchGpu on this device (`configure`: the scene's --set changes) */
  bench(sizes: number[], substeps: number, frames: number, configure?: (scene: Scene) => Scene): Promise<GpuBenchResult[]>;
}

/**
 * Why the GPU solver cannot take `scene`'s colliders (a shape it does not have), as the CLI's one-line usage error,
 * or null; checked before a device is opened, so the answer does not depend on the machine (the solver is checked
 * when the backend is made). Null too when the GPU module does not load (openGpu says that).
 */
export async function gpuRefusal(scene: Scene): Promise<string | null> {
  let gpu: typeof import('../gpu/index.js');
  try {
    gpu = await import('../gpu/index.js');
  } catch {
    return null;
  }
  const why = gpu.colliderRefusal(scene);
  return why && `--backend gpu: ${why}: use --backend cpu`;
}

/** the process's GPU, once opened (see openGpu) */
let opened: Promise<Gpu & { lost: boolean }> | undefined;

/**
 * The process's GPU: opened on first use and kept for the next run in the same process (Dawn compiles each pipeline
 * once per device: 2.4 s of the first run of a small cloth under SwiftShader, nothing after), opened again when its
 * device was lost. It is never destroyed: the process exits with it open.
 */
export async function openGpu(): Promise<Gpu> {
  const kept = opened && (await opened.catch(() => undefined));
  if (kept && !kept.lost) return kept;
  opened = openDevice();
  // a failure is not kept: the next call tries again
  opened.catch(() => { opened = undefined; });
  return opened;
}

async function openDevice(): Promise<Gpu & { lost: boolean }> {
  let node: typeof import('../gpu/node.js'), gpuModule: typeof import('../gpu/index.js');
  try {
    [node, gpuModule] = await Promise.all([import('../gpu/node.js'), import('../gpu/index.js')]);
  } catch (e) {
    throw new UsageError(`--backend gpu: the WebGPU backend does not load (${(e as Error).message.split('\n')[0]})`);
  }
  let device: GPUDevice, adapter: string;
  try {
    ({ device, adapter } = await node.createNodeDevice());
  } catch (e) {
    throw new UsageError(`--backend gpu: ${(e as Error).message.split('\n')[0]}`);
  }
  const gpu: Gpu & { lost: boolean } = {
    lost: false,
    device,
    adapter,
    async simulate(scene, frames, meshes, kept = [], before) {
      const sim = new Simulation(scene, { kernel: 'ts', meshes });
      try {
        before?.(sim);
        sim.useBackend(await gpuModule.GpuBackend.create(device, sim.model));
        const shapes: Float32Array[] = [];
        const t0 = performance.now();
        let done = 0;
        for (const f of kept) {
          sim.advance(f - done);
          done = f;
          await sim.sync();
          shapes.push(sim.state.positions.slice());
        }
        sim.advance(frames - done);
        await device.queue.onSubmittedWorkDone();
        const msPerFrame = frames > 0 ? (performance.now() - t0) / frames : 0;
        await sim.sync();
        return { sim, msPerFrame, shapes };
      } catch (e) {
        // what the GPU solver refuses (a solver it does not run, a limit) is the user's input
        const message = (e as Error).message;
        if (message.startsWith('GPU solver:')) throw new UsageError(`--backend gpu: ${message.split('\n')[0]}`);
        throw e;
      } finally {
        sim.dispose();
      }
    },
    bench: (sizes, substeps, frames, configure) => gpuModule.benchGpu(device, sizes, substeps, frames, configure),
  };
  device.lost.then(() => { gpu.lost = true; }, () => undefined);
  return gpu;
}
