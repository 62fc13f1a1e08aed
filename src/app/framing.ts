/**
 * What the camera frames: the box around the cloths where they start and their colliders with a size (a plane and
 * the floor are everywhere). No three.js here: unit-tested in framing.test.ts.
 */
import { MeshCollider, type ColliderSpec, type PosedCollider } from '../core/index.js';
import { eulerXYZ } from '../core/mesh/generators.js';

/** an axis-aligned box [m], grown by frameBounds */
export interface Bounds {
  min: [number, number, number];
  max: [number, number, number];
}

/** a box holding nothing yet */
export const emptyBounds = (): Bounds => ({ min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] });

/**
 * Grows `into` by one cloth: its rest positions, and each collider where the scene places it — an analytic shape
 * by a ball around it, a mesh collider by the corners of its file's box (× scale, as `built`, the simulation's
 * colliders for `colliders`, has it) turned by its rotation and moved to its position.
 */
export function frameBounds(rest: Float32Array, colliders: readonly ColliderSpec[], built: readonly PosedCollider[], into: Bounds): void {
  const point = (x: number, y: number, z: number) => {
    into.min[0] = Math.min(into.min[0], x); into.min[1] = Math.min(into.min[1], y); into.min[2] = Math.min(into.min[2], z);
    into.max[0] = Math.max(into.max[0], x); into.max[1] = Math.max(into.max[1], y); into.max[2] = Math.max(into.max[2], z);
  };
  const ball = (p: readonly number[], r: number) => { point(p[0] - r, p[1] - r, p[2] - r); point(p[0] + r, p[1] + r, p[2] + r); };
  for (let i = 0; i < rest.length; i += 3) point(rest[i], rest[i + 1], rest[i + 2]);
  colliders.forEach((c, k) => {
    if (c.type === 'sphere') ball(c.center, c.radius);
    else if (c.type === 'box') ball(c.center, Math.hypot(...c.halfExtents));
    else if (c.type === 'capsule') { ball(c.a, c.radius); ball(c.b, c.radius); }
    else if (c.type === 'cylinder') ball(c.center, Math.hypot(c.radius, c.height / 2));
    else if (c.type === 'mesh') {
      const shape = built[k]?.local;
      if (!(shape instanceof MeshCollider)) return;
      // the root node's box: the whole mesh in its own frame
      const b = shape.bvh.bounds, r = eulerXYZ(c.rotation), o = c.position;
      for (let corner = 0; corner < 8; corner++) {
        const x = b[corner & 1 ? 3 : 0], y = b[corner & 2 ? 4 : 1], z = b[corner & 4 ? 5 : 2];
        point(r[0] * x + r[1] * y + r[2] * z + o[0], r[3] * x + r[4] * y + r[5] * z + o[1], r[6] * x + r[7] * y + r[8] * z + o[2]);
      }
    }
  });
}
