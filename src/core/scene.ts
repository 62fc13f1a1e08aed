import { Ajv, type ErrorObject } from 'ajv';
import { eulerXYZ } from './mesh/generators.js';
import { BEND_SPRING_PER_RIGIDITY, FABRICS, FABRIC_FIELDS, type FabricName, type FabricValues } from './fabrics.js';
import { PIN_PRESETS, sceneSchema } from './scene-schema.js';
import type { StencilModel } from './model.js';
import { plainText, shownValue } from './text.js';

export type Vec3 = [number, number, number];
/** `cloth.shape` (the list: CLOTH_SHAPES in cloth-shape.ts) */
export type ClothShape = 'rectangle' | 'disc' | 'tube' | 'mesh';
export type PinPreset = (typeof PIN_PRESETS)[number];
/** A pin region: every particle whose start position lies in the box from `min` to `max` [m]. */
export interface PinRegion { min: Vec3; max: Vec3 }
/** A round pin region: every particle whose start position lies within `radius` [m] of `center` [m]. */
export interface PinBall { center: Vec3; radius: number }
/** One entry of a pin list: a preset, a particle index or a region. */
export type PinEntry = PinPreset | number | PinRegion | PinBall;

/** Field meanings, units and defaults: see scene-schema.ts (the one source). */
export interface Scene {
  $schema?: string;
  name: string;
  description?: string;
  /** the cloth (the first of `cloths` when the scene has several) */
  cloth: ClothSpec;
  /** the cloth's material (the first of `cloths`') */
  material: Material;
  /**
   * the scene's cloths when it gives them as a list (`cloths` in the file): cloths[0]'s cloth, material and pins
   * are `cloth`, `material` and `pins` themselves (clothEntries reads the first from those); absent in a one-cloth
   * scene. The first cloth is edited through `cloth`, `material` and `pins` (a copy of the scene with a new `cloth`
   * keeps the list), or on the document (sceneDocument, setScenePath, editCloth): a new cloths[0] beside the old
   * top-level parts is not read
   */
  cloths?: ClothEntry[];
  solver: { type: SolverType; substeps: number; iterations: number; bending: BendingModel; stretch: StretchSolve; bendingSolve: BendingSolve; selfContact: boolean; selfContactSpeed: number; depenetrationSpeed: number };
  gravity: Vec3;
  wind: Wind;
  colliders: ColliderSpec[];
  /** the cloth's pins (the first of `cloths`') */
  pins: PinEntry[];
  /** optional list of resolutions (faces per side) to run the scene at, one after another */
  resolutionSweep?: number[];
  /** how long `drape run` simulates when it is not given --frames [s] */
  duration: number;
  /** the standard fabric test the scene is (textile-tests.ts): what the report's `test` measures */
  test?: SceneTest;
}

export interface ClothSpec {
  shape: ClothShape;
  /** mesh file path (shape 'mesh' only) */
  mesh?: string;
  scale: number;
  resolution: number;
  /** how a disc is meshed: concentric rings, or the rectangle's lattice cut round (its threads along x and z) */
  lattice: 'rings' | 'weave';
  width: number;
  height: number;
  orientation: 'horizontal' | 'hanging';
  position: Vec3;
  rotation: Vec3;
  thickness: number;
  /** a rectangle's out-of-plane bulge at the start, 0 for flat [m] */
  imperfection: number;
  /** a seeded waviness of the start pose (perturbation.ts): its root mean square [m] (0: none) and its seed */
  perturbation: { amplitude: number; seed: number };
}

/** One cloth of a scene: its shape and start pose, its material and its pins (pin indices count from its first particle). */
export interface ClothEntry {
  /** what reports call it (cloth k by default) */
  name?: string;
  cloth: ClothSpec;
  material: Material;
  pins: PinEntry[];
}

/** `test`: a cantilever (ASTM D1388) or a Cusick drape (BS 5058) and where its fixture is. */
export type SceneTest =
  | { type: 'cantilever'; edge: Vec3; direction: Vec3 }
  | { type: 'cusick'; center: Vec3; pedestalRadius: number };

export type SolverType = 'xpbd' | 'mass-spring';
/** `solver.bending`: the xpbd solver's bending model */
export type BendingModel = 'springs' | StencilModel;
/** `solver.stretch`: how the xpbd solver solves its springs (one at a time, or together: solvers/global-stretch.ts) */
export type StretchSolve = 'gauss-seidel' | 'two-level' | 'global';
/** `solver.bendingSolve`: how the xpbd solver solves a stencil bending model (one stencil at a time, or together: solvers/global-bending.ts) */
export type BendingSolve = 'gauss-seidel' | 'global';

/**
 * A validated material: a fabric's measured quantities and the tuning values (scene-schema.ts). Exactly one of
 * `arealDensity` and `mass` is present (mass where the scene gave the whole cloth's mass); `bendStiffness`, the
 * older path for the bend, is read as bendingRigidity and never appears here.
 */
export interface Material extends Omit<FabricValues, 'arealDensity'> {
  fabric?: FabricName;
  arealDensity?: number;
  mass?: number;
  scaleWithResolution: boolean;
}

export interface Wind {
  enabled: boolean;
  strength: number;
  direction: Vec3;
  airDensity: number;
  gusts: { enabled: boolean; amplitude: number; frequency: number; seed: number };
}

/** What every collider may have besides its shape (scene-schema.ts colliderCommon). */
export interface ColliderCommon {
  /** keyframed motion relative to the placement */
  motion?: { keyframes: { time: number; translation: Vec3; rotation: Vec3 }[]; pivot?: Vec3; loop: boolean };
  /** particles pinned to the collider and carried with it (a validated scene has it, [] by default) */
  pins?: PinEntry[];
}

export type ColliderSpec = ColliderCommon & (
  | { type: 'sphere'; center: Vec3; radius: number }
  | { type: 'floor'; height: number }
  | { type: 'plane'; point: Vec3; normal: Vec3 }
  | { type: 'box'; center: Vec3; halfExtents: Vec3; rotation: Vec3 }
  | { type: 'capsule'; a: Vec3; b: Vec3; radius: number }
  | { type: 'cylinder'; center: Vec3; axis: Vec3; radius: number; height: number }
  | { type: 'mesh'; mesh: string; scale: number; position: Vec3; rotation: Vec3 });

/**
 * Every field optional, all the way down, but a three-vector stays a whole three-vector and a collider keeps its
 * `type` (what says which fields it has).
 */
export type DeepPartial<T> = T extends Vec3 ? T
  : T extends readonly (infer U)[] ? DeepPartial<U>[]
  : T extends object ? { [K in keyof T]?: DeepPartial<T[K]> }
  : T;

/** One collider as a scene gives it: its `type`, the rest optional (scene-schema.ts has each field's default). */
export type ColliderInput = ColliderSpec extends infer C ? C extends { type: infer K }
  ? { type: K } & DeepPartial<Omit<C, 'type'>> : never : never;

/**
 * A scene as a program or a file gives it, what `new Simulation(...)`, `setScene` and `validateScene` take: every
 * field optional (validateScene fills each missing one with its default, scene-schema.ts, and checks the rest), e.g.
 * `new Simulation({ cloth: { resolution: 20 } })`. A validated `Scene` is one too.
 */
export type SceneInput = DeepPartial<Omit<Scene, 'colliders' | 'cloths'>> & {
  colliders?: ColliderInput[];
  cloths?: DeepPartial<ClothEntry>[];
};

/** The collider `type`s a scene may name, in the schema's order. */
export const COLLIDER_TYPES = ['sphere', 'floor', 'plane', 'box', 'capsule', 'cylinder', 'mesh'] as const;
/** The standard fabric tests a scene's `test.type` names (textile-tests.ts). */
export const TEST_TYPES = ['cantilever', 'cusick'] as const;

/**
 * Bad scene input: the message is one line and names the field. What it quotes of the input (a key, a path, a name)
 * is made safe to print: a control character, line break or bidirectional override in it is replaced (text.ts).
 */
export class SceneError extends Error {
  constructor(message: string) {
    super(plainText(message, 4000));
    this.name = 'SceneError';
  }
}

/** Ajv's options for the scene validator (the site build compiles its validator ahead with the same: app/precompiled-ajv.ts). */
export const SCENE_VALIDATOR_OPTIONS = { allErrors: true, useDefaults: true, discriminator: true, strict: false } as const;
const ajv = new Ajv(SCENE_VALIDATOR_OPTIONS);
const validateFn = ajv.compile(sceneSchema);

/** 'material/bendStiffness' → 'material.bendStiffness', '/colliders/0/radius' → 'colliders[0].radius' */
function fieldName(instancePath: string, extra?: string): string {
  const parts = instancePath.split('/').filter(Boolean);
  if (extra !== undefined) parts.push(extra);
  let out = '';
  for (const p of parts) out += /^\d+$/.test(p) ? `[${p}]` : out ? `.${p}` : p;
  return out || '(scene)';
}

function describe(e: ErrorObject): string {
  const field = fieldName(e.instancePath);
  const p = e.params as Record<string, unknown>;
  switch (e.keyword) {
    case 'additionalProperties':
      return `${fieldName(e.instancePath, String(p.additionalProperty))}: unknown key`;
    case 'required':
      return `${fieldName(e.instancePath, String(p.missingProperty))}: required`;
    case 'enum':
      return `${field}: must be one of ${(p.allowedValues as unknown[]).map((v) => JSON.stringify(v)).join(', ')}`;
    case 'const':
      return `${field}: must be ${JSON.stringify(p.allowedValue)}`;
    case 'minimum': case 'maximum': case 'exclusiveMinimum': case 'exclusiveMaximum':
      return `${field}: must be ${p.comparison} ${p.limit}`;
    case 'minItems': case 'maxItems':
      return `${field}: ${e.message}`;
    case 'discriminator': {
      // a collider's or the fabric test's type (the two objects chosen by their type)
      const types: readonly string[] = field === 'test' ? TEST_TYPES : COLLIDER_TYPES;
      const allowed = types.map((t) => JSON.stringify(t)).join(', ');
      return p.tagValue === undefined ? `${field}.type: required (one of ${allowed})` : `${field}.type: must be one of ${allowed}, got ${shownValue(p.tagValue)}`;
    }
    default:
      return `${field}: ${e.message ?? 'invalid'}`;
  }
}

/** Picks the most useful error: the deepest one, preferring concrete ones to anyOf/oneOf summaries. */
function pickError(errors: ErrorObject[]): ErrorObject {
  const concrete = errors.filter((e) => e.keyword !== 'anyOf' && e.keyword !== 'oneOf' && e.keyword !== 'if');
  const pool = concrete.length ? concrete : errors;
  // pins items are "preset or integer": say both
  return pool.reduce((best, e) => (e.instancePath.length > best.instancePath.length ? e : best), pool[0]);
}

/**
 * Largest scene file (and, later, mesh file) the CLI and the app read [bytes]: 32 MiB, room for a scene pinning
 * every particle of the largest cloth or a 100k-triangle mesh, small enough to read in well under a second.
 */
export const MAX_INPUT_BYTES = 32 * 2 ** 20;

/** Deepest nesting a scene document may have: the schema's own is 6 (colliders[0].motion.keyframes[0].rotation[0]). */
const MAX_DEPTH = 32;

/** Refuses absurdly nested documents before anything recursive (structuredClone, the validator) sees them. */
function checkDepth(input: object, source: string): void {
  const stack: [unknown, number, string][] = [[input, 1, '']];
  while (stack.length) {
    const [v, depth, path] = stack.pop()!;
    if (v === null || typeof v !== 'object') continue;
    if (depth > MAX_DEPTH) throw new SceneError(`${source}: nested more than ${MAX_DEPTH} levels deep; a scene is at most 6`);
    for (const [key, child] of Object.entries(v)) {
      const at = `${path}/${key}`;
      // NaN and ±Infinity (no JSON has them: a library caller's) fail every range test as it is written, so the
      // schema would name the wrong one ("must be <= 10"): they are named for what they are
      if (typeof child === 'number' && !Number.isFinite(child)) throw new SceneError(`${source}: ${fieldName(at)}: must be a finite number, got ${child}`);
      if (child !== null && typeof child === 'object') stack.push([child, depth + 1, at]);
    }
  }
}

/**
 * The fields of a cloth that the WebAssembly kernel's and the GPU's passes read as one value for the whole model
 * (contact, the springs' damping and stretch limit): where the cloths of a scene differ in one, those passes run
 * in the TypeScript reference (the kernel) or the scene is refused (the GPU). Path → value.
 */
export const PER_CLOTH_FIELDS: readonly [string, (e: ClothEntry) => number][] = [
  ['cloth.thickness', (e) => e.cloth.thickness],
  ['material.damping', (e) => e.material.damping],
  ['material.stretchFactor', (e) => e.material.stretchFactor],
  ['material.friction', (e) => e.material.friction],
  ['material.staticFriction', (e) => e.material.staticFriction],
];

/**
 * The raw parts of one cloth of a document (the top level's cloth and material, or an entry of cloths), before the
 * schema: a mesh file makes the cloth a 'mesh'; a named fabric fills every material field not set (`at` prefixes
 * the fields in errors: '' or 'cloths[1].'). Returns whether the material gives the older `mass`.
 */
function prepareCloth(cloth: unknown, material: unknown, at: string, source: string): boolean {
  const c = cloth !== null && typeof cloth === 'object' && !Array.isArray(cloth) ? cloth as Record<string, unknown> : null;
  // a cloth given by a mesh file is a 'mesh' without saying so
  if (c && c.mesh !== undefined && c.shape === undefined) c.shape = 'mesh';
  // what the scene sets itself, before the schema's defaults fill the rest
  const raw = material !== null && typeof material === 'object' && !Array.isArray(material) ? material as Record<string, unknown> : null;
  const given = (k: string) => raw !== null && Object.hasOwn(raw, k);
  for (const [x, y] of ALIASES) {
    if (given(x) && given(y)) throw new SceneError(`${source}: ${at}material.${y}: give either ${at}material.${x} or ${at}material.${y}, not both (${ALIAS_MEANING[y]})`);
  }
  // a named fabric fills every field the scene leaves out (an unknown name is the schema's to refuse)
  const fabric = raw && typeof raw.fabric === 'string' && Object.hasOwn(FABRICS, raw.fabric) ? FABRICS[raw.fabric as FabricName] : null;
  if (raw && fabric) {
    for (const k of FABRIC_FIELDS) if (!given(k) && !given(ALIAS_OF[k] ?? '')) raw[k] = fabric[k];
  }
  return given('mass');
}

/**
 * One validated cloth's own checks (`at` as in prepareCloth): the older material paths read as theirs (`massGiven`:
 * the whole cloth's mass stands instead of the areal density the schema's default filled), the shape and the mesh
 * file together, pin indices a rectangle has.
 */
function finishCloth(entry: ClothEntry, massGiven: boolean, at: string, source: string): void {
  const m = entry.material as Material & { bendStiffness?: number };
  if (massGiven) delete m.arealDensity;
  if (m.bendStiffness !== undefined) {
    m.bendingRigidity = m.bendStiffness / BEND_SPRING_PER_RIGIDITY;
    delete m.bendStiffness;
  }
  const c = entry.cloth;
  if (c.shape === 'mesh' && c.mesh === undefined) {
    throw new SceneError(`${source}: ${at}cloth.mesh: required when ${at}cloth.shape is 'mesh' (the OBJ or glTF file of the cloth)`);
  }
  if (c.shape !== 'mesh' && c.mesh !== undefined) {
    throw new SceneError(`${source}: ${at}cloth.mesh: only for ${at}cloth.shape 'mesh', and this cloth is a '${c.shape}'`);
  }
  // other shapes check their pins when the model is built (pins.ts resolvePins)
  if (c.shape === 'rectangle') checkPinIndices(entry.pins, (c.resolution + 1) ** 2, `${at}pins`, source);
}

/** Refuses a pin index past the particles a cloth has (n), naming the entry. */
function checkPinIndices(pins: readonly PinEntry[], n: number, field: string, source: string): void {
  pins.forEach((p, k) => {
    if (typeof p === 'number' && p >= n) {
      throw new SceneError(`${source}: ${field}[${k}]: particle ${p} does not exist (cloth has ${n} particles, 0…${n - 1})`);
    }
  });
}

/**
 * Validates a scene document and fills in defaults. Returns a new object; the input is not changed.
 * Throws SceneError with one line naming the field.
 *
 * A document gives its cloth either as `cloth`, `material` and `pins` or as a list `cloths` (never both); the
 * validated scene has `cloth`, `material` and `pins` in either case (the first cloth's), and `cloths` when the
 * document had it (sceneDocument writes it back in that form).
 */
export function validateScene(input: unknown, source = 'scene'): Scene {
  if (input === null || typeof input !== 'object' || Array.isArray(input)) {
    throw new SceneError(`${source}: must be a JSON object`);
  }
  checkDepth(input, source);
  const doc = structuredClone(isValidatedForm(input) ? sceneDocument(input as Scene) : input) as Record<string, unknown>;
  const list = Object.hasOwn(doc, 'cloths') ? doc.cloths : undefined;
  // per cloth (the top level's is [0]): whether its material gives the older mass
  const massGiven: boolean[] = [];
  if (list !== undefined) {
    const both = ['cloth', 'material', 'pins'].find((k) => Object.hasOwn(doc, k));
    if (both) throw new SceneError(`${source}: ${both}: give the cloths either as cloth, material and pins or as a list cloths, not both`);
    if (Array.isArray(list)) {
      list.forEach((e, k) => {
        if (e !== null && typeof e === 'object' && !Array.isArray(e)) {
          const entry = e as Record<string, unknown>;
          massGiven[k] = prepareCloth(entry.cloth, entry.material, `cloths[${k}].`, source);
        }
      });
    }
  } else {
    massGiven[0] = prepareCloth(doc.cloth, doc.material, '', source);
  }
  if (!validateFn(doc)) {
    const errors = validateFn.errors ?? [];
    const isPin = (e: ErrorObject) => /^(\/cloths\/\d+)?\/pins\//.test(e.instancePath);
    const pinErr = errors.find(isPin);
    if (pinErr && errors.every(isPin)) {
      throw new SceneError(`${source}: ${fieldName(pinErr.instancePath)}: must be one of ${PIN_PRESETS.join(', ')} or a particle index (integer ≥ 0)`);
    }
    throw new SceneError(`${source}: ${describe(pickError(errors))}`);
  }
  const scene = doc as unknown as Scene;
  if (scene.cloths) {
    scene.cloths.forEach((e, k) => finishCloth(e, massGiven[k] ?? false, `cloths[${k}].`, source));
    const [first] = scene.cloths;
    // the first cloth is the scene's cloth (the schema's defaults filled the top level: replaced)
    scene.cloth = first.cloth;
    scene.material = first.material;
    scene.pins = first.pins;
  } else {
    finishCloth(scene, massGiven[0] ?? false, '', source);
  }
  scene.colliders.forEach((c, k) => {
    // directions must have a length (the schema bounds each component, not the vector)
    const dir = c.type === 'plane' ? ['normal', c.normal] as const : c.type === 'cylinder' ? ['axis', c.axis] as const : null;
    if (dir && !(Math.hypot(dir[1][0], dir[1][1], dir[1][2]) > 1e-9)) {
      throw new SceneError(`${source}: colliders[${k}].${dir[0]}: must not be zero (a direction)`);
    }
    const keys = c.motion?.keyframes ?? [];
    for (let i = 1; i < keys.length; i++) {
      if (keys[i].time < keys[i - 1].time) {
        throw new SceneError(`${source}: colliders[${k}].motion.keyframes[${i}].time: must not be before the previous key's (${keys[i - 1].time} s)`);
      }
      // a jump is not a motion: contact would take it as the surface's speed and fling the cloth
      if (keys[i].time === keys[i - 1].time && !samePose(keys[i], keys[i - 1])) {
        throw new SceneError(`${source}: colliders[${k}].motion.keyframes[${i}]: at the time of the key before it, it must be that pose (a collider cannot jump)`);
      }
    }
    if (c.motion?.loop && !(keys[keys.length - 1].time > 0)) {
      throw new SceneError(`${source}: colliders[${k}].motion.loop: needs a last key after time 0 (its time is the period)`);
    }
    if (c.motion?.loop && (keys[0].time !== 0 || !samePose(keys[0], keys[keys.length - 1]))) {
      throw new SceneError(`${source}: colliders[${k}].motion.loop: the keys must start at time 0 and end in the pose they start in (else the collider jumps at each repeat)`);
    }
    const pins = c.pins ?? [];
    if (scene.cloths) {
      // the particles of several cloths are numbered through them in order: a preset would not say whose
      const preset = pins.findIndex((p) => typeof p === 'string');
      if (preset >= 0) throw new SceneError(`${source}: colliders[${k}].pins[${preset}]: in a scene of several cloths, pin a collider's particles by region or by index (numbered through the cloths in order)`);
    } else if (scene.cloth.shape === 'rectangle') {
      checkPinIndices(pins, (scene.cloth.resolution + 1) ** 2, `colliders[${k}].pins`, source);
    }
  });
  // the cantilever's strip overhangs along the horizontal part of test.direction: it must have one
  const dir = scene.test?.type === 'cantilever' ? scene.test.direction : null;
  if (dir && !(Math.hypot(dir[0], dir[2]) > 1e-9 * Math.hypot(dir[0], dir[1], dir[2]))) {
    throw new SceneError(`${source}: test.direction: must have a horizontal part (the strip overhangs along it), got [${dir.join(', ')}]`);
  }
  return scene;
}

/**
 * Whether `input` is a validated scene of several cloths (or one made from it by replacing a part): `cloth`,
 * `material` and `pins` beside `cloths`, one of them the very object of cloths[0]'s. A document read from JSON never
 * shares objects, so one that gives both forms is refused by validateScene.
 */
function isValidatedForm(input: object): boolean {
  const s = input as Record<string, unknown>;
  const first = Array.isArray(s.cloths) ? s.cloths[0] as Record<string, unknown> | undefined : undefined;
  if (first === null || typeof first !== 'object') return false;
  const same = (k: string) => s[k] !== null && typeof s[k] === 'object' && first[k] === s[k];
  return same('cloth') || same('material') || same('pins');
}

/** The cloths of a scene, in order: one for a one-cloth scene; the first is always the scene's cloth, material and pins. */
export function clothEntries(scene: Scene): ClothEntry[] {
  const first: ClothEntry = { cloth: scene.cloth, material: scene.material, pins: scene.pins };
  if (!scene.cloths) return [first];
  const name = scene.cloths[0].name;
  return [name === undefined ? first : { name, ...first }, ...scene.cloths.slice(1)];
}

/**
 * The first field of PER_CLOTH_FIELDS in which a scene's cloths differ, named with the cloth ('cloths[1].material.friction'),
 * or null when they agree in all (one cloth always does).
 */
export function differingClothField(scene: Scene): string | null {
  const entries = clothEntries(scene);
  for (const [path, value] of PER_CLOTH_FIELDS) {
    const k = entries.findIndex((e) => value(e) !== value(entries[0]));
    if (k > 0) return `cloths[${k}].${path}`;
  }
  return null;
}

/** What a cloth is called in reports: its name, or 'cloth k'. */
export function clothName(entry: ClothEntry, k: number): string {
  return entry.name ?? `cloth ${k}`;
}

/**
 * A scene as a document (what files, links and resolvedScene hold, and what validateScene takes back): the scene
 * itself for one cloth; for a list of cloths, `cloths` (the first from the scene's cloth, material and pins) and no
 * top-level cloth, material or pins. A plain document without the top-level three passes through as it is.
 */
export function sceneDocument(scene: Scene | Record<string, unknown>): Record<string, unknown> {
  const s = scene as Record<string, unknown>;
  if (!Array.isArray(s.cloths) || !Object.hasOwn(s, 'cloth')) return { ...s };
  const { cloth: _c, material: _m, pins: _p, ...rest } = s;
  return { ...rest, cloths: clothEntries(scene as Scene) };
}

/** The older material paths and the field each stands for: [old, new]. Only one of a pair may be given. */
const ALIASES = [['mass', 'arealDensity'], ['bendStiffness', 'bendingRigidity']] as const;
const ALIAS_OF: Partial<Record<string, string>> = { arealDensity: 'mass', bendingRigidity: 'bendStiffness', mass: 'arealDensity', bendStiffness: 'bendingRigidity' };
const ALIAS_MEANING: Record<string, string> = {
  arealDensity: 'the whole cloth\'s mass [kg], or its mass per area [kg/m²]',
  bendingRigidity: 'the bend spring\'s constant at 1/32 m [N/m], or the bending rigidity B [N·m]',
};

/** Whether two keys put a collider in the same pose: equal translations, and Euler angles that turn alike (0° and 360°). */
function samePose(a: { translation: Vec3; rotation: Vec3 }, b: { translation: Vec3; rotation: Vec3 }): boolean {
  const ra = eulerXYZ(a.rotation), rb = eulerXYZ(b.rotation);
  const size = 1 + Math.max(...a.translation.map(Math.abs), ...b.translation.map(Math.abs));
  return a.translation.every((v, i) => Math.abs(v - b.translation[i]) <= 1e-9 * size) && ra.every((v, i) => Math.abs(v - rb[i]) <= 1e-9);
}

/**
 * Parses JSON text into a validated scene; malformed JSON gives a SceneError with the position. A leading byte-order
 * mark (editors on Windows save one) is read past, as JSON readers may (RFC 8259 §8.1).
 */
export function parseScene(text: string, source = 'scene'): Scene {
  let doc: unknown;
  try {
    doc = JSON.parse(text.charCodeAt(0) === 0xfeff ? text.slice(1) : text);
  } catch (e) {
    throw new SceneError(`${source}: malformed JSON (${(e as Error).message.split('\n')[0]})`);
  }
  return validateScene(doc, source);
}

/** The scene with every field at its default. */
export function defaultScene(): Scene {
  return validateScene({});
}

/**
 * Reads a `--set` value: JSON when it parses (numbers, booleans, arrays, objects, null), otherwise the raw string.
 */
export function parseSetValue(raw: string): unknown {
  try {
    return JSON.parse(raw);
  } catch {
    return raw;
  }
}

/** Path keys as a scene path reads: an item's index in brackets (`colliders[0].motion`). */
function shownPath(keys: string[]): string {
  return keys.reduce((path, k) => (/^\d+$/.test(k) ? `${path}[${k}]` : path ? `${path}.${k}` : k), '');
}

/**
 * Sets a dotted path (`material.bendStiffness`, `colliders[0].radius`, `colliders.0.radius`) on a plain scene
 * document and re-validates it. Unknown paths and invalid values throw SceneError naming the path, after `source`
 * (what the user wrote: `--set PATH` in the CLI).
 */
export function setScenePath(scene: Scene | Record<string, unknown>, path: string, value: unknown, source = `--set ${path}`): Scene {
  if (typeof path !== 'string') throw new SceneError(`setScenePath: the path must be a string such as 'cloth.resolution', got ${shownValue(path)}`);
  // a value is JSON (what a scene file holds): a symbol or a function is refused here, not as a failed copy later
  // (its depth first: a value nested absurdly deep is named for that, as a scene is)
  if (value !== null && typeof value === 'object') checkDepth(value, source);
  try {
    value = structuredClone(value);
  } catch {
    throw new SceneError(`${source}: must be a JSON value (a number, string, boolean, null, list or object), got ${typeof value === 'object' ? 'an object holding something else' : `a ${typeof value}`}`);
  }
  // every key named: 'cloth..resolution', '.cloth' and 'cloth.' are not paths (they read as one before)
  const keys = path.replace(/\[(\d+)\]/g, '.$1').split('.');
  if (keys.some((k) => k === '' || k === '__proto__' || k === 'constructor' || k === 'prototype')) {
    throw new SceneError(`${source}: not a scene path`);
  }
  if (scene === null || typeof scene !== 'object' || Array.isArray(scene)) {
    throw new SceneError(`setScenePath: the scene must be a scene object (a document or a validated scene), got ${shownValue(scene)}`);
  }
  const doc = structuredClone(sceneDocument(scene));
  // the parts of a cloth: the top level's in a one-cloth scene, an entry of `cloths` in a scene of several
  const clothPart = (k: string | undefined) => k === 'cloth' || k === 'material' || k === 'pins';
  if (Array.isArray(doc.cloths) && clothPart(keys[0])) {
    throw new SceneError(`${source}: this scene has a list of cloths; name one: cloths[0].${keys.join('.')}`);
  }
  if (doc.cloths === undefined && keys[0] === 'cloths' && keys.length >= 2) {
    const instead = clothPart(keys[2]) ? keys.slice(2).join('.') : 'cloth.…, material.… and pins';
    throw new SceneError(`${source}: this scene has one cloth, not a list of cloths: ${instead}`);
  }
  let node: Record<string, unknown> | unknown[] = doc;
  for (let i = 0; i < keys.length; i++) {
    const last = i === keys.length - 1;
    if (Array.isArray(node)) {
      const list = shownPath(keys.slice(0, i));
      // a plain index: '01' would name a property of the list, not an item
      if (!/^(0|[1-9]\d*)$/.test(keys[i])) throw new SceneError(`${source}: ${list} is a list; use an index such as ${list}[0]`);
      // an existing item, or (for the last key) one past the end to append: never a sparse array
      if (Number(keys[i]) > (last ? node.length : node.length - 1)) {
        const items = `${node.length} item${node.length === 1 ? '' : 's'}`;
        throw new SceneError(`${source}: ${list} has ${items}, no item ${keys[i]}${last ? ` (${node.length} appends one)` : ''}`);
      }
    }
    if (last) break;
    const k = keys[i];
    const next = Object.hasOwn(node, k) ? (node as Record<string, unknown>)[k] : undefined;
    if (next === null || typeof next !== 'object') {
      throw new SceneError(`${source}: ${shownPath(keys.slice(0, i + 1))} is not an object in this scene`);
    }
    node = next as Record<string, unknown>;
  }
  (node as Record<string, unknown>)[keys[keys.length - 1]] = value;
  // the cloth the path is in: the top level's ('material.friction') or an entry of cloths ('cloths.1.material.friction')
  const at = keys[0] === 'cloths' && keys.length >= 3 ? 2 : 0;
  const owner = at ? (doc.cloths as Record<string, unknown>[])[Number(keys[1])] : doc;
  const part = keys.length === at + 2 ? owner?.[keys[at]] as Record<string, unknown> | undefined : undefined;
  const field = keys[at + 1];
  if (part && typeof part === 'object' && keys[at] === 'material') {
    // one path of a pair replaces the other; a named fabric puts every field it has back to its value
    const partner = ALIAS_OF[field];
    if (partner) delete part[partner];
    if (field === 'fabric') for (const k of [...FABRIC_FIELDS, 'mass', 'bendStiffness']) delete part[k];
  }
  // the shape and the mesh file go together: a mesh file makes the cloth a 'mesh', another shape drops the file
  if (part && typeof part === 'object' && keys[at] === 'cloth') {
    if (field === 'mesh' && value !== undefined) part.shape = 'mesh';
    if (field === 'shape' && value !== 'mesh') delete part.mesh;
  }
  try {
    return validateScene(doc, source);
  } catch (e) {
    // name the field once when it is the path itself: '--set a.b: must be…', not '--set a.b: a.b: must be…'
    const same = `${source}: ${fieldName('/' + keys.join('/'))}: `;
    if (e instanceof SceneError && e.message.startsWith(same)) throw new SceneError(`${source}: ${e.message.slice(same.length)}`);
    throw e;
  }
}
