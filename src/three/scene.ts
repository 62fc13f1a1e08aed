/**
 * A world's scene: its cloths as the scene's `cloths`, its floor, the colliders made from the user's meshes, and
 * the anchors that carry pins attached to objects that are no colliders, in that order (the order the world drives
 * them in). Pure: unit-tested in scene.test.ts with the core's Simulation.
 */
import { Vector3, type Object3D } from 'three';
import { validateScene, type ClothEntry, type ColliderSpec, type DeepPartial, type Scene, type SceneInput, type Vec3 } from '../core/index.js';
import { Follower } from './follow.js';
import type { DrapeWorldOptions } from './options.js';
import type { ColliderShapeOption } from './colliders.js';

/**
 * How far below the object it follows an anchor's plane lies [m]: the cloth never comes near it (the plane keeps
 * its distance from the object as both move).
 */
export const ANCHOR_DEPTH = 200;

/** A collider of a world: the object that moves it, its scene entry as it was made. */
export interface WorldCollider {
  readonly object: Object3D;
  readonly spec: ColliderSpec;
  /** null: it stays where it was made */
  readonly follower: Follower | null;
  /** the shape it was asked to be ('auto': inferred), to make it again at a new scale (none: an anchor, of no size) */
  readonly shape?: ColliderShapeOption;
}

/** What the scene needs of a cloth: its entry and its particles. */
export interface SceneCloth {
  readonly part: { readonly entry: DeepPartial<ClothEntry> };
  readonly particleCount: number;
}

/** Particles of a cloth attached to an object. */
export interface AttachedPin {
  readonly cloth: SceneCloth;
  /** the cloth's own particles */
  readonly particles: number[];
  readonly to: Object3D;
}

/** the cloth a world without cloths is checked with (never simulated) */
const STAND_IN: DeepPartial<ClothEntry> = {};

/** An anchor for pins on an object that is no collider: a plane ANCHOR_DEPTH below it, facing it, moving with it. */
export function anchorOf(object: Object3D): WorldCollider {
  object.updateWorldMatrix(true, false);
  const o = new Vector3().setFromMatrixPosition(object.matrixWorld);
  const point: Vec3 = [o.x, o.y - ANCHOR_DEPTH, o.z];
  return { object, spec: { type: 'plane', point, normal: [0, 1, 0] }, follower: new Follower(object, point) };
}

/**
 * The validated scene of a world (a SceneError names what is wrong: 'DrapeWorld: path: …'), and its colliders by
 * scene index (null for the floor). A world without cloths is checked with a stand-in one.
 */
export function worldScene(
  o: DrapeWorldOptions, cloths: readonly SceneCloth[], userColliders: readonly WorldCollider[],
  anchors: ReadonlyMap<Object3D, WorldCollider>, attached: readonly AttachedPin[],
): { scene: Scene; colliders: (WorldCollider | null)[] } {
  const colliders: ColliderSpec[] = [];
  const order: (WorldCollider | null)[] = [];
  if (o.floor !== undefined && o.floor !== null) { colliders.push({ type: 'floor', height: o.floor }); order.push(null); }
  // the cloths' first particles in the world's model (the scene's cloths in order), for the pins colliders carry
  const starts = new Map<SceneCloth, number>();
  let n = 0;
  for (const c of cloths) { starts.set(c, n); n += c.particleCount; }
  const carried = (object: Object3D) => attached.filter((p) => p.to === object && starts.has(p.cloth))
    .flatMap((p) => p.particles.map((i) => i + starts.get(p.cloth)!));
  for (const c of userColliders) { colliders.push({ ...c.spec, pins: carried(c.object) }); order.push(c); }
  for (const [object, a] of anchors) {
    const pins = carried(object);
    if (!pins.length || userColliders.some((c) => c.object === object)) continue;
    colliders.push({ ...a.spec, pins });
    order.push(a);
  }
  const w = o.wind ?? {};
  const entries = cloths.length ? cloths.map((c) => c.part.entry) : [STAND_IN];
  const input: SceneInput = {
    name: 'drape-three',
    cloths: entries,
    gravity: o.gravity ?? [0, -9.81, 0],
    // `wind` given: the air acts, its push and its drag (at strength 0, still air: the drag alone); not given: no air
    wind: {
      enabled: o.wind !== undefined, strength: w.strength ?? 0, direction: w.direction ?? [1, 0, 0],
      gusts: { enabled: w.gusts ?? false, seed: w.seed ?? 1 },
    },
    // cloths of one world keep out of each other by default; one cloth alone passes through itself unless asked
    solver: { selfContact: entries.length > 1, ...o.solver },
    colliders,
  };
  return { scene: validateScene(input, 'DrapeWorld'), colliders: order };
}
