/**
 * Drawing straight from the GPU solver's buffers, for the addon's cloths (world.ts) and the app's views
 * (src/render/cloth-view.ts) alike: on a three.js `WebGPURenderer`, whose backend keeps each attribute's GPUBuffer in
 * `backend.get(attribute).buffer` and creates one only when there is none, the solver's buffer takes that place.
 */

/** What is read of the renderer's WebGPU backend: where it keeps an attribute's GPU buffer. */
export interface AttributeBuffers {
  get(attribute: object): { buffer?: GPUBuffer };
}

/**
 * Draws each attribute from its buffer (`array<vec4f>`, VERTEX usage: the solver's positions or normals): the
 * buffer three.js made for it, if any, is destroyed. three.js destroys the solver's buffer with the attribute, so
 * dispose the geometry and the solver together.
 */
export function drawFromSolver(backend: AttributeBuffers, pairs: readonly (readonly [object, GPUBuffer])[]): void {
  for (const [attribute, buffer] of pairs) {
    const data = backend.get(attribute);
    if (data.buffer && data.buffer !== buffer) data.buffer.destroy();
    data.buffer = buffer;
  }
}
