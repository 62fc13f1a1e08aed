/**
 * Every GPU buffer, uniform struct and kernel binding of the WebGPU solver, defined once. The WGSL declarations
 * (structs and `@group/@binding` variables) are generated from these tables and prepended to each kernel's
 * source (shaders.ts), and the solver creates its bind group layouts from the same tables, so the two cannot
 * drift apart.
 *
 * vec3 data (positions, velocities, normals, forces) has stride 4 floats (16 bytes) on the GPU: `array<vec4f>`,
 * w = 0. The CPU keeps stride 3; upload/read convert.
 */

import type { ClothModel } from '../core/model.js';
import {
  COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_MESH, COLLIDER_PLANE, COLLIDER_SPHERE,
  COARSE_OVERSHOOT, GOLDEN_ITERATIONS, MESH_SHARP_EDGE, MESH_SIGNED, SELF_EDGE_SHARE, TRIANGLE_SPREAD_MOST,
} from '../core/layout.generated.js';

/**
 * Shared with the CPU through the one table (core/gen-layout.mjs): the collider type ids the GPU knows, the
 * golden-section iterations of triangle contact, and a mesh collider's triangle flags (colliders/mesh.ts).
 */
export {
  COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_MESH, COLLIDER_PLANE, COLLIDER_SPHERE,
  GOLDEN_ITERATIONS, MESH_SHARP_EDGE, MESH_SIGNED,
};

/** Threads per workgroup of every kernel (1-D) but factorSolve. */
export const WORKGROUP_SIZE = 64;
/**
 * Threads of factorSolve's one workgroup (the most WebGPU's default limits allow): the rows of a level of a
 * triangular solve are shared among them, a barrier between levels.
 */
export const FACTOR_WORKGROUP = 256;
/**
 * factorIndex's header (global-bending.ts FactorLayout): the levels of the forward and backward solves, then where
 * each of its tables starts (in u32 elements of factorIndex; `upperValues`: where the entries by columns start in
 * factorValues).
 */
export const FACTOR_SLOTS = {
  forwardLevels: 0, backwardLevels: 1, rowOf: 2, lowerStart: 3, lowerCols: 4, upperStart: 5, upperRows: 6,
  forwardLevelStart: 7, forwardRows: 8, backwardLevelStart: 9, backwardRows: 10, rowBlock: 11, upperValues: 12,
} as const;
/** u32 elements of factorIndex's header */
export const FACTOR_HEADER = 16;
/** Most workgroups along x in one dispatch; bigger dispatches spill into y (see `flatIndex` in the preamble). */
export const MAX_WORKGROUPS_X = 65535;

/** The workgroups (x, y) of a dispatch over `count` threads, spilling into y past MAX_WORKGROUPS_X. */
export function workgroupsFor(count: number): [number, number] {
  const groups = Math.ceil(count / WORKGROUP_SIZE);
  return groups <= MAX_WORKGROUPS_X ? [groups, 1] : [MAX_WORKGROUPS_X, Math.ceil(groups / MAX_WORKGROUPS_X)];
}

/** Floats per vec3 element on the GPU. */
export const VEC4 = 4;
/** Byte stride of the dynamic-offset uniform records (minUniformBufferOffsetAlignment is at most 256). */
export const RECORD_STRIDE = 256;
/**
 * Entries of the fixed stack of a mesh collider's BVH walks (meshCollider.wgsl, triangleContact.wgsl): a walk keeps
 * at most one node per level below the root, so a hierarchy at most this deep (TriangleBvh.depth) fits; a deeper
 * one is refused (meshes.ts meshRefusal). Binned SAH makes 24 levels of a UV sphere of 998 000 triangles, 22 of a
 * terrain of 980 000, 16 of an icosphere of 20 480.
 */
export const MESH_STACK = 64;


/**
 * Self-contact (the selfContact phase; docs/gpu.md, "Self-contact"). Corrections are summed per particle with integer
 * atomics in fixed point: SELF_FIXED units per metre (2^26: 1.5e-8 m resolution, ±32 m per particle and pass), each
 * pair's share clamped to ±SELF_CLAMP m first, so that a sum wraps only past 128 shares at that clamp in one pass (a
 * particle's corrections there are a contact distance, millimetres). Integer sums do not depend on the order the
 * threads add in, so a pass gives the same result every run.
 */
export const SELF_FIXED = 2 ** 26;
export const SELF_CLAMP = 0.25;
/** Buckets each workgroup of the self-contact grid's prefix sum scans (4 per thread). */
export const SCAN_BLOCK = 4 * 64;
/** Primitives (triangles, edges) of a self-contact grid build; the build's Pass record says which (`flags`). */
export const SELF_TRIANGLES = 0;
export const SELF_EDGES = 1;

/**
 * Candidate pairs the self-contact list holds per primitive of the larger grid (selfGridSize `pairs`): 4× the most
 * measured (fold at 32², corner first onto the floor in layers: 2.0 edge pairs and 1.9 particle pairs per edge).
 * Pairs past it are counted, not kept: those contacts are not resolved that substep.
 */
export const SELF_PAIRS_PER_PRIMITIVE = 8;

/**
 * Jacobi passes of the edge pairs per substep (selfEdges then selfApply, over the one list of candidates). Several,
 * where the CPU's Gauss–Seidel sweep is one: in a fold every edge pair of two vertices' fans measures the same
 * vertex–vertex gap (up to 6 × 6 pairs), so a particle averages a pair that passed through with a dozen that only
 * ask for a fraction of a millimetre, and one pass closed 0.24 mm of the 4.3 mm the pair lacked. Measured on the
 * drag of docs/physics.md "A fast grab" (`node scripts/grab-drag.mjs --faces 24|40 --kernel gpu`), one pass: 1 then
 * 4 crossing pairs at 24² (frames 20–21), 8–26 at 40² from frame 19; two: none over 30 frames at either; a second
 * pass of the particle pairs instead: 1 at 24². Four since 2026-12-07: with two, the built-in fold at 32² crossed
 * itself at its landing corner (two triangles one apart, from frame 8 on, still at frame 300) once the coarse
 * correction became the default stretch solve (a88a5a3; the sweep alone crossed nowhere); four edge passes keep it
 * apart with either stretch solve, two particle passes only with the coarse correction (it then crossed with the
 * sweep alone), three of each with both (SwiftShader, frames 8, 10 and 20).
 */
export const SELF_EDGE_PASSES = 4;

/**
 * The sizes of a model's self-contact grid: `primitives` = the larger of its triangle and edge counts (one grid at a
 * time holds either), `buckets` of the spatial hash (a power of two, at least twice the primitives and SCAN_BLOCK),
 * `blocks` = buckets / SCAN_BLOCK, `entries` = 8 per primitive (a box spans at most 2 cells per axis: the cell is
 * the largest box), `pairs` the candidates' list holds (`pairsPerPrimitive` per primitive, SELF_PAIRS_PER_PRIMITIVE
 * unless a test asks for fewer).
 */
export function selfGridSize(model: ClothModel, pairsPerPrimitive = SELF_PAIRS_PER_PRIMITIVE): { primitives: number; buckets: number; blocks: number; entries: number; pairs: number } {
  const primitives = Math.max(model.triangles.length / 3, model.edges.length / 2);
  const buckets = Math.max(SCAN_BLOCK, 2 ** Math.ceil(Math.log2(Math.max(1, 2 * primitives))));
  return { primitives, buckets, blocks: buckets / SCAN_BLOCK, entries: 8 * primitives, pairs: Math.max(1, Math.floor(pairsPerPrimitive * primitives)) };
}

/** Flags of a solve or bending pass record. */
export const PASS_CAP = 1; // apply the hard stretch cap (structural and shear batches; never set on a bending batch)
export const PASS_READ_LAMBDA = 2; // start from the accumulated λ (second and later iterations)

/**
 * Structs, each one list of fields in declaration order: the WGSL declaration and the byte offsets the solver writes
 * at are both derived from it (`structLayout`, WGSL's layout rules, which for these types are the same in uniform
 * and storage buffers), so they cannot drift apart. Uniforms: `Globals` is written by setParams and (the grab) by
 * every step; `Substep` is one record per substep at RECORD_STRIDE, selected with a dynamic offset; `Pass` likewise,
 * one record per solve batch / bending batch / collider pass. Storage: `Collider` (the `colliders` buffer), `Carry`
 * (`carried`), `MeshNode` (`meshNodes`) and `MeshTriangle` (`meshTriangles`).
 */
type Field = readonly [name: string, type: string, doc: string];

/** Alignment and size [bytes] of the WGSL types the structs use (WGSL §"Memory layout"). */
const TYPES: Record<string, { align: number; size: number }> = {
  f32: { align: 4, size: 4 }, u32: { align: 4, size: 4 }, i32: { align: 4, size: 4 },
  vec3f: { align: 16, size: 12 }, vec4f: { align: 16, size: 16 },
};

type Layout<F extends readonly Field[]> = { readonly [K in F[number][0]]: number } & { readonly size: number };

/** Byte offset of every field and the struct's size, by WGSL's rules for uniform buffers. */
function structLayout<const F extends readonly Field[]>(fields: F): Layout<F> {
  const out: Record<string, number> = {};
  let at = 0, align = 1;
  for (const [name, type] of fields) {
    const t = TYPES[type];
    if (!t) throw new Error(`layout: no WGSL layout for ${type}`);
    at = Math.ceil(at / t.align) * t.align;
    out[name] = at;
    at += t.size;
    align = Math.max(align, t.align);
  }
  out.size = Math.ceil(at / align) * align;
  return out as Layout<F>;
}

/** The WGSL declaration of a struct. */
function wgslStruct(name: string, fields: readonly Field[]): string {
  return `struct ${name} {\n${fields.map(([f, type, doc]) => `  ${f}: ${type}, // ${doc}`).join('\n')}\n}`;
}

/**
 * A collider in one substep (colliders.ts writes it from its PosedCollider): its shape in its own frame, where that
 * frame is at the substep's end, and how its surface moved over the substep.
 */
const COLLIDER_FIELDS = [
  ['pose0', 'vec4f', 'world = R·local + o at the end of the substep (PosedCollider.R, .o): row 0 of R, o.x in w [m]'],
  ['pose1', 'vec4f', 'row 1 of R, o.y in w [m]'],
  ['pose2', 'vec4f', 'row 2 of R, o.z in w [m]'],
  ['motion0', 'vec4f', 'the surface motion over the substep at world point p is M·p + m [m], M = I − RD, m = −oD (PosedCollider.surfaceMotion): row 0 of M, m.x in w; zero while it does not move'],
  ['motion1', 'vec4f', 'row 1 of M, m.y in w [m]'],
  ['motion2', 'vec4f', 'row 2 of M, m.z in w [m]'],
  ['shape', 'vec4f', 'PosedCollider.shapeParams in xyz [m]: sphere radius; box half extents; capsule half length, radius; cylinder radius, half height'],
  ['kind', 'u32', 'COLLIDER_* type id'],
  ['moving', 'u32', '1 when its surface moved over the substep (PosedCollider.moving)'],
  ['meshRoot', 'u32', 'a mesh collider\'s root node in meshNodes (its hierarchy, in its own frame); 0 for other shapes'],
  ['meshClosed', 'u32', '1 when a mesh collider has a closed piece (a point with no triangle within reach may be inside it), else 0'],
] as const satisfies readonly Field[];

/** A particle a collider carries (params.carried): the carry kernel puts it at R·local + o of its collider. */
const CARRY_FIELDS = [
  ['local', 'vec3f', 'its position in the collider\'s own frame [m]'],
  ['particle', 'u32', 'the particle'],
  ['collider', 'u32', 'the collider, an index into params.colliders'],
] as const satisfies readonly Field[];

/**
 * A node of a mesh collider's BVH (colliders/bvh.ts TriangleBvh: its `bounds` and `nodes`), every mesh collider of
 * the params in one array (gpu/meshes.ts), indices made absolute: an inner node's children are `first` and
 * `first` + 1 of this array, a leaf's triangles `first` … `first` + count − 1 of meshTriangles.
 */
const MESH_NODE_FIELDS = [
  ['lo', 'vec3f', 'the box of the node\'s triangles, lowest corner, in the mesh\'s own frame [m]'],
  ['first', 'u32', 'inner node (count 0): its first child in meshNodes; leaf: its first triangle in meshTriangles'],
  ['hi', 'vec3f', 'the box\'s highest corner [m]'],
  ['count', 'u32', 'triangles of a leaf; 0 for an inner node'],
] as const satisfies readonly Field[];

/**
 * A triangle of a mesh collider (colliders/mesh.ts MeshCollider, leaf order), its own frame: corners, unit normal,
 * the triangles across its edges (for the edge pseudo-normal) and the angle-weighted pseudo-normals of its corners.
 */
const MESH_TRIANGLE_FIELDS = [
  ['a', 'vec3f', 'corner 0 [m]'],
  ['flags', 'u32', 'MESH_SIGNED (in a closed piece), MESH_SHARP_EDGE << e (owns its sharp edge e, corner e to e + 1)'],
  ['b', 'vec3f', 'corner 1 [m]'],
  ['across0', 'i32', 'the triangle across edge 0 (a to b) in meshTriangles, −1 none (a rim, or an edge of three or more)'],
  ['c', 'vec3f', 'corner 2 [m]'],
  ['across1', 'i32', 'the triangle across edge 1 (b to c), −1 none'],
  ['normal', 'vec3f', 'unit face normal (outward in a closed piece)'],
  ['across2', 'i32', 'the triangle across edge 2 (c to a), −1 none'],
  ['normalA', 'vec3f', 'angle-weighted pseudo-normal of corner a (MeshCollider.vertexNormals: not unit; zero in an open piece) [rad]'],
  ['_p0', 'u32', 'padding'],
  ['normalB', 'vec3f', 'the same of corner b [rad]'],
  ['_p1', 'u32', 'padding'],
  ['normalC', 'vec3f', 'the same of corner c [rad]'],
  ['_p2', 'u32', 'padding'],
] as const satisfies readonly Field[];

export const COLLIDER = structLayout(COLLIDER_FIELDS);
export const CARRY = structLayout(CARRY_FIELDS);
export const MESH_NODE = structLayout(MESH_NODE_FIELDS);
export const MESH_TRIANGLE = structLayout(MESH_TRIANGLE_FIELDS);

/** Storage buffers: WGSL element type and bytes per element. */
export const BUFFERS = {
  /** x, y, z, 0 [m] per particle; also a vertex buffer for renderers */
  positions: { type: 'vec4f', bytes: 16 },
  /** positions at the start of the current substep [m] (x − h·v at the start of a frame) */
  previous: { type: 'vec4f', bytes: 16 },
  /** the part of each position finer than float32 [m] (ClothState.residuals; precision.wgsl) */
  residuals: { type: 'vec4f', bytes: 16 },
  /** the residuals of `previous` [m] */
  previousResiduals: { type: 'vec4f', bytes: 16 },
  /** [m/s] per particle, of the last substep of the last frame */
  velocities: { type: 'vec4f', bytes: 16 },
  /** effective inverse mass of this frame [1/kg]: 0 for pinned and grabbed particles (written by `prepare`) */
  invMass: { type: 'f32', bytes: 4 },
  /** inverse mass of each particle when free [1/kg] (params.particleInvMass) */
  baseInvMass: { type: 'f32', bytes: 4 },
  /** 1 where pinned */
  pinned: { type: 'u32', bytes: 4 },
  /** spring end points (model.springs, sorted by kind then colour) */
  springs: { type: 'vec2u', bytes: 8 },
  /** per spring: rest length [m], compliance [m/N] or −1 for "no constraint" (compliance Infinity on the CPU) */
  springData: { type: 'vec2f', bytes: 8 },
  /** Lagrange multiplier (elastic part) per spring, accumulated over the iterations of a substep */
  lambdas: { type: 'f32', bytes: 4 },
  /**
   * the bending stencils of the params' model (model.stencils.hinges or .laplacian, sorted by colour): the first
   * entry of each and one past the last's (BendingStencils.offsets). This and the next four are placeholders until
   * params first use a stencil model, and are made anew when they switch to the other (buffers.ts makeStencils)
   */
  stencilOffsets: { type: 'u32', bytes: 4 },
  /** the particle of each stencil entry (BendingStencils.vertices) */
  stencilVertices: { type: 'u32', bytes: 4 },
  /** the weight K of each stencil entry (BendingStencils.weights): C = Σ K_k x_k [-] */
  stencilWeights: { type: 'f32', bytes: 4 },
  /** per stencil: compliance A/B [m/N] or −1 for "no constraint" (params.stencilCompliance Infinity on the CPU) */
  stencilCompliance: { type: 'f32', bytes: 4 },
  /**
   * Lagrange multipliers of the stencils, 3 per stencil (flat: `array<vec3f>` would have stride 16) [N·s²]
   * (ClothState.bendingLambdas), accumulated over the iterations of a substep
   */
  stencilLambdas: { type: 'f32', bytes: 4 },
  /**
   * the global bending step (solver.bendingSolve 'global'; global-bending.ts). Per stencil: its stiffness in the
   * step's matrix (1 + τ/h)/α and its damping's pull (τ/h)/α [N/m] (core BendingSystem stiffness, pull). This and
   * the next five are placeholders until params first solve the stencils together, made anew for another system
   */
  bendingCoefficients: { type: 'vec2f', bytes: 8 },
  /** per stencil: its force term d = (1 + τ/h)/α·C(x) − (τ/h)/α·C(x_prev), x, y, z, 0 [N] (bendingForces) */
  stencilForce: { type: 'vec4f', bytes: 16 },
  /**
   * particle → its stencil entries: n + 1 starts (already offset by n + 1, in pairs), then per entry the entry's
   * index k (into stencilVertices, stencilWeights) and its stencil e
   */
  stencilIncidence: { type: 'u32', bytes: 4 },
  /**
   * the structure of the factor L of the step's matrix (core SparseCholesky, in its nested-dissection order; global-
   * bending.ts FactorLayout): FACTOR_SLOTS first (where each table starts), then each particle's row, L's entries
   * outside its blocks by rows and by columns, the rows of each level of the two triangular solves, and each row's
   * block (first row, one past its last, where the row's row of the block's inverse starts in factorValues)
   */
  factorIndex: { type: 'u32', bytes: 4 },
  /** L's values for factorIndex's tables: the entries outside the blocks by rows, then by columns, then the blocks' inverses */
  factorValues: { type: 'f32', bytes: 4 },
  /**
   * by row: the step's right-hand side (bendingGather), then the forward solve's y, then the solution Δx = x − x*
   * (factorSolve) [m]
   */
  globalX: { type: 'vec4f', bytes: 16 },
  /** by row: what a block's rows gather from outside it, before its inverse is applied (factorSolve) [m] */
  globalT: { type: 'vec4f', bytes: 16 },
  /** z = A⁻¹·e_g by row for the grabbed particle g (core PrefactoredSystem.z): the grab held without a refactor [m²/N] */
  grabColumn: { type: 'f32', bytes: 4 },
  /**
   * the global stretch step (solver.stretch 'global'; core global-stretch.ts). Per spring (model.springs): its
   * stiffness k [N/m] (0: not in the step), rest length L [m], damping weight β/h and the step's weight k + β/h [N/m].
   * This and the next six are placeholders until params first solve the springs together
   */
  stretchCoefficients: { type: 'vec4f', bytes: 16 },
  /**
   * per spring: its part of the right-hand side of A·Δx = Σ S_sᵀ·f_s, f_s = k·L·n + (β/h)·q − (k + β/h)·(y_a − y_b),
   * x, y, z, 0 [N] (stretchForces)
   */
  springForce: { type: 'vec4f', bytes: 16 },
  /** particle → its springs: n + 1 starts (already offset by n + 1), then per spring 2s (its first end) or 2s + 1 */
  springIncidence: { type: 'u32', bytes: 4 },
  /** per particle: the predicted positions y the passes start from (stretchStart) [m] */
  globalY: { type: 'vec4f', bytes: 16 },
  /** the stretch step's factor as factorIndex holds the bending step's (FactorLayout) */
  stretchFactorIndex: { type: 'u32', bytes: 4 },
  /** its values, as factorValues */
  stretchFactorValues: { type: 'f32', bytes: 4 },
  /** its z = A⁻¹·e_g, as grabColumn [m²/N] */
  stretchGrabColumn: { type: 'f32', bytes: 4 },
  /**
   * the springs' coarse correction (solver.stretch 'two-level'; core coarse-stretch.ts, coarse-stretch.ts here). Per
   * spring: its unit direction now and its residual L − |x_a − x_b| [m], all 0 where it takes no part (no stiffness,
   * both ends fixed, no length) (coarseDirections). This and the next seventeen are placeholders until params first
   * correct the springs so (CoarseTables, made once per model)
   */
  coarseDir: { type: 'vec4f', bytes: 16 },
  /**
   * per aggregate: the right-hand side Σ (L − len) of its springs [m], then the forward solve's y, then μ [N·s²]
   * (coarseSolve); α̃ = Σ α/h² of its springs [1/kg]; the right-hand side again, kept for a second solve (coarseRows); 0
   */
  coarseRhs: { type: 'vec4f', bytes: 16 },
  /** per spring: its aggregate */
  coarseSpringAggregate: { type: 'u32', bytes: 4 },
  /**
   * the indirect dispatches (workgroups x, y, z) of the five kernels that make the matrix anew and solve again
   * (coarseTouch, coarseAssemble, coarseFactor, coarseInvert, coarseSolve) in a substep after the frame's first:
   * coarseCheck copies the next fifteen words (their full dispatches, written once per model) where the step of the
   * last factor overshoots under the matrix now, else zeroes; then the check's two sums, μᵀ·r and μᵀ·A·μ (f32 bits),
   * which the tests read; INDIRECT usage
   */
  coarseArgs: { type: 'u32', bytes: 4 },
  /**
   * per thread of coarseCheckParts (an aggregate and a particle): its terms of μᵀ·r and of μᵀ·A·μ (the check of a
   * step of the last factor)
   */
  coarsePartials: { type: 'vec2f', bytes: 8 },
  /** per aggregate: where its springs start and end in coarseMembers, its cloth, 0 */
  coarseAggregates: { type: 'vec4u', bytes: 16 },
  /** the springs of each aggregate, aggregate after aggregate */
  coarseMembers: { type: 'u32', bytes: 4 },
  /**
   * per cloth, two rows: its first aggregate, its aggregates, its matrix's half bandwidth b and the rows of a block
   * of its triangular solves (min(b + 1, FACTOR_WORKGROUP)); where its matrix starts in coarseMatrix and coarseFactor,
   * where its blocks' inverses start in coarseInverse, 0, 0
   */
  coarseBlocks: { type: 'vec4u', bytes: 16 },
  /**
   * particle → its springs, each particle's sorted by aggregate: n + 1 starts (already offset by n + 1), then per
   * spring 2s (its first end) or 2s + 1
   */
  coarseIncidence: { type: 'u32', bytes: 4 },
  /**
   * the (particle, aggregate) pairs, one per aggregate a particle's springs belong to: the particle, the aggregate,
   * where its springs start and end in coarseIncidence
   */
  coarsePairs: { type: 'vec4u', bytes: 16 },
  /** per pair: v = Σ ±n_s over its springs [-] and the particle's inverse mass [1/kg] (coarseTouch) */
  coarsePairVec: { type: 'vec4f', bytes: 16 },
  /** per entry of the banded matrices (coarseMatrix's order): where its pairs of pairs start in coarseEntryPairs; one more */
  coarseEntryStart: { type: 'u32', bytes: 4 },
  /** per entry, the pairs (i, g) and (i, h) of each particle i whose springs are in both aggregates g and h */
  coarseEntryPairs: { type: 'vec2u', bytes: 8 },
  /**
   * the cloths' banded matrices R·(J·M⁻¹·Jᵀ + α̃)·Rᵀ, row i of a cloth's holding entries (i, i − b … i) [1/kg]
   * (coarseAssemble), overwritten by the Schur complements of the factorisation (coarseFactor)
   */
  coarseMatrix: { type: 'f32', bytes: 4 },
  /** their Cholesky factors L, laid out as coarseMatrix [1/√kg] (coarseFactor) */
  coarseFactor: { type: 'f32', bytes: 4 },
  /** the inverses of L's diagonal blocks (a block's rows by rows, packed lower triangles) [√kg] (coarseInvert) */
  coarseInverse: { type: 'f32', bytes: 4 },
  /** per spring: the four aggregates its multiplier is interpolated between */
  coarseNear: { type: 'vec4u', bytes: 16 },
  /** per spring: their bilinear weights [-] */
  coarseWeights: { type: 'vec4f', bytes: 16 },
  /** per particle: nearest pin (−1: none) and the rest distance to it [m] */
  tethers: { type: 'Tether', bytes: 8 },
  /** triangle vertex indices, 3 per triangle (flat: `array<vec3u>` would have stride 16) */
  triangles: { type: 'u32', bytes: 4 },
  /** wind force of each triangle, one third of it per vertex [N] */
  triForces: { type: 'vec4f', bytes: 16 },
  /** particle → incident triangles, CSR: n + 1 offsets (already offset by n + 1), then triangle indices */
  adjacency: { type: 'u32', bytes: 4 },
  /** area-weighted vertex normals, unit length, for renderers */
  normals: { type: 'vec4f', bytes: 16 },
  /**
   * the grab's frame (2 elements): [0] the grabbed particle's position at the start of the frame, [1] where the
   * grab carries it by the frame's end (grabFrame, kept out of the colliders by grabOutside) [m]
   */
  grabStart: { type: 'vec4f', bytes: 16 },
  /**
   * every collider's pose and surface motion: one record per collider (params.colliders order) while none moves,
   * else one per collider per substep of the frame (Substep.colliderBase says where a substep's start)
   */
  colliders: { type: 'Collider', bytes: COLLIDER.size },
  /** the particles colliders carry (params.carried), Globals.carriedCount of them */
  carried: { type: 'Carry', bytes: CARRY.size },
  /** the BVH nodes of every mesh collider of the params (Collider.meshRoot: where each one's root is) */
  meshNodes: { type: 'MeshNode', bytes: MESH_NODE.size },
  /** the triangles of every mesh collider of the params, each one's in its BVH's leaf order */
  meshTriangles: { type: 'MeshTriangle', bytes: MESH_TRIANGLE.size },
  /**
   * the mesh's edges (model.edges: a < b). This and the self-contact buffers below are 16-byte placeholders until
   * params first turn self-contact on (buffers.ts makeSelfContact), then sized by selfGridSize
   */
  edges: { type: 'vec2u', bytes: 8 },
  /**
   * each primitive of the grid being built (triangles or edges): its box over the substep (start ∪ end positions),
   * widened by the self-contact distance h (an edge's by h/2), two rows: lowest corner, highest corner [m]
   */
  selfBoxes: { type: 'vec4f', bytes: 16 },
  /** 8 per primitive: its place in each of its cells' buckets (selfCount), for selfScatter */
  selfRanks: { type: 'u32', bytes: 4 },
  /**
   * the grid being built: [0] the largest box extent (f32 bits: positive floats order as their bits) [m], then the
   * primitives in each bucket; zeroed again by selfScanAdd once the starts are made
   */
  selfCounts: { type: 'atomic<u32>', bytes: 4 },
  /** [0] the grid's largest box extent (f32 bits) [m], then each bucket's first entry in selfEntries, and the total */
  selfStarts: { type: 'u32', bytes: 4 },
  /** each SCAN_BLOCK buckets' count, then its exclusive prefix (selfScan, selfScanTotals) */
  selfBlocks: { type: 'u32', bytes: 4 },
  /** the primitives of each bucket, bucket after bucket (counting sort) */
  selfEntries: { type: 'u32', bytes: 4 },
  /**
   * the candidate pairs of the pass being made (particle, triangle) or (edge, later edge): [0] how many were found
   * (atomic; selfPairArgs zeroes it), then the pairs, at most globals.selfPairCapacity of them
   */
  selfPairs: { type: 'atomic<u32>', bytes: 4 },
  /**
   * the indirect dispatch of the pair pass (workgroups x, y, z) and the pairs it resolves; then the most pairs any
   * pass found since the last readback (more than the list's capacity: pairs that went unresolved), which the
   * readback zeroes; INDIRECT usage
   */
  selfArgs: { type: 'u32', bytes: 4 },
  /**
   * per particle: the sum of its corrections of one pass in fixed point (xyz, SELF_FIXED per metre) and how many
   * pairs moved it (w); zeroed by selfApply
   */
  selfDelta: { type: 'atomic<i32>', bytes: 4 },
} as const;
export type BufferName = keyof typeof BUFFERS;

type Access = 'read' | 'read_write';
/**
 * A kernel: its WGSL file (src/gpu/shaders/<name>.wgsl, or `file`), the libraries it includes, its storage bindings.
 * One file with other libraries is another kernel (the contact kernels of analytic colliders and of mesh colliders:
 * the same loop over another `localDistance` and `triangleDeepest`).
 */
export interface KernelSpec {
  /**
   * group(1) bindings in binding order: the WGSL variable (named as the buffer whose type it has), its access, and
   * the buffer bound to it where that is another of the same type (a kernel file run on two sets of buffers)
   */
  readonly bindings: readonly (readonly [BufferName, Access] | readonly [BufferName, Access, BufferName])[];
  /** other .wgsl files (function libraries) placed before the kernel */
  readonly libs?: readonly string[];
  /** the .wgsl file of its entry point, where that is not the kernel's name */
  readonly file?: string;
}

/** Every kernel. At most 8 storage buffers each (the default maxStorageBuffersPerShaderStage). */
export const KERNELS = {
  /** beginStep: effective inverse masses (pins, grab), previous = x − h·v */
  prepare: {
    bindings: [
      ['baseInvMass', 'read'], ['pinned', 'read'], ['invMass', 'read_write'], ['positions', 'read'],
      ['previous', 'read_write'], ['velocities', 'read'], ['residuals', 'read'], ['previousResiduals', 'read_write'],
    ],
    libs: ['precision'],
  },
  /** accumulateWind, per triangle: F = ½ρ|v|(v·n)·area·n on the relative air velocity */
  wind: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['triangles', 'read'], ['baseInvMass', 'read'],
      ['triForces', 'read_write'],
    ],
  },
  /** integrate: gathers the wind of incident triangles (no atomics) */
  integrate: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['triForces', 'read'],
      ['adjacency', 'read'], ['residuals', 'read_write'], ['previousResiduals', 'read_write'],
    ],
    libs: ['precision'],
  },
  /** grabFrameTarget, once per frame: where the grab carries its particle by the frame's end, one thread */
  grabFrame: { bindings: [['grabStart', 'read_write']] },
  /** keepGrabOutside on that point, for a run of analytic colliders (twice over the runs: two rounds), one thread */
  grabOutside: {
    bindings: [['grabStart', 'read_write'], ['colliders', 'read']],
    libs: ['pose', 'colliders', 'shapes'],
  },
  /** the same for a run of mesh colliders (the mesh's walks in a kernel of their own, as collideMeshParticles) */
  grabOutsideMesh: {
    file: 'grabOutside',
    bindings: [['grabStart', 'read_write'], ['colliders', 'read'], ['meshNodes', 'read'], ['meshTriangles', 'read']],
    libs: ['pose', 'colliders', 'meshCollider'],
  },
  /** moveGrabbed: the grabbed particle, one thread */
  grab: { bindings: [['positions', 'read_write'], ['grabStart', 'read'], ['residuals', 'read_write']] },
  /** solveDistanceConstraints for one colour batch */
  solve: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read'], ['invMass', 'read'], ['springs', 'read'],
      ['springData', 'read'], ['lambdas', 'read_write'],
    ],
  },
  /** solveBending (solvers/xpbd.ts) for one colour batch of bending stencils (hinges or Laplacian vertices) */
  bending: {
    bindings: [
      ['positions', 'read_write'], ['invMass', 'read'], ['stencilOffsets', 'read'], ['stencilVertices', 'read'],
      ['stencilWeights', 'read'], ['stencilCompliance', 'read'], ['stencilLambdas', 'read_write'],
    ],
  },
  /**
   * the global bending step (core solveGlobalBending), 1 of 4: each stencil's force term from its curvature now and
   * at the substep's start
   */
  bendingForces: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['stencilOffsets', 'read'], ['stencilVertices', 'read'],
      ['stencilWeights', 'read'], ['bendingCoefficients', 'read'], ['stencilForce', 'read_write'],
    ],
  },
  /** 2 of 4: each particle's right-hand side, −Σ K·d over its stencil entries (0 where pinned), into its row */
  bendingGather: {
    bindings: [
      ['stencilIncidence', 'read'], ['stencilWeights', 'read'], ['stencilForce', 'read'], ['pinned', 'read'],
      ['factorIndex', 'read'], ['globalX', 'read_write'],
    ],
  },
  /** 3 of 4: L·Lᵀ·Δx = b, both triangular solves block level by block level in one workgroup of FACTOR_WORKGROUP threads */
  factorSolve: { bindings: [['factorIndex', 'read'], ['factorValues', 'read'], ['globalX', 'read_write'], ['globalT', 'read_write']] },
  /** 4 of 4: x += Δx for the free particles, the grabbed one held where the grab put it */
  bendingApply: {
    bindings: [
      ['positions', 'read_write'], ['pinned', 'read'], ['factorIndex', 'read'], ['globalX', 'read'], ['grabColumn', 'read'],
    ],
    libs: ['heldCorrection'],
  },
  /**
   * the global stretch step (core solveGlobalStretch), its start: y ← x (the positions the passes start from)
   */
  stretchStart: { bindings: [['positions', 'read'], ['globalY', 'read_write']] },
  /** each pass, 1 of 4: each spring's local step, its direction at its rest length, as its force term */
  stretchForces: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['globalY', 'read'], ['springs', 'read'], ['stretchCoefficients', 'read'],
      ['springForce', 'read_write'],
    ],
  },
  /** 2 of 4: each particle's right-hand side, Σ ±f_s over its springs (0 where pinned), into its row */
  stretchGather: {
    bindings: [
      ['springIncidence', 'read'], ['springForce', 'read'], ['pinned', 'read'], ['factorIndex', 'read', 'stretchFactorIndex'],
      ['globalX', 'read_write'],
    ],
  },
  /** 3 of 4: factorSolve with the stretch step's factor */
  stretchSolve: {
    file: 'factorSolve',
    bindings: [
      ['factorIndex', 'read', 'stretchFactorIndex'], ['factorValues', 'read', 'stretchFactorValues'], ['globalX', 'read_write'],
      ['globalT', 'read_write'],
    ],
  },
  /** 4 of 4: x = y + Δx for the free particles, the grabbed one held where the grab put it */
  stretchApply: {
    bindings: [
      ['positions', 'read_write'], ['globalY', 'read'], ['pinned', 'read'], ['factorIndex', 'read', 'stretchFactorIndex'],
      ['globalX', 'read'], ['grabColumn', 'read', 'stretchGrabColumn'],
    ],
    libs: ['heldCorrection'],
  },
  /** the springs' coarse correction (core solveCoarseStretch), 1: each spring's direction and residual */
  coarseDirections: {
    bindings: [['positions', 'read'], ['invMass', 'read'], ['springs', 'read'], ['springData', 'read'], ['coarseDir', 'read_write']],
  },
  /** 2: each aggregate's right-hand side and α̃, from its springs */
  coarseRows: {
    bindings: [['coarseAggregates', 'read'], ['coarseMembers', 'read'], ['coarseDir', 'read'], ['springData', 'read'], ['coarseRhs', 'read_write']],
  },
  /**
   * 3a, after a solve with the last factor (not in a frame's first substep): the terms of whether its step overshoots
   * under the matrix now, one aggregate's and one particle's per thread
   */
  coarseCheckParts: {
    bindings: [
      ['coarseRhs', 'read'], ['coarseIncidence', 'read'], ['coarseDir', 'read'], ['coarseSpringAggregate', 'read'], ['invMass', 'read'],
      ['coarsePartials', 'read_write'],
    ],
  },
  /** 3b: their sum, the step's Rayleigh quotient past COARSE_OVERSHOOT or not, and the dispatches that follow (one workgroup) */
  coarseCheck: { bindings: [['coarsePartials', 'read'], ['coarseArgs', 'read_write']] },
  /** 4 (a frame's first substep, or a stale factor): each (particle, aggregate) pair's Σ ±n_s */
  coarseTouch: {
    bindings: [
      ['coarsePairs', 'read'], ['coarseIncidence', 'read'], ['coarseDir', 'read'], ['invMass', 'read'], ['coarsePairVec', 'read_write'],
    ],
  },
  /** 5 (the same): each aggregate's row of its cloth's banded matrix */
  coarseAssemble: {
    bindings: [
      ['coarseAggregates', 'read'], ['coarseBlocks', 'read'], ['coarseEntryStart', 'read'], ['coarseEntryPairs', 'read'],
      ['coarsePairVec', 'read'], ['coarseRhs', 'read'], ['coarseMatrix', 'read_write'],
    ],
  },
  /** 6 (the same): banded Cholesky, one workgroup of FACTOR_WORKGROUP threads per cloth */
  coarseFactor: { bindings: [['coarseBlocks', 'read'], ['coarseMatrix', 'read_write'], ['coarseFactor', 'read_write']] },
  /** 7 (the same): the inverses of the factors' diagonal blocks, a column per thread */
  coarseInvert: {
    bindings: [['coarseAggregates', 'read'], ['coarseBlocks', 'read'], ['coarseFactor', 'read'], ['coarseInverse', 'read_write']],
  },
  /** both triangular solves by blocks, one workgroup of FACTOR_WORKGROUP threads per cloth: μ (before coarseCheck and after 7) */
  coarseSolve: {
    bindings: [['coarseBlocks', 'read'], ['coarseFactor', 'read'], ['coarseInverse', 'read'], ['coarseRhs', 'read_write']],
  },
  /** 9: each spring's λ, interpolated between the aggregates around it */
  coarseLambda: {
    bindings: [['coarseDir', 'read'], ['coarseNear', 'read'], ['coarseWeights', 'read'], ['coarseRhs', 'read'], ['lambdas', 'read_write']],
  },
  /** 10: each free particle moved by M⁻¹·Jᵀ·λ */
  coarseMove: {
    bindings: [['positions', 'read_write'], ['invMass', 'read'], ['coarseIncidence', 'read'], ['coarseDir', 'read'], ['lambdas', 'read']],
  },
  /** limitStretch (phases.ts), which XPBD runs after the tethers, for one structural or shear batch */
  limitStretch: {
    bindings: [['positions', 'read_write'], ['invMass', 'read'], ['springs', 'read'], ['springData', 'read']],
  },
  /** solveTethers */
  tethers: { bindings: [['positions', 'read_write'], ['invMass', 'read'], ['tethers', 'read']] },
  /** carryPinned: each carried particle to where its collider puts it at the substep's end */
  carry: {
    bindings: [['positions', 'read_write'], ['carried', 'read'], ['colliders', 'read'], ['residuals', 'read_write']],
    libs: ['pose'],
  },
  /** collide, particle part, for a run of analytic colliders */
  collideParticles: {
    bindings: [['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['colliders', 'read']],
    libs: ['pose', 'colliders', 'shapes'],
  },
  /** collide, triangle part, for one analytic collider and one triangle colour */
  collideTriangles: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['triangles', 'read'],
      ['colliders', 'read'],
    ],
    libs: ['pose', 'colliders', 'shapes', 'triangleContact', 'shapeTriangles'],
  },
  /**
   * collide, particle part, for a run of mesh colliders: collideParticles over the mesh's distance (a kernel of its
   * own, so that the analytic shapes' kernels carry none of the mesh's walks)
   */
  collideMeshParticles: {
    file: 'collideParticles',
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['colliders', 'read'],
      ['meshNodes', 'read'], ['meshTriangles', 'read'],
    ],
    libs: ['pose', 'colliders', 'meshCollider'],
  },
  /** collide, triangle part, for one mesh collider and one triangle colour: collideTriangles over the mesh's */
  collideMeshTriangles: {
    file: 'collideTriangles',
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['triangles', 'read'],
      ['colliders', 'read'], ['meshNodes', 'read'], ['meshTriangles', 'read'],
    ],
    libs: ['pose', 'colliders', 'meshCollider', 'triangleContact', 'meshTriangles'],
  },
  /** self-contact grid, 1: each primitive's box over the substep, and the largest extent (the cell size) */
  selfBoxes: {
    bindings: [['positions', 'read'], ['previous', 'read'], ['triangles', 'read'], ['edges', 'read'], ['selfBoxes', 'read_write'], ['selfCounts', 'read_write']],
    libs: ['selfGrid'],
  },
  /** self-contact grid, 2: each primitive counted into the buckets of its cells, its rank in each kept */
  selfCount: {
    bindings: [['selfBoxes', 'read'], ['selfCounts', 'read_write'], ['selfRanks', 'read_write']],
    libs: ['selfGrid'],
  },
  /** self-contact grid, 3: exclusive prefix sums of the counts within each block of SCAN_BLOCK buckets */
  selfScan: { bindings: [['selfCounts', 'read'], ['selfStarts', 'read_write'], ['selfBlocks', 'read_write']] },
  /** self-contact grid, 4: exclusive prefix sum of the blocks' totals (one workgroup) */
  selfScanTotals: { bindings: [['selfBlocks', 'read_write']] },
  /** self-contact grid, 5: each bucket's start made global, the total and the cell size written, the counts zeroed */
  selfScanAdd: { bindings: [['selfCounts', 'read_write'], ['selfStarts', 'read_write'], ['selfBlocks', 'read']] },
  /** self-contact grid, 6: each primitive written into its cells' buckets (counting sort) */
  selfScatter: {
    bindings: [['selfBoxes', 'read'], ['selfStarts', 'read'], ['selfRanks', 'read'], ['selfEntries', 'read_write']],
    libs: ['selfGrid'],
  },
  /** collideSelf's candidates, particle part: each particle (pinned and grabbed ones too) against the triangles of its cells, pairs listed */
  selfFindPoints: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['triangles', 'read'], ['selfBoxes', 'read'],
      ['selfStarts', 'read'], ['selfEntries', 'read'], ['selfPairs', 'read_write'],
    ],
    libs: ['selfGrid', 'selfList'],
  },
  /** collideSelf's candidates, edge part (collideEdges): each edge against the later edges of its cells, pairs listed */
  selfFindEdges: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['edges', 'read'], ['selfBoxes', 'read'], ['selfStarts', 'read'],
      ['selfEntries', 'read'], ['selfPairs', 'read_write'],
    ],
    libs: ['selfGrid', 'selfList'],
  },
  /** the indirect dispatch of the pair pass from the candidates listed, the list's count zeroed */
  selfPairArgs: { bindings: [['selfPairs', 'read_write'], ['selfArgs', 'read_write']] },
  /** collideSelf, particle part (resolvePair): one particle–triangle pair per thread, corrections summed (Jacobi) */
  selfPoints: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['invMass', 'read'], ['triangles', 'read'], ['selfPairs', 'read'],
      ['selfArgs', 'read'], ['selfDelta', 'read_write'],
    ],
    libs: ['selfCorrect'],
  },
  /** collideSelf, edge part (resolveEdges): one edge pair per thread, corrections summed (Jacobi) */
  selfEdges: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['invMass', 'read'], ['edges', 'read'], ['selfPairs', 'read'],
      ['selfArgs', 'read'], ['selfDelta', 'read_write'],
    ],
    libs: ['selfCorrect'],
  },
  /** the summed corrections of a self-contact pass applied, each particle by their mean, and zeroed */
  selfApply: { bindings: [['positions', 'read_write'], ['selfDelta', 'read_write']] },
  /** updateVelocities, once per frame */
  velocities: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['velocities', 'read_write'], ['residuals', 'read'], ['previousResiduals', 'read'],
    ],
  },
  /** vertex normals for rendering */
  normals: {
    bindings: [['positions', 'read'], ['triangles', 'read'], ['adjacency', 'read'], ['normals', 'read_write']],
  },
} as const satisfies Record<string, KernelSpec>;
export type KernelName = keyof typeof KERNELS;

const GLOBALS_FIELDS = [
  ['gravity', 'vec3f', '[m/s²]'],
  ['iterations', 'u32', 'constraint passes per substep'],
  ['damping', 'f32', 'β [N·s/m]'],
  ['stretchFactor', 'f32', 'stretch cap × rest length'],
  ['friction', 'f32', 'kinetic friction coefficient'],
  ['staticFriction', 'f32', 'static friction coefficient'],
  ['thickness', 'f32', 'contact thickness [m]'],
  ['reach', 'f32', 'thickness + 2·maxTriangleEdge [m]'],
  ['windK', 'f32', '¼ρ/3'],
  ['grabbed', 'i32', 'grabbed particle, −1 none'],
  ['grabTarget', 'vec3f', '[m]'],
  ['particleCount', 'u32', 'particles of the model'],
  ['triangleCount', 'u32', 'triangles of the model'],
  ['colliderCount', 'u32', 'colliders in use (params.colliders)'],
  ['carriedCount', 'u32', 'particles the colliders carry (params.carried)'],
  ['edgeCount', 'u32', 'edges of the model (model.edges)'],
  ['selfDistance', 'f32', 'the self-contact distance h (core selfContactDistance) [m]'],
  ['selfBuckets', 'u32', 'buckets of the self-contact grid (selfGridSize of the model)'],
  ['selfBlockCount', 'u32', 'its blocks of SCAN_BLOCK buckets'],
  ['selfPairCapacity', 'u32', 'the candidate pairs selfPairs holds (selfGridSize)'],
] as const satisfies readonly Field[];

const SUBSTEP_FIELDS = [
  ['wind', 'vec3f', 'wind velocity at this substep\'s start time [m/s]'],
  ['h', 'f32', 'substep [s]'],
  ['h2', 'f32', 'c·h², c = ½ on the very first substep (Taylor start), else 1'],
  ['invH', 'f32', '1/h'],
  ['invH2', 'f32', '1/h²'],
  ['betaOverH', 'f32', 'damping/h'],
  ['grabFraction', 'f32', '(sub + 1)/substeps'],
  ['grabMaxMove', 'f32', 'most the grab carries its particle this frame, params.grabSpeed × dt; −1: no limit [m]'],
  ['windOn', 'u32', '1 when the wind blows'],
  ['recover', 'f32', 'depenetrationSpeed·h: most a collider overlap the cloth did not move into is undone [m]'],
  ['recoverTriangle', 'f32', 'recover / model.maxTriangleValence: the same for triangle contact [m]'],
  ['colliderBase', 'u32', 'this substep\'s first record in the colliders buffer: 0 while no collider moves, else substep × colliderCount'],
] as const satisfies readonly Field[];

const PASS_FIELDS = [
  ['start', 'u32', 'first element (spring, bending stencil, triangle, or collider)'],
  ['end', 'u32', 'one past the last'],
  ['cap', 'f32', 'stretch cap (× rest length)'],
  ['flags', 'u32', 'PASS_* flags, or the collider index of a triangle pass'],
] as const satisfies readonly Field[];

export const GLOBALS = structLayout(GLOBALS_FIELDS);
export const SUBSTEP = structLayout(SUBSTEP_FIELDS);
export const PASS = structLayout(PASS_FIELDS);

/** A number as a WGSL f32 literal (an integer gets its '.0': `2` alone would be an integer). */
export function wgslFloat(v: number): string {
  if (!Number.isFinite(v)) throw new Error(`wgslFloat: ${v} is not a finite number`);
  return Number.isInteger(v) && Math.abs(v) < 1e21 ? `${v}.0` : String(v);
}

/** WGSL text of the shared declarations, prepended to every kernel. */
export function wgslPreamble(): string {
  return `// ---- generated from src/gpu/layout.ts ----
const WG: u32 = ${WORKGROUP_SIZE}u;
const MAX_WORKGROUPS_X: u32 = ${MAX_WORKGROUPS_X}u;
const COLLIDER_SPHERE: u32 = ${COLLIDER_SPHERE}u;
const COLLIDER_FLOOR: u32 = ${COLLIDER_FLOOR}u;
const COLLIDER_PLANE: u32 = ${COLLIDER_PLANE}u;
const COLLIDER_BOX: u32 = ${COLLIDER_BOX}u;
const COLLIDER_CAPSULE: u32 = ${COLLIDER_CAPSULE}u;
const COLLIDER_CYLINDER: u32 = ${COLLIDER_CYLINDER}u;
const COLLIDER_MESH: u32 = ${COLLIDER_MESH}u;
const MESH_SIGNED: u32 = ${MESH_SIGNED}u;
const MESH_SHARP_EDGE: u32 = ${MESH_SHARP_EDGE}u;
const MESH_STACK: u32 = ${MESH_STACK}u;
const GOLDEN_ITERATIONS: u32 = ${GOLDEN_ITERATIONS}u;
const TRIANGLE_SPREAD_MOST: f32 = ${wgslFloat(TRIANGLE_SPREAD_MOST)};
const PASS_CAP: u32 = ${PASS_CAP}u;
const PASS_READ_LAMBDA: u32 = ${PASS_READ_LAMBDA}u;
const COARSE_OVERSHOOT: f32 = ${wgslFloat(COARSE_OVERSHOOT)};
const SELF_FIXED: f32 = ${wgslFloat(SELF_FIXED)};
const SELF_CLAMP: f32 = ${wgslFloat(SELF_CLAMP)};
const SELF_EDGE_SHARE: f32 = ${wgslFloat(SELF_EDGE_SHARE)};
const SCAN_BLOCK: u32 = ${SCAN_BLOCK}u;
const SELF_TRIANGLES: u32 = ${SELF_TRIANGLES}u;
const SELF_EDGES: u32 = ${SELF_EDGES}u;
const FACTOR_WORKGROUP: u32 = ${FACTOR_WORKGROUP}u;
${Object.entries(FACTOR_SLOTS).map(([name, slot]) => `const FACTOR_${name.replace(/[A-Z]/g, (c) => `_${c}`).toUpperCase()}: u32 = ${slot}u;`).join('\n')}

${wgslStruct('Collider', COLLIDER_FIELDS)}

${wgslStruct('Carry', CARRY_FIELDS)}

${wgslStruct('MeshNode', MESH_NODE_FIELDS)}

${wgslStruct('MeshTriangle', MESH_TRIANGLE_FIELDS)}

${wgslStruct('Globals', GLOBALS_FIELDS)}

${wgslStruct('Substep', SUBSTEP_FIELDS)}

${wgslStruct('Pass', PASS_FIELDS)}

struct Tether {
  anchor: i32,
  length: f32,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var<uniform> sub: Substep;
@group(0) @binding(2) var<uniform> batch: Pass;

/** Thread index of a 1-D dispatch that may spill into y when it needs more than ${MAX_WORKGROUPS_X} workgroups. */
fn flatIndex(gid: vec3u, nwg: vec3u) -> u32 {
  return gid.x + gid.y * nwg.x * WG;
}
`;
}

/**
 * WGSL `var` declarations of a kernel's storage bindings (group 1). A buffer of atomics bound read-only is read as
 * its plain type (WGSL allows atomics only in read_write storage).
 */
export function wgslBindings(kernel: KernelName): string {
  const spec: KernelSpec = KERNELS[kernel];
  return spec.bindings
    .map(([name, access], i) => {
      const type: string = BUFFERS[name].type;
      const element = access === 'read' ? type.replace(/^atomic<(.*)>$/, '$1') : type;
      return `@group(1) @binding(${i}) var<storage, ${access}> ${name}: array<${element}>;`;
    })
    .join('\n');
}
