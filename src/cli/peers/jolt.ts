/**
 * Benchmark peer: runs a cloth given as particles + distance constraints in
 * Jolt Physics' soft body system (JoltPhysics.js, WebAssembly, single-threaded
 * `wasm-compat` build), so `drape bench` can compare Drape's XPBD solver with it.
 *
 * `jolt-physics` is an optional (dev) dependency: it is only loaded, lazily, when
 * {@link runJoltCloth} is called.
 */
import { createRequire } from 'node:module';
import type JoltTypes from 'jolt-physics';

/** A cloth described as particles + distance constraints, solver-agnostic. */
export interface PeerClothSpec {
  /** particle positions [m], xyz interleaved, length 3n */
  positions: Float32Array;
  /** inverse masses [1/kg], length n; 0 = pinned (kinematic) */
  invMass: Float32Array;
  /** distance constraints as index pairs, length 2m */
  edges: Uint32Array;
  /** per-constraint XPBD compliance [m/N], length m (Jolt's Edge.mCompliance) */
  compliance: Float32Array;
  /** triangles as index triples, length 3t (Jolt faces; needed for its soft body) */
  triangles: Uint32Array;
  /** a static sphere collider, or none */
  sphere: { center: [number, number, number]; radius: number } | null;
  /** floor height [m]: a static box whose top face is at this y; null for none */
  floorY: number | null;
  gravity: [number, number, number];
  /** Jolt SoftBodySharedSettings/creation mNumIterations (it substeps per iteration) */
  iterations: number;
  /** friction coefficient for the soft body */
  friction: number;
  /** contact thickness / vertex radius [m] */
  vertexRadius: number;
}

export interface PeerResult {
  /** mean wall-clock ms per simulated 1/60 s frame (PhysicsSystem.Update with 1 collision step), over `frames` timed frames after `warmup` frames */
  msPerFrame: number;
  /** true if every vertex position is finite at the end */
  finite: boolean;
  /** mean vertex position at the end */
  centroid: [number, number, number];
  /** Jolt version/build string if obtainable, else 'jolt-physics' */
  name: string;
}

/** The resolved JoltPhysics.js module object (classes, enums, destroy, HEAP views). */
type JoltModule = typeof JoltTypes;
type InitJolt = (target?: object) => Promise<JoltModule>;

const FRAME_DT = 1 / 60;
const LAYER_NON_MOVING = 0;
const LAYER_MOVING = 1;
const NUM_OBJECT_LAYERS = 2;
const NUM_BROAD_PHASE_LAYERS = 2;

/**
 * One WebAssembly instance per process: instantiating the module costs ~100 ms
 * and a fresh 128 MiB heap, so repeated runs share it (and free what they make).
 */
let joltPromise: Promise<JoltModule> | undefined;

function loadJolt(): Promise<JoltModule> {
  if (!joltPromise) {
    joltPromise = (async () => {
      let init: InitJolt;
      try {
        const mod = (await import('jolt-physics')) as unknown as { default: InitJolt };
        init = mod.default;
      } catch (err) {
        const why = err instanceof Error ? err.message.split('\n')[0] : String(err);
        const code = (err as { code?: unknown } | null)?.code;
        if (code === 'ERR_MODULE_NOT_FOUND' || code === 'MODULE_NOT_FOUND') {
          throw new Error(`jolt-physics is not installed (npm install --save-dev jolt-physics): ${why}`);
        }
        throw new Error(`failed to load jolt-physics: ${why}`);
      }
      if (typeof init !== 'function') {
        throw new Error('jolt-physics: unexpected module shape (no default init function)');
      }
      return init();
    })();
    // A failed load must not be cached forever.
    joltPromise.catch(() => {
      joltPromise = undefined;
    });
  }
  return joltPromise;
}

function joltName(): string {
  try {
    const require = createRequire(import.meta.url);
    const pkg = require('jolt-physics/package.json') as { version?: unknown };
    if (typeof pkg.version === 'string') return `jolt-physics@${pkg.version} (wasm-compat, 1 thread)`;
  } catch {
    // fall through
  }
  return 'jolt-physics';
}

function validate(spec: PeerClothSpec): number {
  const n = spec.invMass.length;
  if (spec.positions.length !== 3 * n) {
    throw new Error(`PeerClothSpec: positions has length ${spec.positions.length}, expected 3 * ${n}`);
  }
  if (spec.edges.length % 2 !== 0 || spec.compliance.length !== spec.edges.length / 2) {
    throw new Error(
      `PeerClothSpec: edges (length ${spec.edges.length}) and compliance (length ${spec.compliance.length}) do not match`,
    );
  }
  if (spec.triangles.length % 3 !== 0) {
    throw new Error(`PeerClothSpec: triangles has length ${spec.triangles.length}, not a multiple of 3`);
  }
  for (const idx of [spec.edges, spec.triangles]) {
    for (let k = 0; k < idx.length; k++) {
      if (idx[k]! >= n) throw new Error(`PeerClothSpec: vertex index ${idx[k]} out of range (n = ${n})`);
    }
  }
  if (!(spec.iterations >= 1)) throw new Error(`PeerClothSpec: iterations must be >= 1, got ${spec.iterations}`);
  return n;
}

/**
 * The cloth of a spec in its own Jolt physics system, stepped a frame at a time and read back: what runJoltCloth
 * times, and what the bench's hanging sheet watches settle. `dispose()` frees it (Jolt's heap is shared by the
 * process; each cloth frees what it made).
 */
export class JoltCloth {
  /** Jolt version/build string if obtainable, else 'jolt-physics' */
  readonly name = joltName();
  private readonly bodies: JoltTypes.Body[] = [];
  private shared: JoltTypes.SoftBodySharedSettings | undefined;
  private cloth: JoltTypes.Body | undefined;
  private disposed = false;

  private constructor(private readonly Jolt: JoltModule, private readonly jolt: JoltTypes.JoltInterface, readonly particles: number) {}

  /** Builds the spec's cloth and colliders. Loads jolt-physics lazily; throws a one-line Error if it is not installed. */
  static async create(spec: PeerClothSpec): Promise<JoltCloth> {
    const n = validate(spec);
    const Jolt = await loadJolt();
    // --- Physics system: two object layers (non-moving / moving), 1:1 broad phase layers.
    const objectFilter = new Jolt.ObjectLayerPairFilterTable(NUM_OBJECT_LAYERS);
    objectFilter.EnableCollision(LAYER_NON_MOVING, LAYER_MOVING);
    objectFilter.EnableCollision(LAYER_MOVING, LAYER_MOVING);
    const bpNonMoving = new Jolt.BroadPhaseLayer(0);
    const bpMoving = new Jolt.BroadPhaseLayer(1);
    const bpInterface = new Jolt.BroadPhaseLayerInterfaceTable(NUM_OBJECT_LAYERS, NUM_BROAD_PHASE_LAYERS);
    bpInterface.MapObjectToBroadPhaseLayer(LAYER_NON_MOVING, bpNonMoving);
    bpInterface.MapObjectToBroadPhaseLayer(LAYER_MOVING, bpMoving);
    Jolt.destroy(bpNonMoving); // copied into bpInterface
    Jolt.destroy(bpMoving);
    const settings = new Jolt.JoltSettings();
    settings.mObjectLayerPairFilter = objectFilter;
    settings.mBroadPhaseLayerInterface = bpInterface;
    settings.mObjectVsBroadPhaseLayerFilter = new Jolt.ObjectVsBroadPhaseLayerFilterTable(
      bpInterface,
      NUM_BROAD_PHASE_LAYERS,
      objectFilter,
      NUM_OBJECT_LAYERS,
    );
    // The JoltInterface takes ownership of the three filter/layer objects.
    const jolt = new Jolt.JoltInterface(settings);
    Jolt.destroy(settings);
    const self = new JoltCloth(Jolt, jolt, n);
    try {
      self.build(spec);
    } catch (e) {
      self.dispose();
      throw e;
    }
    return self;
  }

  private build(spec: PeerClothSpec): void {
    const { Jolt, jolt, bodies } = this;
    const n = this.particles;
    const physicsSystem = jolt.GetPhysicsSystem();
    const bodyInterface = physicsSystem.GetBodyInterface();
    const g = new Jolt.Vec3(spec.gravity[0], spec.gravity[1], spec.gravity[2]);
    physicsSystem.SetGravity(g);
    Jolt.destroy(g);

    const identity = new Jolt.Quat(0, 0, 0, 1);
    // Jolt combines friction as sqrt(f1 * f2); giving the colliders the same
    // coefficient makes the effective cloth/collider friction equal spec.friction.
    const addStatic = (shape: JoltTypes.Shape, x: number, y: number, z: number): void => {
      const pos = new Jolt.RVec3(x, y, z);
      const bcs = new Jolt.BodyCreationSettings(shape, pos, identity, Jolt.EMotionType_Static, LAYER_NON_MOVING);
      bcs.mFriction = spec.friction;
      bcs.mRestitution = 0;
      const body = bodyInterface.CreateBody(bcs);
      Jolt.destroy(bcs);
      Jolt.destroy(pos);
      bodyInterface.AddBody(body.GetID(), Jolt.EActivation_DontActivate);
      bodies.push(body);
    };
    if (spec.sphere) {
      const [sx, sy, sz] = spec.sphere.center;
      addStatic(new Jolt.SphereShape(spec.sphere.radius), sx, sy, sz);
    }
    if (spec.floorY !== null) {
      // a 100 m x 1 m x 100 m static box whose top face is at floorY
      const half = new Jolt.Vec3(50, 0.5, 50);
      addStatic(new Jolt.BoxShape(half, 0.05), 0, spec.floorY - 0.5, 0);
      Jolt.destroy(half);
    }

    // --- Soft body: vertices, edge constraints, faces (no bend/volume/LRA constraints).
    const shared = new Jolt.SoftBodySharedSettings();
    this.shared = shared;
    shared.AddRef(); // we hold a reference until after the body is destroyed
    const vertex = new Jolt.SoftBodySharedSettingsVertex();
    const vertexPos = vertex.mPosition; // view into `vertex`
    const vertices = shared.mVertices;
    vertices.reserve(n);
    for (let i = 0; i < n; i++) {
      vertexPos.x = spec.positions[3 * i]!;
      vertexPos.y = spec.positions[3 * i + 1]!;
      vertexPos.z = spec.positions[3 * i + 2]!;
      vertex.mInvMass = spec.invMass[i]!;
      vertices.push_back(vertex);
    }
    Jolt.destroy(vertex);

    const m = spec.compliance.length;
    const edge = new Jolt.SoftBodySharedSettingsEdge(0, 0, 0);
    const edgeList = shared.mEdgeConstraints;
    edgeList.reserve(m);
    for (let e = 0; e < m; e++) {
      edge.set_mVertex(0, spec.edges[2 * e]!);
      edge.set_mVertex(1, spec.edges[2 * e + 1]!);
      edge.mCompliance = spec.compliance[e]!;
      edgeList.push_back(edge);
    }
    Jolt.destroy(edge);
    shared.CalculateEdgeLengths(); // rest lengths from the initial positions

    const face = new Jolt.SoftBodySharedSettingsFace(0, 0, 0, 0);
    for (let t = 0; t < spec.triangles.length; t += 3) {
      face.set_mVertex(0, spec.triangles[t]!);
      face.set_mVertex(1, spec.triangles[t + 1]!);
      face.set_mVertex(2, spec.triangles[t + 2]!);
      shared.AddFace(face); // AddFace drops degenerate triangles
    }
    Jolt.destroy(face);
    shared.Optimize(); // reorders constraints into parallel groups; vertex order is kept

    // Vertices are given in world space; the body starts at the origin with identity rotation.
    const origin = new Jolt.RVec3(0, 0, 0);
    const sbcs = new Jolt.SoftBodyCreationSettings(shared, origin, identity, LAYER_MOVING);
    Jolt.destroy(origin);
    sbcs.mNumIterations = spec.iterations;
    sbcs.mFriction = spec.friction;
    sbcs.mRestitution = 0;
    sbcs.mPressure = 0;
    sbcs.mGravityFactor = 1;
    sbcs.mVertexRadius = spec.vertexRadius;
    sbcs.mUpdatePosition = true;
    sbcs.mMakeRotationIdentity = true;
    sbcs.mAllowSleeping = false;
    const cloth = bodyInterface.CreateSoftBody(sbcs);
    Jolt.destroy(sbcs);
    bodyInterface.AddBody(cloth.GetID(), Jolt.EActivation_Activate);
    bodies.push(cloth);
    this.cloth = cloth;
    Jolt.destroy(identity);
  }

  /** Steps `frames` frames of 1/60 s (one collision step each); returns the wall-clock ms they took. */
  step(frames: number): number {
    if (this.disposed) throw new Error('JoltCloth: stepped after dispose()');
    const t0 = performance.now();
    for (let f = 0; f < frames; f++) this.jolt.Step(FRAME_DT, 1);
    return performance.now() - t0;
  }

  /** The particles' world positions [m], xyz interleaved, into `out` (made when not given). */
  positions(out = new Float32Array(3 * this.particles)): Float32Array {
    if (this.disposed) throw new Error('JoltCloth: read after dispose()');
    const { Jolt } = this;
    const cloth = this.cloth!;
    // Soft body vertex positions are relative to the body's centre-of-mass transform (which moves with the cloth
    // when mUpdatePosition).
    const motion = Jolt.castObject(cloth.GetMotionProperties(), Jolt.SoftBodyMotionProperties);
    const xf = cloth.GetCenterOfMassTransform();
    const tr = xf.GetTranslation();
    const T = [tr.GetX(), tr.GetY(), tr.GetZ()] as const;
    const ax = xf.GetAxisX();
    const X = [ax.GetX(), ax.GetY(), ax.GetZ()] as const;
    const ay = xf.GetAxisY();
    const Y = [ay.GetX(), ay.GetY(), ay.GetZ()] as const;
    const az = xf.GetAxisZ();
    const Z = [az.GetX(), az.GetY(), az.GetZ()] as const;
    const count = Math.min(motion.GetVertices().size(), this.particles);
    // Read positions straight from the wasm heap: wrapping 16k vertices with
    // GetVertex(i) would fill emscripten's per-pointer wrapper cache.
    const heap = Jolt.HEAPF32;
    let base = 0;
    let stride = 0;
    let posOffset = 0;
    if (count > 0) {
      const v0 = motion.GetVertex(0);
      base = Jolt.getPointer(v0);
      posOffset = Jolt.getPointer(v0.mPosition) - base;
      stride = count > 1 ? Jolt.getPointer(motion.GetVertex(1)) - base : 0;
    }
    out.fill(NaN);
    for (let i = 0; i < count; i++) {
      const p = (base + i * stride + posOffset) >> 2;
      const lx = heap[p]!;
      const ly = heap[p + 1]!;
      const lz = heap[p + 2]!;
      out[3 * i] = T[0] + X[0] * lx + Y[0] * ly + Z[0] * lz;
      out[3 * i + 1] = T[1] + X[1] * lx + Y[1] * ly + Z[1] * lz;
      out[3 * i + 2] = T[2] + X[2] * lx + Y[2] * ly + Z[2] * lz;
    }
    return out;
  }

  /** Frees the bodies, the shared settings and the physics system. */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    const { Jolt, jolt } = this;
    // Bodies first (they hold references to shapes and the shared settings), then the system.
    const bodyInterface = jolt.GetPhysicsSystem().GetBodyInterface();
    for (const body of this.bodies) {
      const id = body.GetID();
      bodyInterface.RemoveBody(id);
      bodyInterface.DestroyBody(id);
    }
    this.shared?.Release();
    Jolt.destroy(jolt);
  }
}

/**
 * Simulates `warmup + frames` frames of 1/60 s of the cloth in Jolt and times
 * the last `frames` of them. Never throws for a blow-up: NaN/Inf positions are
 * reported as `finite: false`.
 *
 * Loads jolt-physics lazily (dynamic import). Throws an Error with a one-line message if it is not installed.
 */
export async function runJoltCloth(spec: PeerClothSpec, frames: number, warmup: number): Promise<PeerResult> {
  if (!(Number.isInteger(frames) && frames >= 1)) throw new Error(`frames must be an integer >= 1, got ${frames}`);
  if (!(Number.isInteger(warmup) && warmup >= 0)) throw new Error(`warmup must be an integer >= 0, got ${warmup}`);
  const cloth = await JoltCloth.create(spec);
  try {
    cloth.step(warmup);
    let totalMs = 0;
    // frame by frame, as before: the time of Jolt's steps only
    for (let f = 0; f < frames; f++) totalMs += cloth.step(1);
    const x = cloth.positions();
    const n = cloth.particles;
    let finite = true;
    let cx = 0;
    let cy = 0;
    let cz = 0;
    for (let i = 0; i < n; i++) {
      if (!(Number.isFinite(x[3 * i]) && Number.isFinite(x[3 * i + 1]) && Number.isFinite(x[3 * i + 2]))) finite = false;
      cx += x[3 * i];
      cy += x[3 * i + 1];
      cz += x[3 * i + 2];
    }
    const inv = n > 0 ? 1 / n : NaN;
    return { msPerFrame: totalMs / frames, finite, centroid: [cx * inv, cy * inv, cz * inv], name: cloth.name };
  } finally {
    cloth.dispose();
  }
}
