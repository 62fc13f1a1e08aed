import { QUERY, distanceOf, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { Y: QUERY_Y, D: QUERY_D } = QUERY;

/** The half-space y < height. A triangle's deepest point in a half-space is a vertex, so particle contact suffices. */
export class FloorCollider implements ColliderShape {
  readonly type = 'floor';
  readonly minCurvatureRadius = Infinity;
  constructor(/** plane height [m] */ readonly height: number) {}

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    normal[0] = 0; normal[1] = 1; normal[2] = 0;
    q[QUERY_D] = q[QUERY_Y] - this.height;
  }
}
