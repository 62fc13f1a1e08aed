/**
 * A shape built in its own local frame, placed in the scene by a rigid transform: world = R·local + position, R the
 * Euler XYZ rotation [degrees] of mesh/generators.ts eulerXYZ (as cloth.rotation and box.rotation). Used for the mesh
 * collider (its file's coordinates × scale); a stand-in for a general pose of every collider.
 *
 * Distances and barycentric weights do not change under a rigid motion: the point (or triangle) goes into the local
 * frame, the shape answers there, and the normal comes back rotated.
 */
import { eulerXYZ } from '../mesh/generators.js';
import type { ColliderShape } from './shape.js';

const local = new Float32Array(9);

export class PlacedCollider implements ColliderShape {
  readonly type: string;
  readonly minCurvatureRadius: number;
  /** rotation, row-major */
  readonly r: readonly number[];
  readonly triangleDeepest?: ColliderShape['triangleDeepest'];

  constructor(
    readonly shape: ColliderShape,
    readonly position: readonly [number, number, number],
    readonly rotation: readonly [number, number, number],
  ) {
    this.type = shape.type;
    this.minCurvatureRadius = shape.minCurvatureRadius;
    this.r = eulerXYZ(rotation);
    const inner = shape.triangleDeepest;
    if (inner) {
      this.triangleDeepest = (a, ia, b, ib, c, ic, bary, normal, within) => {
        this.toLocal(a[ia], a[ia + 1], a[ia + 2], 0);
        this.toLocal(b[ib], b[ib + 1], b[ib + 2], 3);
        this.toLocal(c[ic], c[ic + 1], c[ic + 2], 6);
        const d = inner.call(shape, local, 0, local, 3, local, 6, bary, normal, within);
        this.rotate(normal);
        return d;
      };
    }
  }

  /** Rᵀ·(p − position) into local[o..o+2]. */
  private toLocal(px: number, py: number, pz: number, o: number): void {
    const r = this.r, dx = px - this.position[0], dy = py - this.position[1], dz = pz - this.position[2];
    local[o] = r[0] * dx + r[3] * dy + r[6] * dz;
    local[o + 1] = r[1] * dx + r[4] * dy + r[7] * dz;
    local[o + 2] = r[2] * dx + r[5] * dy + r[8] * dz;
  }

  /** n ← R·n */
  private rotate(n: Float64Array): void {
    const r = this.r, x = n[0], y = n[1], z = n[2];
    n[0] = r[0] * x + r[1] * y + r[2] * z;
    n[1] = r[3] * x + r[4] * y + r[5] * z;
    n[2] = r[6] * x + r[7] * y + r[8] * z;
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within?: number): number {
    const r = this.r, dx = px - this.position[0], dy = py - this.position[1], dz = pz - this.position[2];
    const d = this.shape.signedDistance(
      r[0] * dx + r[3] * dy + r[6] * dz, r[1] * dx + r[4] * dy + r[7] * dz, r[2] * dx + r[5] * dy + r[8] * dz, normal, within,
    );
    this.rotate(normal);
    return d;
  }
}

/** The shape placed at `position`, turned by `rotation`; the shape itself when that is no motion at all. */
export function placed(
  shape: ColliderShape, position: readonly [number, number, number], rotation: readonly [number, number, number],
): ColliderShape {
  if (position.every((v) => v === 0) && rotation.every((v) => v === 0)) return shape;
  return new PlacedCollider(shape, position, rotation);
}
