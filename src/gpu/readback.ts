/**
 * Reading a GPU cloth back into a CPU state: positions, previous positions, velocities and the springs' λ of the last
 * substep, through one staging buffer, one read at a time; and with self-contact, the most candidate pairs a pass
 * found since the last read (layout.ts selfArgs).
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import type { ClothState } from '../core/state.js';
import { fromVec4, type ClothBuffers } from './buffers.js';

const ZERO = new Uint32Array(1);

/** The readback of one cloth: a staging buffer made on first use, reads serialised. */
export class Readback {
  private readonly device: GPUDevice;
  private readonly model: ClothModel;
  private readonly buffers: ClothBuffers;
  private staging: GPUBuffer | undefined;
  private reading: Promise<void> = Promise.resolve();
  private destroyed = false;
  /** counts the times the cloth was put anew (upload): a copy made before the last of them is of a cloth gone */
  private generation = 0;
  /** the most self-contact candidate pairs any pass found, over the reads since the cloth was last uploaded (0 without self-contact) */
  selfPairsMost = 0;

  /** A readback of `buffers` (a cloth of `model`) on `device`. */
  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers) {
    this.device = device;
    this.model = model;
    this.buffers = buffers;
  }

  /** Copies the GPU cloth into `state`; resolves once the data is there. Calls are serialised. */
  read(state: ClothState): Promise<void> {
    const next = this.reading.then(() => this.readNow(state));
    this.reading = next.catch(() => undefined);
    return next;
  }

  private async readNow(state: ClothState, again = false): Promise<void> {
    // a read asked for before the cloth's buffers were freed runs after the reads ahead of it: by then there may be
    // nothing to copy, and a copy submitted from freed buffers is a validation error on the device, which an error
    // scope open elsewhere (a new solver being made: solver.ts create) would take for its own
    if (this.destroyed) throw new Error('GPU readback: the cloth was freed before its read ran');
    const n = this.model.particleCount;
    const vecBytes = n * 16;
    const lambdaBytes = this.model.restLengths.length * 4;
    const self = this.buffers.hasSelfContact;
    const size = 3 * vecBytes + lambdaBytes + (self ? 4 : 0);
    if (!this.staging || this.staging.size < size) {
      this.staging?.destroy();
      this.staging = this.device.createBuffer({ label: 'drape readback', size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    }
    const staging = this.staging;
    const b = this.buffers.buffers;
    const generation = this.generation;
    const encoder = this.device.createCommandEncoder({ label: 'drape read' });
    encoder.copyBufferToBuffer(b.positions, 0, staging, 0, vecBytes);
    encoder.copyBufferToBuffer(b.previous, 0, staging, vecBytes, vecBytes);
    encoder.copyBufferToBuffer(b.velocities, 0, staging, 2 * vecBytes, vecBytes);
    if (lambdaBytes) encoder.copyBufferToBuffer(b.lambdas, 0, staging, 3 * vecBytes, lambdaBytes);
    if (self) encoder.copyBufferToBuffer(b.selfArgs, 16, staging, 3 * vecBytes + lambdaBytes, 4);
    this.device.queue.submit([encoder.finish()]);
    // the count starts again after what was just copied (the queue keeps the order)
    if (self) this.device.queue.writeBuffer(b.selfArgs, 16, ZERO);
    await staging.mapAsync(GPUMapMode.READ, 0, size);
    if (generation !== this.generation) {
      // the cloth was put anew while this copy was on its way (a reset, a state copied in): it would write the old
      // cloth over the new one, so it is read again, after the upload — once: if it is put anew during that read
      // too, the state keeps what was put (the uploaded cloth)
      staging.unmap();
      if (!again) return this.readNow(state, true);
      return;
    }
    try {
      const all = new Float32Array(staging.getMappedRange(0, size));
      fromVec4(all.subarray(0, 4 * n), state.positions);
      fromVec4(all.subarray(4 * n, 8 * n), state.previousPositions);
      fromVec4(all.subarray(8 * n, 12 * n), state.velocities);
      // the positions' residuals stay on the GPU: a state read back holds its positions to float32 (what a move
      // to the CPU loses is below a position's last bit, once)
      state.residuals.fill(0);
      state.previousResiduals.fill(0);
      if (lambdaBytes) state.lambdas.set(all.subarray(12 * n, 12 * n + this.model.restLengths.length));
      if (self) this.selfPairsMost = Math.max(this.selfPairsMost, new Uint32Array(all.buffer, all.byteOffset + 3 * vecBytes + lambdaBytes, 1)[0]);
    } finally {
      staging.unmap();
    }
  }

  /**
   * The cloth was put anew (an upload): a read whose copy was made before reads again; the self-contact pair count
   * starts again (selfPairsMost 0, and the GPU's since the last read too).
   */
  uploaded(): void {
    this.generation++;
    this.selfPairsMost = 0;
    if (this.buffers.hasSelfContact) this.device.queue.writeBuffer(this.buffers.buffers.selfArgs, 16, ZERO);
  }

  /** Frees the staging buffer; reads not yet run reject without touching the device. */
  destroy(): void {
    this.destroyed = true;
    this.staging?.destroy();
  }
}
