/** Read-only measurements of a running cloth: energy, strain, penetration, extent. */
import { BEND, STRUCTURAL, bendingStencils, type ClothModel } from './model.js';
import type { SimParams } from './params.js';
import type { ClothState } from './state.js';
import { heldHingeShare } from './solvers/global-bending.js';

export interface Energy {
  /** Σ ½·m·|v|² [J] */
  kinetic: number;
  /** Σ −m·(g · x) [J], zero at the origin */
  gravitational: number;
  /**
   * elastic energy stored in the cloth's shape [J], from the positions for every solver: Σ ½·k·(|d| − L)² over the
   * springs with the stiffness they act with (params.stiffness) and, with a stencil bending model (hinges,
   * Laplacian), Σ ½·|C|²/α over its stencils (solvers/xpbd.ts solveBending; with the hinges solved together, a hinge
   * beside a held triangle with the global step's compliance, solvers/global-bending.ts heldHingeShare). A constraint the solver leaves unconverged shows as energy: a cloth
   * stretched beyond what its load explains is visibly overstretched here
   */
  elastic: number;
  /** the part of `elastic` in bending [J]: the bend springs, or the bending stencils */
  bending: number;
}

/** Energy of the cloth (see Energy), from its positions and velocities. */
export function energy(model: ClothModel, state: ClothState, params: SimParams): Energy {
  const x = state.positions, v = state.velocities;
  const g = params.gravity;
  let kinetic = 0, gravitational = 0, elastic = 0, bending = 0;
  for (let i = 0; i < model.particleCount; i++) {
    const m = params.particleMass[i];
    const j = 3 * i;
    if (!state.pinned[i]) kinetic += 0.5 * m * (v[j] * v[j] + v[j + 1] * v[j + 1] + v[j + 2] * v[j + 2]);
    gravitational -= m * (g[0] * x[j] + g[1] * x[j + 1] + g[2] * x[j + 2]);
  }
  const sp = model.springs, rest = model.restLengths, k = params.stiffness, kinds = model.springKinds;
  for (let s = 0; s < rest.length; s++) {
    if (!(k[s] > 0)) continue;
    const a = 3 * sp[2 * s], b = 3 * sp[2 * s + 1];
    const len = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
    const e = 0.5 * k[s] * (len - rest[s]) ** 2;
    elastic += e;
    if (kinds[s] === BEND) bending += e;
  }
  const stencils = bendingStencils(model, params.bending);
  if (stencils) {
    const { offsets, vertices, weights: K } = stencils, compliance = params.stencilCompliance;
    const held = params.bending === 'hinges' && params.bendingSolve === 'global';
    let bent = 0;
    for (let e = 0; e < compliance.length; e++) {
      if (compliance[e] === Infinity) continue;
      const alpha = held ? compliance[e] * heldHingeShare(model.restPositions, vertices, offsets[e], state.pinned) : compliance[e];
      let c2 = 0;
      for (let d = 0; d < 3; d++) {
        let c = 0;
        for (let q = offsets[e]; q < offsets[e + 1]; q++) c += K[q] * x[3 * vertices[q] + d];
        c2 += c * c;
      }
      bent += (0.5 * c2) / alpha;
    }
    bending += bent;
    elastic += bent;
  }
  return { kinetic, gravitational, elastic, bending };
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

/** The box of particles first … end − 1 (all by default) [m]. */
export function bounds(state: ClothState, first = 0, end = state.positions.length / 3): Bounds {
  const x = state.positions;
  const min: [number, number, number] = [Infinity, Infinity, Infinity];
  const max: [number, number, number] = [-Infinity, -Infinity, -Infinity];
  for (let j = 3 * first; j < 3 * end; j += 3) {
    for (let k = 0; k < 3; k++) {
      if (x[j + k] < min[k]) min[k] = x[j + k];
      if (x[j + k] > max[k]) max[k] = x[j + k];
    }
  }
  return { min, max };
}

/** The mean position of particles first … end − 1 (all by default) [m]. */
export function centroid(state: ClothState, first = 0, end = state.positions.length / 3): [number, number, number] {
  const x = state.positions;
  let cx = 0, cy = 0, cz = 0;
  for (let j = 3 * first; j < 3 * end; j += 3) { cx += x[j]; cy += x[j + 1]; cz += x[j + 2]; }
  const n = end - first;
  return [cx / n, cy / n, cz / n];
}

/** True when every position is a finite number. */
export function isFinite3(state: ClothState): boolean {
  const x = state.positions;
  for (let j = 0; j < x.length; j++) if (!Number.isFinite(x[j])) return false;
  return true;
}
