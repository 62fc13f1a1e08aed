/**
 * Drape's WebGPU backend: the XPBD solver as compute kernels and the GPU benchmark. Browser-safe; the Node device
 * helper lives in ./node.js (it imports node: modules and the `webgpu` package).
 */
export { GpuClothSolver, type GpuSolverOptions, type SubstepTraffic } from './solver.js';
export { GpuBackend } from './backend.js';
export { colliderRefusal, sceneRefusal } from './encoder.js';
export { benchGpu, measureCopyBandwidth, type GpuBenchResult } from './bench.js';
export { kernelSource } from './shaders.js';
export { triangleAdjacency } from './topology.js';
export * as gpuLayout from './layout.js';
