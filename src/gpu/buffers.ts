/**
 * The cloth's storage buffers on the GPU (layout.ts BUFFERS) and each kernel's bind group over them: made for a
 * model with its static data (springs, triangles, adjacency, the rest pose), then written from the CPU: the
 * params' per-particle, per-spring and per-stencil values, a state's particles, its pins and tethers. The
 * colliders' buffers (their poses, the particles they carry, the mesh colliders' tables) depend on the params and
 * grow on demand (`reserve`); the bending stencils' are made with their static data on the first params that bend
 * with a stencil model, and anew when params switch to the other, and the self-contact grid's (with the edges) on the
 * first params with self-contact (`writeParams`).
 */
import type {} from 'webgpu';
import { bendingStencils, type ClothModel, type StencilModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { ClothState } from '../core/state.js';
import { updateTethers } from '../core/tethers.js';
import { BUFFERS, KERNELS, SELF_PAIRS_PER_PRIMITIVE, VEC4, selfGridSize, type BufferName, type KernelName, type KernelSpec } from './layout.js';
import { triangleAdjacency } from './topology.js';

/** The buffers of the bending stencils: placeholders until params first use a stencil model. */
const STENCIL_BUFFERS = ['stencilOffsets', 'stencilVertices', 'stencilWeights', 'stencilCompliance', 'stencilLambdas'] as const;
/** The buffers of self-contact: placeholders until params first turn it on. */
const SELF_BUFFERS = [
  'edges', 'selfBoxes', 'selfRanks', 'selfCounts', 'selfStarts', 'selfBlocks', 'selfEntries', 'selfPairs', 'selfArgs', 'selfDelta',
] as const;
/**
 * Usages a buffer has besides STORAGE and COPY_DST: drawn (VERTEX, INDEX), read back (COPY_SRC: the state; the
 * self-contact counts; the coarse correction's check, which its tests read), read by indirect dispatches (INDIRECT).
 */
function extraUsage(name: BufferName): number {
  switch (name) {
    case 'positions': case 'normals': return GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_SRC;
    case 'previous': case 'velocities': case 'lambdas': case 'coarseRhs': case 'coarseDir': case 'coarsePartials': return GPUBufferUsage.COPY_SRC;
    case 'triangles': return GPUBufferUsage.INDEX;
    case 'selfArgs': case 'coarseArgs': return GPUBufferUsage.INDIRECT | GPUBufferUsage.COPY_SRC;
    default: return 0;
  }
}

/** The storage buffers of one cloth and the kernels' bind groups over them. */
export class ClothBuffers {
  /** every storage buffer, by name */
  readonly buffers: Record<BufferName, GPUBuffer>;
  /** group 1 of each kernel */
  readonly storageGroups: Record<KernelName, GPUBindGroup>;
  private readonly storageLayouts: Record<KernelName, GPUBindGroupLayout>;
  /** whether any particle has a tether anchor (the tethers kernel has work), as of the last writePins */
  hasTethers = false;
  /** the stencil model whose stencils the stencil buffers hold (made by writeParams), or null: placeholders */
  private stencilsMade: StencilModel | null = null;
  /** whether the self-contact buffers are made (makeSelfContact), else placeholders */
  private selfMade = false;
  /** the pairs the self-contact candidates' list holds (0 before it is made) */
  private selfPairRoom = 0;

  /** whether the self-contact buffers are made (the first params with self-contact make them) */
  get hasSelfContact(): boolean {
    return this.selfMade;
  }
  private readonly device: GPUDevice;
  private readonly model: ClothModel;

  /**
   * Buffers for `model` with its static data; the cloth at its rest pose, unpinned. `pairsPerPrimitive`: the
   * self-contact candidates' list's room per primitive (layout.ts selfGridSize).
   */
  constructor(device: GPUDevice, model: ClothModel, storageLayouts: Record<KernelName, GPUBindGroupLayout>, readonly pairsPerPrimitive = SELF_PAIRS_PER_PRIMITIVE) {
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
      // placeholders: a cloth that bends with springs spends nothing on stencils (makeStencils)
      stencilOffsets: 0, stencilVertices: 0, stencilWeights: 0, stencilCompliance: 0, stencilLambdas: 0,
      // placeholders until params solve the stencils together (global-bending.ts)
      bendingCoefficients: 0, stencilForce: 0, stencilIncidence: 0, factorIndex: 0, factorValues: 0, globalX: 0, globalT: 0, grabColumn: 0,
      // placeholders until params solve the springs together (global-stretch.ts)
      stretchCoefficients: 0, springForce: 0, springIncidence: 0, globalY: 0, stretchFactorIndex: 0, stretchFactorValues: 0,
      stretchGrabColumn: 0,
      // placeholders until params first correct the springs on a coarse space (coarse-stretch.ts)
      coarseDir: 0, coarseRhs: 0, coarseSpringAggregate: 0, coarseArgs: 0, coarsePartials: 0, coarseAggregates: 0, coarseMembers: 0, coarseBlocks: 0, coarseIncidence: 0, coarsePairs: 0,
      coarsePairVec: 0, coarseEntryStart: 0, coarseEntryPairs: 0, coarseMatrix: 0, coarseFactor: 0, coarseInverse: 0, coarseNear: 0,
      coarseWeights: 0,
      triangles: 3 * triangleCount, triForces: triangleCount, adjacency: adjacency.length,
      normals: n, grabStart: 2, colliders: 1, carried: 1, meshNodes: 1, meshTriangles: 1,
      // placeholders: a cloth without self-contact spends nothing on its grid (makeSelfContact)
      edges: 0, selfBoxes: 0, selfRanks: 0, selfCounts: 0, selfStarts: 0, selfBlocks: 0, selfEntries: 0, selfPairs: 0, selfArgs: 0,
      selfDelta: 0,
    };
    const buffers = {} as Record<BufferName, GPUBuffer>;
    for (const name of Object.keys(BUFFERS) as BufferName[]) buffers[name] = this.createBuffer(name, counts[name]);
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

  private createBuffer(name: BufferName, count: number): GPUBuffer {
    return this.device.createBuffer({
      label: `drape ${name}`,
      size: Math.max(16, Math.ceil((count * BUFFERS[name].bytes) / 4) * 4),
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | extraUsage(name),
    });
  }

  private makeGroup(kernel: KernelName): GPUBindGroup {
    const spec: KernelSpec = KERNELS[kernel];
    return this.device.createBindGroup({
      label: `drape ${kernel}`,
      layout: this.storageLayouts[kernel],
      entries: spec.bindings.map((b, i) => ({ binding: i, resource: { buffer: this.buffers[b[2] ?? b[0]] } })),
    });
  }

  /**
   * Room for `count` elements in buffer `name` (its contents are lost when it grows, and the bind groups of the
   * kernels that read it are made anew). Call it before encoding a frame that uses it, never during.
   */
  reserve(name: 'colliders' | 'carried' | 'meshNodes' | 'meshTriangles', count: number): void {
    if (count * BUFFERS[name].bytes <= this.buffers[name].size) return;
    this.buffers[name].destroy();
    this.buffers[name] = this.createBuffer(name, count);
    this.regroup([name]);
  }

  /**
   * Buffers made anew at these sizes [elements], their contents lost, and the bind groups of the kernels that read
   * them (the global bending step's tables, global-bending.ts). Like `reserve`, before the kernels that read them are
   * encoded.
   */
  remake(sizes: Partial<Record<BufferName, number>>): void {
    const names = Object.keys(sizes) as BufferName[];
    for (const name of names) {
      this.buffers[name].destroy();
      this.buffers[name] = this.createBuffer(name, sizes[name]!);
    }
    this.regroup(names);
  }

  /** Makes anew the bind groups of the kernels that read any of `names` (after those buffers were replaced). */
  private regroup(names: readonly BufferName[]): void {
    for (const kernel of Object.keys(KERNELS) as KernelName[]) {
      const spec: KernelSpec = KERNELS[kernel];
      if (spec.bindings.some((b) => names.includes(b[2] ?? b[0]))) this.storageGroups[kernel] = this.makeGroup(kernel);
    }
  }

  /**
   * The stencil buffers at the size of the model's stencils of `kind` (model.stencils), with their entries: made on
   * the first params with a stencil model, and anew when params switch to the other, so that a cloth bending with
   * springs spends no GPU memory on them (hinges: 56 B each, about 3 per particle; the Laplacian: 20 B per stencil
   * and 8 B per entry, about 6 entries per particle). Like `reserve`, never during a frame's encoding.
   */
  private makeStencils(kind: StencilModel): void {
    if (this.stencilsMade === kind) return;
    this.stencilsMade = kind;
    const stencils = this.model.stencils[kind];
    const count = stencils.areas.length, entries = stencils.vertices.length;
    const sizes: Record<(typeof STENCIL_BUFFERS)[number], number> = {
      stencilOffsets: count + 1, stencilVertices: entries, stencilWeights: entries, stencilCompliance: count, stencilLambdas: 3 * count,
    };
    for (const name of STENCIL_BUFFERS) {
      this.buffers[name].destroy();
      this.buffers[name] = this.createBuffer(name, sizes[name]);
    }
    const q = this.device.queue;
    q.writeBuffer(this.buffers.stencilOffsets, 0, bytes(stencils.offsets));
    if (entries) q.writeBuffer(this.buffers.stencilVertices, 0, bytes(stencils.vertices));
    if (entries) q.writeBuffer(this.buffers.stencilWeights, 0, bytes(stencils.weights));
    this.regroup(STENCIL_BUFFERS);
  }

  /**
   * The self-contact buffers at their sizes for the model (layout.ts selfGridSize: P primitives, B buckets), with
   * the edges: made on the first params with self-contact, kept after (they depend on the model alone). 8 B per edge;
   * per primitive its box (32 B), ranks (32 B), entries (32 B) and candidate pairs (64 B); 8 B per bucket; 16 B per
   * particle: about 580 B per particle on a grid (P = the edges, about 3 per particle; B ≈ 2P to 4P), 610 MB at
   * 1025². Refused, before anything changes, where one of them is larger than the device binds. Like `reserve`,
   * never during a frame's encoding.
   */
  private makeSelfContact(): void {
    if (this.selfMade) return;
    this.checkParams({ selfContact: true });
    const { sizes, pairs } = this.selfSizes();
    this.selfMade = true;
    this.selfPairRoom = pairs;
    for (const name of SELF_BUFFERS) {
      this.buffers[name].destroy();
      this.buffers[name] = this.createBuffer(name, sizes[name]);
    }
    if (this.model.edges.length) this.device.queue.writeBuffer(this.buffers.edges, 0, bytes(this.model.edges));
    this.regroup(SELF_BUFFERS);
  }

  /**
   * The self-contact candidates' list anew with room for `pairs` pairs (empty: what it held is of passes already
   * resolved), and the bind groups of the kernels that read it; the most the device binds in one buffer at most.
   * Returns the pairs it holds now. Like `reserve`, never during a frame's encoding; only once self-contact's buffers
   * are made.
   */
  growSelfPairs(pairs: number): number {
    if (!this.selfMade) throw new Error('GPU solver: the self-contact list grows only once self-contact is on');
    const room = Math.min(pairs, this.selfPairMost);
    if (room <= this.selfPairRoom) return this.selfPairRoom;
    this.buffers.selfPairs.destroy();
    this.buffers.selfPairs = this.createBuffer('selfPairs', 1 + 2 * room);
    this.regroup(['selfPairs']);
    this.selfPairRoom = room;
    return room;
  }

  /** the most pairs a self-contact candidates' list can hold: what the device binds in one buffer */
  get selfPairMost(): number {
    return Math.floor((this.device.limits.maxStorageBufferBindingSize / BUFFERS.selfPairs.bytes - 1) / 2);
  }

  /** the pairs the self-contact candidates' list holds now (selfGridSize's `pairs` until growSelfPairs) */
  get selfPairCapacity(): number {
    return this.selfPairRoom;
  }

  /** The self-contact buffers' sizes [elements] for the model, and the candidate pairs the list holds. */
  private selfSizes(): { sizes: Record<(typeof SELF_BUFFERS)[number], number>; pairs: number } {
    const { primitives, buckets, blocks, entries, pairs } = selfGridSize(this.model, this.pairsPerPrimitive);
    return {
      sizes: {
        edges: this.model.edges.length / 2, selfBoxes: 2 * primitives, selfRanks: 8 * primitives, selfCounts: 1 + buckets,
        selfStarts: 2 + buckets, selfBlocks: blocks, selfEntries: entries, selfPairs: 1 + 2 * pairs, selfArgs: 5,
        selfDelta: 4 * this.model.particleCount,
      },
      pairs,
    };
  }

  /**
   * Throws, changing nothing, where `params` need what this device cannot hold: self-contact's buffers past what it
   * binds in one (GpuClothSolver.setParams asks before it changes anything).
   */
  checkParams(params: Pick<SimParams, 'selfContact'>): void {
    if (!params.selfContact || this.selfMade) return;
    const { sizes } = this.selfSizes();
    const limit = this.device.limits.maxStorageBufferBindingSize;
    const over = SELF_BUFFERS.find((name) => sizes[name] * BUFFERS[name].bytes > limit);
    if (over) {
      throw new Error(`GPU solver: self-contact needs ${Math.ceil((sizes[over] * BUFFERS[over].bytes) / 2 ** 20)} MiB in one buffer (${over}) for ${this.model.particleCount} particles; this device binds at most ${Math.floor(limit / 2 ** 20)} MiB`);
    }
  }

  /**
   * The params' per-particle inverse masses, per-spring rest length and compliance, and, with a stencil bending
   * model, per-stencil compliance (−1 for both: no constraint); the stencil buffers made first if they do not hold
   * that model's, and the self-contact buffers on the first params with self-contact.
   */
  writeParams(params: SimParams): void {
    const model = this.model;
    if (params.selfContact) this.makeSelfContact();
    this.device.queue.writeBuffer(this.buffers.baseInvMass, 0, bytes(params.particleInvMass));
    const springCount = model.restLengths.length;
    const data = new Float32Array(2 * springCount);
    for (let s = 0; s < springCount; s++) {
      data[2 * s] = model.restLengths[s];
      const c = params.compliance[s];
      data[2 * s + 1] = Number.isFinite(c) ? c : -1;
    }
    if (springCount) this.device.queue.writeBuffer(this.buffers.springData, 0, data);
    const stencils = bendingStencils(model, params.bending);
    if (params.bending === 'springs' || !stencils || stencils.areas.length === 0) return; // no bending phase runs
    this.makeStencils(params.bending);
    const compliance = new Float32Array(stencils.areas.length);
    for (let e = 0; e < compliance.length; e++) {
      const c = params.stencilCompliance[e];
      compliance[e] = Number.isFinite(c) ? c : -1;
    }
    this.device.queue.writeBuffer(this.buffers.stencilCompliance, 0, compliance);
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
