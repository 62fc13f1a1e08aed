/** Drape's simulation core: pure TypeScript, no DOM, runs in Node and the browser. */
export * from './model.js';
export * from './state.js';
export * from './params.js';
export * from './scene.js';
export { sceneSchema, PIN_PRESETS } from './scene-schema.js';
export { SCENE_NAMES, builtinScene, isBuiltinScene } from './scenes.js';
export * from './metrics.js';
export * from './pins.js';
export * from './pick.js';
export { plainText, safeJson } from './text.js';
export { windVelocity } from './wind.js';
export { mulberry32 } from './random.js';
export { SOLVERS, step, type StepFn } from './solvers/index.js';
export * from './colliders/index.js';
export { Simulation, modelFor, needsRebuild, AUTO_THREADS_MIN_PARTICLES, type Report, type CpuKernel, type SimulationOptions } from './simulation.js';
export { createWasmState, wasmKernelAvailable, XpbdKernel, type HelperSpawner, type KernelHelperInit } from './wasm/xpbd-wasm.js';
