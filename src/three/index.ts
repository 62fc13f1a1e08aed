/**
 * `drape/three`: Drape's cloth in a three.js scene — a DrapeWorld of DrapeCloths (meshes to add to your scene),
 * colliders made from your meshes, pins on any Object3D, picking and grabbing. It runs in a browser; it resolves in
 * Node too (types, bundlers). three.js is imported by this addon only, never by the core. Guide: docs/three.md.
 */
export { DrapeWorld, type DrapeHit } from './world.js';
export { DrapeCloth } from './cloth.js';
export { PointerGrab, type PointerGrabOptions } from './pointer.js';
export { inferShape, type ColliderShapeOption } from './colliders.js';
export type {
  DrapeBackend, DrapeWorldOptions, DrapeClothOptions, DrapeColliderOptions, DrapePin, RendererLike,
} from './options.js';
export { FABRIC_NAMES, type FabricName } from '../core/index.js';
