/**
 * A static collider as the contact phase sees it. Shapes (sphere, floor, plane, box, capsule, cylinder) implement this interface
 * and are built by createColliders in colliders/index.ts; the solvers never name a shape.
 */
export interface ColliderShape {
  readonly type: string;
  /**
   * Smallest radius of curvature of the surface [m]: Infinity for a plane, the radius for a sphere or capsule,
   * 0 for shapes with sharp edges. Decides whether triangle contact is needed for a given mesh size.
   */
  readonly minCurvatureRadius: number;
  /**
   * Signed distance of point p from the surface [m] (negative inside), and the outward unit normal of the
   * closest surface point written to `normal[0..2]`. With `within`, a shape may return any value ≥ `within`
   * without writing the normal when the point is at least that far away (the contact loop's early out).
   */
  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within?: number): number;
  /**
   * Deepest point of triangle (a, b, c) with respect to this shape, for shapes whose surface can poke through a
   * triangle between its vertices (a sphere can; a half-space cannot, so it leaves this undefined).
   * Writes the barycentric weights of that point to `bary[0..2]` and the outward normal to `normal[0..2]`;
   * returns its signed distance [m]. With `within`, a shape may return any value ≥ `within` (writing nothing) when
   * the whole triangle is at least that far away.
   */
  triangleDeepest?(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, within?: number,
  ): number;
}
