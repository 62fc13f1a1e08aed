/**
 * A user's `THREE.Mesh` as a Drape collider: which shape (given, or inferred from its geometry) and the shape's
 * numbers in the world where the mesh is now (its `matrixWorld`: position, rotation and scale). Pure: no renderer,
 * no DOM; unit-tested in colliders.test.ts. How the collider then follows the mesh is follow.ts.
 */
import { Box3, BufferGeometry, Matrix4, Quaternion, Sphere, Vector3, type Mesh } from 'three';
import type { ColliderSpec, TriangleMesh, Vec3 } from '../core/index.js';
import { meshOfGeometry } from './geometry.js';
import { coreEuler } from './rotation.js';

/** The collider shapes a mesh can be; 'auto' infers one from the geometry. */
export type ColliderShapeOption = 'auto' | 'sphere' | 'box' | 'capsule' | 'cylinder' | 'mesh';
export const COLLIDER_SHAPE_OPTIONS: readonly ColliderShapeOption[] = ['auto', 'sphere', 'box', 'capsule', 'cylinder', 'mesh'];

/**
 * The shape 'auto' picks for a geometry: its own kind for three.js's `SphereGeometry`, `BoxGeometry`,
 * `CapsuleGeometry` and `CylinderGeometry` (one of equal radii at both ends, whole turn), else 'mesh' (its triangles).
 */
export function inferShape(geometry: BufferGeometry): Exclude<ColliderShapeOption, 'auto'> {
  const p = (geometry as BufferGeometry & { parameters?: Record<string, number> }).parameters ?? {};
  switch (geometry.type) {
    case 'SphereGeometry':
      // a whole sphere only: a dome or a band is no sphere
      return (p.phiLength ?? 2 * Math.PI) >= 2 * Math.PI - 1e-9 && (p.thetaStart ?? 0) === 0 && (p.thetaLength ?? Math.PI) >= Math.PI - 1e-9 ? 'sphere' : 'mesh';
    case 'BoxGeometry':
      return 'box';
    case 'CapsuleGeometry':
      return 'capsule';
    case 'CylinderGeometry':
      return p.radiusTop === p.radiusBottom && !p.openEnded && (p.thetaLength ?? 2 * Math.PI) >= 2 * Math.PI - 1e-9 ? 'cylinder' : 'mesh';
    default:
      return 'mesh';
  }
}

/** A collider made from a mesh: its scene entry as the mesh stands now, and, for a mesh shape, its triangles. */
export interface MeshColliderSource {
  shape: Exclude<ColliderShapeOption, 'auto'>;
  /** the scene's collider entry in world coordinates (a mesh entry names `meshName`) */
  spec: ColliderSpec;
  /** the centre the collider turns about when it follows the mesh (the spec's centre, or the mesh's origin) [m] */
  pivot: Vec3;
  /** for shape 'mesh': the geometry's triangles in the mesh's own frame × its world scale [m] */
  triangles?: TriangleMesh;
}

const v = new Vector3(), half = new Vector3(), scale = new Vector3(), position = new Vector3(), quaternion = new Quaternion();
const box = new Box3(), sphere = new Sphere(), rotation = new Matrix4();

const vec = (x: Vector3): Vec3 => [x.x, x.y, x.z];

/**
 * The collider a mesh makes where it stands now (`mesh.matrixWorld`, which the caller brings up to date).
 * `shape` 'auto' infers it (inferShape). Every shape fits the geometry's bounds, which for three.js's own
 * geometries is the shape itself: a sphere its bounding sphere, a box its bounding box (turned with the mesh), a
 * capsule or cylinder along the mesh's own y axis, as wide as the wider of its x and z extents and as long as its y
 * extent (a capsule's caps included); a mesh its triangles. The mesh's scale is read here: when it changes, DrapeWorld makes the collider again. `meshName` names the triangles of a
 * mesh shape in the scene. Throws an Error naming the mesh for a geometry without positions.
 */
export function colliderOfMesh(mesh: Mesh, shapeOption: ColliderShapeOption, meshName: string): MeshColliderSource {
  const geometry = mesh.geometry;
  const label = `DrapeWorld.addCollider(${mesh.name ? `'${mesh.name}'` : 'mesh'})`;
  if (!(geometry instanceof BufferGeometry) || !geometry.getAttribute('position')) {
    throw new TypeError(`${label}: the mesh's geometry has no position attribute`);
  }
  const shape = shapeOption === 'auto' ? inferShape(geometry) : shapeOption;
  mesh.matrixWorld.decompose(position, quaternion, scale);
  const sx = Math.abs(scale.x), sy = Math.abs(scale.y), sz = Math.abs(scale.z);
  rotation.makeRotationFromQuaternion(quaternion);
  const euler = coreEuler(rotation);
  geometry.computeBoundingBox();
  box.copy(geometry.boundingBox!);
  const centre = vec(box.getCenter(v).applyMatrix4(mesh.matrixWorld));
  box.getSize(half).multiplyScalar(0.5);
  const axis = vec(v.set(0, 1, 0).applyQuaternion(quaternion));
  switch (shape) {
    case 'sphere': {
      geometry.computeBoundingSphere();
      sphere.copy(geometry.boundingSphere!);
      const center = vec(sphere.center.applyMatrix4(mesh.matrixWorld));
      return { shape, spec: { type: 'sphere', center, radius: sphere.radius * Math.max(sx, sy, sz) }, pivot: center };
    }
    case 'box':
      return { shape, spec: { type: 'box', center: centre, halfExtents: [half.x * sx, half.y * sy, half.z * sz], rotation: euler }, pivot: centre };
    case 'capsule': {
      // along the mesh's y: a radius as wide as the wider of x and z, the straight middle what the caps leave
      const radius = Math.max(half.x * sx, half.z * sz);
      const halfLength = Math.max(0, half.y * sy - radius);
      const a: Vec3 = [centre[0] - axis[0] * halfLength, centre[1] - axis[1] * halfLength, centre[2] - axis[2] * halfLength];
      const b: Vec3 = [centre[0] + axis[0] * halfLength, centre[1] + axis[1] * halfLength, centre[2] + axis[2] * halfLength];
      return { shape, spec: { type: 'capsule', a, b, radius }, pivot: centre };
    }
    case 'cylinder': {
      const radius = Math.max(half.x * sx, half.z * sz);
      return { shape, spec: { type: 'cylinder', center: centre, axis, radius, height: 2 * half.y * sy }, pivot: centre };
    }
    case 'mesh': {
      // the triangles in the mesh's own frame, its scale baked in: the scene places the origin and turns it
      const triangles = meshOfGeometry(geometry, label, new Matrix4().makeScale(scale.x, scale.y, scale.z));
      const origin = vec(position);
      return { shape, spec: { type: 'mesh', mesh: meshName, scale: 1, position: origin, rotation: euler }, pivot: origin, triangles };
    }
  }
}
