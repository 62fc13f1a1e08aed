/**
 * The global stretch step on the GPU (solver.stretch 'global'): the CPU's Projective Dynamics step of the springs
 * (core/solvers/global-stretch.ts), solved with the CPU's own factor, as the global bending step is (global-bending.ts,
 * whose FactorLayout it shares). The CPU orders and factors the matrix once per substep length and pins; this module
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
import { FactorLayout } from './global-bending.js';

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
export class GlobalStretchTables {
  private readonly device: GPUDevice;
  private readonly model: ClothModel;
  private readonly buffers: ClothBuffers;
  /** the system whose tables the buffers hold (null: placeholders) */
  private system: StretchSystem | null = null;
  private layout: FactorLayout | null = null;
  private values = new Float32Array(0);
  /** the factor (chol.factors) whose values the buffers hold, and the grabbed particle whose z they hold */
  private factors = -1;
  private grabbed = -1;

  constructor(device: GPUDevice, model: ClothModel, buffers: ClothBuffers) {
    this.device = device;
    this.model = model;
    this.buffers = buffers;
  }

  /** The factor as the solves read it: L's entries outside the blocks and the values of the blocks' inverses (0 before the first) */
  get factorSize(): { outside: number; inverse: number } {
    return { outside: this.layout?.outside ?? 0, inverse: this.layout?.inverseValues ?? 0 };
  }

  /**
   * Before a frame whose substeps solve the springs together, with substep h [s]: the CPU's system for these params,
   * refactored where the pins or h changed (globalStretchSystem), and the GPU's tables made current with it: the
   * structure and the springs' coefficients for a new system, the values for a new factor, z for a newly grabbed
   * particle. Before the frame's kernels are encoded (it may make the buffers anew).
   */
  prepare(state: ClothState, params: SimParams, h: number): void {
    const system = globalStretchSystem(this.model, params, state.pinned, h);
    const q = this.device.queue, model = this.model, n = model.particleCount, springCount = model.restLengths.length;
    if (system !== this.system) {
      const layout = new FactorLayout(system.chol, system.row);
      const incidence = springIncidence(model.springs, n);
      this.buffers.remake({
        stretchCoefficients: springCount, springForce: springCount, springIncidence: incidence.length, globalY: n,
        stretchFactorIndex: layout.index.length, stretchFactorValues: layout.valueCount, globalX: n, globalT: n, stretchGrabColumn: n,
      });
      const b = this.buffers.buffers;
      q.writeBuffer(b.stretchFactorIndex, 0, layout.index);
      q.writeBuffer(b.springIncidence, 0, incidence);
      this.system = system;
      this.layout = layout;
      this.values = new Float32Array(layout.valueCount);
      this.factors = -1;
    }
    const b = this.buffers.buffers;
    if (system.chol.factors !== this.factors) {
      this.layout!.values(system.chol, this.values);
      q.writeBuffer(b.stretchFactorValues, 0, this.values);
      // the springs the CPU's system takes (those with stiffness), with its weights for this h
      const coefficients = new Float32Array(4 * springCount);
      for (let s = 0; s < springCount; s++) {
        const k = params.stiffness[s];
        if (!(k > 0)) continue;
        const damping = params.springDamping[s] / h;
        coefficients.set([k, model.restLengths[s], damping, k + damping], 4 * s);
      }
      if (coefficients.length) q.writeBuffer(b.stretchCoefficients, 0, coefficients);
      this.factors = system.chol.factors;
      this.grabbed = -1;
    }
    const g = system.grabbed(state);
    if (g >= 0 && g !== this.grabbed) {
      q.writeBuffer(b.stretchGrabColumn, 0, Float32Array.from(system.z));
      this.grabbed = g;
    }
  }
}
