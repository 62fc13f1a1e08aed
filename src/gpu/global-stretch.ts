/**
 * The global stretch step on the GPU (solver.stretch 'global'): the CPU's Projective Dynamics step of the springs
 * (core/solvers/global-stretch.ts), solved with the CPU's own factor, as the global bending step is (global-bending.ts;
 * both keep their factors with factor-tables.ts). The CPU orders and factors the matrix once per substep length and pins; this module
 * puts the factor on the GPU, with each spring's coefficients and the grab's column z. Per substep the GPU copies
 * the predicted positions y (stretchStart), then runs solver.iterations passes of four kernels: each spring's local
 * step as its force term (stretchForces), the right-hand side by row (stretchGather), both triangular solves in one
 * workgroup (stretchSolve, factorSolve.wgsl on this factor's buffers), x = y + Δx (stretchApply).
 *
 * The GPU solves for the correction Δx = x − y, not for the positions as the CPU does: float32's error in a solve
 * grows with what is solved for, and the correction of one substep is millimetres where a position is metres.
 */
import type {} from 'webgpu';
import type { ClothModel } from '../core/model.js';
import type { SimParams } from '../core/params.js';
import type { ClothState } from '../core/state.js';
import { globalStretchSystem, type StretchSystem } from '../core/solvers/global-stretch.js';
import type { ClothBuffers } from './buffers.js';
import { FactorTables } from './factor-tables.js';
import type { BufferName } from './layout.js';

/** particle → its springs, as the springIncidence buffer holds them (layout.ts): 2s at the first end, 2s + 1 at the other */
function springIncidence(springs: Uint32Array, n: number): Uint32Array<ArrayBuffer> {
  const m = springs.length / 2;
  const out = new Uint32Array(n + 1 + 2 * m);
  const count = new Uint32Array(n + 1);
  for (let k = 0; k < 2 * m; k++) count[springs[k] + 1]++;
  out[0] = n + 1;
  for (let i = 0; i < n; i++) out[i + 1] = out[i] + count[i + 1];
  const fill = out.slice(0, n);
  for (let k = 0; k < 2 * m; k++) out[fill[springs[k]]++] = k;
  return out;
}

/** The global stretch step's tables on the GPU of one cloth, kept current with the CPU's system (prepare). */
export class GlobalStretchTables extends FactorTables<StretchSystem> {
  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers) {
    super(device, model, buffers, { index: 'stretchFactorIndex', values: 'stretchFactorValues', z: 'stretchGrabColumn' });
  }

  /**
   * Before a frame whose substeps solve the springs together, with substep h [s]: the CPU's system for these params,
   * refactored where the pins or h changed (globalStretchSystem), and the GPU's tables made current with it: the
   * structure and the springs' incidence for a new system, the values and the springs' coefficients for a new factor,
   * z for a newly grabbed particle.
   */
  prepare(state: ClothState, params: SimParams, h: number): void {
    this.update(globalStretchSystem(this.model, params, state.pinned, h), state, params, h);
  }

  protected sizes(): Partial<Record<BufferName, number>> {
    const n = this.model.particleCount, springs = this.model.restLengths.length;
    return { stretchCoefficients: springs, springForce: springs, springIncidence: n + 1 + 2 * springs, globalY: n };
  }

  protected made(): void {
    this.device.queue.writeBuffer(this.buffers.buffers.springIncidence, 0, springIncidence(this.model.springs, this.model.particleCount));
  }

  /** each spring's coefficients: the springs the CPU's system takes (those with stiffness), with its weights for h */
  protected factored(_system: StretchSystem, params: SimParams, h: number): void {
    const model = this.model, springCount = model.restLengths.length, coefficients = new Float32Array(4 * springCount);
    for (let s = 0; s < springCount; s++) {
      const k = params.stiffness[s];
      if (!(k > 0)) continue;
      const damping = params.springDamping[s] / h;
      coefficients.set([k, model.restLengths[s], damping, k + damping], 4 * s);
    }
    if (coefficients.length) this.device.queue.writeBuffer(this.buffers.buffers.stretchCoefficients, 0, coefficients);
  }
}
