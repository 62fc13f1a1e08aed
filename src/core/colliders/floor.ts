import type { ColliderShape } from './shape.js';

/** The half-space y < height. A triangle's deepest point in a half-space is a vertex, so particle contact suffices. */
export class FloorCollider implements ColliderShape {
  readonly type = 'floor';
  readonly minCurvatureRadius = Infinity;
  constructor(/** plane height [m] */ readonly height: number) {}

  signedDistance(_px: number, py: number, _pz: number, normal: Float64Array): number {
    normal[0] = 0; normal[1] = 1; normal[2] = 0;
    return py - this.height;
  }
}
