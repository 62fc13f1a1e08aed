import type { ColliderSpec } from '../scene.js';
import { BoxCollider } from './box.js';
import { CapsuleCollider } from './capsule.js';
import { CylinderCollider } from './cylinder.js';
import { FloorCollider } from './floor.js';
import { PlaneCollider } from './plane.js';
import type { ColliderShape } from './shape.js';
import { SphereCollider } from './sphere.js';

export type { ColliderShape } from './shape.js';
export { SphereCollider, closestPointOnTriangle } from './sphere.js';
export { FloorCollider } from './floor.js';
export { PlaneCollider } from './plane.js';
export { BoxCollider } from './box.js';
export { CapsuleCollider } from './capsule.js';
export { CylinderCollider } from './cylinder.js';

/** Builds the shapes a scene's `colliders` list describes. */
export function createColliders(specs: readonly ColliderSpec[]): ColliderShape[] {
  return specs.map((s) => {
    switch (s.type) {
      case 'sphere':
        return new SphereCollider(s.center[0], s.center[1], s.center[2], s.radius);
      case 'floor':
        return new FloorCollider(s.height);
      case 'plane':
        return new PlaneCollider(s.point, s.normal);
      case 'box':
        return new BoxCollider(s.center, s.halfExtents, s.rotation);
      case 'capsule':
        return new CapsuleCollider(s.a, s.b, s.radius);
      case 'cylinder':
        return new CylinderCollider(s.center, s.axis, s.radius, s.height);
    }
  });
}
