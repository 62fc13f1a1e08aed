/**
 * Built-in scenes shared by the CLI, the tests and the app. Material values and their sources: docs/materials.md.
 * Each is a partial scene document; everything it leaves out takes the schema's defaults.
 */
import { SceneError, validateScene, type Scene } from './scene.js';

const fabrics = {
  cotton: { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 },
  silk: { mass: 0.061, structuralStiffness: 3700, shearStiffness: 17, bendStiffness: 0.19, damping: 0.05, stretchFactor: 1.1, friction: 0.2, staticFriction: 0.25 },
  leather: { mass: 0.65, structuralStiffness: 5000, shearStiffness: 1700, bendStiffness: 94, damping: 0.5, stretchFactor: 1.15, friction: 0.4, staticFriction: 0.5 },
  rubber: { mass: 0.38, structuralStiffness: 600, shearStiffness: 200, bendStiffness: 0.75, damping: 0.2, stretchFactor: 1.8, friction: 0.8, staticFriction: 1.0 },
} as const;

const drop = (name: string, description: string, material: object) => ({ name, description, material });

const BUILTIN: Record<string, object> = {
  'cotton-basic': drop('cotton-basic', 'A 1 m cotton sheet dropped on a sphere', fabrics.cotton),
  'silk-drape': drop('silk-drape', 'Light, soft silk dropped on a sphere', fabrics.silk),
  'leather-stiff': drop('leather-stiff', 'Heavy, stiff garment leather dropped on a sphere', fabrics.leather),
  'rubber-stretch': drop('rubber-stretch', 'A stretchy latex sheet dropped on a sphere', fabrics.rubber),
  custom: drop('custom', 'Cotton on the sphere, for tweaking every parameter', fabrics.cotton),
  wind: {
    name: 'wind',
    description: 'A flag pinned along one edge, in gusty wind',
    cloth: { orientation: 'hanging', width: 1.5, height: 1, position: [0, 2, 0] },
    material: fabrics.cotton,
    wind: { enabled: true, strength: 8, direction: [1, 0, 0.2], gusts: { enabled: true, amplitude: 0.5, frequency: 0.4, seed: 7 } },
    colliders: [{ type: 'floor', height: 0 }],
    pins: ['left-edge'],
  },
  pins: {
    name: 'pins',
    description: 'Four corners pinned: a hammock',
    cloth: { position: [0, 1.5, 0] },
    material: fabrics.cotton,
    colliders: [{ type: 'floor', height: 0 }],
    pins: ['top-left', 'top-right', 'bottom-left', 'bottom-right'],
  },
  tablecloth: {
    name: 'tablecloth',
    description: 'A cotton tablecloth falling on a table (a 90 × 60 × 75 cm box) on the floor',
    cloth: { width: 1.4, height: 1.1, position: [0, 1, 0] },
    material: fabrics.cotton,
    colliders: [
      { type: 'box', center: [0, 0.375, 0], halfExtents: [0.45, 0.375, 0.3], rotation: [0, 0, 0] },
      { type: 'floor', height: 0 },
    ],
  },
  resolution: {
    name: 'resolution',
    description: 'The seed\'s mesh-resolution demo: the same cotton cloth dropped with 1 to 4096 faces',
    cloth: { resolution: 1 },
    material: fabrics.cotton,
    resolutionSweep: [1, 2, 4, 8, 16, 32, 64],
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
  return validateScene(BUILTIN[name], `scene '${name}'`);
}
