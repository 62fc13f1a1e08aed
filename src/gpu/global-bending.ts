/**
 * The global bending step on the GPU (solver.bendingSolve 'global' with a stencil bending model): the CPU's
 * backward-Euler step of the stencils (core/solvers/global-bending.ts), solved with the CPU's own factor. The CPU
 * orders and factors the matrix (in double precision, once per substep length and pins: rarely), and this module puts
 * the factor on the GPU (factor-tables.ts: its structure as tables the triangular solves walk level by level, its values
 * in float32, the grab's column z) with the stencils' coefficients. Per substep the GPU then runs four kernels: each
 * stencil's force term (bendingForces), the right-hand side by row (bendingGather), both triangular solves in one
 * workgroup (factorSolve), the correction applied (bendingApply).
 *
 * The GPU solves for the correction Δx = x − x*, not for the positions as the CPU does: float32's error in a solve
 * grows with what is solved for, and the correction of one substep is millimetres where a position is metres.
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { ClothState } from '../core/state.js';
import { globalBendingSystem, type BendingSystem } from '../core/solvers/global-bending.js';
import type { ClothBuffers } from './buffers.js';
import { FactorTables } from './factor-tables.js';
import type { BufferName } from './layout.js';

/** particle → its stencil entries (k, e), as the stencilIncidence buffer holds them (layout.ts) */
function stencilIncidence(offsets: Uint32Array, vertices: Uint32Array, n: number): Uint32Array<ArrayBuffer> {
  const out = new Uint32Array(n + 1 + 2 * vertices.length);
  const count = new Uint32Array(n + 1);
  for (let k = 0; k < vertices.length; k++) count[vertices[k] + 1]++;
  out[0] = n + 1;
  for (let i = 0; i < n; i++) out[i + 1] = out[i] + 2 * count[i + 1];
  const fill = out.slice(0, n);
  for (let e = 0; e + 1 < offsets.length; e++) {
    for (let k = offsets[e]; k < offsets[e + 1]; k++) {
      const at = fill[vertices[k]];
      out[at] = k;
      out[at + 1] = e;
      fill[vertices[k]] = at + 2;
    }
  }
  return out;
}

/** The global bending step's tables on the GPU of one cloth, kept current with the CPU's system (prepare). */
export class GlobalBendingTables extends FactorTables<BendingSystem> {
  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers) {
    super(device, model, buffers, { index: 'factorIndex', values: 'factorValues', z: 'grabColumn' });
  }

  /**
   * Before a frame whose substeps solve the stencils together, with substep h [s]: the CPU's system for these params,
   * refactored where the pins or h changed (globalBendingSystem), and the GPU's tables made current with it: the
   * structure and the stencils' incidence for a new system, the values and coefficients for a new factor, z for a
   * newly grabbed particle.
   */
  prepare(state: ClothState, params: SimParams, h: number): void {
    const system = globalBendingSystem(this.model, params, state.pinned, h);
    if (!system) throw new Error('GPU solver: the global bending step needs a stencil bending model (solver.bending \'hinges\' or \'laplacian\')');
    this.update(system, state, params, h);
  }

  protected sizes(system: BendingSystem): Partial<Record<BufferName, number>> {
    const { offsets, vertices } = system.stencils, stencils = offsets.length - 1;
    return { bendingCoefficients: stencils, stencilForce: stencils, stencilIncidence: this.model.particleCount + 1 + 2 * vertices.length };
  }

  protected made(system: BendingSystem): void {
    const { offsets, vertices } = system.stencils;
    this.device.queue.writeBuffer(this.buffers.buffers.stencilIncidence, 0, stencilIncidence(offsets, vertices, this.model.particleCount));
  }

  protected factored(system: BendingSystem): void {
    const { stiffness, pull } = system, coefficients = new Float32Array(2 * stiffness.length);
    for (let e = 0; e < stiffness.length; e++) {
      coefficients[2 * e] = stiffness[e];
      coefficients[2 * e + 1] = pull[e];
    }
    if (coefficients.length) this.device.queue.writeBuffer(this.buffers.buffers.bendingCoefficients, 0, coefficients);
  }

  /** the stencils the force kernel runs over (0 before the first prepare) */
  get stencilCount(): number {
    return this.system ? this.system.stiffness.length : 0;
  }
}
