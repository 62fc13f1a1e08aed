/**
 * The colliders as the GPU's kernels read them: the `colliders` buffer (layout.ts `Collider`: each collider's shape
 * in its own frame, where that frame is at the end of a substep, and how its surface moved over the substep) and
 * the `carried` buffer (layout.ts `Carry`: the particles colliders carry, params.carried).
 *
 * While no collider moves, the buffer holds one record per collider, written when the params change, and every
 * substep reads those (Substep.colliderBase = 0). While one moves (keyframes, or a drive the library sets:
 * PosedCollider.animated), the encoder puts every collider where it is at the end of each substep it encodes
 * (`poseSubstep`: PosedCollider.moveTo(state.time, state.time + h), as the TypeScript contact and carry phases do),
 * one record per collider per substep, and the frame's records are written before its command buffer is submitted
 * (Substep.colliderBase = substep × colliders). So the GPU's colliders are exactly the CPU's PosedColliders, pose
 * by pose, and the CPU's colliders stand where the frame left them (what views and reports read).
 *
 * A mesh collider's hierarchy and triangles, in its own frame, are the `meshNodes` and `meshTriangles` buffers
 * (meshes.ts), written with the params when their meshes change; its records say where its root is. So a mesh moves
 * by its pose records alone, as every collider does.
 */
import type {} from 'webgpu';
import type { MeshCollider, PosedCollider } from '../core/colliders/index.js';
import type { SimParams } from '../core/params.js';
import type { ClothBuffers } from './buffers.js';
import {
  CARRY, COLLIDER, COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_MESH, COLLIDER_PLANE,
  COLLIDER_SPHERE, MESH_NODE, MESH_TRIANGLE,
} from './layout.js';
import { meshLayout, packMeshes, type MeshLayout } from './meshes.js';

/** The collider types the GPU's kernels know (colliders.wgsl, meshCollider.wgsl, triangleContact.wgsl). */
const GPU_TYPES: readonly number[] = [
  COLLIDER_SPHERE, COLLIDER_FLOOR, COLLIDER_PLANE, COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_MESH,
];

/** Byte offsets of the rows of R (with o) and of M (with m) in a record. */
const POSE_ROWS = [COLLIDER.pose0, COLLIDER.pose1, COLLIDER.pose2];
const MOTION_ROWS = [COLLIDER.motion0, COLLIDER.motion1, COLLIDER.motion2];

/**
 * The type id the GPU's kernels know a collider by (PosedCollider.typeId), or null for a shape they do not know
 * (the GPU then refuses the contact phase: encoder.ts).
 */
export function gpuCollider(shape: PosedCollider): number | null {
  return GPU_TYPES.includes(shape.typeId) ? shape.typeId : null;
}

/** The colliders' GPU records of one cloth: written with the params, and per frame while a collider moves. */
export class ColliderTables {
  private readonly device: GPUDevice;
  private readonly buffers: ClothBuffers;
  /** the records of the frame being encoded (or the static ones), CPU side */
  private data = new ArrayBuffer(COLLIDER.size);
  private view = new DataView(this.data);
  /** colliders in the params */
  private count = 0;
  /** whether this frame's records are per substep (some collider moves) */
  private perSubstep = false;
  /** the last substep of this frame whose records are made (−1: none yet) */
  private posed = -1;
  /** whether the buffer holds the static records of the current params */
  private staticCurrent = false;
  /** where the params' meshes are in the meshNodes and meshTriangles buffers (each collider's root) */
  private meshes: MeshLayout = meshLayout([]);
  /** the meshes those buffers hold (meshes that come back after params without them are not written again) */
  private held: readonly MeshCollider[] = [];

  constructor(device: GPUDevice, buffers: ClothBuffers) {
    this.device = device;
    this.buffers = buffers;
  }

  /**
   * The carried particles of `params`, and its mesh colliders' tables when its meshes are not those the buffers
   * hold (a GPU solver error where they need more than the device binds); the collider records are written by the
   * next frame.
   */
  setParams(params: SimParams): void {
    this.setMeshes(params);
    this.count = params.colliders.length;
    this.staticCurrent = false;
    const { particles, collider, local } = params.carried;
    const n = particles.length;
    if (n === 0) return;
    this.buffers.reserve('carried', n);
    const table = new DataView(new ArrayBuffer(n * CARRY.size));
    for (let k = 0; k < n; k++) {
      const at = k * CARRY.size;
      for (let j = 0; j < 3; j++) table.setFloat32(at + CARRY.local + 4 * j, local[3 * k + j], true);
      table.setUint32(at + CARRY.particle, particles[k], true);
      table.setUint32(at + CARRY.collider, collider[k], true);
    }
    this.device.queue.writeBuffer(this.buffers.buffers.carried, 0, table.buffer);
  }

  /**
   * Before a frame of `params.substeps` substeps is encoded: makes room for its records, writes the static ones if
   * they are not in the buffer yet, and returns how many records each substep's start is after the last one's
   * (Substep.colliderBase = substep × that): the collider count while one moves, else 0.
   */
  beginFrame(params: SimParams): number {
    const n = this.count;
    this.posed = -1;
    const colliders = params.colliders;
    let moves = false;
    for (let k = 0; k < n && !moves; k++) moves = colliders[k].animated;
    this.perSubstep = moves;
    if (!this.perSubstep) {
      if (!this.staticCurrent && n > 0) {
        this.buffers.reserve('colliders', n);
        this.ensureData(n);
        for (let k = 0; k < n; k++) this.encode(colliders[k], k, k, false);
        this.device.queue.writeBuffer(this.buffers.buffers.colliders, 0, this.data, 0, n * COLLIDER.size);
      }
      this.staticCurrent = true;
      return 0;
    }
    this.staticCurrent = false;
    const records = n * params.substeps;
    this.buffers.reserve('colliders', records);
    this.ensureData(records);
    return n;
  }

  /**
   * The records of substep `sub`, which starts at t0 [s] and lasts h [s]: every collider moved to where it is at
   * the substep's end (PosedCollider.moveTo), once per substep however many phases ask. Nothing while none moves.
   */
  poseSubstep(params: SimParams, sub: number, t0: number, h: number): void {
    if (!this.perSubstep || this.posed === sub) return;
    this.posed = sub;
    const base = sub * this.count, colliders = params.colliders;
    for (let k = 0; k < this.count; k++) {
      const c = colliders[k];
      c.moveTo(t0, t0 + h);
      this.encode(c, k, base + k, c.moving);
    }
  }

  /** After the frame is encoded, before it is submitted: its per-substep records to the GPU. */
  endFrame(params: SimParams): void {
    if (!this.perSubstep) return;
    this.device.queue.writeBuffer(this.buffers.buffers.colliders, 0, this.data, 0, this.count * params.substeps * COLLIDER.size);
  }

  /**
   * The params' mesh tables to the GPU, unless the buffers hold these very meshes already (a GPU solver error,
   * before anything changes, where they need more than the device binds).
   */
  private setMeshes(params: SimParams): void {
    const layout = meshLayout(params.colliders);
    const held = this.held;
    if (layout.meshes.length === 0 || (layout.meshes.length === held.length && layout.meshes.every((m, k) => m === held[k]))) {
      this.meshes = layout;
      return;
    }
    const limit = this.device.limits.maxStorageBufferBindingSize;
    for (const [what, bytes] of [['BVH', layout.nodeCount * MESH_NODE.size], ['triangles', layout.triangleCount * MESH_TRIANGLE.size]] as const) {
      if (bytes > limit) {
        throw new Error(`GPU solver: the mesh colliders' ${what} take ${(bytes / 2 ** 20).toFixed(0)} MiB, more than this device binds (${(limit / 2 ** 20).toFixed(0)} MiB)`);
      }
    }
    const tables = packMeshes(layout);
    this.buffers.reserve('meshNodes', layout.nodeCount);
    this.buffers.reserve('meshTriangles', layout.triangleCount);
    this.device.queue.writeBuffer(this.buffers.buffers.meshNodes, 0, tables.nodes);
    this.device.queue.writeBuffer(this.buffers.buffers.meshTriangles, 0, tables.triangles);
    this.meshes = layout;
    this.held = layout.meshes;
  }

  private ensureData(records: number): void {
    if (this.data.byteLength >= records * COLLIDER.size) return;
    this.data = new ArrayBuffer(records * COLLIDER.size);
    this.view = new DataView(this.data);
  }

  /**
   * Record `r`: collider k's pose and shape as it is now (a mesh: where its tables are), and its surface motion if
   * `moving` (else zero).
   */
  private encode(c: PosedCollider, k: number, r: number, moving: boolean): void {
    const v = this.view, at = r * COLLIDER.size, R = c.R, o = c.o, D = c.RD, oD = c.oD;
    const rows = POSE_ROWS, motion = MOTION_ROWS;
    for (let i = 0; i < 3; i++) {
      for (let j = 0; j < 3; j++) {
        v.setFloat32(at + rows[i] + 4 * j, R[3 * i + j], true);
        // M = I − RD in f64 first: the motion M·p + m is small, and would be lost to f32 rounding of p − RD·p
        v.setFloat32(at + motion[i] + 4 * j, moving ? (i === j ? 1 : 0) - D[3 * i + j] : 0, true);
      }
      v.setFloat32(at + rows[i] + 12, o[i], true);
      v.setFloat32(at + motion[i] + 12, moving ? -oD[i] : 0, true);
      v.setFloat32(at + COLLIDER.shape + 4 * i, c.shapeParams[i], true);
    }
    v.setFloat32(at + COLLIDER.shape + 12, 0, true);
    v.setUint32(at + COLLIDER.kind, c.typeId, true);
    v.setUint32(at + COLLIDER.moving, moving ? 1 : 0, true);
    v.setUint32(at + COLLIDER.meshRoot, this.meshes.roots[k], true);
    v.setUint32(at + COLLIDER.meshClosed, this.meshes.closed[k], true);
  }
}
