/**
 * Drawing straight from the GPU solver's buffers, for the addon's cloths and the app's (cloth-drawing.ts) alike: on a three.js `WebGPURenderer`, whose backend keeps each attribute's GPUBuffer in
 * `backend.get(attribute).buffer` and creates one only when there is none, the solver's buffer takes that place.
 */

/** What is read of the renderer's WebGPU backend: where it keeps an attribute's GPU buffer. */
export interface AttributeBuffers {
  get(attribute: object): { buffer?: GPUBuffer };
}

/** A `WebGPURenderer`'s backend as it is read here: its device, and where it keeps an attribute's GPU buffer. */
export interface WebGpuBackendLike extends AttributeBuffers {
  readonly isWebGPUBackend?: boolean;
  readonly device?: GPUDevice | null;
}

/**
 * The renderer's WebGPU backend, when it is a three.js `WebGPURenderer` running on WebGPU (not on its WebGL2
 * fallback) with a device; else null. For the addon's worlds and the app's views alike.
 */
export function webGpuBackend(renderer: { readonly isWebGPURenderer?: boolean; readonly backend?: object } | null | undefined): WebGpuBackendLike | null {
  const b = renderer?.backend as WebGpuBackendLike | undefined;
  return renderer?.isWebGPURenderer && b?.isWebGPUBackend && b.device && typeof b.get === 'function' ? b : null;
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
