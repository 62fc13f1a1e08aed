/**
 * The URL hash holds what is on screen, so that a link reproduces it: the built-in scene it starts from and every
 * scene field that differs from it, as dotted paths (the CLI's `--set` syntax), plus a few view settings.
 *
 *   #scene=silk-drape&material.damping=0.3&wind.enabled=true&pins=["top-left"]&view=strain
 *
 * Values are JSON when they parse (numbers, booleans, arrays), otherwise strings. No DOM here: unit-tested.
 *
 * A scene of several cloths is diffed as its document (core sceneDocument: the list `cloths`, no top-level cloth),
 * cloth by cloth against a base of as many (`#scene=layers&cloths[1].material.fabric=silk`); against a base of
 * another number of cloths, its whole list is one key, `cloths=[…]`, read first.
 *
 * A scene whose mannequin (cape, skirt) was posed anew says so in one key, `mannequin=t-pose,walk` (pose,
 * animation), instead of its colliders' keys: the diff is then taken against the built-in scene with its mannequin
 * so posed (core withMannequin), and reading the link poses it so before any other key.
 */
import {
  FABRICS, MANNEQUIN_ANIMATIONS, MANNEQUIN_POSES, SCENE_NAMES, SceneError, builtinMannequin, builtinScene, clothEntries, editCloth, isBuiltinScene,
  defaultScene, parseSetValue, pathCloth, plainText, sceneDocument, sceneMannequin, setScenePath, validateScene, withMannequin,
  type FabricName, type MannequinAnimation, type MannequinPose, type Scene,
} from '../core/index.js';
import { baseName, missingMeshes, type SceneMeshFile } from './meshes.js';
import { withoutMesh } from './shape-change.js';

/** hash keys that are not scene paths */
export const VIEW_KEYS = ['view', 'sweep', 'backend'] as const;
export type ViewKey = (typeof VIEW_KEYS)[number];

export interface HashState {
  scene: Scene;
  /** built-in scene the link starts from ('' for the schema defaults) */
  base: string;
  view: Partial<Record<ViewKey, string>>;
}

/** The scene a diff is taken against: a built-in by name, or the schema defaults. */
export function baseScene(base: string): Scene {
  if (!base) return defaultScene();
  if (!isBuiltinScene(base)) throw new SceneError(`link: unknown scene '${base}' (one of ${SCENE_NAMES.join(', ')})`);
  return builtinScene(base);
}

type Json = null | boolean | number | string | Json[] | { [k: string]: Json };

function isPlainObject(v: unknown): v is Record<string, Json> {
  return v !== null && typeof v === 'object' && !Array.isArray(v);
}

/**
 * Leaf paths where `scene` differs from `base` (arrays are leaves), in a stable order, on their documents: a list of
 * cloths item by item (`cloths[1].material.fabric`) when the base has as many, else the whole list first (`cloths`;
 * a one-cloth scene against a base of several is a list of one, the same cloth). A material of another named fabric
 * is its fabric, then only the fields that differ from that fabric's.
 */
export function sceneDiff(scene: Scene, base: Scene): [string, Json][] {
  const out: [string, Json][] = [];
  const walk = (a: unknown, b: unknown, path: string) => {
    if (isPlainObject(a) && isPlainObject(b) && /^(cloths\[\d+\]\.)?material$/.test(path) && a.fabric !== b.fabric && isFabric(a.fabric)) {
      // another named fabric: it first, then the other fields against what it gives them (naming a fabric puts
      // every field it has to its value, and drops the older paths: core setScenePath)
      const { mass: _m, bendStiffness: _b, ...kept } = b;
      const given: Record<string, Json> = { ...kept, ...FABRICS[a.fabric] };
      walk(a.fabric, b.fabric, `${path}.fabric`);
      for (const k of Object.keys(a)) if (k !== 'fabric') walk(a[k], given[k], `${path}.${k}`);
      return;
    }
    if (isPlainObject(a)) {
      // where the base has no object (an imported scene's `test` against a built-in without one): the whole value
      if (path && !isPlainObject(b)) { out.push([path, a as Json]); return; }
      for (const k of Object.keys(a)) {
        if (k === '$schema') continue;
        walk(a[k], isPlainObject(b) ? b[k] : undefined, path ? `${path}.${k}` : k);
      }
      return;
    }
    if (JSON.stringify(a) !== JSON.stringify(b)) out.push([path, a as Json]);
  };
  const doc = sceneDocument(base.cloths && !scene.cloths ? asList(scene) : scene) as Record<string, Json>;
  const was = sceneDocument(base) as Record<string, Json>;
  const { cloths, ...rest } = doc;
  if (Array.isArray(cloths)) {
    const before = Array.isArray(was.cloths) && was.cloths.length === cloths.length ? was.cloths : null;
    if (before) cloths.forEach((c, k) => walk(c, before[k], `cloths[${k}]`));
    else out.push(['cloths', cloths]);
  }
  walk(rest, was, '');
  // a list the base has and the scene dropped (an imported mesh drops the Mesh Resolution scene's resolutionSweep):
  // an empty one, which means the same
  for (const [k, v] of Object.entries(was)) if (Array.isArray(v) && v.length && k !== 'cloths' && !(k in doc)) out.push([k, []]);
  return out;
}

function isFabric(name: unknown): name is FabricName {
  return typeof name === 'string' && Object.hasOwn(FABRICS, name);
}

/** A one-cloth scene as a list of that one cloth (the same cloth: core/cloths.test.ts). */
function asList(scene: Scene): Scene {
  const { cloth, material, pins, ...rest } = scene;
  return validateScene({ ...rest, cloths: [{ cloth, material, pins }] });
}

/** The scene with its cloths replaced by a link's whole list (`cloths=[…]`), whatever form it had. */
function withClothList(scene: Scene, list: unknown): Scene {
  const { cloth: _c, material: _m, pins: _p, cloths: _l, ...rest } = sceneDocument(scene);
  return validateScene({ ...rest, cloths: list }, 'link');
}

function encodeValue(v: Json): string {
  const s = typeof v === 'string' && parseSetValue(v) === v ? v : JSON.stringify(v);
  // keep brackets, commas, quotes and colons readable; escape what would break the hash
  return encodeURIComponent(s).replace(/%5B/g, '[').replace(/%5D/g, ']').replace(/%2C/g, ',').replace(/%22/g, '"').replace(/%3A/g, ':');
}

export function encodeHash(state: HashState): string {
  const parts: string[] = [];
  if (state.base) parts.push(`scene=${encodeURIComponent(state.base)}`);
  let base = baseScene(state.base);
  // a mannequin posed or moved anew: one key, and the diff against the built-in so posed
  const now = sceneMannequin(state.scene, state.base)?.options, was = builtinMannequin(state.base)?.options;
  if (now && was && (now.pose !== was.pose || now.animation !== was.animation)) {
    parts.push(`mannequin=${now.pose},${now.animation}`);
    base = withMannequin(base, builtinMannequin(state.base)!, now);
  }
  const diff = sceneDiff(state.scene, base);
  for (const [path, value] of diff) {
    // cloth.mesh makes the cloth a 'mesh' by itself (and 'cloth.shape=mesh' alone, read first, would be refused)
    const mesh = pathCloth(path)?.field === 'cloth.shape' ? path.replace(/shape$/, 'mesh') : null;
    if (mesh && value === 'mesh' && diff.some(([p]) => p === mesh)) continue;
    parts.push(`${path}=${encodeValue(value)}`);
  }
  for (const k of VIEW_KEYS) {
    const v = state.view[k];
    if (v !== undefined) parts.push(`${k}=${encodeURIComponent(v)}`);
  }
  // the schema defaults as they are: a hash of its own (an empty one is no link, and the page then starts from its
  // default built-in scene, not this one)
  if (!parts.length && !state.base) return '#scene=';
  return parts.length ? `#${parts.join('&')}` : '';
}

/**
 * Reads a hash (with or without '#'). An empty hash gives null. Anything wrong throws SceneError with one line
 * naming the key.
 */
export function decodeHash(hash: string): HashState | null {
  const text = hash.replace(/^#/, '');
  if (!text.trim()) return null;
  const pairs: [string, string][] = [];
  for (const part of text.split('&')) {
    if (!part) continue;
    const eq = part.indexOf('=');
    if (eq < 1) throw new SceneError(`link: '${safeDecode(part)}' is not key=value`);
    pairs.push([safeDecode(part.slice(0, eq)), safeDecode(part.slice(eq + 1))]);
  }
  const sceneKey = pairs.find(([k]) => k === 'scene');
  const base = sceneKey ? sceneKey[1] : '';
  let scene = baseScene(base);
  const posed = pairs.find(([k]) => k === 'mannequin');
  if (posed) scene = posedMannequin(scene, base, posed[1]);
  const view: HashState['view'] = {};
  for (const [key, raw] of pairs) {
    if (key === 'scene' || key === 'mannequin') continue;
    if ((VIEW_KEYS as readonly string[]).includes(key)) { view[key as ViewKey] = raw; continue; }
    if (key === 'cloths') { scene = withClothList(scene, parseSetValue(raw)); continue; }
    try {
      scene = setScenePath(scene, key, parseSetValue(raw));
    } catch (e) {
      const msg = (e as Error).message;
      const dup = `--set ${key}: `;
      // the core names the field twice ('--set a.b: a.b: must be…'); say it once
      throw new SceneError(msg.startsWith(dup) && msg.slice(dup.length).startsWith(key) ? `link: ${msg.slice(dup.length)}` : msg.replace(/^--set /, 'link: '));
    }
  }
  return { scene, base, view };
}

/** The built-in `base` with its mannequin posed as a link's `mannequin=pose,animation` says. */
function posedMannequin(scene: Scene, base: string, value: string): Scene {
  const m = builtinMannequin(base);
  if (!m) throw new SceneError(`link: mannequin: scene '${base}' has no mannequin`);
  const [pose, animation, ...rest] = value.split(',');
  if (rest.length || !(MANNEQUIN_POSES as readonly string[]).includes(pose) || !(MANNEQUIN_ANIMATIONS as readonly string[]).includes(animation)) {
    throw new SceneError(`link: mannequin: must be pose,animation with pose one of ${MANNEQUIN_POSES.join(', ')} and animation one of ${MANNEQUIN_ANIMATIONS.join(', ')}`);
  }
  return withMannequin(scene, m, { pose: pose as MannequinPose, animation: animation as MannequinAnimation });
}

function safeDecode(s: string): string {
  try {
    return decodeURIComponent(s);
  } catch {
    throw new SceneError(`link: '${s}' is not valid URL encoding`);
  }
}

/**
 * A link's scene as the page can show it: a link names mesh files but cannot carry them, so a cloth's mesh file the
 * page has not imported becomes the default rectangle, and a mesh collider whose file it has not imported is left
 * out. `missing`: those files (empty when the scene is shown as it is); `note` says which to import ('' when none).
 */
export function linkScene(scene: Scene, has: (path: string) => boolean): { scene: Scene; missing: SceneMeshFile[]; note: string } {
  const missing = missingMeshes(scene, has);
  if (!missing.length) return { scene, missing, note: '' };
  const name = (path: string) => plainText(baseName(path) || path, 80);
  const cloths = missing.flatMap((f) => (f.cloth === undefined ? [] : [f.cloth]));
  const left = missing.flatMap((f) => (f.collider === undefined ? [] : [f.collider]));
  let shown = scene;
  for (const k of cloths) shown = editCloth(shown, k, withoutMesh);
  if (left.length) shown = { ...shown, colliders: shown.colliders.filter((_, k) => !left.includes(k)) };
  const several = clothEntries(scene).length > 1;
  const whose = (f: SceneMeshFile) => (f.collider !== undefined ? `colliders[${f.collider}]` : several ? `cloths[${f.cloth}]` : 'the cloth');
  const what = missing.map((f) => `${whose(f)} is the mesh file ${name(f.path)}`);
  const files = [...new Set(missing.map((f) => name(f.path)))];
  const meanwhile = [
    ...(cloths.length ? [several ? `${cloths.length > 1 ? 'rectangles' : 'a rectangle'} as ${cloths.map((k) => `cloths[${k}]`).join(', ')}` : 'a rectangle cloth'] : []),
    ...(left.length ? [`the scene without ${left.map((k) => `colliders[${k}]`).join(', ')}`] : []),
  ];
  return {
    scene: shown,
    missing,
    note: `link: ${what.join(' and ')}, which a link cannot carry: import the mesh file${files.length > 1 ? 's' : ''} ${files.join(', ')} ` +
      `(Scene & export → import mesh…) to see ${missing.length > 1 ? 'them' : 'it'}; showing ${meanwhile.join(' and ')} meanwhile`,
  };
}
