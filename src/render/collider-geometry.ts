/**
 * The geometry of each collider shape in its own frame (core colliders/pose.ts: centred at the origin, its axis or
 * normal along y), from the shape as the simulation built it, so that Stage.poseColliders puts it where
 * PosedCollider.poseAt says: a sphere, box, capsule and cylinder from their numbers (PosedCollider.shapeParams), a
 * plane as a 20 m square, and a mesh collider as its triangles — welded and scaled as the physics has them,
 * flat-shaded, since its facets are what the cloth meets.
 */
import {
  BoxGeometry, BufferAttribute, BufferGeometry, CapsuleGeometry, CylinderGeometry, PlaneGeometry, SphereGeometry,
} from 'three/webgpu';
import { MeshCollider, type PosedCollider } from '../core/index.js';

export interface ColliderGeometry {
  geometry: BufferGeometry;
  /** seen from both sides: a plane's square, a mesh collider with open pieces (a bowl, a terrain: thin shells) */
  twoSided: boolean;
}

/** The geometry of a collider in its own frame; null for a floor (the stage's own ground) or a shape it does not know. */
export function colliderGeometry(c: PosedCollider): ColliderGeometry | null {
  const [p0, p1, p2] = c.shapeParams;
  const solid = (geometry: BufferGeometry): ColliderGeometry => ({ geometry, twoSided: false });
  switch (c.type) {
    case 'sphere': return solid(new SphereGeometry(p0, 96, 48));
    // the quad lies in its xy plane; the plane's frame has its normal along y
    case 'plane': return { geometry: new PlaneGeometry(20, 20).rotateX(-Math.PI / 2), twoSided: true };
    case 'box': return solid(new BoxGeometry(2 * p0, 2 * p1, 2 * p2));
    // along y from −half length to +half length
    case 'capsule': return solid(new CapsuleGeometry(p1, 2 * p0, 16, 48));
    case 'cylinder': return solid(new CylinderGeometry(p0, p0, 2 * p1, 96, 1));
    case 'mesh': return c.local instanceof MeshCollider ? meshGeometry(c.local) : null;
    default: return null;
  }
}

/** A mesh collider's triangles, three vertices each with the face's normal (its closed pieces face outward). */
function meshGeometry(shape: MeshCollider): ColliderGeometry {
  const x = shape.bvh.positions, tri = shape.bvh.triangles, n = shape.faceNormals;
  const m = tri.length / 3;
  const positions = new Float32Array(9 * m), normals = new Float32Array(9 * m);
  for (let t = 0; t < m; t++) {
    for (let v = 0; v < 3; v++) {
      const i = 3 * tri[3 * t + v], o = 9 * t + 3 * v;
      positions[o] = x[i]; positions[o + 1] = x[i + 1]; positions[o + 2] = x[i + 2];
      normals[o] = n[3 * t]; normals[o + 1] = n[3 * t + 1]; normals[o + 2] = n[3 * t + 2];
    }
  }
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions, 3));
  geometry.setAttribute('normal', new BufferAttribute(normals, 3));
  return { geometry, twoSided: shape.openPieces > 0 };
}
