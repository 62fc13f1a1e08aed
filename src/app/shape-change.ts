/**
 * A new cloth shape for the current scene: the panel's Shape control (rectangle, disc, tube), an imported mesh
 * file, and a link's mesh that the page does not have. Only the cloth changes; the rest of the scene stays. Two
 * rules keep the change from being refused for reasons the panel cannot fix:
 * - pins: particle numbers belong to the old cloth's topology and are dropped; the corner and edge presets need a
 *   rectangle, so another shape keeps only 'center' (saying which went);
 * - height: the new cloth starts with its lowest point where the old one's was (a horizontal tube is a cylinder
 *   lying on its side: kept at the rectangle's height it would cut through the sphere below), so a cloth that
 *   started clear of the colliders still does.
 * No DOM here: unit-tested in shape-change.test.ts.
 */
import {
  SceneError, defaultScene, discMesh, modelFor, placeMesh, plainText, setScenePath, tubeMesh,
  type MeshResolver, type PinEntry, type Scene,
} from '../core/index.js';
import { resolutionPins } from './limits.js';

/** shapes the panel offers ('mesh' comes from an import) */
export const PANEL_SHAPES = ['rectangle', 'disc', 'tube'] as const;
export type PanelShape = (typeof PANEL_SHAPES)[number];

export interface ShapeChange {
  scene: Scene;
  /** one line on what the change dropped ('' when nothing) */
  note: string;
}

/** the cloths' lowest point is measured on a generated shape of at most this resolution (the outline is the same) */
const MEASURE_RESOLUTION = 64;

/**
 * The lowest point (y) of a scene's cloth where it starts, without building its model: a rectangle's corners, a
 * disc's or a tube's generated vertices, a mesh file's vertices placed as the scene says. `meshes` resolves
 * cloth.mesh (throws SceneError when the file is not here).
 */
export function restBottom(scene: Scene, meshes: MeshResolver): number {
  const c = scene.cloth;
  let positions: Float32Array;
  switch (c.shape) {
    case 'rectangle':
      // a plane rectangle: its lowest point is a corner, and resolution 1 is the four corners
      positions = modelFor({ ...scene, cloth: { ...c, resolution: 1 } }).restPositions;
      break;
    case 'disc':
      positions = discMesh({ ...c, resolution: Math.min(c.resolution, MEASURE_RESOLUTION) }).positions;
      break;
    case 'tube':
      positions = tubeMesh({ ...c, resolution: Math.min(c.resolution, MEASURE_RESOLUTION) }).positions;
      break;
    case 'mesh': {
      const raw = meshes(c.mesh ?? '').positions;
      const scaled = new Float32Array(raw.length);
      for (let k = 0; k < raw.length; k++) scaled[k] = raw[k] * c.scale;
      positions = placeMesh(scaled, c);
      break;
    }
  }
  let lo = Infinity;
  for (let k = 1; k < positions.length; k += 3) lo = Math.min(lo, positions[k]);
  return lo;
}

/** The scene with its cloth moved up or down so that its lowest point is at `bottom` (to 0.1 mm). */
function startingAt(scene: Scene, bottom: number, meshes: MeshResolver): Scene {
  const now = restBottom(scene, meshes);
  if (!Number.isFinite(now) || !Number.isFinite(bottom)) return scene;
  const [x, y, z] = scene.cloth.position;
  const to = Math.round((y + bottom - now) * 1e4) / 1e4;
  if (to === y) return scene;
  return setScenePath(scene, 'cloth.position', [x, Math.min(1000, Math.max(-1000, to)), z], 'cloth.position');
}

/** The pins a cloth of `shape` can take from `pins`, and a note on the ones it cannot. */
function pinsFor(pins: readonly PinEntry[], shape: Scene['cloth']['shape']): { pins: PinEntry[]; note: string } {
  const kept: PinEntry[] = [], presets: string[] = [];
  let indices = 0;
  for (const p of pins) {
    if (typeof p === 'number') indices++;
    // a region is where particles start, whatever the shape
    else if (typeof p === 'object' || shape === 'rectangle' || p === 'center') kept.push(p);
    else presets.push(p);
  }
  const why: string[] = [];
  if (presets.length) why.push(`pin preset${presets.length > 1 ? 's' : ''} ${presets.join(', ')} (a ${shape} has no corners or edges)`);
  if (indices) why.push(`${indices} particle pin${indices > 1 ? 's' : ''} (their numbers belong to the old cloth)`);
  return { pins: kept, note: why.length ? `dropped ${why.join(' and ')}` : '' };
}

/** The panel's Shape control: the scene with a rectangle, disc or tube cloth (cloth.mesh goes). */
export function withShape(scene: Scene, shape: PanelShape, meshes: MeshResolver): ShapeChange {
  if (!(PANEL_SHAPES as readonly string[]).includes(shape)) throw new SceneError(`cloth.shape: '${plainText(String(shape), 40)}' is not one of ${PANEL_SHAPES.join(', ')}`);
  const { pins, note } = pinsFor(scene.pins, shape);
  const bottom = restBottom(scene, meshes);
  const next = setScenePath({ ...scene, pins }, 'cloth.shape', shape, 'cloth.shape');
  return { scene: startingAt(next, bottom, meshes), note };
}

/**
 * An imported mesh file as the scene's cloth: cloth.mesh is the file's name (shape 'mesh'), pins cleared (a mesh's
 * particle numbers are its own, and presets other than 'center' need a rectangle), a resolution sweep dropped (a
 * mesh has its own resolution); it starts with its lowest point where the old cloth's was. `meshes` must resolve
 * `name` already.
 */
export function withMesh(scene: Scene, name: string, meshes: MeshResolver): Scene {
  const bottom = restBottom(scene, meshes);
  const base: Scene = { ...scene, pins: [] };
  delete base.resolutionSweep;
  return startingAt(setScenePath(base, 'cloth.mesh', name, 'cloth.mesh'), bottom, meshes);
}

/**
 * A scene whose mesh file the page does not have (a link cannot carry one): the same scene with the default
 * rectangle cloth instead (its pins: the presets and regions), so that what can be shown is.
 */
export function withoutMesh(scene: Scene): Scene {
  return { ...scene, cloth: defaultScene().cloth, pins: resolutionPins(scene.pins) };
}
