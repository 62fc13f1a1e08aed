import type { MeshResolver } from '../cloth-shape.js';
import type { ColliderSpec } from '../scene.js';
import { BoxCollider } from './box.js';
import { CapsuleCollider } from './capsule.js';
import { CylinderCollider } from './cylinder.js';
import { FloorCollider } from './floor.js';
import { loadMeshCollider } from './mesh.js';
import { PlaneCollider } from './plane.js';
import { eulerXYZ } from '../mesh/generators.js';
import { PosedCollider } from './pose.js';
import { SphereCollider } from './sphere.js';

export {
  QUERY, TRIANGLE, pointQuery, triangleQuery,
  type ColliderShape,
} from './shape.js';
export { PosedCollider, type ColliderPose, type ColliderMotion, type ColliderKeyframe } from './pose.js';
export { SphereCollider, closestPointOnTriangle } from './sphere.js';
export { FloorCollider } from './floor.js';
export { PlaneCollider } from './plane.js';
export { BoxCollider } from './box.js';
export { CapsuleCollider } from './capsule.js';
export { CylinderCollider } from './cylinder.js';
export { MeshCollider, meshCollider, MAX_COLLIDER_TRIANGLES, SHARP_EDGE_DEGREES } from './mesh.js';
export { TriangleBvh } from './bvh.js';

const IDENTITY = [1, 0, 0, 0, 1, 0, 0, 0, 1];

/** A rotation (row-major) taking the y axis to direction u (unit or not; zero: none): the frame of an axis or a normal. */
export function frameOfAxis(u: readonly number[]): number[] {
  const l = Math.hypot(u[0], u[1], u[2]);
  if (!(l > 0)) return IDENTITY;
  const y = [u[0] / l, u[1] / l, u[2] / l];
  // x: perpendicular to y, from the world axis y is least aligned with; z = x × y
  const ax = Math.abs(y[0]), ay = Math.abs(y[1]), az = Math.abs(y[2]);
  const w = ax <= ay && ax <= az ? [1, 0, 0] : ay <= az ? [0, 1, 0] : [0, 0, 1];
  const d = w[0] * y[0] + w[1] * y[1] + w[2] * y[2];
  let x = [w[0] - d * y[0], w[1] - d * y[1], w[2] - d * y[2]];
  const xl = Math.hypot(x[0], x[1], x[2]);
  x = [x[0] / xl, x[1] / xl, x[2] / xl];
  const z = [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
  // columns x, y, z
  return [x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]];
}

/**
 * Builds the colliders a scene's `colliders` list describes: each shape in its own frame (centred at the origin,
 * its axis or normal along y), placed where the scene puts it, moving as its `motion` says (pose.ts).
 */
export function createColliders(specs: readonly ColliderSpec[], meshes?: MeshResolver): PosedCollider[] {
  return specs.map((s, k) => {
    switch (s.type) {
      case 'sphere':
        return new PosedCollider(new SphereCollider(0, 0, 0, s.radius), IDENTITY, s.center, s.motion);
      case 'floor':
        return new PosedCollider(new FloorCollider(0), IDENTITY, [0, s.height, 0], s.motion);
      case 'plane':
        return new PosedCollider(new PlaneCollider([0, 0, 0], [0, 1, 0]), frameOfAxis(s.normal), s.point, s.motion);
      case 'box':
        return new PosedCollider(new BoxCollider([0, 0, 0], s.halfExtents), eulerXYZ(s.rotation), s.center, s.motion);
      case 'capsule': {
        const u = [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]];
        const half = Math.hypot(u[0], u[1], u[2]) / 2;
        const mid = [(s.a[0] + s.b[0]) / 2, (s.a[1] + s.b[1]) / 2, (s.a[2] + s.b[2]) / 2] as const;
        return new PosedCollider(new CapsuleCollider([0, -half, 0], [0, half, 0], s.radius), frameOfAxis(u), mid, s.motion);
      }
      case 'cylinder':
        return new PosedCollider(new CylinderCollider([0, 0, 0], [0, 1, 0], s.radius, s.height), frameOfAxis(s.axis), s.center, s.motion);
      case 'mesh':
        // built in the file's frame × scale, its origin placed at `position`
        return new PosedCollider(loadMeshCollider(s.mesh, s.scale, `colliders[${k}].mesh`, meshes), eulerXYZ(s.rotation), s.position, s.motion);
    }
  });
}
