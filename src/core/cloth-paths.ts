/**
 * One cloth of a scene, addressed: the scene path of a field of cloth k ('material.damping' is
 * 'cloths[1].material.damping' in a scene of several cloths), the cloth a path is in, a particle of the merged model
 * as its cloth's own and back, and an edit made to the scene as if cloth k were its only cloth, written back into
 * the list. What an editor of one cloth at a time (the app's panel, pin tool and shape changes) is built on.
 */
import { clothOf, type ClothModel } from './model.js';
import { clothEntries, sceneDocument, validateScene, type ClothEntry, type ColliderSpec, type Scene } from './scene.js';
import { plainText } from './text.js';

/** The first keys of the paths inside one cloth: its shape and pose, its material, its pins. */
const CLOTH_KEYS: readonly string[] = ['cloth', 'material', 'pins'];

/** How many cloths a scene has (1 without a list). */
export function clothCount(scene: Scene): number {
  return scene.cloths?.length ?? 1;
}

/**
 * The scene path of `field` ('material.damping', 'cloth.resolution', 'pins') of cloth k: the field itself in a
 * one-cloth scene, `cloths[k].field` in a scene of several. Throws RangeError for a cloth the scene does not have.
 */
export function clothPath(scene: Scene, k: number, field: string): string {
  if (!Number.isInteger(k) || k < 0 || k >= clothCount(scene)) throw new RangeError(`scene '${scene.name}' has no cloth ${k}`);
  return scene.cloths ? `cloths[${k}].${field}` : field;
}

/** A path inside one cloth: which cloth, and the path within its entry. */
export interface ClothField {
  cloth: number;
  /** 'material.damping', 'cloth.shape', 'pins', … */
  field: string;
}

/**
 * The cloth a scene path is in and the path within it: 'cloths[2].material.damping' (or 'cloths.2.material.damping')
 * is cloth 2's 'material.damping', 'material.damping' and 'pins' are cloth 0's; null for a path outside every cloth
 * ('solver.substeps', 'cloths', 'cloths[1]').
 */
export function pathCloth(path: string): ClothField | null {
  const m = /^cloths(?:\[(\d+)\]|\.(\d+))\.(.+)$/.exec(path);
  if (m) return { cloth: Number(m[1] ?? m[2]), field: m[3] };
  return CLOTH_KEYS.includes(path.split(/[.[]/)[0]) ? { cloth: 0, field: path } : null;
}

/** A particle of a model of several cloths (the scene's numbering) as its cloth's own: which cloth, and its index there. */
export function clothParticle(model: ClothModel, i: number): { cloth: number; index: number } {
  if (!Number.isInteger(i) || i < 0 || i >= model.particleCount) throw new RangeError(`no particle ${i} (the model has ${model.particleCount})`);
  const cloth = clothOf(model, i);
  return { cloth, index: i - model.clothStarts[cloth] };
}

/** Cloth k's particle `index` in the scene's numbering (clothParticle's inverse). */
export function sceneParticle(model: ClothModel, cloth: number, index: number): number {
  const cloths = model.clothStarts.length - 1;
  if (!(Number.isInteger(cloth) && cloth >= 0 && cloth < cloths)) throw new RangeError(`no cloth ${cloth} (the model has ${cloths})`);
  const count = model.clothStarts[cloth + 1] - model.clothStarts[cloth];
  if (!(Number.isInteger(index) && index >= 0 && index < count)) throw new RangeError(`cloth ${cloth} has no particle ${index} (it has ${count})`);
  return model.clothStarts[cloth] + index;
}

/** Cloth k's own model (its particles numbered from 0): the model itself for one cloth. */
export function clothModelOf(model: ClothModel, k: number): ClothModel {
  return model.clothParts?.[k] ?? model;
}

/**
 * The scene as if cloth k were its only cloth: its cloth, material and pins at the top level, no list, and the
 * colliders without the pins they carry (those count particles through every cloth). The scene itself when it has
 * one cloth.
 */
export function clothScene(scene: Scene, k: number): Scene {
  if (!scene.cloths) {
    if (k !== 0) throw new RangeError(`scene '${plainText(scene.name, 100)}' has no cloth ${k} (it has one cloth, 0)`);
    return scene;
  }
  const e = clothEntries(scene)[k];
  if (!e) throw new RangeError(`scene '${plainText(scene.name, 100)}' has no cloth ${k}`);
  const { cloths: _list, ...rest } = scene;
  const colliders = scene.colliders.map((c): ColliderSpec => {
    const { pins: _pins, ...shape } = c;
    return shape as ColliderSpec;
  });
  return { ...rest, cloth: e.cloth, material: e.material, pins: e.pins, colliders };
}

/**
 * An edit of cloth k: `edit` gets the scene as cloth k alone (clothScene) and returns it changed; its cloth,
 * material and pins become cloth k's (its name kept), the rest of the scene as it was, and the whole validated
 * again. In a one-cloth scene, `edit`'s scene is the result. Throws SceneError when the scene refuses the change.
 */
export function editCloth(scene: Scene, k: number, edit: (one: Scene) => Scene): Scene {
  if (!scene.cloths) return edit(clothScene(scene, k));
  const one = edit(clothScene(scene, k));
  const doc = sceneDocument(scene);
  const cloths = (doc.cloths as ClothEntry[]).slice();
  const name = cloths[k].name;
  cloths[k] = { ...(name === undefined ? {} : { name }), cloth: one.cloth, material: one.material, pins: one.pins };
  return validateScene({ ...doc, cloths });
}
