/**
 * The cloth's storage buffers on the GPU (layout.ts BUFFERS) and each kernel's bind group over them: made for a
 * model with its static data (springs, triangles, adjacency, the rest pose), then written from the CPU: the
 * params' per-particle, per-spring and per-hinge values, a state's particles, its pins and tethers. The colliders'
 * buffers (their poses, the particles they carry) depend on the params and grow on demand (`reserve`); the bending
 * hinges' are made with their static data on the first params that bend with hinges (`writeParams`).
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { ClothState } from '../core/state.js';
import { updateTethers } from '../core/tethers.js';
import { BUFFERS, KERNELS, VEC4, type BufferName, type KernelName, type KernelSpec } from './layout.js';
import { triangleAdjacency } from './topology.js';

/** The buffers of the bending hinges: placeholders until params first use the hinge model. */
const HINGE_BUFFERS = ['hinges', 'hingeWeights', 'hingeCompliance', 'hingeLambdas'] as const;

/** The storage buffers of one cloth and the kernels' bind groups over them. */
export class ClothBuffers {
  /** every storage buffer, by name */
  readonly buffers: Record<BufferName, GPUBuffer>;
  /** group 1 of each kernel */
  readonly storageGroups: Record<KernelName, GPUBindGroup>;
  private readonly storageLayouts: Record<KernelName, GPUBindGroupLayout>;
  /** whether any particle has a tether anchor (the tethers kernel has work), as of the last writePins */
  hasTethers = false;
  /** whether the hinge buffers hold the model's hinges (made by the first writeParams with the hinge model) */
  private hingesMade = false;
  private readonly device: GPUDevice;
  private readonly model: ClothModel;

  /** Buffers for `model` with its static data; the cloth at its rest pose, unpinned. */
  constructor(device: GPUDevice, model: ClothModel, storageLayouts: Record<KernelName, GPUBindGroupLayout>) {
    this.device = device;
    this.model = model;
    this.storageLayouts = storageLayouts;
    const n = model.particleCount;
    const springCount = model.restLengths.length;
    const triangleCount = model.triangles.length / 3;
    const adjacency = triangleAdjacency(model);

    const counts: Record<BufferName, number> = {
      positions: n, previous: n, residuals: n, previousResiduals: n, velocities: n, invMass: n, baseInvMass: n, pinned: n,
      springs: springCount, springData: springCount, lambdas: springCount, tethers: n,
      // placeholders: a cloth that bends with springs spends nothing on hinges (makeHinges)
      hinges: 0, hingeWeights: 0, hingeCompliance: 0, hingeLambdas: 0,
      triangles: 3 * triangleCount, triForces: triangleCount, adjacency: adjacency.length,
      normals: n, grabStart: 1, colliders: 1, carried: 1,
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
      buffers[name] = this.createBuffer(name, counts[name], extraUsage[name] ?? 0);
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
    for (const kernel of Object.keys(KERNELS) as KernelName[]) this.storageGroups[kernel] = this.makeGroup(kernel);
  }

  private createBuffer(name: BufferName, count: number, extraUsage: number): GPUBuffer {
    return this.device.createBuffer({
      label: `drape ${name}`,
      size: Math.max(16, Math.ceil((count * BUFFERS[name].bytes) / 4) * 4),
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | extraUsage,
    });
  }

  private makeGroup(kernel: KernelName): GPUBindGroup {
    const spec: KernelSpec = KERNELS[kernel];
    return this.device.createBindGroup({
      label: `drape ${kernel}`,
      layout: this.storageLayouts[kernel],
      entries: spec.bindings.map(([name], i) => ({ binding: i, resource: { buffer: this.buffers[name] } })),
    });
  }

  /**
   * Room for `count` elements in buffer `name` (its contents are lost when it grows, and the bind groups of the
   * kernels that read it are made anew). Call it before encoding a frame that uses it, never during.
   */
  reserve(name: 'colliders' | 'carried', count: number): void {
    if (count * BUFFERS[name].bytes <= this.buffers[name].size) return;
    this.buffers[name].destroy();
    this.buffers[name] = this.createBuffer(name, count, 0);
    this.regroup([name]);
  }

  /** Makes anew the bind groups of the kernels that read any of `names` (after those buffers were replaced). */
  private regroup(names: readonly BufferName[]): void {
    for (const kernel of Object.keys(KERNELS) as KernelName[]) {
      const spec: KernelSpec = KERNELS[kernel];
      if (spec.bindings.some(([b]) => names.includes(b))) this.storageGroups[kernel] = this.makeGroup(kernel);
    }
  }

  /**
   * The hinge buffers at the model's size, with its hinges and their stencils (model.hinges, model.hingeWeights):
   * made once, on the first params with the hinge model, so that a cloth bending with springs spends no GPU memory
   * on them (48 B per hinge, about 3 hinges per particle). Like `reserve`, never during a frame's encoding.
   */
  private makeHinges(): void {
    if (this.hingesMade) return;
    this.hingesMade = true;
    const model = this.model;
    const hingeCount = model.hingeAreas.length;
    if (hingeCount === 0) return;
    for (const name of HINGE_BUFFERS) {
      this.buffers[name].destroy();
      this.buffers[name] = this.createBuffer(name, name === 'hingeLambdas' ? 3 * hingeCount : hingeCount, 0);
    }
    this.device.queue.writeBuffer(this.buffers.hinges, 0, bytes(model.hinges));
    this.device.queue.writeBuffer(this.buffers.hingeWeights, 0, bytes(model.hingeWeights));
    this.regroup(HINGE_BUFFERS);
  }

  /**
   * The params' per-particle inverse masses, per-spring rest length and compliance, and, with the hinge model,
   * per-hinge compliance (−1 for both: no constraint); the hinge buffers made first if they are not yet.
   */
  writeParams(params: SimParams): void {
    const model = this.model;
    this.device.queue.writeBuffer(this.buffers.baseInvMass, 0, bytes(params.particleInvMass));
    const springCount = model.restLengths.length;
    const data = new Float32Array(2 * springCount);
    for (let s = 0; s < springCount; s++) {
      data[2 * s] = model.restLengths[s];
      const c = params.compliance[s];
      data[2 * s + 1] = Number.isFinite(c) ? c : -1;
    }
    if (springCount) this.device.queue.writeBuffer(this.buffers.springData, 0, data);
    const hingeCount = model.hingeAreas.length;
    if (params.bending !== 'hinges' || hingeCount === 0) return; // the bending phase runs for no other model
    this.makeHinges();
    const hinge = new Float32Array(hingeCount);
    for (let e = 0; e < hingeCount; e++) {
      const c = params.hingeCompliance[e];
      hinge[e] = Number.isFinite(c) ? c : -1;
    }
    this.device.queue.writeBuffer(this.buffers.hingeCompliance, 0, hinge);
  }

  /** A state's positions, previous positions, their residuals and velocities. */
  writeParticles(state: ClothState): void {
    const q = this.device.queue;
    q.writeBuffer(this.buffers.positions, 0, toVec4(state.positions));
    q.writeBuffer(this.buffers.previous, 0, toVec4(state.previousPositions));
    q.writeBuffer(this.buffers.residuals, 0, toVec4(state.residuals));
    q.writeBuffer(this.buffers.previousResiduals, 0, toVec4(state.previousResiduals));
    q.writeBuffer(this.buffers.velocities, 0, toVec4(state.velocities));
  }

  /** A state's pins and tethers (recomputed on the CPU first when `state.tethersStale`). */
  writePins(state: ClothState): void {
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

  /** Frees every buffer. */
  destroy(): void {
    for (const buf of Object.values(this.buffers)) buf.destroy();
  }
}

/** A typed array as writeBuffer wants it (core's arrays are typed over ArrayBufferLike). */
function bytes(view: ArrayBufferView): GPUAllowSharedBufferSource {
  return view as GPUAllowSharedBufferSource;
}

/** stride 3 → stride 4 (w = 0) */
function toVec4(src: Float32Array): Float32Array<ArrayBuffer> {
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
