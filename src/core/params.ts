import { shapeNotes, type MeshResolver } from './cloth-shape.js';
import { createColliders, type PosedCollider } from './colliders/index.js';
import { BEND_SPRING_PER_RIGIDITY } from './fabrics.js';
import { BEND, SHEAR, SPRING_KINDS, STRUCTURAL, bendingStencils, type ClothModel } from './model.js';
import { resolvePins } from './pins.js';
import { PHASE } from './layout.generated.js';
import { MAX_SUBSTEPS } from './scene-schema.js';
import { contactDistanceFor, selfContactSubsteps } from './self-contact.js';
import { SceneError, clothEntries, type BendingModel, type Scene, type SolverType, type StretchSolve, type BendingSolve } from './scene.js';

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

/**
 * Why a kernel that reads one value for the whole model (the WebAssembly kernel, the GPU) cannot run phase `id`
 * with these params, or null: the scene's cloths differ in a value the phase reads (params.perCloth) — contact
 * reads the thickness and friction, the springs' pass their damping and stretch limit, the tethers and the
 * stretch limit the stretch limit.
 */
export function perClothRefusal(id: number, params: SimParams): string | null {
  // (called every frame for each phase: constant strings and no closure, so that it allocates nothing)
  const p = params.perCloth;
  if (id === PHASE.contact || id === PHASE.contactTriangles) {
    if (varies(p.thickness)) return "the scene's cloths differ in cloth.thickness";
    if (varies(p.friction)) return "the scene's cloths differ in material.friction";
    if (varies(p.staticFriction)) return "the scene's cloths differ in material.staticFriction";
  } else if (id === PHASE.distance) {
    if (varies(p.damping)) return "the scene's cloths differ in material.damping";
    if (varies(p.stretchFactor)) return "the scene's cloths differ in material.stretchFactor";
  } else if (id === PHASE.tethers || id === PHASE.stretchLimit) {
    if (varies(p.stretchFactor)) return "the scene's cloths differ in material.stretchFactor";
  }
  return null;
}

/** Whether the cloths' values differ. */
function varies(v: Float64Array): boolean {
  for (let i = 1; i < v.length; i++) if (v[i] !== v[0]) return true;
  return false;
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
  /** mass of the whole cloth [kg] (of all the cloths): material.mass, or material.arealDensity × the rest area, summed */
  mass: number;
  /** mass of each particle [kg]: its cloth's mass × its share of it (model.massWeights) */
  particleMass: Float64Array;
  /** inverse mass of each particle when free [1/kg] */
  particleInvMass: Float32Array;
  /** effective Hooke constant of each spring [N/m] (after resolution scaling and any stability clamp) */
  stiffness: Float32Array;
  /** XPBD compliance of each spring, 1/stiffness [m/N]; Infinity for a spring with no stiffness */
  compliance: Float32Array;
  /** the xpbd solver's bending model (solver.bending; the mass-spring solver always uses springs) */
  bending: BendingModel;
  /** how the xpbd solver solves its springs (solver.stretch; 'gauss-seidel' for the mass-spring solver, unused there) */
  stretch: StretchSolve;
  /** how the xpbd solver solves a stencil bending model (solver.bendingSolve; 'gauss-seidel' where there are no stencils) */
  bendingSolve: BendingSolve;
  /** whether the cloth is kept from passing through itself (solver.selfContact; self-contact.ts) */
  selfContact: boolean;
  /**
   * fastest the grab carries its particle [m/s]: with self-contact, solver.selfContactSpeed (the speed the substeps
   * let self-contact catch; a faster drag tears the grabbed corner through the cloth), else Infinity
   */
  grabSpeed: number;
  /** bending rigidity B of the sheet [N·m] (material.bendingRigidity; the first cloth's, each stencil's own is in stencilCompliance) */
  bendingRigidity: number;
  /**
   * XPBD compliance of each bending stencil of the params' model (model.stencils[bending]: hinges or Laplacian
   * vertices), A/B [m²/(N·m)]; Infinity where B = 0 or the stencil's weights are all zero; empty for the springs
   */
  stencilCompliance: Float32Array;
  /**
   * damping time τ of each bending stencil [s], for the bending solved together (solver.bendingSolve 'global'): its
   * cloth's material.damping over its bend spring's stiffness, β/(BEND_SPRING_PER_RIGIDITY·B), the time a skip-one
   * bend spring's damping has; 0 where B = 0 (empty for the springs)
   */
  stencilDamping: Float32Array;
  /** spring damping on relative velocity [N·s/m] (material.damping; the xpbd solver's β) */
  damping: number;
  /** the mass-spring solver's damping of each spring [N·s/m]: `damping`, lowered where the stability limit needs it */
  springDamping: Float64Array;
  /** mass-spring stretch limit: max length / rest length of structural and shear springs [-] */
  stretchFactor: number;
  /** kinetic friction coefficient [-] */
  friction: number;
  /** static friction coefficient, at least the kinetic one [-] */
  staticFriction: number;
  /** contact thickness [m]; with several cloths the largest of theirs (what bounds contact's reach) */
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
  /** the cloth of each particle (model.clothStarts): its index into `perCloth` */
  owner: Uint8Array;
  /**
   * each cloth's own contact and spring values, indexed by cloth: contact thickness [m], kinetic and static
   * friction [-], spring damping [N·s/m], stretch limit [-]. The TypeScript reference reads these (a particle or a
   * spring by its cloth; between two cloths the mean thickness and the geometric mean of the frictions); the scalars
   * `thickness` … `stretchFactor` above are the cloths' one value where they agree (else the kernels that read
   * them refuse the phases: perClothRefusal)
   */
  perCloth: { thickness: Float64Array; friction: Float64Array; staticFriction: Float64Array; damping: Float64Array; stretchFactor: Float64Array };

  /** one line per value that had to be clamped, for the UI and CLI to show; empty when none */
  clamps: string[];
}

/**
 * The most particles a cloth solved together (solver.stretch or solver.bendingSolve 'global') may have: its factor is
 * made on the CPU, whichever backend steps it, every time the params or the pins change. On a grid (cotton-basic,
 * hinges) at 128 faces a side (16 641 particles) the factor has 1.3 million entries and takes 0.45 s to order and
 * factor on this machine, at 256 (66 049) 6.6 million and 2.6 s, at 512 (263 169) 32 million, 21 s and 1.7 GB:
 * past 256 a slider's change would stop the app for many seconds, and 1024 would not fit in memory.
 */
export const GLOBAL_SOLVE_MOST_PARTICLES = 66_049;

/**
 * Safety margins of the explicit mass-spring step (see limitPerSpring): every particle keeps w_i·Σk ≤ this / h²
 * (so h²·λ_max(M⁻¹K) ≤ 2, where Verlet is stable below 4) and w_i·Σc ≤ this / h for the spring damping (so
 * h·λ_max(M⁻¹C) ≤ 1, stable below 2). For a mode of both K and C (eigenvalues ω², γ; they share their modes where
 * c/k is the same on every spring) that gives h²ω² + 2hγ ≤ 4 even with both at their bounds, the damped Verlet
 * step's own stability condition (its trace and determinant: det = 1 − hγ, and 1 + det ≥ |trace| =
 * |2 − h²ω² − hγ|), so the two limits do not add up to an unstable pair.
 */
const MASS_SPRING_STIFFNESS_MARGIN = 1;
const MASS_SPRING_DAMPING_MARGIN = 0.5;

/**
 * Limits per-spring coefficients (stiffness k [N/m] or damping c [N·s/m], in place) so that at every particle
 * w_i·Σ_{springs at i} value ≤ limit, lowering only the springs at the particles that need it:
 * f_i = min(1, limit / (w_i·Σ_i value)), and each spring is scaled by min(f_a, f_b) of its two ends.
 *
 * Why this keeps the explicit step stable: the step is stable while h²·λ_max(M⁻¹K) (and h·λ_max(M⁻¹C)) stays
 * below a bound. M⁻¹K is similar to the symmetric M^-½·K·M^-½, so its eigenvalues are real, and by Gershgorin's
 * theorem in block form (Feingold & Varga 1962: 3×3 blocks, spectral norms) each lies within the sum of row i's
 * block norms for some i: the diagonal block w_i·Σ_s k_s·d̂_s d̂_sᵀ and one block w_i·k_s·d̂_s d̂_sᵀ per neighbour,
 * each of norm ≤ w_i·k_s (a spring's Hessian k·(d̂d̂ᵀ + (1 − L/|d|)(I − d̂d̂ᵀ)) has norm k from half its rest length
 * up), so λ_max ≤ 2·max_i(w_i·Σ_s k_s). After the scaling, row i sums to 2·w_i·Σ_s k_s·min(f_a, f_b) ≤
 * 2·f_i·w_i·Σ_s k_s ≤ 2·limit: the same bound the global clamp (every spring scaled by the worst particle's f)
 * gave, while springs whose two ends both satisfy the bound keep their full value. The same argument holds for the
 * damping matrix C (the same structure with c_s for k_s).
 *
 * Returns how many springs were lowered, the smallest factor, and the smallest factor of each spring kind.
 */
function limitPerSpring(model: ClothModel, invMass: Float32Array, values: Float32Array | Float64Array, limit: number): { limited: number; worst: number; worstByKind: [number, number, number] } {
  const n = model.particleCount, springs = model.springs, m = values.length;
  const sum = new Float64Array(n);
  for (let s = 0; s < m; s++) {
    sum[springs[2 * s]] += values[s];
    sum[springs[2 * s + 1]] += values[s];
  }
  const f = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    const load = invMass[i] * sum[i];
    f[i] = load > limit ? limit / load : 1;
  }
  let limited = 0, worst = 1;
  const worstByKind: [number, number, number] = [1, 1, 1];
  for (let s = 0; s < m; s++) {
    const g = Math.min(f[springs[2 * s]], f[springs[2 * s + 1]]);
    if (g >= 1 || values[s] === 0) continue;
    values[s] *= g;
    limited++;
    if (g < worst) worst = g;
    const kind = model.springKinds[s];
    if (g < worstByKind[kind]) worstByKind[kind] = g;
  }
  return { limited, worst, worstByKind };
}

const fmt = (v: number) => (Math.abs(v) >= 100 ? v.toFixed(0) : v.toPrecision(3));
/** a fraction as a percentage in words: '3.1 %', '0.00016 %' */
const percent = (f: number) => `${+(100 * f).toPrecision(2)} %`;

/**
 * The axis springs' constant k_s [N/m] of a square grid that also has both diagonals (shear springs, k_d) for which
 * the sheet's tensile stiffness is k. In a uniform strain the diagonals store k_d·((ε_x + ε_y)²/2 + 2ε_xy²) per unit
 * area beside the axis springs' ½k_s(ε_x² + ε_y²), so the shear stiffness is k_d and, pulled along an axis and free to
 * contract across it, the sheet's stiffness is k_s + k_d·k_s/(k_s + k_d). Solved for k_s: the positive root of
 * k_s² + (2k_d − k)·k_s − k·k_d = 0. (Without this, rubber's diagonals made its sheet 1.3 times as stiff as its k.)
 */
export function axisSpringStiffness(k: number, kd: number): number {
  if (!(kd > 0) || !(k > 0)) return k;
  const b = 2 * kd - k;
  // the positive root, written so that it does not cancel when k_d ≫ k
  return b >= 0 ? (2 * k * kd) / (b + Math.sqrt(b * b + 4 * k * kd)) : (-b + Math.sqrt(b * b + 4 * k * kd)) / 2;
}

export function resolveParams(model: ClothModel, scene: Scene, dt = FRAME_DT, meshes?: MeshResolver): SimParams {
  const entries = clothEntries(scene), parts = model.clothParts ?? [model];
  if (parts.length !== entries.length) throw new Error(`resolveParams: the model has ${parts.length} cloths, the scene ${entries.length}`);
  const m = scene.material;
  const n = model.particleCount;
  const springCount = model.restLengths.length;
  // each cloth's spring constants by kind [N/m] and mass [kg]; the bend springs' constant at the reference spacing
  // from B (docs/materials.md, "Bend spring")
  const kindKs = entries.map(({ material: mc }, c) => {
    const axis = mc.scaleWithResolution && parts[c].springCounts[SHEAR] > 0 ? axisSpringStiffness(mc.structuralStiffness, mc.shearStiffness) : mc.structuralStiffness;
    return [axis, mc.shearStiffness, mc.bendingRigidity * BEND_SPRING_PER_RIGIDITY];
  });
  const kindK = kindKs[0];
  const clothMass = entries.map(({ material: mc }, c) => mc.mass ?? (mc.arealDensity ?? 0) * parts[c].area);
  const mass = clothMass.reduce((a, b) => a + b, 0);
  // what a cloth's spec asks that its shape does not do: said, not done silently
  const clamps: string[] = entries.flatMap((e, c) => shapeNotes(e.cloth, scene.cloths ? `cloths[${c}].` : ''));
  // the cloth of each particle
  const owner = new Uint8Array(n);
  for (let c = 1; c < parts.length; c++) owner.fill(c, model.clothStarts[c], model.clothStarts[c + 1]);

  const particleMass = new Float64Array(n), particleInvMass = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    particleMass[i] = clothMass[owner[i]] * model.massWeights[i];
    particleInvMass[i] = 1 / particleMass[i];
  }

  const stiffness = new Float32Array(springCount);
  for (let s = 0; s < springCount; s++) stiffness[s] = kindKs[owner[model.springs[2 * s]]][model.springKinds[s]] * model.stiffnessScales[s];

  const perCloth = {
    thickness: Float64Array.from(entries, (e) => e.cloth.thickness),
    friction: Float64Array.from(entries, (e) => e.material.friction),
    staticFriction: Float64Array.from(entries, (e) => Math.max(e.material.staticFriction, e.material.friction)),
    damping: Float64Array.from(entries, (e) => e.material.damping),
    stretchFactor: Float64Array.from(entries, (e) => e.material.stretchFactor),
  };
  // self-contact keeps two layers apart only while they move less than the contact distance in one substep
  // (docs/physics.md, "Substeps for self-contact"): on a fine mesh or a thin cloth, more substeps than the scene asks
  const asked = scene.solver.substeps, speed = scene.solver.selfContactSpeed;
  const hContact = scene.solver.selfContact ? contactDistanceFor(model, perCloth.thickness) : 0;
  const forContact = selfContactSubsteps(hContact, speed, dt);
  const substeps = Math.max(asked, Math.min(forContact, MAX_SUBSTEPS));
  if (forContact > asked) {
    clamps.push(
      `self-contact at ${asked} substeps: cloth moving at ${Number(speed.toPrecision(3))} m/s (solver.selfContactSpeed) would travel ` +
      `${fmt((speed * dt) / asked / hContact)} times the contact distance (${fmt(hContact * 1000)} mm) in one substep and could pass ` +
      `through itself, so it runs at ${substeps} substeps${forContact > MAX_SUBSTEPS ? ` (the most there can be; ${forContact} would keep it apart)` : ''} — ` +
      'fewer with a thicker cloth (cloth.thickness), a coarser mesh (h is at most half the thinnest triangle\'s ' +
      'smallest altitude: one sliver sets it), a lower solver.selfContactSpeed, or self-contact off',
    );
  }
  const h = dt / substeps;
  const damping = m.damping;

  const springDamping = new Float64Array(springCount);
  for (let s = 0; s < springCount; s++) springDamping[s] = perCloth.damping[owner[model.springs[2 * s]]];
  if (scene.solver.type === 'mass-spring') {
    const kindNames = SPRING_KINDS;
    const k = limitPerSpring(model, particleInvMass, stiffness, MASS_SPRING_STIFFNESS_MARGIN / (h * h));
    // said in words a student follows: what was changed, why, and the fix
    if (k.limited > 0) {
      const kinds = k.worstByKind.map((f, kind) => {
        if (f >= 1) return '';
        return kind === STRUCTURAL && parts.length === 1 ? `structural ${fmt(kindK[kind] * f)} of ${fmt(kindK[kind])} N/m` : `${kindNames[kind]} ${percent(f)}`;
      }).filter(Boolean);
      clamps.push(
        `mass-spring at ${substeps} substeps: ${k.limited} of ${springCount} springs are too stiff for so long a ` +
        `time step and were softened, the most to ${percent(k.worst)} of their stiffness (${kinds.join('; ')}) — ` +
        'at full stiffness these explicit springs would overshoot and blow up. For the full stiffness: more ' +
        'substeps (solver.substeps), or the xpbd solver',
      );
    }
    const d = limitPerSpring(model, particleInvMass, springDamping, MASS_SPRING_DAMPING_MARGIN / h);
    if (d.limited > 0) {
      clamps.push(
        `mass-spring at ${substeps} substeps: the damping is too strong for so long a time step on ${d.limited} of ` +
        `${springCount} springs and was weakened there, the most to ${fmt(damping * d.worst)} N·s/m (asked ` +
        `${fmt(damping)}) — more would overshoot and blow up. For the full damping: more substeps ` +
        '(solver.substeps), or the xpbd solver',
      );
    }
  }

  // the xpbd solver bends with springs or with a stencil model (hinges, Laplacian), not both
  const bending: BendingModel = scene.solver.type === 'xpbd' ? scene.solver.bending : 'springs';
  // the solves together up to GLOBAL_SOLVE_MOST_PARTICLES; past it, one constraint at a time, saying so
  const large = n > GLOBAL_SOLVE_MOST_PARTICLES;
  let stretch = scene.solver.type === 'xpbd' ? scene.solver.stretch : 'gauss-seidel';
  let bendingSolve = bending !== 'springs' ? scene.solver.bendingSolve : 'gauss-seidel';
  for (const [path, asked] of [['solver.stretch', stretch], ['solver.bendingSolve', bendingSolve]] as const) {
    if (asked !== 'global' || !large) continue;
    clamps.push(
      `${path} 'global' at ${n.toLocaleString('en')} particles: a cloth solved together has at most ` +
      `${GLOBAL_SOLVE_MOST_PARTICLES.toLocaleString('en')} (257 × 257), whose factor takes seconds to make on the CPU ` +
      'whenever a parameter or a pin changes, and a larger one far more time and memory — so this one is solved one ' +
      'constraint at a time (\'gauss-seidel\'); for the solve together, a coarser mesh (cloth.resolution)',
    );
  }
  if (large) {
    if (stretch === 'global') stretch = 'gauss-seidel';
    bendingSolve = 'gauss-seidel';
  }
  if (bending !== 'springs') for (let s = 0; s < springCount; s++) if (model.springKinds[s] === BEND) stiffness[s] = 0;
  const compliance = new Float32Array(springCount);
  for (let s = 0; s < springCount; s++) compliance[s] = stiffness[s] > 0 ? 1 / stiffness[s] : Infinity;
  const bendingRigidity = m.bendingRigidity;
  const stencils = bendingStencils(model, bending);
  const stencilCompliance = new Float32Array(stencils ? stencils.areas.length : 0);
  const stencilDamping = new Float32Array(stencilCompliance.length);
  for (let e = 0; e < stencilCompliance.length; e++) {
    const { offsets, vertices, weights, areas } = stencils!;
    let any = false;
    for (let k = offsets[e]; k < offsets[e + 1]; k++) if (weights[k] !== 0) any = true;
    const { bendingRigidity: B, damping: beta } = entries[owner[vertices[offsets[e]]]].material;
    stencilCompliance[e] = B > 0 && any ? areas[e] / B : Infinity;
    stencilDamping[e] = B > 0 ? beta / (BEND_SPRING_PER_RIGIDITY * B) : 0;
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
    particleMass,
    particleInvMass,
    stiffness,
    compliance,
    bending,
    stretch,
    bendingSolve,
    selfContact: scene.solver.selfContact,
    grabSpeed: scene.solver.selfContact && speed > 0 ? speed : Infinity,
    bendingRigidity,
    stencilDamping,
    stencilCompliance,
    damping,
    springDamping,
    stretchFactor: m.stretchFactor,
    friction: m.friction,
    staticFriction: Math.max(m.staticFriction, m.friction),
    thickness: Math.max(...perCloth.thickness),
    depenetrationSpeed: scene.solver.depenetrationSpeed,
    wind: {
      // on: the air acts, its drag on the moving cloth and its push where it blows (strength 0 or no direction: still air)
      enabled: scene.wind.enabled,
      strength: scene.wind.strength,
      direction,
      airDensity: scene.wind.airDensity,
      gusts: { ...scene.wind.gusts },
    },
    colliders,
    carried: carriedBy(model, scene, colliders),
    owner,
    perCloth,
    clamps,
  };
}
