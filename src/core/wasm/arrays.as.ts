// The kernel's arrays: byte offsets into the memory, laid out by the caller (xpbd-wasm.ts) and set by configure()
// in every instance (each thread's). Read by the phases; written only here.

/** positions, f32 × 3n */
export let X: usize = 0;
/** previous positions, f32 × 3n */
export let XP: usize = 0;
/** residuals of the positions (the part finer than f32), f32 × 3n */
export let XR: usize = 0;
/** residuals of the previous positions, f32 × 3n */
export let XPR: usize = 0;
/** inverse masses, f32 × n */
export let W: usize = 0;
/** forces, f32 × 3n */
export let F: usize = 0;
/** each particle's inverse mass when free (params.particleInvMass: the wind's cap), f32 × n */
export let BASE_W: usize = 0;
/** λ per spring, f32 */
export let LAMBDA: usize = 0;
/** tether anchor per particle, i32 */
export let ANCHOR: usize = 0;
/** tether length per particle, f32 */
export let TLEN: usize = 0;
/** particle pairs, u32 × 2 per spring */
export let SPRINGS: usize = 0;
/** rest length per spring, f32 */
export let REST: usize = 0;
/** compliance per spring, f32 */
export let ALPHA: usize = 0;
/** i32 × 3 per batch: start, end, kind */
export let BATCHES: usize = 0;
/** colour batches */
export let BATCH_COUNT: i32 = 0;
// Each bending stencil model's arrays (model.ts BendingStencils; 0 the hinges, 1 the Laplacian): entry offsets
// (u32 × stencils + 1), particles (u32 per entry), weights K (f32 per entry), colour batches (i32 × 2: start, end).
// Plain globals, as every offset here: the kernel allocates nothing (its static data would sit in the control block).
export let HINGE_OFFSETS: usize = 0;
export let HINGE_VERTICES: usize = 0;
export let HINGE_WEIGHTS: usize = 0;
export let HINGE_BATCHES: usize = 0;
export let HINGE_BATCH_COUNT: i32 = 0;
export let LAPLACIAN_OFFSETS: usize = 0;
export let LAPLACIAN_VERTICES: usize = 0;
export let LAPLACIAN_WEIGHTS: usize = 0;
export let LAPLACIAN_BATCHES: usize = 0;
export let LAPLACIAN_BATCH_COUNT: i32 = 0;
/** compliance per stencil of the model in use, f32 */
export let STENCIL_ALPHA: usize = 0;
/** λ per stencil of the model in use, f32 × 3 */
export let STENCIL_LAMBDA: usize = 0;
/** the cloth's triangles, u32 × 3 each (model.triangles: triangle contact) */
export let TRIANGLES: usize = 0;
export let TRIANGLE_COUNT: i32 = 0;
/** particles */
export let N: i32 = 0;

/** Sets the arrays' byte offsets and the counts (the caller's layout, the same in every instance). */
export function configure(
  x: usize, xp: usize, xr: usize, xpr: usize, w: usize, f: usize, lambda: usize, anchor: usize, tlen: usize,
  springs: usize, rest: usize, alpha: usize, batches: usize, batchCount: i32, particles: i32,
  hingeOffsets: usize, hingeVertices: usize, hingeWeights: usize, hingeBatches: usize, hingeBatchCount: i32,
  laplacianOffsets: usize, laplacianVertices: usize, laplacianWeights: usize, laplacianBatches: usize, laplacianBatchCount: i32,
  stencilAlpha: usize, stencilLambda: usize, triangles: usize, triangleCount: i32, baseW: usize,
): void {
  X = x; XP = xp; XR = xr; XPR = xpr; W = w; F = f; LAMBDA = lambda; ANCHOR = anchor; TLEN = tlen;
  SPRINGS = springs; REST = rest; ALPHA = alpha; BATCHES = batches; BATCH_COUNT = batchCount; N = particles;
  HINGE_OFFSETS = hingeOffsets; HINGE_VERTICES = hingeVertices; HINGE_WEIGHTS = hingeWeights;
  HINGE_BATCHES = hingeBatches; HINGE_BATCH_COUNT = hingeBatchCount;
  LAPLACIAN_OFFSETS = laplacianOffsets; LAPLACIAN_VERTICES = laplacianVertices; LAPLACIAN_WEIGHTS = laplacianWeights;
  LAPLACIAN_BATCHES = laplacianBatches; LAPLACIAN_BATCH_COUNT = laplacianBatchCount;
  STENCIL_ALPHA = stencilAlpha; STENCIL_LAMBDA = stencilLambda;
  TRIANGLES = triangles; TRIANGLE_COUNT = triangleCount; BASE_W = baseW;
}
