import { BoxGeometry, CapsuleGeometry, CylinderGeometry, Mesh, SphereGeometry, TorusKnotGeometry, Vector3 } from 'three';
import { describe, expect, it } from 'vitest';
import { createColliders, type ColliderSpec } from '../core/index.js';
import { colliderOfMesh, inferShape } from './colliders.js';

/** a mesh placed in the world: position, rotation about x, y, z [rad] (three's order XYZ), scale */
function placed(mesh: Mesh, pos: [number, number, number], rot: [number, number, number] = [0, 0, 0], scale: [number, number, number] = [1, 1, 1]): Mesh {
  mesh.position.set(...pos);
  mesh.rotation.set(...rot);
  mesh.scale.set(...scale);
  mesh.updateMatrixWorld(true);
  return mesh;
}

/** the signed distance of the core's collider built from `spec` at the world point p */
function distance(spec: ColliderSpec, p: Vector3, meshes?: Parameters<typeof createColliders>[1]): number {
  const [c] = createColliders([spec], meshes);
  return c.signedDistance(p.x, p.y, p.z, new Float64Array(3));
}

describe('a THREE.Mesh as a collider', () => {
  it('infers the shape from three.js\'s own geometries, else takes the triangles', () => {
    expect(inferShape(new SphereGeometry(1))).toBe('sphere');
    expect(inferShape(new SphereGeometry(1, 8, 6, 0, Math.PI))).toBe('mesh'); // half a sphere
    expect(inferShape(new BoxGeometry())).toBe('box');
    expect(inferShape(new CapsuleGeometry(0.2, 1))).toBe('capsule');
    expect(inferShape(new CylinderGeometry(0.3, 0.3, 1))).toBe('cylinder');
    expect(inferShape(new CylinderGeometry(0.1, 0.3, 1))).toBe('mesh'); // a cone
    expect(inferShape(new TorusKnotGeometry())).toBe('mesh');
  });

  it('a scaled, moved sphere mesh: centre and radius in the world', () => {
    const m = placed(new Mesh(new SphereGeometry(0.5, 16, 12)), [1, 2, 3], [0, 0, 0], [2, 2, 2]);
    const c = colliderOfMesh(m, 'auto', 'x');
    expect(c.spec).toMatchObject({ type: 'sphere', center: [1, 2, 3] });
    expect((c.spec as { radius: number }).radius).toBeCloseTo(1, 6);
    expect(c.pivot).toEqual([1, 2, 3]);
  });

  it('a turned, scaled box: the core\'s box is where the mesh is (surface points at distance 0)', () => {
    const m = placed(new Mesh(new BoxGeometry(1, 0.4, 0.6)), [0.5, 1, -0.2], [0.3, -0.7, 1.1], [2, 1, 0.5]);
    const c = colliderOfMesh(m, 'auto', 'x');
    expect(c.spec.type).toBe('box');
    // the centres of three faces, in the mesh's frame, to the world
    for (const local of [[0.5, 0, 0], [0, 0.2, 0], [0, 0, -0.3]]) {
      const p = new Vector3(...local).applyMatrix4(m.matrixWorld);
      expect(Math.abs(distance(c.spec, p))).toBeLessThan(1e-6);
    }
    expect(distance(c.spec, new Vector3(0.5, 1, -0.2))).toBeLessThan(0);
  });

  it('a tilted capsule and cylinder lie along the mesh\'s y axis', () => {
    const cap = placed(new Mesh(new CapsuleGeometry(0.2, 1, 4, 8)), [0, 1, 0], [0, 0, Math.PI / 2]);
    const c = colliderOfMesh(cap, 'auto', 'x');
    expect(c.spec.type).toBe('capsule');
    const spec = c.spec as { a: number[]; b: number[]; radius: number };
    expect(spec.radius).toBeCloseTo(0.2, 6);
    // turned a quarter about z: the axis runs along x, from −0.5 to 0.5
    expect(Math.abs(spec.a[0]) + Math.abs(spec.b[0])).toBeCloseTo(1, 5);
    expect(spec.a[1]).toBeCloseTo(1, 6);
    // the tip of a cap, in the world: on the surface
    const tip = new Vector3(0, 0.7, 0).applyMatrix4(cap.matrixWorld);
    expect(Math.abs(distance(c.spec, tip))).toBeLessThan(1e-6);

    const cyl = placed(new Mesh(new CylinderGeometry(0.3, 0.3, 0.8, 24)), [0, 0.4, 0], [0.4, 0, 0], [1, 1.5, 1]);
    const d = colliderOfMesh(cyl, 'auto', 'x');
    expect(d.spec.type).toBe('cylinder');
    expect((d.spec as { radius: number }).radius).toBeCloseTo(0.3, 6);
    expect((d.spec as { height: number }).height).toBeCloseTo(1.2, 6);
    const top = new Vector3(0, 0.4, 0).applyMatrix4(cyl.matrixWorld);
    expect(Math.abs(distance(d.spec, top))).toBeLessThan(1e-6);
  });

  it('an explicit shape fits the bounds; a mesh collider keeps its triangles, scaled, placed at the origin', () => {
    const knot = placed(new Mesh(new TorusKnotGeometry(0.3, 0.1, 32, 6)), [0, 1, 0], [0, 0.5, 0], [1.5, 1.5, 1.5]);
    const asBox = colliderOfMesh(knot, 'box', 'x');
    expect(asBox.spec.type).toBe('box');
    const mesh = colliderOfMesh(knot, 'auto', 'knot');
    expect(mesh.spec).toMatchObject({ type: 'mesh', mesh: 'knot', scale: 1, position: [0, 1, 0] });
    expect(mesh.triangles!.triangles.length).toBe(knot.geometry.getIndex()!.count);
    // a vertex of the geometry, in the world: on the core's mesh collider's surface
    const v = new Vector3().fromBufferAttribute(knot.geometry.getAttribute('position'), 5).applyMatrix4(knot.matrixWorld);
    expect(Math.abs(distance(mesh.spec, v, () => mesh.triangles!))).toBeLessThan(1e-5);
  });

  it('refuses a mesh without positions, naming it', () => {
    const m = new Mesh();
    m.geometry.deleteAttribute('position');
    m.name = 'ghost';
    expect(() => colliderOfMesh(m, 'auto', 'x')).toThrow(/DrapeWorld\.addCollider\('ghost'\): .*position/);
  });
});
