/**
 * The WebGPU XPBD solver: the phases of src/core/solvers/xpbd.ts `step`, in the same order and with the same
 * parameters, as compute kernels over the same ClothModel. One frame (all its substeps) is one command buffer and
 * one submit; the CPU keeps the bookkeeping (`state.time`, `state.substeps`, tethers, gust wind) so that the
 * Taylor start and the gusts match the CPU solver exactly.
 *
 * Per frame: `prepare` (effective inverse masses, previous = x − h·v), then per substep: wind (per triangle) →
 * integrate (position Verlet + grab, gathers the wind) → one dispatch per constraint colour batch × iterations →
 * tethers → stretch limit (per structural/shear batch) → contact (particles, then per triangle colour for spheres
 * that need it); then velocities from the last substep and vertex normals.
 */
import type {} from 'webgpu'; // WebGPU types (@webgpu/types through the webgpu package); erased at runtime
import { FloorCollider, SphereCollider, type ColliderShape } from '../core/colliders/index.js';
import { BEND, type ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import { needsTriangleContact } from '../core/phases.js';
import type { ClothState } from '../core/state.js';
import { updateTethers } from '../core/tethers.js';
import { windVelocity } from '../core/wind.js';
import {
  BUFFERS, COLLIDER_BYTES, COLLIDER_FLOOR, COLLIDER_SPHERE, GLOBALS, KERNELS, MAX_COLLIDERS, MAX_WORKGROUPS_X, PASS,
  PASS_CAP, PASS_READ_LAMBDA, RECORD_STRIDE, SUBSTEP, VEC4, WORKGROUP_SIZE,
  type BufferName, type KernelName, type KernelSpec,
} from './layout.js';
import { kernelSource } from './shaders.js';
import { triangleAdjacency } from './topology.js';

/** A run of contact work in one substep: particles against colliders [first, last), or one triangle colour. */
type CollidePass = { kernel: 'collideParticles' | 'collideTriangles'; record: number; count: number };

/** Pass-record indices of one constraint batch: first iteration (λ from 0), later ones (λ accumulated). */
interface BatchRecords { first: number; later: number; count: number; stretch: boolean }

const KERNEL_NAMES = Object.keys(KERNELS) as KernelName[];

/** Bytes one substep's kernels read and write, as written (each element access counted once per thread). */
export interface SubstepTraffic {
  total: number;
  byKernel: Record<string, number>;
}

/** A device's compiled kernels: every solver on the device shares them. */
interface Kernels {
  uniformLayout: GPUBindGroupLayout;
  pipelines: Record<KernelName, GPUComputePipeline>;
  storageLayouts: Record<KernelName, GPUBindGroupLayout>;
}
const compiled = new WeakMap<GPUDevice, Promise<Kernels>>();

/** The kernels of `device`, compiled on first use (a failed compile is not kept: the next call tries again). */
function kernelsFor(device: GPUDevice): Promise<Kernels> {
  let kernels = compiled.get(device);
  if (!kernels) {
    kernels = compileKernels(device);
    compiled.set(device, kernels);
    kernels.catch(() => compiled.delete(device));
  }
  return kernels;
}

async function compileKernels(device: GPUDevice): Promise<Kernels> {
  const uniformLayout = device.createBindGroupLayout({
    label: 'drape uniforms',
    entries: [
      { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
      { binding: 1, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform', hasDynamicOffset: true, minBindingSize: SUBSTEP.size } },
      { binding: 2, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform', hasDynamicOffset: true, minBindingSize: PASS.size } },
    ],
  });
  const pipelines = {} as Record<KernelName, GPUComputePipeline>;
  const storageLayouts = {} as Record<KernelName, GPUBindGroupLayout>;
  await Promise.all(KERNEL_NAMES.map(async (kernel) => {
    const spec: KernelSpec = KERNELS[kernel];
    const layout = device.createBindGroupLayout({
      label: `drape ${kernel} storage`,
      entries: spec.bindings.map(([, access], i) => ({
        binding: i,
        visibility: GPUShaderStage.COMPUTE,
        buffer: { type: access === 'read' ? 'read-only-storage' as const : 'storage' as const },
      })),
    });
    storageLayouts[kernel] = layout;
    const code = kernelSource(kernel);
    const module = device.createShaderModule({ label: `drape ${kernel}.wgsl`, code });
    const info = await module.getCompilationInfo();
    const errors = info.messages.filter((m) => m.type === 'error');
    if (errors.length) {
      const lines = code.split('\n');
      const where = (m: GPUCompilationMessage) => `'${(lines[m.lineNum - 1] ?? '').trim()}': ${m.message}`;
      throw new Error(`GPU solver: ${kernel} kernel does not compile: ${errors.map(where).join('; ')}`);
    }
    pipelines[kernel] = await device.createComputePipelineAsync({
      label: `drape ${kernel}`,
      layout: device.createPipelineLayout({ bindGroupLayouts: [uniformLayout, layout] }),
      compute: { module, entryPoint: 'main' },
    });
  }));
  return { uniformLayout, pipelines, storageLayouts };
}

export class GpuClothSolver {
  readonly device: GPUDevice;
  readonly model: ClothModel;
  private readonly buffers: Record<BufferName, GPUBuffer>;
  private readonly pipelines: Record<KernelName, GPUComputePipeline>;
  private readonly storageGroups: Record<KernelName, GPUBindGroup>;
  private readonly uniformLayout: GPUBindGroupLayout;
  private readonly globalsBuffer: GPUBuffer;
  private substepBuffer: GPUBuffer;
  private passBuffer: GPUBuffer;
  private uniformGroup: GPUBindGroup;
  private readonly globals = new ArrayBuffer(GLOBALS.size);
  private readonly grabData = new ArrayBuffer(16);
  private readonly grabView = new DataView(this.grabData);
  private substepData = new ArrayBuffer(RECORD_STRIDE);
  private substepView = new DataView(this.substepData);
  private params: SimParams | undefined;
  private batchRecords: BatchRecords[] = [];
  private collidePasses: CollidePass[] = [];
  private hasTethers = false;
  private staging: GPUBuffer | undefined;
  private reading: Promise<void> = Promise.resolve();
  private readonly wind = new Float64Array(3);
  private destroyed = false;

  /**
   * Creates the buffers for `model` (the kernels are compiled once per device and reused: they do not depend on
   * the model); the cloth starts at its rest pose, unpinned.
   */
  static async create(device: GPUDevice, model: ClothModel): Promise<GpuClothSolver> {
    device.pushErrorScope('validation');
    device.pushErrorScope('out-of-memory');
    let solver: GpuClothSolver | undefined;
    let failure: unknown;
    try {
      const { uniformLayout, pipelines, storageLayouts } = await kernelsFor(device);
      solver = new GpuClothSolver(device, model, uniformLayout, pipelines, storageLayouts);
    } catch (e) {
      failure = e;
    }
    const oom = await device.popErrorScope();
    const invalid = await device.popErrorScope();
    if (failure) throw failure;
    if (oom) { solver?.destroy(); throw new Error(`GPU solver: out of GPU memory for ${model.particleCount} particles: ${oom.message}`); }
    if (invalid) { solver?.destroy(); throw new Error(`GPU solver: ${invalid.message.split('\n')[0]}`); }
    return solver!;
  }

  private constructor(
    device: GPUDevice, model: ClothModel, uniformLayout: GPUBindGroupLayout,
    pipelines: Record<KernelName, GPUComputePipeline>, storageLayouts: Record<KernelName, GPUBindGroupLayout>,
  ) {
    this.device = device;
    this.model = model;
    this.uniformLayout = uniformLayout;
    this.pipelines = pipelines;
    const n = model.particleCount;
    const springCount = model.restLengths.length;
    const triangleCount = model.triangles.length / 3;
    const adjacency = triangleAdjacency(model);

    const counts: Record<BufferName, number> = {
      positions: n, previous: n, velocities: n, invMass: n, baseInvMass: n, pinned: n,
      springs: springCount, springData: springCount, lambdas: springCount, tethers: n,
      triangles: 3 * triangleCount, triForces: triangleCount, adjacency: adjacency.length,
      normals: n, grabStart: 1,
    };
    const extraUsage: Partial<Record<BufferName, number>> = {
      positions: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_SRC,
      previous: GPUBufferUsage.COPY_SRC,
      velocities: GPUBufferUsage.COPY_SRC,
      normals: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_SRC,
      lambdas: GPUBufferUsage.COPY_SRC,
      triangles: GPUBufferUsage.INDEX,
    };
    const buffers = {} as Record<BufferName, GPUBuffer>;
    for (const name of Object.keys(BUFFERS) as BufferName[]) {
      buffers[name] = device.createBuffer({
        label: `drape ${name}`,
        size: Math.max(16, Math.ceil((counts[name] * BUFFERS[name].bytes) / 4) * 4),
        usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | (extraUsage[name] ?? 0),
      });
    }
    this.buffers = buffers;

    // static model data
    const q = device.queue;
    q.writeBuffer(buffers.springs, 0, bytes(model.springs));
    q.writeBuffer(buffers.triangles, 0, bytes(model.triangles));
    q.writeBuffer(buffers.adjacency, 0, bytes(adjacency));
    const pos = toVec4(model.restPositions);
    q.writeBuffer(buffers.positions, 0, pos);
    q.writeBuffer(buffers.previous, 0, pos);
    const tethers = new Int32Array(2 * n).fill(-1);
    for (let i = 0; i < n; i++) tethers[2 * i + 1] = 0;
    q.writeBuffer(buffers.tethers, 0, tethers);

    this.storageGroups = {} as Record<KernelName, GPUBindGroup>;
    for (const kernel of KERNEL_NAMES) {
      const spec: KernelSpec = KERNELS[kernel];
      this.storageGroups[kernel] = device.createBindGroup({
        label: `drape ${kernel}`,
        layout: storageLayouts[kernel],
        entries: spec.bindings.map(([name], i) => ({ binding: i, resource: { buffer: buffers[name] } })),
      });
    }

    this.globalsBuffer = device.createBuffer({ label: 'drape globals', size: GLOBALS.size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
    this.substepBuffer = this.recordBuffer('drape substeps', 1);
    this.passBuffer = this.recordBuffer('drape passes', 1);
    this.uniformGroup = this.makeUniformGroup();
    const g = new DataView(this.globals);
    g.setUint32(GLOBALS.particleCount, n, true);
    g.setUint32(GLOBALS.triangleCount, triangleCount, true);
    g.setInt32(GLOBALS.grabbed, -1, true);
  }

  /** Position buffer (`array<vec4f>`, x y z 0 per particle [m], usage VERTEX | STORAGE) for renderers. */
  get positionBuffer(): GPUBuffer { return this.buffers.positions; }
  /** Vertex normals (`array<vec4f>`, unit, usage VERTEX | STORAGE), updated at the end of every step. */
  get normalBuffer(): GPUBuffer { return this.buffers.normals; }
  /** Velocities (`array<vec4f>` [m/s]). */
  get velocityBuffer(): GPUBuffer { return this.buffers.velocities; }
  /** Triangle indices (u32, usage INDEX | STORAGE), the model's `triangles`. */
  get indexBuffer(): GPUBuffer { return this.buffers.triangles; }
  /** Triangle colours used by triangle contact. */
  get triangleColourCount(): number { return this.model.triangleBatches.length; }

  private recordBuffer(label: string, records: number): GPUBuffer {
    return this.device.createBuffer({ label, size: records * RECORD_STRIDE, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  private makeUniformGroup(): GPUBindGroup {
    return this.device.createBindGroup({
      label: 'drape uniforms',
      layout: this.uniformLayout,
      entries: [
        { binding: 0, resource: { buffer: this.globalsBuffer } },
        { binding: 1, resource: { buffer: this.substepBuffer, size: SUBSTEP.size } },
        { binding: 2, resource: { buffer: this.passBuffer, size: PASS.size } },
      ],
    });
  }

  /**
   * Takes new parameters (stiffness, damping, mass, gravity, wind, colliders, substeps, iterations...) without
   * rebuilding anything but the uniform tables. `step` calls it by itself when handed a different params object;
   * call it after changing a params object in place. Throws for what the GPU path does not support (the
   * mass-spring solver, collider types other than sphere and floor, more than 64 colliders).
   */
  setParams(params: SimParams): void {
    this.checkAlive();
    if (params.solver !== 'xpbd') throw new Error(`GPU solver: only the xpbd solver runs on the GPU (params.solver is '${params.solver}')`);
    if (params.colliders.length > MAX_COLLIDERS) throw new Error(`GPU solver: at most ${MAX_COLLIDERS} colliders (got ${params.colliders.length})`);
    const model = this.model;
    const q = this.device.queue;
    this.params = params;

    q.writeBuffer(this.buffers.baseInvMass, 0, bytes(params.particleInvMass));
    const springCount = model.restLengths.length;
    const data = new Float32Array(2 * springCount);
    for (let s = 0; s < springCount; s++) {
      data[2 * s] = model.restLengths[s];
      const c = params.compliance[s];
      data[2 * s + 1] = Number.isFinite(c) ? c : -1;
    }
    if (springCount) q.writeBuffer(this.buffers.springData, 0, data);

    // globals
    const g = new DataView(this.globals);
    for (let k = 0; k < 3; k++) g.setFloat32(GLOBALS.gravity + 4 * k, params.gravity[k], true);
    g.setUint32(GLOBALS.iterations, params.iterations, true);
    g.setFloat32(GLOBALS.damping, params.damping, true);
    g.setFloat32(GLOBALS.stretchFactor, params.stretchFactor, true);
    g.setFloat32(GLOBALS.friction, params.friction, true);
    g.setFloat32(GLOBALS.staticFriction, params.staticFriction, true);
    g.setFloat32(GLOBALS.thickness, params.thickness, true);
    g.setFloat32(GLOBALS.reach, params.thickness + 2 * model.maxTriangleEdge, true);
    g.setFloat32(GLOBALS.windK, (0.25 * params.wind.airDensity) / 3, true);
    g.setUint32(GLOBALS.colliderCount, params.colliders.length, true);
    const triangleShapes: boolean[] = [];
    params.colliders.forEach((shape, k) => {
      const at = GLOBALS.colliders + k * COLLIDER_BYTES;
      const { kind, data4 } = encodeCollider(shape);
      for (let j = 0; j < 4; j++) g.setFloat32(at + 4 * j, data4[j], true);
      g.setUint32(at + 16, kind, true);
      triangleShapes.push(kind === COLLIDER_SPHERE && needsTriangleContact(model, shape, params.thickness));
    });
    q.writeBuffer(this.globalsBuffer, 0, this.globals);

    // pass records: constraint batches (two variants each), then contact
    const records: number[][] = []; // [start, end, cap(float), flags]
    this.batchRecords = model.batches.map((b) => {
      const cap = b.kind === BEND ? 0 : PASS_CAP;
      const at = records.length;
      records.push([b.start, b.end, params.stretchFactor, cap]);
      records.push([b.start, b.end, params.stretchFactor, cap | PASS_READ_LAMBDA]);
      return { first: at, later: at + 1, count: b.end - b.start, stretch: b.kind !== BEND };
    });
    this.collidePasses = [];
    let first = 0;
    const shapes = params.colliders.length;
    for (let k = 0; k < shapes; k++) {
      if (!triangleShapes[k] && k + 1 < shapes) continue;
      this.collidePasses.push({ kernel: 'collideParticles', record: records.length, count: model.particleCount });
      records.push([first, k + 1, 0, 0]);
      first = k + 1;
      if (!triangleShapes[k]) continue;
      for (const b of model.triangleBatches) {
        this.collidePasses.push({ kernel: 'collideTriangles', record: records.length, count: b.end - b.start });
        records.push([b.start, b.end, 0, k]);
      }
    }
    if (records.length * RECORD_STRIDE > this.passBuffer.size) {
      this.passBuffer.destroy();
      this.passBuffer = this.recordBuffer('drape passes', records.length);
      this.uniformGroup = this.makeUniformGroup();
    }
    const table = new DataView(new ArrayBuffer(Math.max(1, records.length) * RECORD_STRIDE));
    records.forEach(([start, end, cap, flags], r) => {
      const at = r * RECORD_STRIDE;
      table.setUint32(at + PASS.start, start, true);
      table.setUint32(at + PASS.end, end, true);
      table.setFloat32(at + PASS.cap, cap, true);
      table.setUint32(at + PASS.flags, flags, true);
    });
    q.writeBuffer(this.passBuffer, 0, table.buffer);

    if (params.substeps * RECORD_STRIDE > this.substepBuffer.size) {
      this.substepBuffer.destroy();
      this.substepBuffer = this.recordBuffer('drape substeps', params.substeps);
      this.uniformGroup = this.makeUniformGroup();
    }
    if (this.substepData.byteLength < params.substeps * RECORD_STRIDE) {
      this.substepData = new ArrayBuffer(params.substeps * RECORD_STRIDE);
      this.substepView = new DataView(this.substepData);
    }
  }

  /**
   * Copies the cloth from a CPU state: positions, previous positions, velocities, pins and tethers (recomputed
   * first when `state.tethersStale`). The grab is read by every `step`.
   */
  upload(state: ClothState): void {
    this.checkAlive();
    const q = this.device.queue;
    q.writeBuffer(this.buffers.positions, 0, toVec4(state.positions));
    q.writeBuffer(this.buffers.previous, 0, toVec4(state.previousPositions));
    q.writeBuffer(this.buffers.velocities, 0, toVec4(state.velocities));
    this.uploadPins(state);
    this.refreshNormals();
  }

  /** Recomputes the vertex normals from the current positions (step does this itself; upload calls it). */
  refreshNormals(): void {
    this.checkAlive();
    const encoder = this.device.createCommandEncoder({ label: 'drape normals' });
    const pass = encoder.beginComputePass({ label: 'drape normals' });
    this.dispatch(pass, 'normals', this.model.particleCount, 0, 0);
    pass.end();
    this.device.queue.submit([encoder.finish()]);
  }

  private uploadPins(state: ClothState): void {
    if (state.tethersStale) updateTethers(this.model, state);
    const n = this.model.particleCount;
    const pinned = new Uint32Array(n);
    for (let i = 0; i < n; i++) pinned[i] = state.pinned[i];
    const tethers = new ArrayBuffer(8 * n);
    const anchors = new Int32Array(tethers), lengths = new Float32Array(tethers);
    let any = false;
    for (let i = 0; i < n; i++) {
      anchors[2 * i] = state.tetherAnchors[i];
      lengths[2 * i + 1] = state.tetherLengths[i];
      if (state.tetherAnchors[i] >= 0) any = true;
    }
    this.hasTethers = any;
    this.device.queue.writeBuffer(this.buffers.pinned, 0, pinned);
    this.device.queue.writeBuffer(this.buffers.tethers, 0, tethers);
  }

  /**
   * Advances the GPU cloth by dt [s] in params.substeps substeps: one command buffer, one submit, no readback.
   * Updates state.time and state.substeps (and the tethers when the pins changed: `state.tethersStale`) on the
   * CPU; the particle arrays of `state` are left alone until `read`. `timestampWrites` (benchmarks) times the
   * frame's compute pass on devices with 'timestamp-query'.
   */
  step(state: ClothState, params: SimParams, dt: number, timestampWrites?: GPUComputePassTimestampWrites): void {
    this.checkAlive();
    if (params !== this.params) this.setParams(params);
    if (state.tethersStale) this.uploadPins(state);
    const device = this.device, q = device.queue, b = this.buffers;
    const n = params.substeps;
    const h = dt / n;

    // the grab: particle, target; its start position is copied on the GPU below
    const grabbed = state.grabbed >= 0 && state.grabbed < this.model.particleCount ? state.grabbed : -1;
    const gv = this.grabView;
    gv.setInt32(0, grabbed, true);
    for (let k = 0; k < 3; k++) gv.setFloat32(4 + 4 * k, state.grabTarget[k], true);
    q.writeBuffer(this.globalsBuffer, GLOBALS.grabbed, this.grabData);

    // per-substep records, with the CPU's own time accumulation (gusts) and Taylor start
    const sv = this.substepView;
    const windOn = params.wind.enabled;
    let t = state.time;
    for (let sub = 0; sub < n; sub++) {
      const at = sub * RECORD_STRIDE;
      if (windOn) windVelocity(params, t, this.wind); else this.wind.fill(0);
      for (let k = 0; k < 3; k++) sv.setFloat32(at + SUBSTEP.wind + 4 * k, this.wind[k], true);
      const c = state.substeps + sub === 0 ? 0.5 : 1;
      sv.setFloat32(at + SUBSTEP.h, h, true);
      sv.setFloat32(at + SUBSTEP.h2, c * h * h, true);
      sv.setFloat32(at + SUBSTEP.invH, 1 / h, true);
      sv.setFloat32(at + SUBSTEP.invH2, 1 / (h * h), true);
      sv.setFloat32(at + SUBSTEP.betaOverH, params.damping / h, true);
      sv.setFloat32(at + SUBSTEP.grabFraction, (sub + 1) / n, true);
      sv.setUint32(at + SUBSTEP.windOn, windOn ? 1 : 0, true);
      sv.setFloat32(at + SUBSTEP.recover, params.depenetrationSpeed * h, true);
      sv.setFloat32(at + SUBSTEP.recoverTriangle, (params.depenetrationSpeed * h) / Math.max(1, this.model.maxTriangleValence), true);
      t += h;
    }
    q.writeBuffer(this.substepBuffer, 0, this.substepData, 0, n * RECORD_STRIDE);

    const encoder = device.createCommandEncoder({ label: 'drape step' });
    if (grabbed >= 0) encoder.copyBufferToBuffer(b.positions, grabbed * 16, b.grabStart, 0, 16);
    const pass = encoder.beginComputePass(timestampWrites ? { label: 'drape step', timestampWrites } : { label: 'drape step' });
    const particles = this.model.particleCount, triangles = this.model.triangles.length / 3;
    this.dispatch(pass, 'prepare', particles, 0, 0); // substep 0's record: h
    for (let sub = 0; sub < n; sub++) {
      const so = sub * RECORD_STRIDE;
      if (windOn) this.dispatch(pass, 'wind', triangles, so, 0);
      this.dispatch(pass, 'integrate', particles, so, 0);
      for (let it = 0; it < params.iterations; it++) {
        for (const r of this.batchRecords) {
          this.dispatch(pass, 'solve', r.count, so, (it === 0 ? r.first : r.later) * RECORD_STRIDE);
        }
      }
      if (this.hasTethers) this.dispatch(pass, 'tethers', particles, so, 0);
      for (const r of this.batchRecords) if (r.stretch) this.dispatch(pass, 'limitStretch', r.count, so, r.first * RECORD_STRIDE);
      for (const c of this.collidePasses) this.dispatch(pass, c.kernel, c.count, so, c.record * RECORD_STRIDE);
    }
    this.dispatch(pass, 'velocities', particles, (n - 1) * RECORD_STRIDE, 0);
    this.dispatch(pass, 'normals', particles, 0, 0);
    pass.end();
    q.submit([encoder.finish()]);
    state.time = t;
    state.substeps += n;
  }

  private dispatch(pass: GPUComputePassEncoder, kernel: KernelName, count: number, substepOffset: number, passOffset: number): void {
    if (count <= 0) return;
    pass.setPipeline(this.pipelines[kernel]);
    pass.setBindGroup(0, this.uniformGroup, [substepOffset, passOffset]);
    pass.setBindGroup(1, this.storageGroups[kernel]);
    const groups = Math.ceil(count / WORKGROUP_SIZE);
    if (groups <= MAX_WORKGROUPS_X) pass.dispatchWorkgroups(groups);
    else pass.dispatchWorkgroups(MAX_WORKGROUPS_X, Math.ceil(groups / MAX_WORKGROUPS_X));
  }

  /**
   * Copies the GPU cloth back into `state`: positions, previous positions, velocities and the springs' λ of the
   * last substep (what `energy` reads). Resolves once the data is in `state`. Calls are serialised.
   */
  read(state: ClothState): Promise<void> {
    this.checkAlive();
    const next = this.reading.then(() => this.readNow(state));
    this.reading = next.catch(() => undefined);
    return next;
  }

  private async readNow(state: ClothState): Promise<void> {
    const n = this.model.particleCount;
    const vecBytes = n * 16;
    const lambdaBytes = this.model.restLengths.length * 4;
    const size = 3 * vecBytes + lambdaBytes;
    if (!this.staging || this.staging.size < size) {
      this.staging?.destroy();
      this.staging = this.device.createBuffer({ label: 'drape readback', size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    }
    const staging = this.staging;
    const encoder = this.device.createCommandEncoder({ label: 'drape read' });
    encoder.copyBufferToBuffer(this.buffers.positions, 0, staging, 0, vecBytes);
    encoder.copyBufferToBuffer(this.buffers.previous, 0, staging, vecBytes, vecBytes);
    encoder.copyBufferToBuffer(this.buffers.velocities, 0, staging, 2 * vecBytes, vecBytes);
    if (lambdaBytes) encoder.copyBufferToBuffer(this.buffers.lambdas, 0, staging, 3 * vecBytes, lambdaBytes);
    this.device.queue.submit([encoder.finish()]);
    await staging.mapAsync(GPUMapMode.READ, 0, size);
    try {
      const all = new Float32Array(staging.getMappedRange(0, size));
      fromVec4(all.subarray(0, 4 * n), state.positions);
      fromVec4(all.subarray(4 * n, 8 * n), state.previousPositions);
      fromVec4(all.subarray(8 * n, 12 * n), state.velocities);
      if (lambdaBytes) state.lambdas.set(all.subarray(12 * n, 12 * n + this.model.restLengths.length));
    } finally {
      staging.unmap();
    }
  }

  /** Bytes one substep's kernels move with the current params (see docs/gpu.md, "Benchmark"). */
  substepTraffic(): SubstepTraffic {
    const params = this.params;
    if (!params) throw new Error('GPU solver: setParams first');
    const model = this.model;
    const n = model.particleCount, T = model.triangles.length / 3, S = model.restLengths.length;
    const by: Record<string, number> = {};
    const add = (k: string, bytes: number) => { by[k] = (by[k] ?? 0) + bytes; };
    if (params.wind.enabled) {
      add('wind', T * (12 + 3 * 16 + 3 * 16 + 12 + 16)); // indices, x, x_prev, base w, force
      add('integrate', n * 8 + 3 * T * 20); // adjacency offsets, then index + force per incident triangle
    }
    add('integrate', n * (16 + 16 + 4 + 16 + 16)); // x, x_prev, w in; x_prev, x out
    let solve = S * (8 + 8 + 8 + 32 + 32); // springData, springs, w×2, x×2 in and out
    if (params.damping > 0) solve += S * 32; // previous×2
    solve += S * 4; // λ written
    solve *= params.iterations;
    solve += S * 4 * (params.iterations - 1); // λ read after the first pass
    add('solve', solve);
    if (this.hasTethers) add('tethers', n * (8 + 4 + 16 + 16 + 16));
    const stretchSprings = model.springCounts[0] + model.springCounts[1];
    add('limitStretch', stretchSprings * (8 + 8 + 8 + 32)); // springs, rest, w×2, x×2 in (written only when over)
    for (const c of this.collidePasses) {
      if (c.kernel === 'collideParticles') add('collideParticles', n * (4 + 16 + 16 + 16));
      else add('collideTriangles', c.count * (12 + 48 + 48)); // indices, positions and previous positions of 3 particles
    }
    add('perFrame', (n * (4 + 4 + 4 + 16 + 16 + 16) + n * 48) / params.substeps); // prepare + velocities, per substep
    let total = 0;
    for (const k of Object.keys(by)) { by[k] = Math.round(by[k]); total += by[k]; }
    return { total, byKernel: by };
  }

  /** Dispatches one frame encodes (for reports). */
  dispatchesPerFrame(params: SimParams): number {
    const stretchBatches = this.batchRecords.filter((r) => r.stretch).length;
    const perSubstep = (params.wind.enabled ? 1 : 0) + 1 + params.iterations * this.batchRecords.length + stretchBatches +
      (this.hasTethers ? 1 : 0) + this.collidePasses.length;
    return 3 + params.substeps * perSubstep;
  }

  /** Frees every GPU buffer. The solver cannot be used afterwards. */
  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    for (const buf of Object.values(this.buffers)) buf.destroy();
    this.globalsBuffer.destroy();
    this.substepBuffer.destroy();
    this.passBuffer.destroy();
    this.staging?.destroy();
  }

  private checkAlive(): void {
    if (this.destroyed) throw new Error('GPU solver: used after destroy()');
  }
}

/** A typed array as writeBuffer wants it (core's arrays are typed over ArrayBufferLike). */
function bytes(view: ArrayBufferView): GPUAllowSharedBufferSource {
  return view as GPUAllowSharedBufferSource;
}

function encodeCollider(shape: ColliderShape): { kind: number; data4: [number, number, number, number] } {
  if (shape instanceof SphereCollider) return { kind: COLLIDER_SPHERE, data4: [shape.cx, shape.cy, shape.cz, shape.radius] };
  if (shape instanceof FloorCollider) return { kind: COLLIDER_FLOOR, data4: [shape.height, 0, 0, 0] };
  throw new Error(`GPU solver: collider type '${shape.type}' is not supported on the GPU (sphere, floor)`);
}

/** stride 3 → stride 4 (w = 0) */
export function toVec4(src: Float32Array): Float32Array<ArrayBuffer> {
  const n = src.length / 3;
  const out = new Float32Array(VEC4 * n);
  for (let i = 0; i < n; i++) {
    out[4 * i] = src[3 * i];
    out[4 * i + 1] = src[3 * i + 1];
    out[4 * i + 2] = src[3 * i + 2];
  }
  return out;
}

/** stride 4 → stride 3, into `out` */
export function fromVec4(src: Float32Array, out: Float32Array): void {
  const n = out.length / 3;
  for (let i = 0; i < n; i++) {
    out[3 * i] = src[4 * i];
    out[3 * i + 1] = src[4 * i + 1];
    out[3 * i + 2] = src[4 * i + 2];
  }
}
