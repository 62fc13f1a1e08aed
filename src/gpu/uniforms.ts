/**
 * The uniform tables every kernel reads (group 0, layout.ts): `Globals` (the params, and the grab of each frame),
 * one `Substep` record per substep (written every frame), and one `Pass` record per constraint batch variant, per
 * bending batch variant and per contact pass (written with the params), with the lists of those passes the encoder
 * dispatches.
 */
import type {} from 'webgpu';
import { BEND, bendingStencils, type ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import { airFactor, needsTriangleContact } from '../core/phases.js';
import { selfContactDistance } from '../core/self-contact.js';
import type { ClothState } from '../core/state.js';
import { windVelocity } from '../core/wind.js';
import {
  COLLIDER_MESH, GLOBALS, PASS, PASS_CAP, PASS_READ_LAMBDA, RECORD_STRIDE, SELF_EDGES, SELF_TRIANGLES, SUBSTEP, SELF_PAIRS_PER_PRIMITIVE, selfGridSize,
} from './layout.js';

/**
 * A run of contact work in one substep: particles against colliders [first, last) of one family (analytic or
 * mesh: each has its kernels), or one triangle colour against one collider.
 */
export interface CollidePass {
  readonly kernel: 'collideParticles' | 'collideTriangles' | 'collideMeshParticles' | 'collideMeshTriangles';
  /** a triangle pass (the contactTriangles phase), else a particle pass (contact) */
  readonly triangles: boolean;
  /** its Pass record */
  readonly record: number;
  /** threads: particles or triangles */
  readonly count: number;
  /** colliders each thread meets: last − first, or 1 */
  readonly colliders: number;
}

/** Pass-record indices of one constraint batch: first iteration (λ from 0), later ones (λ accumulated). */
export interface BatchRecords {
  readonly first: number;
  readonly later: number;
  /** springs */
  readonly count: number;
  /** structural or shear: stretch limiting runs over it */
  readonly stretch: boolean;
}

/** Pass-record indices of one colour batch of bending stencils: first pass (λ from 0), later ones (λ accumulated). */
export interface StencilBatchRecords {
  /** its Pass record for a substep's first pass (λ from 0) */
  readonly first: number;
  /** its Pass record for the later passes (PASS_READ_LAMBDA) */
  readonly later: number;
  /** stencils in the batch (threads) */
  readonly count: number;
}

/** Pass-record indices of the self-contact grid's two builds (triangles, edges), and how many of each. */
export interface SelfRecords {
  readonly triangles: number;
  readonly edges: number;
  readonly triangleCount: number;
  readonly edgeCount: number;
  /** the grid's buckets (selfGridSize) */
  readonly buckets: number;
}

/** The uniform buffers of one cloth, their bind group, and the pass lists of the current params. */
export class UniformTables {
  /** group 0 over the three tables (replaced when a table grows) */
  group: GPUBindGroup;
  /** the constraint batches' records, in model.batches order */
  batchRecords: BatchRecords[] = [];
  /** the bending stencils' batch records, in their batches' order; none unless params.bending is a stencil model */
  stencilRecords: StencilBatchRecords[] = [];
  /** the contact passes of a substep, in order */
  collidePasses: CollidePass[] = [];
  /**
   * the self-contact grid's build records, or null when the params have no self-contact or its distance is 0 (a
   * thickness of 0: nothing to keep apart, as on the CPU)
   */
  selfRecords: SelfRecords | null = null;
  private readonly device: GPUDevice;
  private readonly model: ClothModel;
  private readonly layout: GPUBindGroupLayout;
  private readonly globalsBuffer: GPUBuffer;
  private substepBuffer: GPUBuffer;
  private passBuffer: GPUBuffer;
  private readonly globals = new ArrayBuffer(GLOBALS.size);
  private readonly grabData = new ArrayBuffer(16);
  private readonly grabView = new DataView(this.grabData);
  private substepData = new ArrayBuffer(RECORD_STRIDE);
  private substepView = new DataView(this.substepData);
  private readonly wind = new Float64Array(3);

  /**
   * Tables for `model` (nothing grabbed); setParams fills in the params. `pairsPerPrimitive`: the self-contact
   * candidates' list's room per primitive (layout.ts selfGridSize).
   */
  constructor(device: GPUDevice, model: ClothModel, layout: GPUBindGroupLayout, pairsPerPrimitive = SELF_PAIRS_PER_PRIMITIVE) {
    this.device = device;
    this.model = model;
    this.layout = layout;
    this.globalsBuffer = device.createBuffer({ label: 'drape globals', size: GLOBALS.size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
    this.substepBuffer = this.recordBuffer('drape substeps', 1);
    this.passBuffer = this.recordBuffer('drape passes', 1);
    this.group = this.makeGroup();
    const g = new DataView(this.globals);
    g.setUint32(GLOBALS.particleCount, model.particleCount, true);
    g.setUint32(GLOBALS.triangleCount, model.triangles.length / 3, true);
    g.setUint32(GLOBALS.edgeCount, model.edges.length / 2, true);
    const grid = selfGridSize(model, pairsPerPrimitive);
    g.setUint32(GLOBALS.selfBuckets, grid.buckets, true);
    g.setUint32(GLOBALS.selfBlockCount, grid.blocks, true);
    g.setUint32(GLOBALS.selfPairCapacity, grid.pairs, true);
    g.setInt32(GLOBALS.grabbed, -1, true);
    // on the GPU at once: a cloth uploaded before its first params (GpuBackend) has its normals computed for its
    // particles, not for none
    device.queue.writeBuffer(this.globalsBuffer, 0, this.globals);
  }

  /** The candidate pairs the self-contact list holds now (after ClothBuffers.growSelfPairs): for the next frame. */
  setSelfPairCapacity(pairs: number): void {
    const g = new DataView(this.globals);
    g.setUint32(GLOBALS.selfPairCapacity, pairs, true);
    this.device.queue.writeBuffer(this.globalsBuffer, GLOBALS.selfPairCapacity, this.globals, GLOBALS.selfPairCapacity, 4);
  }

  private recordBuffer(label: string, records: number): GPUBuffer {
    return this.device.createBuffer({ label, size: records * RECORD_STRIDE, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  private makeGroup(): GPUBindGroup {
    return this.device.createBindGroup({
      label: 'drape uniforms',
      layout: this.layout,
      entries: [
        { binding: 0, resource: { buffer: this.globalsBuffer } },
        { binding: 1, resource: { buffer: this.substepBuffer, size: SUBSTEP.size } },
        { binding: 2, resource: { buffer: this.passBuffer, size: PASS.size } },
      ],
    });
  }

  /**
   * Globals and pass records for `params` (every collider of a type the GPU knows: colliders.ts gpuCollider), and
   * room for params.substeps substep records.
   */
  setParams(params: SimParams): void {
    const model = this.model;
    const q = this.device.queue;
    const g = new DataView(this.globals);
    for (let k = 0; k < 3; k++) g.setFloat32(GLOBALS.gravity + 4 * k, params.gravity[k], true);
    g.setUint32(GLOBALS.iterations, params.iterations, true);
    g.setFloat32(GLOBALS.damping, params.damping, true);
    g.setFloat32(GLOBALS.stretchFactor, params.stretchFactor, true);
    g.setFloat32(GLOBALS.friction, params.friction, true);
    g.setFloat32(GLOBALS.staticFriction, params.staticFriction, true);
    g.setFloat32(GLOBALS.thickness, params.thickness, true);
    g.setFloat32(GLOBALS.reach, params.thickness + 2 * model.maxTriangleEdge, true);
    g.setFloat32(GLOBALS.windK, airFactor(params), true);
    g.setUint32(GLOBALS.colliderCount, params.colliders.length, true);
    g.setUint32(GLOBALS.carriedCount, params.carried.particles.length, true);
    const selfDistance = params.selfContact ? selfContactDistance(model, params) : 0;
    g.setFloat32(GLOBALS.selfDistance, selfDistance, true);
    // shapes whose surface can poke between a triangle's vertices (not a half-space), as the CPU decides
    const triangleShapes = params.colliders.map((shape) => needsTriangleContact(model, shape, params.thickness));
    q.writeBuffer(this.globalsBuffer, 0, this.globals);

    // pass records: constraint batches (two variants each), bending stencil batches (two each, only for a stencil
    // model: the bending phase runs for no other), then contact
    const records: number[][] = []; // [start, end, cap(float), flags]
    this.batchRecords = model.batches.map((b) => {
      const cap = b.kind === BEND ? 0 : PASS_CAP;
      const at = records.length;
      records.push([b.start, b.end, params.stretchFactor, cap]);
      records.push([b.start, b.end, params.stretchFactor, cap | PASS_READ_LAMBDA]);
      return { first: at, later: at + 1, count: b.end - b.start, stretch: b.kind !== BEND };
    });
    this.stencilRecords = (bendingStencils(model, params.bending)?.batches ?? []).map((b) => {
      const at = records.length;
      records.push([b.start, b.end, 0, 0]);
      records.push([b.start, b.end, 0, PASS_READ_LAMBDA]);
      return { first: at, later: at + 1, count: b.end - b.start };
    });
    this.collidePasses = [];
    let first = 0;
    const shapes = params.colliders.length;
    const mesh = params.colliders.map((shape) => shape.typeId === COLLIDER_MESH);
    for (let k = 0; k < shapes; k++) {
      // a run of particle contact ends where triangle contact follows, at the last collider, and before a collider
      // of the other family (particle contact touches only its own particle: runs in order are the CPU's order)
      if (!triangleShapes[k] && k + 1 < shapes && mesh[k + 1] === mesh[k]) continue;
      const particles = mesh[k] ? 'collideMeshParticles' : 'collideParticles';
      this.collidePasses.push({ kernel: particles, triangles: false, record: records.length, count: model.particleCount, colliders: k + 1 - first });
      records.push([first, k + 1, 0, 0]);
      first = k + 1;
      if (!triangleShapes[k]) continue;
      for (const b of model.triangleBatches) {
        const kernel = mesh[k] ? 'collideMeshTriangles' : 'collideTriangles';
        this.collidePasses.push({ kernel, triangles: true, record: records.length, count: b.end - b.start, colliders: 1 });
        records.push([b.start, b.end, 0, k]);
      }
    }
    // self-contact: the grid's two builds, each record naming its primitives and how many
    this.selfRecords = null;
    if (selfDistance > 0) {
      const triangleCount = model.triangles.length / 3, edgeCount = model.edges.length / 2;
      const at = records.length;
      records.push([0, triangleCount, 0, SELF_TRIANGLES]);
      records.push([0, edgeCount, 0, SELF_EDGES]);
      this.selfRecords = { triangles: at, edges: at + 1, triangleCount, edgeCount, buckets: selfGridSize(model).buckets };
    }
    if (records.length * RECORD_STRIDE > this.passBuffer.size) {
      this.passBuffer.destroy();
      this.passBuffer = this.recordBuffer('drape passes', records.length);
      this.group = this.makeGroup();
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
      this.group = this.makeGroup();
    }
    if (this.substepData.byteLength < params.substeps * RECORD_STRIDE) {
      this.substepData = new ArrayBuffer(params.substeps * RECORD_STRIDE);
      this.substepView = new DataView(this.substepData);
    }
  }

  /**
   * A frame's per-frame inputs: the grab (particle, target) and one record per substep of dt [s], with the CPU's own
   * time accumulation (gusts) and Taylor start, as the frame loop will count them from `state`; substep k's
   * colliders start at record k × `colliderStride` of the colliders buffer (ColliderTables.beginFrame).
   */
  writeFrame(state: ClothState, params: SimParams, dt: number, colliderStride: number): void {
    const q = this.device.queue;
    const n = params.substeps;
    const h = dt / n;
    const grabbed = state.grabbed >= 0 && state.grabbed < this.model.particleCount ? state.grabbed : -1;
    const gv = this.grabView;
    gv.setInt32(0, grabbed, true);
    for (let k = 0; k < 3; k++) gv.setFloat32(4 + 4 * k, state.grabTarget[k], true);
    q.writeBuffer(this.globalsBuffer, GLOBALS.grabbed, this.grabData);

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
      sv.setFloat32(at + SUBSTEP.grabMaxMove, Number.isFinite(params.grabSpeed) ? params.grabSpeed * dt : -1, true);
      sv.setUint32(at + SUBSTEP.windOn, windOn ? 1 : 0, true);
      sv.setFloat32(at + SUBSTEP.recover, params.depenetrationSpeed * h, true);
      sv.setFloat32(at + SUBSTEP.recoverTriangle, (params.depenetrationSpeed * h) / Math.max(1, this.model.maxTriangleValence), true);
      sv.setUint32(at + SUBSTEP.colliderBase, sub * colliderStride, true);
      t += h;
    }
    q.writeBuffer(this.substepBuffer, 0, this.substepData, 0, n * RECORD_STRIDE);
  }

  /** Frees the uniform buffers. */
  destroy(): void {
    this.globalsBuffer.destroy();
    this.substepBuffer.destroy();
    this.passBuffer.destroy();
  }
}
