import type { MeshResolver } from '../cloth-shape.js';
import type { ColliderSpec } from '../scene.js';
import { BoxCollider } from './box.js';
import { CapsuleCollider } from './capsule.js';
import { CylinderCollider } from './cylinder.js';
import { FloorCollider } from './floor.js';
import { loadMeshCollider } from './mesh.js';
import { placed } from './placed.js';
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
export { MeshCollider, meshCollider, MAX_COLLIDER_TRIANGLES, SHARP_EDGE_DEGREES } from './mesh.js';
export { TriangleBvh } from './bvh.js';
export { PlacedCollider } from './placed.js';

/**
 * Builds the shapes a scene's `colliders` list describes. A 'mesh' reads its file through `meshes` (the host's
 * resolver, as for cloth.mesh); without one, or when the file is bad, a SceneError names colliders[k].mesh.
 */
export function createColliders(specs: readonly ColliderSpec[], meshes?: MeshResolver): ColliderShape[] {
  return specs.map((s, k) => {
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
      case 'mesh':
        // built in the file's frame × scale; placing it is a separate rigid step (to become the collider pose)
        return placed(loadMeshCollider(s.mesh, s.scale, `colliders[${k}].mesh`, meshes), s.position, s.rotation);
    }
  });
}
