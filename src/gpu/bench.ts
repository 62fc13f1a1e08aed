/**
 * GPU benchmark hook for `drape bench --backend gpu`: the default scene (cotton dropped on a sphere over a floor)
 * at several sizes, timed over many frames, against the device's own measured copy bandwidth.
 */
import type {} from 'webgpu';
import { FRAME_DT, resolveParams } from '../core/params.js';
import { defaultScene, type Scene } from '../core/scene.js';
import { modelFor } from '../core/cloth-shape.js';
import { createState } from '../core/state.js';
import { GpuClothSolver } from './solver.js';

export interface GpuBenchResult {
  /** particles per side */
  size: number;
  particles: number;
  springs: number;
  substeps: number;
  /** frames timed */
  frames: number;
  /** compute dispatches in one frame */
  dispatchesPerFrame: number;
  /** wall time per 1/60 s frame, submit to onSubmittedWorkDone over `frames` frames back to back [ms] */
  msPerFrame: number;
  /** GPU time per frame from timestamp queries [ms], when the device has 'timestamp-query'; else null */
  gpuMsPerFrame: number | null;
  /** particles × substeps per second of wall time */
  particleSubstepsPerSecond: number;
  /** bytes one substep's kernels read and write, counted per kernel (docs/gpu.md) */
  bytesPerSubstep: number;
  /** measured device copy bandwidth (copyBufferToBuffer, read + write bytes) [GB/s] */
  copyBandwidthGBs: number;
  /** time the traffic of one frame takes at that bandwidth [ms] */
  bandwidthFloorMs: number;
  /** bandwidthFloorMs / (gpuMsPerFrame ?? msPerFrame): 1 = memory-bound at copy speed */
  fractionOfBandwidthFloor: number;
}

const bandwidthCache = new WeakMap<GPUDevice, number>();

/** Device copy bandwidth [bytes/s]: copyBufferToBuffer of a large buffer, read + write bytes over time. */
export async function measureCopyBandwidth(device: GPUDevice): Promise<number> {
  const cached = bandwidthCache.get(device);
  if (cached) return cached;
  const size = Math.min(256 * 2 ** 20, Math.floor(device.limits.maxBufferSize / 4) * 4);
  const src = device.createBuffer({ size, usage: GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
  const dst = device.createBuffer({ size, usage: GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
  const copies = (k: number) => {
    const enc = device.createCommandEncoder();
    for (let i = 0; i < k; i++) enc.copyBufferToBuffer(i % 2 ? dst : src, 0, i % 2 ? src : dst, 0, size);
    device.queue.submit([enc.finish()]);
    return device.queue.onSubmittedWorkDone();
  };
  await copies(2); // warm-up: first touch of the memory
  let reps = 4;
  let seconds = 0;
  for (;;) {
    const t0 = performance.now();
    await copies(reps);
    seconds = (performance.now() - t0) / 1000;
    if (seconds > 0.2 || reps >= 256) break;
    reps *= 4;
  }
  src.destroy();
  dst.destroy();
  const bw = (2 * size * reps) / seconds;
  bandwidthCache.set(device, bw);
  return bw;
}

/**
 * Runs the default scene at each size (particles per side) for `frames` frames of `substeps` substeps after a
 * short warm-up, and reports time per frame, throughput, traffic and the fraction of the bandwidth floor;
 * `configure` changes the scene after that (the CLI's --set: another bending model or solve). Numbers from
 * SwiftShader (a CPU driver) only prove that it runs.
 */
export async function benchGpu(
  device: GPUDevice, sizes: number[], substeps: number, frames: number, configure?: (scene: Scene) => Scene,
): Promise<GpuBenchResult[]> {
  const bandwidth = await measureCopyBandwidth(device);
  const timestamps = device.features.has('timestamp-query');
  const results: GpuBenchResult[] = [];
  for (const size of sizes) {
    if (!Number.isInteger(size) || size < 2 || size > 1025) throw new Error(`benchGpu: size must be 2…1025 particles per side, got ${size}`);
    let scene = defaultScene();
    scene.cloth.resolution = size - 1;
    scene.solver.substeps = substeps;
    if (configure) scene = configure(scene);
    const model = modelFor(scene);
    const params = resolveParams(model, scene);
    const state = createState(model);
    const solver = await GpuClothSolver.create(device, model);
    try {
      solver.setParams(params);
      solver.upload(state);
      const warm = Math.min(5, frames);
      for (let f = 0; f < warm; f++) solver.step(state, params, FRAME_DT);
      await device.queue.onSubmittedWorkDone();

      const t0 = performance.now();
      for (let f = 0; f < frames; f++) solver.step(state, params, FRAME_DT);
      await device.queue.onSubmittedWorkDone();
      const ms = (performance.now() - t0) / frames;

      let gpuMs: number | null = null;
      if (timestamps) gpuMs = await timeWithQueries(device, solver, state, params, Math.min(frames, 32));

      const bytes = solver.substepTraffic().total;
      const floorMs = ((bytes * params.substeps) / bandwidth) * 1000;
      results.push({
        size,
        particles: model.particleCount,
        springs: model.restLengths.length,
        substeps: params.substeps,
        frames,
        dispatchesPerFrame: solver.dispatchesPerFrame(params),
        msPerFrame: ms,
        gpuMsPerFrame: gpuMs,
        particleSubstepsPerSecond: (model.particleCount * params.substeps) / (ms / 1000),
        bytesPerSubstep: bytes,
        copyBandwidthGBs: bandwidth / 1e9,
        bandwidthFloorMs: floorMs,
        fractionOfBandwidthFloor: floorMs / (gpuMs ?? ms),
      });
    } finally {
      solver.destroy();
    }
  }
  return results;
}

/** Mean GPU time of a frame's compute pass over `frames` frames, from timestamp queries [ms]. */
async function timeWithQueries(
  device: GPUDevice, solver: GpuClothSolver, state: Parameters<GpuClothSolver['step']>[0],
  params: Parameters<GpuClothSolver['step']>[1], frames: number,
): Promise<number> {
  const querySet = device.createQuerySet({ type: 'timestamp', count: 2 * frames });
  const resolve = device.createBuffer({ size: 16 * frames, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC });
  const read = device.createBuffer({ size: 16 * frames, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  try {
    for (let f = 0; f < frames; f++) {
      solver.step(state, params, FRAME_DT, { querySet, beginningOfPassWriteIndex: 2 * f, endOfPassWriteIndex: 2 * f + 1 });
    }
    const enc = device.createCommandEncoder();
    enc.resolveQuerySet(querySet, 0, 2 * frames, resolve, 0);
    enc.copyBufferToBuffer(resolve, 0, read, 0, 16 * frames);
    device.queue.submit([enc.finish()]);
    await read.mapAsync(GPUMapMode.READ);
    const t = new BigInt64Array(read.getMappedRange());
    let total = 0;
    for (let f = 0; f < frames; f++) total += Number(t[2 * f + 1] - t[2 * f]);
    read.unmap();
    return total / frames / 1e6;
  } finally {
    querySet.destroy();
    resolve.destroy();
    read.destroy();
  }
}
