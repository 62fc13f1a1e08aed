/**
 * A static collider as the contact phase sees it. Shapes (sphere, floor, plane, box, capsule, cylinder) implement this interface
 * and are built by createColliders in colliders/index.ts; the solvers never name a shape.
 *
 * **No number crosses a call boundary** (no allocation inside a step): V8 boxes every non-integer number passed to
 * or returned from a call it does not inline, a heap allocation each (up to 28 MB a frame in the TypeScript kernel's
 * contact, `node scripts/step-garbage.mjs --kernel ts`), and which calls it inlines depends on the code's size and on
 * what it has seen before. So each query has two forms: `distanceIn` and `triangleDeepestIn` take and give their
 * numbers through a Float64Array record, and the contact loops (phases.ts) and the shapes' own queries of
 * themselves and of each other fill and read records; `signedDistance` and `triangleDeepest` are wrappers over
 * them (distanceOf, deepestOf below) for other callers. A body reads its record's inputs before it makes any query
 * of its own and writes its answer last, so the wrappers can share one record.
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
  /** signedDistance through a record: p from q[QUERY.X…Z], `within` from q[QUERY.WITHIN] (Infinity: none); the distance to q[QUERY.D]. */
  distanceIn(q: Float64Array, normal: Float64Array): void;
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
  /** triangleDeepest through a record: `within` from t[TRIANGLE.WITHIN] (Infinity: none); the distance to t[TRIANGLE.D]. */
  triangleDeepestIn?(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, t: Float64Array,
  ): void;
}

/**
 * the slots of a point query's record (ColliderShape.distanceIn): the point [m], the bound `within` [m], the answer
 * [m]. Users copy them into module constants (`const { X: QUERY_X, … } = QUERY`): an imported binding read in a hot
 * loop is a getter call under the test runner's module loader (vitest), which took the contact tests twice as long
 */
export const QUERY = Object.freeze({ X: 0, Y: 1, Z: 2, WITHIN: 3, D: 4 });
/** the slots of a triangle query's record (ColliderShape.triangleDeepestIn): the bound `within` [m], the answer [m] */
export const TRIANGLE = Object.freeze({ WITHIN: 0, D: 1 });
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { WITHIN: TRIANGLE_WITHIN, D: TRIANGLE_D } = TRIANGLE;

/** a record for point queries (each module keeps its own) */
export function pointQuery(): Float64Array {
  return new Float64Array(5);
}
/** a record for triangle queries */
export function triangleQuery(): Float64Array {
  return new Float64Array(2);
}

const query = pointQuery();
const triangle = triangleQuery();

/** shape.signedDistance(…) through the record: what every shape's signedDistance is. */
export function distanceOf(shape: ColliderShape, px: number, py: number, pz: number, normal: Float64Array, within: number): number {
  const q = query;
  q[QUERY_X] = px; q[QUERY_Y] = py; q[QUERY_Z] = pz; q[QUERY_WITHIN] = within;
  shape.distanceIn(q, normal);
  return q[QUERY_D];
}

/** shape.triangleDeepest(…) through the record: what every shape's triangleDeepest is. */
export function deepestOf(
  shape: ColliderShape, a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
  bary: Float64Array, normal: Float64Array, within: number,
): number {
  const t = triangle;
  t[TRIANGLE_WITHIN] = within;
  shape.triangleDeepestIn!(a, ia, b, ib, c, ic, bary, normal, t);
  return t[TRIANGLE_D];
}
