import type { ColliderSpec } from '../scene.js';
import { FloorCollider } from './floor.js';
import type { ColliderShape } from './shape.js';
import { SphereCollider } from './sphere.js';

export type { ColliderShape } from './shape.js';
export { SphereCollider, closestPointOnTriangle } from './sphere.js';
export { FloorCollider } from './floor.js';

/** Builds the shapes a scene's `colliders` list describes. */
export function createColliders(specs: readonly ColliderSpec[]): ColliderShape[] {
  return specs.map((s) => {
    switch (s.type) {
      case 'sphere':
        return new SphereCollider(s.center[0], s.center[1], s.center[2], s.radius);
      case 'floor':
        return new FloorCollider(s.height);
    }
  });
}
