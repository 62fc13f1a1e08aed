/**
 * Built-in scenes shared by the CLI, the tests and the app. Their materials are named fabrics (fabrics.ts; values and
 * sources: docs/materials.md).
 * Each is a partial scene document; everything it leaves out takes the schema's defaults.
 */
import {
  MANNEQUIN_ANIMATIONS, MANNEQUIN_CHEST, MANNEQUIN_PARTS, MANNEQUIN_PELVIS, MANNEQUIN_POSES, mannequinColliders, type MannequinOptions,
} from './mannequin.js';
import { tubeMesh } from './mesh/generators.js';
import { SceneError, validateScene, type ColliderSpec, type PinEntry, type Scene } from './scene.js';


/**
 * A scene's mannequin (mannequin.ts): how it stands and moves, and the pins its colliders carry. Its colliders are
 * the scene's first MANNEQUIN_PARTS.length; `carrier` is the one that carries `pins`.
 */
export interface SceneMannequin {
  options: MannequinOptions;
  /** which of the mannequin's colliders carries the cloth's pins (MANNEQUIN_CHEST, MANNEQUIN_PELVIS) */
  carrier: number;
  pins: PinEntry[];
}

/** The colliders of a mannequin, its pins on the carrier. */
function colliders(m: SceneMannequin): ColliderSpec[] {
  return mannequinColliders(m.options).map((c, k) => (k === m.carrier ? { ...c, pins: m.pins } : c));
}

/** The skirt: a tube round the waist, its top ring carried by the pelvis. */
const skirtCloth = { shape: 'tube', orientation: 'hanging', resolution: 24, width: 0.38, height: 0.55, position: [0, 0.755, 0], rotation: [0, 0, 0] } as const;
/** The top ring of a hanging tube: its particles (the generator's vertex order, which the model keeps) at the top. */
function topRing(cloth: typeof skirtCloth): number[] {
  const x = tubeMesh(cloth).positions;
  let top = -Infinity;
  for (let i = 1; i < x.length; i += 3) top = Math.max(top, x[i]);
  const ring: number[] = [];
  for (let i = 0; i < x.length / 3; i++) if (x[3 * i + 1] > top - 1e-6) ring.push(i);
  return ring;
}

/** The mannequins of the built-in scenes that have one, by scene name. */
const MANNEQUINS: Record<string, () => SceneMannequin> = {
  cape: () => ({ options: { pose: 'stand', animation: 'turn' }, carrier: MANNEQUIN_CHEST, pins: ['top-edge'] }),
  skirt: () => ({ options: { pose: 'stand', animation: 'walk' }, carrier: MANNEQUIN_PELVIS, pins: topRing(skirtCloth) }),
};

/**
 * Where the cantilever's clamp ends [m]: the middle of the 8 cm strip, so that 4 cm (about twice cotton's bending
 * length, 1.88 cm) overhang and the edge falls on a row of particles at every even resolution.
 */
const CANTILEVER_EDGE = 0;

/** Self-contact on (issue 12): every built-in scene has it but the two standard fabric tests (see `cantilever`). */
const SELF = { selfContact: true } as const;

/**
 * The standard fabric tests' bending: the hinges (Bergou et al. 2006) solved together each substep, damped
 * (solvers/global-bending.ts), on every backend. With them every named fabric's bending length reads within 3 % of
 * theory at 16, 32 and 64 faces, and the Cusick disc drapes silk < cotton < leather; with the default skip-one springs
 * every strip hangs nearly straight down (0.07–0.31 of its bending length) and every fabric drapes alike, 0.26–0.29
 * (docs/physics.md "Bending solved together", "The standard fabric tests").
 */
const FABRIC_TEST_SOLVER = { bending: 'hinges', bendingSolve: 'global' } as const;

/**
 * Still air, for the standard fabric tests: they are made in a room, whose air drags on a swinging strip or a disc's
 * skirt until it comes to rest (the wind on at 0 m/s: the drag alone, docs/physics.md "Forces").
 */
const STILL_AIR = { enabled: true, strength: 0 } as const;

const drop = (name: string, description: string, material: object) => ({ name, description, material, solver: SELF });

/** The built-in scene documents; a function makes its document when asked (the mannequin's keys are work to make). */
const BUILTIN: Record<string, object | (() => object)> = {
  'cotton-basic': drop('cotton-basic', 'A 1 m cotton sheet dropped on a sphere', { fabric: 'cotton' }),
  'silk-drape': drop('silk-drape', 'Light, soft silk dropped on a sphere', { fabric: 'silk' }),
  'leather-stiff': drop('leather-stiff', 'Heavy, stiff garment leather dropped on a sphere', { fabric: 'leather' }),
  'rubber-stretch': drop('rubber-stretch', 'A stretchy latex sheet dropped on a sphere', { fabric: 'rubber' }),
  custom: drop('custom', 'Cotton on the sphere, for tweaking every parameter', { fabric: 'cotton' }),
  wind: {
    name: 'wind',
    description: 'A flag pinned along its pole, in gusty wind',
    // a millimetre's bulge: a real flag is never flat; an exactly flat one cannot buckle and droop (docs/physics.md)
    cloth: { orientation: 'hanging', width: 1.5, height: 1, position: [0, 2, 0], imperfection: 0.001 },
    material: { fabric: 'cotton' },
    solver: SELF,
    wind: { enabled: true, strength: 8, direction: [1, 0, 0.2], gusts: { enabled: true, amplitude: 0.5, frequency: 0.4, seed: 7 } },
    // the pole the flag's left edge is pinned along, 1 cm from it: a 4 cm post from the floor to above the flag,
    // which the flag meets when it droops or folds back
    colliders: [{ type: 'cylinder', center: [-0.78, 1.3, 0], axis: [0, 1, 0], radius: 0.02, height: 2.6 }, { type: 'floor', height: 0 }],
    pins: ['left-edge'],
  },
  pins: {
    name: 'pins',
    description: 'Four corners pinned: a hammock',
    cloth: { position: [0, 1.5, 0] },
    material: { fabric: 'cotton' },
    solver: SELF,
    colliders: [{ type: 'floor', height: 0 }],
    pins: ['top-left', 'top-right', 'bottom-left', 'bottom-right'],
  },
  tablecloth: {
    name: 'tablecloth',
    description: 'A cotton tablecloth falling on a table (a 90 × 60 × 75 cm box) on the floor',
    cloth: { width: 1.4, height: 1.1, position: [0, 1, 0] },
    material: { fabric: 'cotton' },
    solver: SELF,
    colliders: [
      { type: 'box', center: [0, 0.375, 0], halfExtents: [0.45, 0.375, 0.3], rotation: [0, 0, 0] },
      { type: 'floor', height: 0 },
    ],
  },
  cape: () => ({
    name: 'cape',
    description: 'A cotton cape hanging from the shoulders of a mannequin that turns 70° to either side and back',
    // swung back 15° about its top edge (y 1.42 m, 15 cm behind the figure's axis), so that it starts clear of every
    // pose and animation the app offers (at a walk's start a shin is bent back 55°, into a cape hanging straight);
    // it falls onto the figure in its first frames
    cloth: { orientation: 'hanging', resolution: 20, width: 0.7, height: 1, position: [0, 0.937037, -0.279409], rotation: [15, 0, 0] },
    material: { fabric: 'cotton' },
    // the mannequin moves its cloth at 1–2 m/s (it turns at most 1.9 rad/s, a leg swings at most 2.3 rad/s): 10
    // substeps keep cloth at 3 m/s within the 5 mm contact distance in a substep
    solver: { ...SELF, substeps: 10, selfContactSpeed: 3 },
    colliders: [...colliders(MANNEQUINS.cape()), { type: 'floor', height: 0 }],
  }),
  skirt: () => ({
    name: 'skirt',
    description: 'A silk skirt (a tube) held at the waist of a mannequin walking in place',
    cloth: skirtCloth,
    material: { fabric: 'silk' },
    solver: { ...SELF, substeps: 10, selfContactSpeed: 3 },
    colliders: [...colliders(MANNEQUINS.skirt()), { type: 'floor', height: 0 }],
  }),
  // The two standard fabric tests keep self-contact off: their specimens never reach themselves (a strip bending
  // over an edge, a disc's folds hanging apart: 0 crossing pairs without it) and it would cost the cantilever's
  // fine strip 20× its frame (docs/physics.md "Self-contact").
  cantilever: {
    name: 'cantilever',
    description: 'ASTM D1388 / Peirce cantilever: a 2.5 cm cotton strip clamped flat, 4 cm (about twice cotton\'s bending length) overhanging the edge; reports the bending length its tip angle gives',
    cloth: { width: 0.025, height: 0.08, resolution: 32, position: [0, 0.5, 0] },
    material: { fabric: 'cotton' },
    colliders: [{ type: 'floor', height: 0 }],
    // the clamp: every particle that starts behind the edge or on it (1 µm spare for the rows' rounding, as the
    // measurement takes a clamped row: textile-tests.ts), half the strip
    pins: [{ min: [-1, 0, -1], max: [1, 1, CANTILEVER_EDGE + 1e-6] }],
    solver: FABRIC_TEST_SOLVER,
    wind: STILL_AIR,
    duration: 6,
    test: { type: 'cantilever', edge: [0, 0.5, CANTILEVER_EDGE], direction: [0, 0, 1] },
  },
  cusick: {
    name: 'cusick',
    description: 'BS 5058 / ISO 9073-9 Cusick drape: a 30 cm woven cotton disc clamped on an 18 cm pedestal; reports the drape coefficient and the folds',
    // the specimen cut from a woven lattice (threads along x and z, so that it shears as softly as the fabric does),
    // clamped between two discs of the pedestal's size as the standard has it: every particle within its radius;
    // laid as unevenly as a real specimen (1 mm RMS), seed 1 of the standard's three specimens
    cloth: { shape: 'disc', lattice: 'weave', width: 0.3, resolution: 48, position: [0, 0.506, 0], perturbation: { amplitude: 0.001, seed: 1 } },
    material: { fabric: 'cotton' },
    pins: [{ center: [0, 0.506, 0], radius: 0.09 }],
    colliders: [{ type: 'cylinder', center: [0, 0.25, 0], axis: [0, 1, 0], radius: 0.09, height: 0.5 }, { type: 'floor', height: 0 }],
    solver: FABRIC_TEST_SOLVER,
    wind: STILL_AIR,
    duration: 6,
    test: { type: 'cusick', center: [0, 0, 0], pedestalRadius: 0.09 },
  },
  resolution: {
    name: 'resolution',
    description: 'The seed\'s mesh-resolution demo: the same cotton cloth dropped with 1 to 4096 faces',
    cloth: { resolution: 1 },
    material: { fabric: 'cotton' },
    solver: SELF,
    resolutionSweep: [1, 2, 4, 8, 16, 32, 64],
  },
  fold: {
    name: 'fold',
    description: 'A cotton sheet dropped corner first onto the floor: it lands in layers, which self-contact keeps apart',
    // hanging and turned 45° about z: a corner points down, 3 cm above the floor
    cloth: { orientation: 'hanging', resolution: 32, position: [0, 0.737, 0], rotation: [0, 0, 45] },
    material: { fabric: 'cotton' },
    solver: SELF,
    colliders: [{ type: 'floor', height: 0 }],
    duration: 3,
  },
  layers: {
    name: 'layers',
    description: 'Three cloths of different fabrics dropped one after another onto the sphere: leather first, then cotton, then silk on top',
    solver: SELF,
    colliders: [{ type: 'sphere', center: [0, 0, 0], radius: 0.5 }, { type: 'floor', height: -0.5 }],
    // each a little larger than the one below it and turned against it, so that no edges line up
    cloths: [
      { name: 'leather', cloth: { resolution: 20, width: 0.9, height: 0.9, position: [0, 0.7, 0] }, material: { fabric: 'leather' } },
      { name: 'cotton', cloth: { resolution: 20, width: 1, height: 1, position: [0, 1.0, 0], rotation: [0, 25, 0] }, material: { fabric: 'cotton' } },
      { name: 'silk', cloth: { resolution: 20, width: 1.1, height: 1.1, position: [0, 1.3, 0], rotation: [0, 50, 0] }, material: { fabric: 'silk' } },
    ],
    duration: 4,
  },
};

/** Names of the built-in scenes, in menu order. */
export const SCENE_NAMES = Object.keys(BUILTIN);

/** Whether `name` is a built-in scene (own names only: 'constructor' or '__proto__' are not scenes). */
export function isBuiltinScene(name: string): boolean {
  return typeof name === 'string' && Object.hasOwn(BUILTIN, name);
}

/** A fresh, validated copy of a built-in scene; throws SceneError naming the built-in scenes for an unknown name. */
export function builtinScene(name: string): Scene {
  if (!isBuiltinScene(name)) {
    throw new SceneError(`unknown scene '${String(name).slice(0, 100)}' (built-in scenes: ${SCENE_NAMES.join(', ')})`);
  }
  const doc = BUILTIN[name];
  return validateScene(typeof doc === 'function' ? doc() : doc, `scene '${name}'`);
}

/** The mannequin of a built-in scene (a fresh copy), or undefined when it has none. */
export function builtinMannequin(name: string): SceneMannequin | undefined {
  if (!isBuiltinScene(name) || !Object.hasOwn(MANNEQUINS, name)) return undefined;
  return MANNEQUINS[name]();
}

/**
 * `scene` with its mannequin (the first MANNEQUIN_PARTS.length colliders, as `mannequin` made them) posed and moved
 * as `options` say instead, carrying the same pins; the cloth and everything else kept. Validated: a cloth the new
 * pose cuts through is refused when the simulation takes the scene.
 */
export function withMannequin(scene: Scene, mannequin: SceneMannequin, options: MannequinOptions): Scene {
  const m = { ...mannequin, options: { ...mannequin.options, ...options } };
  return validateScene({ ...scene, colliders: [...colliders(m), ...scene.colliders.slice(MANNEQUIN_PARTS.length)] }, `scene '${scene.name}'`);
}

/**
 * The mannequin of a scene that started as built-in `name`, with the pose and animation its colliders have now
 * (a link or an edit may have changed them); undefined when `name` has none or the scene's first colliders are not
 * a mannequin of that kind any more.
 */
export function sceneMannequin(scene: Scene, name: string): SceneMannequin | undefined {
  const base = builtinMannequin(name);
  if (!base) return undefined;
  const now = JSON.stringify(scene.colliders.slice(0, MANNEQUIN_PARTS.length));
  for (const pose of MANNEQUIN_POSES) {
    for (const animation of MANNEQUIN_ANIMATIONS) {
      const m = { ...base, options: { ...base.options, pose, animation } };
      if (JSON.stringify(validateScene({ colliders: colliders(m) }).colliders) === now) return m;
    }
  }
  return undefined;
}
