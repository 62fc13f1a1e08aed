/** Read-only measurements of a running cloth: energy, strain, penetration, extent. */
import { STRUCTURAL, type ClothModel } from './model.js';
import { FRAME_DT, type SimParams } from './params.js';
import type { ClothState } from './state.js';

export interface Energy {
  /** Σ ½·m·|v|² [J] */
  kinetic: number;
  /** Σ −m·(g · x) [J], zero at the origin */
  gravitational: number;
  /**
   * elastic energy of the springs [J]: mass-spring Σ ½·k·(|d| − L)²; XPBD Σ ½·α·f² with the force the solver
   * applied in the last substep, f = λ/h² (the same thing once the constraints converge; while they have not, the
   * length error of a stiff spring is solver lag, not stored energy)
   */
  elastic: number;
}

/** Energy of the cloth; `dt` is the frame length the state was stepped with (for XPBD's f = λ/h²). */
export function energy(model: ClothModel, state: ClothState, params: SimParams, dt = FRAME_DT): Energy {
  const x = state.positions, v = state.velocities, mw = model.massWeights;
  const g = params.gravity;
  let kinetic = 0, gravitational = 0, elastic = 0;
  for (let i = 0; i < model.particleCount; i++) {
    const m = params.mass * mw[i];
    const j = 3 * i;
    if (!state.pinned[i]) kinetic += 0.5 * m * (v[j] * v[j] + v[j + 1] * v[j + 1] + v[j + 2] * v[j + 2]);
    gravitational -= m * (g[0] * x[j] + g[1] * x[j + 1] + g[2] * x[j + 2]);
  }
  if (params.solver === 'xpbd') {
    const h = dt / params.substeps;
    const lambdas = state.lambdas, compliance = params.compliance;
    for (let s = 0; s < lambdas.length; s++) {
      const f = lambdas[s] / (h * h);
      if (compliance[s] !== Infinity) elastic += 0.5 * compliance[s] * f * f;
    }
    return { kinetic, gravitational, elastic };
  }
  const sp = model.springs, rest = model.restLengths, k = params.stiffness;
  for (let s = 0; s < rest.length; s++) {
    const a = 3 * sp[2 * s], b = 3 * sp[2 * s + 1];
    const len = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
    const e = len - rest[s];
    elastic += 0.5 * k[s] * e * e;
  }
  return { kinetic, gravitational, elastic };
}

/** Largest (length − rest)/rest over structural springs [-]. */
export function maxStructuralStrain(model: ClothModel, state: ClothState): number {
  const x = state.positions, sp = model.springs, rest = model.restLengths;
  let worst = -Infinity;
  for (let s = 0; s < rest.length; s++) {
    if (model.springKinds[s] !== STRUCTURAL) continue;
    const a = 3 * sp[2 * s], b = 3 * sp[2 * s + 1];
    const strain = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]) / rest[s] - 1;
    if (strain > worst) worst = strain;
  }
  return worst === -Infinity ? 0 : worst;
}

const normal = new Float64Array(3);
const bary = new Float64Array(3);

/**
 * Deepest point of the cloth surface — any particle, or any point of a triangle for shapes that can poke
 * between vertices — inside any collider [m]; 0 when nothing is inside. Measured against the collider surface,
 * not the contact thickness.
 */
export function maxPenetration(model: ClothModel, state: ClothState, params: SimParams): number {
  const x = state.positions;
  let deepest = 0;
  for (const shape of params.colliders) {
    for (let i = 0; i < model.particleCount; i++) {
      const d = shape.signedDistance(x[3 * i], x[3 * i + 1], x[3 * i + 2], normal);
      if (-d > deepest) deepest = -d;
    }
    if (!shape.triangleDeepest) continue;
    const t = model.triangles;
    for (let k = 0; k < t.length; k += 3) {
      const d = shape.triangleDeepest(x, 3 * t[k], x, 3 * t[k + 1], x, 3 * t[k + 2], bary, normal);
      if (-d > deepest) deepest = -d;
    }
  }
  return deepest;
}

export interface Bounds {
  min: [number, number, number];
  max: [number, number, number];
}

export function bounds(state: ClothState): Bounds {
  const x = state.positions;
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (let j = 0; j < x.length; j += 3) {
    for (let k = 0; k < 3; k++) {
      if (x[j + k] < min[k]) min[k] = x[j + k];
      if (x[j + k] > max[k]) max[k] = x[j + k];
    }
  }
  return { min, max };
}

export function centroid(state: ClothState): [number, number, number] {
  const x = state.positions;
  let cx = 0, cy = 0, cz = 0;
  for (let j = 0; j < x.length; j += 3) { cx += x[j]; cy += x[j + 1]; cz += x[j + 2]; }
  const n = x.length / 3;
  return [cx / n, cy / n, cz / n];
}

/** True when every position is a finite number. */
export function isFinite3(state: ClothState): boolean {
  const x = state.positions;
  for (let j = 0; j < x.length; j++) if (!Number.isFinite(x[j])) return false;
  return true;
}
