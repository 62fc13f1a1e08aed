/**
 * Every GPU buffer, uniform struct and kernel binding of the WebGPU solver, defined once. The WGSL declarations
 * (structs and `@group/@binding` variables) are generated from these tables and prepended to each kernel's
 * source (shaders.ts), and the solver creates its bind group layouts from the same tables, so the two cannot
 * drift apart.
 *
 * vec3 data (positions, velocities, normals, forces) has stride 4 floats (16 bytes) on the GPU: `array<vec4f>`,
 * w = 0. The CPU keeps stride 3; upload/read convert.
 */

/** Threads per workgroup of every kernel (1-D). */
export const WORKGROUP_SIZE = 64;
/** Most workgroups along x in one dispatch; bigger dispatches spill into y (see `flatIndex` in the preamble). */
export const MAX_WORKGROUPS_X = 65535;
/** Floats per vec3 element on the GPU. */
export const VEC4 = 4;
/** The schema allows up to 64 colliders; the uniform block holds that many. */
export const MAX_COLLIDERS = 64;
/** Byte stride of the dynamic-offset uniform records (minUniformBufferOffsetAlignment is at most 256). */
export const RECORD_STRIDE = 256;

/** Collider kinds as the kernels see them. */
export const COLLIDER_SPHERE = 0;
export const COLLIDER_FLOOR = 1;

/** Flags of a solve pass record. */
export const PASS_CAP = 1; // apply the hard stretch cap (structural and shear batches)
export const PASS_READ_LAMBDA = 2; // start from the accumulated λ (second and later iterations)

/** Storage buffers: WGSL element type and bytes per element. */
export const BUFFERS = {
  /** x, y, z, 0 [m] per particle; also a vertex buffer for renderers */
  positions: { type: 'vec4f', bytes: 16 },
  /** positions at the start of the current substep [m] (x − h·v at the start of a frame) */
  previous: { type: 'vec4f', bytes: 16 },
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
  /** position of the grabbed particle at the start of the frame (1 element) */
  grabStart: { type: 'vec4f', bytes: 16 },
} as const;
export type BufferName = keyof typeof BUFFERS;

type Access = 'read' | 'read_write';
/** A kernel: its WGSL file (src/gpu/shaders/<name>.wgsl), the libraries it includes, its storage bindings. */
export interface KernelSpec {
  /** group(1) bindings in binding order */
  readonly bindings: readonly (readonly [BufferName, Access])[];
  /** other .wgsl files (function libraries) placed before the kernel */
  readonly libs?: readonly string[];
}

/** Every kernel. At most 8 storage buffers each (the default maxStorageBuffersPerShaderStage). */
export const KERNELS = {
  /** beginStep: effective inverse masses (pins, grab), previous = x − h·v */
  prepare: {
    bindings: [
      ['baseInvMass', 'read'], ['pinned', 'read'], ['invMass', 'read_write'], ['positions', 'read'],
      ['previous', 'read_write'], ['velocities', 'read'],
    ],
  },
  /** accumulateWind, per triangle: F = ½ρ|v|(v·n)·area·n on the relative air velocity */
  wind: {
    bindings: [
      ['positions', 'read'], ['previous', 'read'], ['triangles', 'read'], ['baseInvMass', 'read'],
      ['triForces', 'read_write'],
    ],
  },
  /** integrate + moveGrabbed: gathers the wind of incident triangles (no atomics) */
  integrate: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['triForces', 'read'],
      ['adjacency', 'read'], ['grabStart', 'read'],
    ],
  },
  /** solveDistanceConstraints for one colour batch */
  solve: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read'], ['invMass', 'read'], ['springs', 'read'],
      ['springData', 'read'], ['lambdas', 'read_write'],
    ],
  },
  /** limitStretch (phases.ts), which XPBD runs after the tethers, for one structural or shear batch */
  limitStretch: {
    bindings: [['positions', 'read_write'], ['invMass', 'read'], ['springs', 'read'], ['springData', 'read']],
  },
  /** solveTethers */
  tethers: { bindings: [['positions', 'read_write'], ['invMass', 'read'], ['tethers', 'read']] },
  /** collide, particle part, for a run of colliders */
  collideParticles: {
    bindings: [['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read']],
    libs: ['colliders'],
  },
  /** collide, triangle part, for one collider and one triangle colour */
  collideTriangles: {
    bindings: [
      ['positions', 'read_write'], ['previous', 'read_write'], ['invMass', 'read'], ['triangles', 'read'],
    ],
    libs: ['colliders'],
  },
  /** updateVelocities, once per frame */
  velocities: { bindings: [['positions', 'read'], ['previous', 'read'], ['velocities', 'read_write']] },
  /** vertex normals for rendering */
  normals: {
    bindings: [['positions', 'read'], ['triangles', 'read'], ['adjacency', 'read'], ['normals', 'read_write']],
  },
} as const satisfies Record<string, KernelSpec>;
export type KernelName = keyof typeof KERNELS;

/**
 * Uniform structs: fields in declaration order with their byte offsets (std140-like WGSL uniform rules, checked
 * by hand: vec3f aligns to 16, scalars to 4). `Globals` is written by setParams and (the grab) by every step;
 * `Substep` is one record per substep at RECORD_STRIDE, selected with a dynamic offset; `Pass` likewise, one
 * record per solve batch / collider pass.
 */
export const GLOBALS = {
  gravity: 0, // vec3f [m/s²]
  iterations: 12, // u32
  damping: 16, // f32 β [N·s/m]
  stretchFactor: 20, // f32
  friction: 24, // f32
  staticFriction: 28, // f32
  thickness: 32, // f32 [m]
  reach: 36, // f32: thickness + 2·maxTriangleEdge [m]
  windK: 40, // f32: ¼ρ/3
  grabbed: 44, // i32, −1 none
  grabTarget: 48, // vec3f [m]
  particleCount: 60, // u32
  triangleCount: 64, // u32
  colliderCount: 68, // u32
  colliders: 80, // array<Collider, MAX_COLLIDERS>, 32 bytes each: data vec4f, kind u32, 3 × pad
  size: 80 + 32 * MAX_COLLIDERS,
} as const;
export const COLLIDER_BYTES = 32;

export const SUBSTEP = {
  wind: 0, // vec3f wind velocity at this substep's start time [m/s]
  h: 12, // f32 substep [s]
  h2: 16, // f32 c·h², c = ½ on the very first substep (Taylor start), else 1
  invH: 20, // f32 1/h
  invH2: 24, // f32 1/h²
  betaOverH: 28, // f32 damping/h
  grabFraction: 32, // f32 (sub + 1)/substeps
  windOn: 36, // u32
  recover: 40, // f32 depenetrationSpeed·h: most a collider overlap the cloth did not move into is undone [m]
  recoverTriangle: 44, // f32 recover / model.maxTriangleValence: the same for triangle contact [m]
  size: 48,
} as const;

export const PASS = {
  start: 0, // u32 first element (spring, triangle, or collider)
  end: 4, // u32 one past the last
  cap: 8, // f32 stretch cap (× rest length)
  flags: 12, // u32 PASS_* flags, or the collider index of a triangle pass
  size: 16,
} as const;

/** WGSL text of the shared declarations, prepended to every kernel. */
export function wgslPreamble(): string {
  return `// ---- generated from src/gpu/layout.ts ----
const WG: u32 = ${WORKGROUP_SIZE}u;
const COLLIDER_SPHERE: u32 = ${COLLIDER_SPHERE}u;
const COLLIDER_FLOOR: u32 = ${COLLIDER_FLOOR}u;
const PASS_CAP: u32 = ${PASS_CAP}u;
const PASS_READ_LAMBDA: u32 = ${PASS_READ_LAMBDA}u;

struct Collider {
  data: vec4f, // sphere: centre xyz, radius; floor: height in x
  kind: u32,
  _p0: u32, _p1: u32, _p2: u32,
}

struct Globals {
  gravity: vec3f,
  iterations: u32,
  damping: f32,
  stretchFactor: f32,
  friction: f32,
  staticFriction: f32,
  thickness: f32,
  reach: f32,
  windK: f32,
  grabbed: i32,
  grabTarget: vec3f,
  particleCount: u32,
  triangleCount: u32,
  colliderCount: u32,
  colliders: array<Collider, ${MAX_COLLIDERS}>,
}

struct Substep {
  wind: vec3f,
  h: f32,
  h2: f32,
  invH: f32,
  invH2: f32,
  betaOverH: f32,
  grabFraction: f32,
  windOn: u32,
  recover: f32,
  recoverTriangle: f32,
}

struct Pass {
  start: u32,
  end: u32,
  cap: f32,
  flags: u32,
}

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

/** WGSL `var` declarations of a kernel's storage bindings (group 1). */
export function wgslBindings(kernel: KernelName): string {
  const spec: KernelSpec = KERNELS[kernel];
  return spec.bindings
    .map(([name, access], i) => `@group(1) @binding(${i}) var<storage, ${access}> ${name}: array<${BUFFERS[name].type}>;`)
    .join('\n');
}
