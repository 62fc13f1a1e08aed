/** Drape's WebGPU backend: the XPBD solver as compute kernels, a Node device helper and the GPU benchmark. */
export { GpuClothSolver, type SubstepTraffic } from './solver.js';
export { benchGpu, type GpuBenchResult } from './bench.js';
export { kernelSource } from './shaders.js';
export * as gpuLayout from './layout.js';
