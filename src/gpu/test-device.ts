/**
 * The GPU device the Node tests run on: whatever adapter `createNodeDevice` finds (SwiftShader on the build
 * machines). No adapter: in CI (process.env.CI set) the test file fails with the reason; elsewhere its device tests
 * are skipped with the reason printed. A GPU test never passes without running.
 */
import type {} from 'webgpu';
import {
  FRAME_DT, applyPins, centroid, perturbStart, copyState, createState, grab, modelFor, release, resolveParams, scenePins, setPinned, step,
  type ClothModel, type ClothState, type Scene, type SimParams, type StencilModel, type Vec3,
} from '../core/index.js';
import { createNodeDevice } from './node.js';
import { GpuClothSolver } from './solver.js';

/** the device every GPU test file of this process shares (vitest.config.ts runs them in one, not isolated) */
let shared: Promise<{ device: GPUDevice; adapter: string }> | null = null;

/**
 * The device and adapter for `file`'s tests, or undefined (with a warning) where none is found outside CI. The files
 * share one device, so its kernels are compiled once for all of them (2.6 s on SwiftShader here): a file destroys
 * its solvers, never the device.
 */
export async function testDevice(file: string): Promise<{ device: GPUDevice; adapter: string } | undefined> {
  try {
    if (!shared) {
      const made = createNodeDevice();
      shared = made;
      // a lost device is not handed on: the next file makes its own
      void made.then(({ device }) => device.lost.then(() => { if (shared === made) shared = null; }), () => undefined);
    }
    return await shared;
  } catch (e) {
    shared = null;
    const reason = (e as Error).message;
    if (process.env.CI) throw new Error(`GPU tests need a WebGPU adapter in CI: ${reason}`);
    console.warn(`${file}: GPU tests skipped: ${reason}`);
    return undefined;
  }
}

/** Largest distance between corresponding particles of two position arrays (stride 3) [m]. */
export function maxDistance(a: Float32Array, b: Float32Array): number {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) worst = Math.max(worst, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  return worst;
}

/** Distance between the centroids of two cloth states [m]. */
export function centroidDistance(a: ClothState, b: ClothState): number {
  const p = centroid(a), q = centroid(b);
  return Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

/** One scene on the CPU (the TypeScript reference) and on the GPU, from the same start. */
export interface Pair {
  model: ClothModel;
  /** the params both step with (a test may put others here: a live change) */
  params: SimParams;
  cpu: ClothState;
  gpu: ClothState;
  solver: GpuClothSolver;
  /** steps both `frames` frames, then reads the GPU state back */
  advance(frames: number): Promise<void>;
}

/**
 * A CPU and a GPU cloth of `sc` on `device`, in the same start state (its pins applied); the solver is added to
 * `made`, for the file to destroy. The model lists triangles in colour order, so CPU and GPU triangle contact visit
 * them in the same order (see docs/gpu.md, "Parity").
 */
export async function gpuPair(device: GPUDevice, sc: Scene, made: GpuClothSolver[]): Promise<Pair> {
  const model = modelFor(sc);
  const params = resolveParams(model, sc);
  const cpu = createState(model);
  const pins = scenePins(model, sc);
  applyPins(cpu, pins);
  perturbStart(model, sc, cpu, pins);
  const g = createState(model);
  copyState(cpu, g);
  const solver = await GpuClothSolver.create(device, model);
  made.push(solver);
  solver.setParams(params);
  solver.upload(g);
  const p: Pair = {
    model, params, cpu, gpu: g, solver,
    async advance(frames: number) {
      for (let f = 0; f < frames; f++) {
        step(model, cpu, p.params, FRAME_DT);
        solver.step(g, p.params, FRAME_DT);
      }
      await solver.read(g);
    },
  };
  return p;
}

/**
 * How bent a cloth is: Σ ½·|C|²/A over the stencils of `kind`, C = Σ K_k x_k (model.ts BendingStencils), i.e. the
 * model's bending energy per unit rigidity B, ≈ ½∫κ² dA for a sheet bent without stretching [-].
 */
export function bentness(model: ClothModel, x: Float32Array, kind: StencilModel): number {
  const { offsets, vertices, weights: K, areas } = model.stencils[kind];
  let sum = 0;
  for (let e = 0; e < areas.length; e++) {
    for (let c = 0; c < 3; c++) {
      let C = 0;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) C += K[k] * x[3 * vertices[k] + c];
      sum += (0.5 * C * C) / areas[e];
    }
  }
  return sum;
}

/**
 * How far the GPU's cloth of a 16² pair (`p`, 10 frames in) is from the CPU's 5 frames after each change to the pins
 * and the grab, each made to the CPU's cloth copied to the GPU: particle 0 let go, the middle particle grabbed and
 * carried by `pull` [m], then released [m]; and, 5 frames after the grab, how far apart the grabbed particle is [m].
 */
export async function pinAndGrabChanges(p: Pair, pull: Vec3): Promise<{ apart: [string, number][]; grabbed: number }> {
  const mid = 8 * 17 + 8, x = p.cpu.positions, both = [p.cpu, p.gpu];
  const changes: [string, () => void][] = [
    ['a corner let go', () => { for (const s of both) setPinned(s, 0, false); p.solver.uploadPins(p.gpu); }],
    ['the middle grabbed', () => {
      const t: Vec3 = [x[3 * mid] + pull[0], x[3 * mid + 1] + pull[1], x[3 * mid + 2] + pull[2]];
      for (const s of both) grab(s, mid, t);
    }],
    ['released', () => { for (const s of both) release(s); }],
  ];
  const apart: [string, number][] = [];
  let grabbed = NaN;
  await p.advance(10);
  for (const [what, change] of changes) {
    copyState(p.cpu, p.gpu);
    p.solver.upload(p.gpu);
    change();
    await p.advance(5);
    apart.push([what, maxDistance(p.gpu.positions, p.cpu.positions)]);
    if (what === 'the middle grabbed') grabbed = maxDistance(p.gpu.positions.subarray(3 * mid, 3 * mid + 3), p.cpu.positions.subarray(3 * mid, 3 * mid + 3));
  }
  return { apart, grabbed };
}
