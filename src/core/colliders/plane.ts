import { QUERY, distanceOf, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, D: QUERY_D } = QUERY;

/**
 * The half-space below a plane through `point` with outward unit normal `normal` (a ramp, a wall, a floor at any
 * angle). A triangle's deepest point in a half-space is a vertex, so particle contact suffices.
 */
export class PlaneCollider implements ColliderShape {
  readonly type = 'plane';
  readonly minCurvatureRadius = Infinity;
  /** unit outward normal */
  readonly nx: number; readonly ny: number; readonly nz: number;
  /** n·point: the plane is n·p = offset */
  readonly offset: number;
  constructor(point: readonly number[], normal: readonly number[]) {
    const l = Math.hypot(normal[0], normal[1], normal[2]);
    if (!(l > 0)) throw new RangeError('plane normal must not be zero');
    this.nx = normal[0] / l; this.ny = normal[1] / l; this.nz = normal[2] / l;
    this.offset = this.nx * point[0] + this.ny * point[1] + this.nz * point[2];
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    normal[0] = this.nx; normal[1] = this.ny; normal[2] = this.nz;
    q[QUERY_D] = this.nx * q[QUERY_X] + this.ny * q[QUERY_Y] + this.nz * q[QUERY_Z] - this.offset;
  }
}
