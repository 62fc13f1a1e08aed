/** Drape's simulation core: pure TypeScript, no DOM, runs in Node and the browser. */
export * from './model.js';
export * from './state.js';
export * from './params.js';
export * from './fabrics.js';
export * from './textile-tests.js';
export * from './scene.js';
export * from './cloth-paths.js';
export { sceneSchema, PIN_PRESETS, MAX_CLOTHS } from './scene-schema.js';
export { SCENE_NAMES, builtinScene, isBuiltinScene, builtinMannequin, sceneMannequin, withMannequin, type SceneMannequin } from './scenes.js';
export {
  mannequinColliders, mannequinAngles, forwardKinematics, animationPeriod, MANNEQUIN_PARTS, MANNEQUIN_CHEST, MANNEQUIN_PELVIS,
  MANNEQUIN_POSES, MANNEQUIN_ANIMATIONS, type MannequinOptions, type MannequinPose, type MannequinAnimation, type JointAngles,
} from './mannequin.js';
export * from './metrics.js';
export * from './pins.js';
export { perturbStart } from './perturbation.js';
export * from './pick.js';
export { plainText, safeJson, shownValue } from './text.js';
export { fabricFor, exportCloths, LOOKS, type FabricKind, type LookMaterial } from './looks.js';
export { windVelocity } from './wind.js';
export { mulberry32 } from './random.js';
export { SOLVERS, step, type StepFn } from './solvers/index.js';
export { PHASE, PHASES, PhaseLog, type Phase, type PhaseName, type BackendPhases } from './schedule.js';
export { runFrame, type PhaseBackend, type FrameVars } from './frame.js';
export * from './colliders/index.js';
export { Simulation, needsRebuild, AUTO_THREADS_MIN_PARTICLES, type Report, type ClothReport, type CpuKernel, type SimulationOptions, type ParticleRange, type CarriedState, copyCarried } from './simulation.js';
export { TsBackend, WasmBackend, type Backend, type BackendKind } from './backend.js';
export { wasmKernelAvailable, XpbdKernel, type HelperSpawner, type KernelHelperInit } from './wasm/xpbd-wasm.js';
export { modelFor, parseMeshFile, meshFormat, CLOTH_SHAPES, MESH_EXTENSIONS, type ClothShape, type MeshResolver } from './cloth-shape.js';
export { prepareMesh, MAX_MESH_PARTICLES, MAX_VERTEX_EDGES, WELD_TOLERANCE, type TriangleMesh } from './mesh/triangle-mesh.js';
export { discMesh, tubeMesh, wovenDiscMesh, wovenDiscParticles, placeMesh, type ShapeSpec, type Placement } from './mesh/generators.js';
export type { ExternalReader } from './mesh/gltf.js';
export { toGLB, modelCloths, bakeBytes, BAKE_BYTES_PER_VERTEX, type GlbInput, type ExportCloth, type GlbMaterial, type GlbTexture, type GlbBake } from './mesh/glb.js';
export { toOBJ, toMTL, type ObjInput } from './mesh/obj-export.js';
export { vertexNormals } from './mesh/normals.js';
export { countIntersections } from './intersections.js';
export { selfContacts } from './contacts.js';
export { selfContactDistance } from './self-contact.js';
