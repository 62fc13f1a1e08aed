/**
 * What the global steps (global-stretch.ts, global-bending.ts) share: a linear system over the particles of one model,
 * the same scalar matrix for x, y and z, ordered once by nested dissection and factored once per substep length and
 * pins (sparse.ts), with the grabbed particle held exactly without a refactor.
 */
import type { ClothModel } from '../model.js';
import type { ClothState } from '../state.js';
import { SparseCholesky, nestedDissection, orderedGraph } from './sparse.js';

export class PrefactoredSystem {
  readonly model: ClothModel;
  /** particle masses [kg] */
  readonly mass: Float64Array;
  /** row of each particle in the factored order */
  readonly row: Int32Array;
  readonly chol: SparseCholesky;
  /** the pins (state.pinned) the factor was made for, and its substep length [s] */
  readonly pinned: Uint8Array;
  h = NaN;
  /** the right-hand sides, by row (three coordinates interleaved); then the solution */
  readonly b: Float64Array;
  /** z = A⁻¹·e_g for the grabbed particle `zFor` (-1: none yet), by row */
  readonly z: Float64Array;
  zFor = -1;

  /**
   * The system over the model's particles of these masses [kg], whose matrix joins the particles of the graph
   * (compressed rows).
   */
  constructor(model: ClothModel, mass: ArrayLike<number>, rowStart: Int32Array, cols: Int32Array) {
    this.model = model;
    this.mass = Float64Array.from(mass);
    const n = model.particleCount;
    const ordered = orderedGraph(rowStart, cols, nestedDissection(rowStart, cols));
    this.row = ordered.row;
    this.chol = new SparseCholesky(ordered.rowStart, ordered.cols);
    this.pinned = new Uint8Array(n);
    this.b = new Float64Array(3 * n);
    this.z = new Float64Array(n);
  }

  /**
   * Starts assembling the matrix for substep h and the pins of `pinned` with its inertia, M/h² (a pinned particle's
   * row: the identity); then chol.add …, chol.factor().
   */
  beginFactor(pinned: Uint8Array, h: number): void {
    const { chol, row, mass } = this;
    this.pinned.set(pinned);
    this.h = h;
    this.zFor = -1;
    chol.clear();
    const inertia = 1 / (h * h);
    for (let i = 0; i < mass.length; i++) chol.add(row[i], row[i], pinned[i] ? 1 : mass[i] * inertia);
  }

  /**
   * Sets b to the inertia's part of the right-hand side for substep h: M/h²·t on a free particle's rows, t on a pinned
   * one's (its row is the identity); t by particle, xyz [m].
   */
  inertiaTerms(pinned: Uint8Array, t: ArrayLike<number>, h: number): void {
    const { b, row, mass } = this, inertia = 1 / (h * h);
    for (let i = 0; i < mass.length; i++) {
      const q = 3 * row[i], j = 3 * i, w = pinned[i] ? 1 : mass[i] * inertia;
      b[q] = w * t[j]; b[q + 1] = w * t[j + 1]; b[q + 2] = w * t[j + 2];
    }
  }

  /** Whether the factor is for these pins and this h. */
  current(pinned: Uint8Array, h: number): boolean {
    if (h !== this.h) return false;
    const mine = this.pinned;
    for (let i = 0; i < mine.length; i++) if (mine[i] !== pinned[i]) return false;
    return true;
  }

  /** The particle the solve must hold where the grab put it (-1: none), with z = A⁻¹·e_g solved for it. */
  grabbed(state: ClothState): number {
    const g = state.grabbed >= 0 && !state.pinned[state.grabbed] ? state.grabbed : -1;
    if (g >= 0 && this.zFor !== g) {
      const z = this.z;
      z.fill(0);
      z[this.row[g]] = 1;
      this.chol.solve(z);
      this.zFor = g;
    }
    return g;
  }

  /**
   * Holds particle g at p in the solution b: with z = A⁻¹·e_g, x + z·(p − x_g)/z_g is the exact solution with x_g = p
   * (the grab, without a refactor).
   */
  hold(g: number, px: number, py: number, pz: number): void {
    const { b, z, row } = this;
    const q = 3 * row[g], zg = z[row[g]];
    const m0 = (px - b[q]) / zg, m1 = (py - b[q + 1]) / zg, m2 = (pz - b[q + 2]) / zg;
    for (let i = 0; i < z.length; i++) {
      const zi = z[i], p = 3 * i;
      b[p] += zi * m0; b[p + 1] += zi * m1; b[p + 2] += zi * m2;
    }
  }
}
