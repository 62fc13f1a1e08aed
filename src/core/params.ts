import type { MeshResolver } from './cloth-shape.js';
import { createColliders, type PosedCollider } from './colliders/index.js';
import { BEND_SPRING_PER_RIGIDITY } from './fabrics.js';
import { BEND, bendingStencils, type ClothModel } from './model.js';
import { resolvePins } from './pins.js';
import { SceneError, type BendingModel, type Scene, type SolverType } from './scene.js';

/** Particles carried by colliders: particle i = particles[k] sits at local[3k..3k+2] in collider[k]'s own frame. */
export interface Carried {
  readonly particles: Uint32Array;
  readonly collider: Uint16Array;
  /** position in the collider's frame [m] (where its rest position is in the collider's pose at time 0) */
  readonly local: Float64Array;
}

/** The particles the colliders carry (`colliders[k].pins`): each at its rest position relative to its collider at time 0. */
function carriedBy(model: ClothModel, scene: Scene, colliders: readonly PosedCollider[]): Carried {
  const owner = new Map<number, number>();
  scene.colliders.forEach((c, k) => {
    for (const i of resolvePins(model, c.pins ?? [], `colliders[${k}].pins`)) {
      const other = owner.get(i);
      if (other !== undefined) throw new SceneError(`colliders[${k}].pins: particle ${i} is carried by colliders[${other}] already`);
      owner.set(i, k);
    }
  });
  const particles = new Uint32Array(owner.size), collider = new Uint16Array(owner.size), local = new Float64Array(3 * owner.size);
  const R = new Float64Array(9), o = new Float64Array(3), x = model.restPositions;
  let n = 0;
  // by collider, then particle: the carry phase poses each collider once per substep
  for (const [i, k] of [...owner].sort((a, b) => a[1] - b[1] || a[0] - b[0])) {
    colliders[k].poseAt(0, R, o);
    const dx = x[3 * i] - o[0], dy = x[3 * i + 1] - o[1], dz = x[3 * i + 2] - o[2];
    particles[n] = i; collider[n] = k;
    local[3 * n] = R[0] * dx + R[3] * dy + R[6] * dz;
    local[3 * n + 1] = R[1] * dx + R[4] * dy + R[7] * dz;
    local[3 * n + 2] = R[2] * dx + R[5] * dy + R[8] * dz;
    n++;
  }
  return { particles, collider, local };
}

/** Length of one simulated frame [s]: frames are 1/60 s everywhere (CLI, app, benchmarks). */
export const FRAME_DT = 1 / 60;

/**
 * What a solver step reads: the scene's numbers turned into per-spring values for one model. Derived, never
 * stored physics: rebuild it (cheap, O(springs)) whenever a parameter changes; the model and state stay.
 */
export interface SimParams {
  solver: SolverType;
  /** substeps per frame [-] */
  substeps: number;
  /** constraint passes per substep [-] */
  iterations: number;
  /** gravitational acceleration [m/s²] */
  gravity: Float64Array;
  /** mass of the whole cloth [kg]: material.mass, or material.arealDensity × the model's rest area */
  mass: number;
  /** inverse mass of each particle when free [1/kg] */
  particleInvMass: Float32Array;
  /** effective Hooke constant of each spring [N/m] (after resolution scaling and any stability clamp) */
  stiffness: Float32Array;
  /** XPBD compliance of each spring, 1/stiffness [m/N]; Infinity for a spring with no stiffness */
  compliance: Float32Array;
  /** the xpbd solver's bending model (solver.bending; the mass-spring solver always uses springs) */
  bending: BendingModel;
  /** bending rigidity B of the sheet [N·m] (material.bendingRigidity) */
  bendingRigidity: number;
  /**
   * XPBD compliance of each bending stencil of the params' model (model.stencils[bending]: hinges or Laplacian
   * vertices), A/B [m²/(N·m)]; Infinity where B = 0 or the stencil's weights are all zero; empty for the springs
   */
  stencilCompliance: Float32Array;
  /** spring damping on relative velocity [N·s/m] (after any stability clamp) */
  damping: number;
  /** mass-spring stretch limit: max length / rest length of structural and shear springs [-] */
  stretchFactor: number;
  /** kinetic friction coefficient [-] */
  friction: number;
  /** static friction coefficient, at least the kinetic one [-] */
  staticFriction: number;
  /** contact thickness [m] */
  thickness: number;
  /** fastest an overlap with a collider that the cloth did not move into is undone [m/s] */
  depenetrationSpeed: number;
  wind: {
    enabled: boolean;
    /** wind speed [m/s] */
    strength: number;
    /** unit direction (zero when the scene's direction is zero) */
    direction: Float64Array;
    /** air density [kg/m³] */
    airDensity: number;
    gusts: { enabled: boolean; amplitude: number; frequency: number; seed: number };
  };
  colliders: PosedCollider[];
  /** particles pinned to a collider and carried with it (the `carry` phase) */
  carried: Carried;
  /** one line per value that had to be clamped, for the UI and CLI to show; empty when none */
  clamps: string[];
}

/** Safety margin of the explicit mass-spring step: h²·max_i(w_i·Σk) ≤ this (Verlet is stable below 2). */
const MASS_SPRING_STIFFNESS_MARGIN = 1;
/** and h·max_i(w_i·Σc) ≤ this for the explicit spring damping (stable below 1). */
const MASS_SPRING_DAMPING_MARGIN = 0.5;


const fmt = (v: number) => (Math.abs(v) >= 100 ? v.toFixed(0) : v.toPrecision(3));

export function resolveParams(model: ClothModel, scene: Scene, dt = FRAME_DT, meshes?: MeshResolver): SimParams {
  const m = scene.material;
  const n = model.particleCount;
  const springCount = model.restLengths.length;
  // the bend springs' constant at the reference spacing, from B (docs/materials.md, "Bend spring")
  const kindK = [m.structuralStiffness, m.shearStiffness, m.bendingRigidity * BEND_SPRING_PER_RIGIDITY];
  const mass = m.mass ?? (m.arealDensity ?? 0) * model.area;
  const clamps: string[] = [];

  const particleInvMass = new Float32Array(n);
  for (let i = 0; i < n; i++) particleInvMass[i] = 1 / (mass * model.massWeights[i]);

  const stiffness = new Float32Array(springCount);
  for (let s = 0; s < springCount; s++) stiffness[s] = kindK[model.springKinds[s]] * model.stiffnessScales[s];

  const substeps = scene.solver.substeps;
  const h = dt / substeps;
  let damping = m.damping;

  if (scene.solver.type === 'mass-spring') {
    // Explicit integration is stable only while h·ω stays small. Gershgorin bounds the largest eigenvalue of
    // M⁻¹K by 2·max_i(w_i·Σ_springs k): scale all stiffnesses down together if the step cannot carry them.
    const kSum = new Float64Array(n);
    for (let s = 0; s < springCount; s++) {
      kSum[model.springs[2 * s]] += stiffness[s];
      kSum[model.springs[2 * s + 1]] += stiffness[s];
    }
    let worst = 0;
    let springsAtWorst = 0;
    const count = new Uint16Array(n);
    for (let s = 0; s < 2 * springCount; s++) count[model.springs[s]]++;
    for (let i = 0; i < n; i++) {
      const v = particleInvMass[i] * kSum[i];
      if (v > worst) worst = v;
      if (particleInvMass[i] * count[i] > springsAtWorst) springsAtWorst = particleInvMass[i] * count[i];
    }
    const limit = MASS_SPRING_STIFFNESS_MARGIN / (h * h);
    if (worst > limit) {
      const f = limit / worst;
      for (let s = 0; s < springCount; s++) stiffness[s] *= f;
      clamps.push(
        `mass-spring: stiffness scaled by ${fmt(f)} for stability at ${substeps} substeps ` +
        `(structural ${fmt(m.structuralStiffness * f)} N/m); raise solver.substeps or use xpbd for the full value`,
      );
    }
    const dLimit = MASS_SPRING_DAMPING_MARGIN / (h * springsAtWorst);
    if (damping > dLimit) {
      clamps.push(`mass-spring: damping limited to ${fmt(dLimit)} N·s/m for stability (asked ${fmt(damping)})`);
      damping = dLimit;
    }
  }

  // the xpbd solver bends with springs or with a stencil model (hinges, Laplacian), not both
  const bending: BendingModel = scene.solver.type === 'xpbd' ? scene.solver.bending : 'springs';
  if (bending !== 'springs') for (let s = 0; s < springCount; s++) if (model.springKinds[s] === BEND) stiffness[s] = 0;
  const compliance = new Float32Array(springCount);
  for (let s = 0; s < springCount; s++) compliance[s] = stiffness[s] > 0 ? 1 / stiffness[s] : Infinity;
  const bendingRigidity = m.bendingRigidity;
  const stencils = bendingStencils(model, bending);
  const stencilCompliance = new Float32Array(stencils ? stencils.areas.length : 0);
  for (let e = 0; e < stencilCompliance.length; e++) {
    const { offsets, weights, areas } = stencils!;
    let any = false;
    for (let k = offsets[e]; k < offsets[e + 1]; k++) if (weights[k] !== 0) any = true;
    stencilCompliance[e] = bendingRigidity > 0 && any ? areas[e] / bendingRigidity : Infinity;
  }

  const d = scene.wind.direction;
  const len = Math.hypot(d[0], d[1], d[2]);
  const direction = new Float64Array(len > 0 ? [d[0] / len, d[1] / len, d[2] / len] : [0, 0, 0]);

  const colliders = createColliders(scene.colliders, meshes);
  return {
    solver: scene.solver.type,
    substeps,
    iterations: scene.solver.iterations,
    gravity: new Float64Array(scene.gravity),
    mass,
    particleInvMass,
    stiffness,
    compliance,
    bending,
    bendingRigidity,
    stencilCompliance,
    damping,
    stretchFactor: m.stretchFactor,
    friction: m.friction,
    staticFriction: Math.max(m.staticFriction, m.friction),
    thickness: scene.cloth.thickness,
    depenetrationSpeed: scene.solver.depenetrationSpeed,
    wind: {
      enabled: scene.wind.enabled && len > 0 && scene.wind.strength > 0,
      strength: scene.wind.strength,
      direction,
      airDensity: scene.wind.airDensity,
      gusts: { ...scene.wind.gusts },
    },
    colliders,
    carried: carriedBy(model, scene, colliders),
    clamps,
  };
}
