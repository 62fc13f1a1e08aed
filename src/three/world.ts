/**
 * DrapeWorld: one simulation — its cloths, the colliders made from the user's meshes, gravity, wind and the solver —
 * on the renderer's own WebGPU device (GpuSim: drawn straight from the solver's buffers) or in a Web Worker on the
 * CPU (SimClient: the WebAssembly kernel, helper threads where the page is cross-origin isolated), whichever the
 * renderer and the scene allow, falling back to the CPU by itself (docs/three.md, "Fallback"). Both drivers are the
 * app's own (src/three/sim). The world steps whole 1/60 s frames from the time `update(dt)` is given (the drivers'
 * FrameClock), moves each collider to where its mesh is, and refreshes the cloths' geometries.
 */
import { Vector3, type Mesh, type Object3D, type Raycaster } from 'three';
import {
  FRAME_DT, SceneError, Simulation, copyCarried, modelFor, pickParticle, plainText, resolvePins, shownValue, validateScene, type ClothEntry, type ClothModel, type DeepPartial,
  type ParticleRange, type PinEntry, type Scene, type Vec3,
} from '../core/index.js';
import { isSoftwareAdapter, type AdapterInfoLike } from '../gpu/adapter.js';
import { DrapeCloth } from './cloth.js';
import { ClothDrawing } from './cloth-drawing.js';
import { COLLIDER_SHAPE_OPTIONS, colliderOfMesh } from './colliders.js';
import { Follower } from './follow.js';
import { meshOfGeometry } from './geometry.js';
import {
  DRAPE_BACKENDS, checkObject, checkOneOf, optionError, type DrapeClothOptions, type DrapeColliderOptions, type DrapePin, type DrapeWorldOptions,
} from './options.js';
import { anchorOf, worldScene, type AttachedPin, type WorldCollider } from './scene.js';
import { GpuSim } from './sim/gpu-sim.js';
import { MeshStore } from './sim/meshes.js';
import { webGpuBackend, type WebGpuBackendLike } from './sim/solver-buffers.js';
import { SimClient, type SimDriver } from './sim/sim-client.js';
import { carriable, carryState, chooseBackend } from './sim/backend-choice.js';

/** Where a picking ray met a cloth. */
export interface DrapeHit {
  readonly cloth: DrapeCloth;
  /** the particle of the cloth (counted from its first) nearest the hit point */
  readonly particle: number;
  /** the hit point [m] */
  readonly point: Vector3;
  /** from the ray's origin to the hit [m, for a unit direction] */
  readonly distance: number;
}

const WHERE = 'DrapeWorld';
const vec3 = (v: Vector3): Vec3 => [v.x, v.y, v.z];

/**
 * A core error about the cloth addCloth builds (its mesh, its pins) as the option's: prefixed with the call (the
 * scene checks already are), and its geometry named as such, not by the name the world gave its mesh.
 */
function clothError(e: unknown, where: string, meshName: string | undefined): unknown {
  if (!(e instanceof SceneError) || e.message.startsWith(where)) return e;
  let message = e.message;
  if (meshName) {
    message = message.replace(`cloth.mesh: ${meshName}: `, 'geometry: ').split(meshName).join('the geometry')
      .replace('metres per unit of the file', 'metres per unit of the geometry');
  }
  return new SceneError(`${where}: ${message}`);
}

/** Whether `v` reads as a THREE.Vector3 (by its shape: a page may hold another copy of three.js). */
function isVector(v: unknown): v is Vector3 {
  return v !== null && typeof v === 'object' && typeof (v as Vector3).clone === 'function' &&
    typeof (v as Vector3).x === 'number' && typeof (v as Vector3).y === 'number' && typeof (v as Vector3).z === 'number';
}

/** Throws, naming `method`, unless `target` is a THREE.Vector3 of finite coordinates [m]. */
function checkTarget(method: string, target: unknown): void {
  if (!isVector(target)) throw new TypeError(`${WHERE}.${method}: target must be a THREE.Vector3`);
  if (![target.x, target.y, target.z].every(Number.isFinite)) {
    throw new RangeError(`${WHERE}.${method}: target must have finite coordinates [m], got (${target.x}, ${target.y}, ${target.z})`);
  }
}

export class DrapeWorld {
  /** the cloths, in the order they were added */
  readonly cloths: DrapeCloth[] = [];
  /** why the world does not simulate on the GPU ('' when it does, or was asked for the CPU) */
  backendNote = '';
  /** the last error the simulation reported ('' for none) */
  error = '';
  private readonly options: DrapeWorldOptions;
  private readonly colliders: WorldCollider[] = [];
  private readonly anchors = new Map<Object3D, WorldCollider>();
  private readonly attached: AttachedPin[] = [];
  /** the colliders of the scene, by index (null: the floor) */
  private sceneColliders: (WorldCollider | null)[] = [];
  private readonly meshes = new MeshStore();
  private driver: SimDriver | null = null;
  private starting: Promise<void> | null = null;
  /**
   * the last start made no simulation (no cloth yet, or a scene the core refused): the next change to the cloths or
   * colliders lets the next `update`, `step` or `start` try again
   */
  private startFailed = false;
  /** the world's model the cloths' geometries were made for */
  private model: ClothModel | null = null;
  /** the cloths drawn from the model's positions (CPU) or the GPU solver's buffers: made for `model` */
  private drawing: ClothDrawing | null = null;
  /** new positions arrived since the cloths were last refreshed */
  private fresh = false;
  private lastNow = 0;
  private raf = 0;
  private grabbed: { cloth: DrapeCloth; particle: number } | null = null;
  private disposed = false;
  private names = 0;
  /** the cloths added so far (the default name of the next is 'cloth ' and this) */
  private clothsAdded = 0;

  constructor(options: DrapeWorldOptions = {}) {
    checkObject(WHERE, 'options', options);
    checkOneOf(WHERE, 'options.backend', options.backend, DRAPE_BACKENDS);
    checkObject(WHERE, 'options.wind', options.wind);
    checkObject(WHERE, 'options.solver', options.solver);
    if (options.floor !== undefined && options.floor !== null && !Number.isFinite(options.floor)) {
      throw new TypeError(`${WHERE}: options.floor must be a height in metres or null, got ${shownValue(options.floor)}`);
    }
    if (options.onError !== undefined && typeof options.onError !== 'function') throw new TypeError(`${WHERE}: options.onError must be a function`);
    this.options = options;
    // the world's own values are checked now, by the scene schema
    this.scene();
    if (options.autoUpdate) {
      const loop = () => {
        if (this.disposed) return;
        this.update();
        this.raf = requestAnimationFrame(loop);
      };
      this.raf = requestAnimationFrame(loop);
    }
  }

  /** where the world simulates now: 'gpu', 'cpu', or null before it has started (the first update) */
  get backend(): 'gpu' | 'cpu' | null {
    return this.driver?.kind ?? null;
  }

  /** whether the cloths are drawn straight from the GPU solver's buffers */
  get gpuDrawing(): boolean {
    return this.drawing?.attached ?? false;
  }

  /** frames of 1/60 s simulated since the cloths (re)started */
  get frame(): number {
    return this.driver?.mirrors[0]?.frame ?? 0;
  }

  /**
   * `stepMs`: simulation time per 1/60 s frame, smoothed [ms]; `realTime`: simulated time over wall time (1: real
   * time); `threads`: CPU threads sharing each substep (0 on the GPU; more than 1 only for cloths of 2500 particles
   * or more on a cross-origin isolated page)
   */
  get stats(): { stepMs: number; realTime: number; threads: number } {
    const s = this.driver?.stats;
    return { stepMs: s?.stepMs ?? 0, realTime: s?.realTime ?? 1, threads: s?.threads ?? 0 };
  }

  /** pauses (true) or resumes stepping in `update`; `step` still steps */
  get paused(): boolean {
    return this.driver?.paused ?? this.pausedBeforeStart;
  }

  set paused(p: boolean) {
    this.pausedBeforeStart = p;
    if (this.driver) this.driver.paused = p;
  }

  private pausedBeforeStart = false;

  /**
   * Adds a cloth and returns it: a `THREE.Mesh` to add to your scene (its vertices are world coordinates). Made
   * from a `geometry` or a generated `shape`, of a `fabric`. Added while the world runs, it starts from its start
   * pose and the other cloths go on where they are (on the GPU, from their last readback, up to ~0.1 s before).
   * Throws an error naming the option that is wrong.
   */
  addCloth(options: DrapeClothOptions = {}): DrapeCloth {
    this.alive();
    checkObject(`${WHERE}.addCloth`, 'options', options);
    checkObject(`${WHERE}.addCloth`, 'fabricValues', options.fabricValues);
    checkOneOf(`${WHERE}.addCloth`, 'shape', options.shape, ['rectangle', 'disc', 'tube']);
    if (options.geometry !== undefined && options.shape !== undefined) throw new TypeError(`${WHERE}.addCloth: give geometry or shape, not both`);
    if (options.pins !== undefined && !Array.isArray(options.pins)) throw new TypeError(`${WHERE}.addCloth: pins must be an array`);
    if (options.name !== undefined && typeof options.name !== 'string') throw new TypeError(`${WHERE}.addCloth: name must be a string, got ${shownValue(options.name)}`);
    if (options.geometry !== undefined && typeof (options.geometry as { getAttribute?: unknown } | null)?.getAttribute !== 'function') {
      throw new TypeError(`${WHERE}.addCloth: geometry must be a THREE.BufferGeometry (a mesh's is its .geometry)`);
    }
    const name = options.name ?? `cloth ${this.clothsAdded}`;
    const where = `${WHERE}.addCloth('${plainText(name, 60)}')`;
    const meshName = options.geometry ? `drape-three:cloth-${this.names++}` : undefined;
    if (options.geometry && meshName) this.meshes.add({ name: meshName, mesh: meshOfGeometry(options.geometry, where) });
    const pins = options.pins ?? [];
    const attachedAt = (p: DrapePin): p is { at: PinEntry; to: Object3D } => p !== null && typeof p === 'object' && 'to' in p;
    const entry: DeepPartial<ClothEntry> = {
      name,
      cloth: {
        shape: meshName ? 'mesh' : options.shape ?? 'rectangle',
        ...(meshName ? { mesh: meshName } : {}),
        ...pick(options, ['width', 'height', 'resolution', 'orientation', 'rotation', 'scale', 'thickness']),
        position: options.position ?? [0, 1, 0],
      },
      material: { ...(options.fabric ? { fabric: options.fabric } : {}), ...options.fabricValues },
      // the pins fixed in the world; those attached to objects are carried by colliders (scene.ts)
      pins: pins.filter((p): p is PinEntry => !attachedAt(p)),
    };
    let model: ClothModel;
    const attachedPins: Omit<AttachedPin, 'cloth'>[] = [];
    try {
      // the cloth alone, as the core builds it, and every pin checked in the order given (pins[k] is the user's k)
      const one = validateScene({ cloth: entry.cloth, material: entry.material, pins: pins.map((p) => (attachedAt(p) ? p.at : p)), colliders: [] }, where);
      model = modelFor(one, this.meshes.resolve);
      resolvePins(model, one.pins);
      pins.forEach((p, j) => {
        if (!attachedAt(p)) return;
        if (!p.to || typeof (p.to as Object3D).updateWorldMatrix !== 'function') throw new TypeError(`${where}: pins[${j}].to must be a THREE.Object3D`);
        attachedPins.push({ particles: resolvePins(model, [p.at], `pins[${j}].at`), to: p.to });
      });
    } catch (e) {
      if (meshName) this.meshes.delete(meshName);
      throw optionError(clothError(e, where, meshName));
    }
    const cloth = new DrapeCloth({ entry, model }, options.material, name);
    const newAnchors: Object3D[] = [];
    for (const p of attachedPins) {
      this.attached.push({ ...p, cloth });
      if (!this.anchors.has(p.to) && !this.colliders.some((c) => c.object === p.to)) {
        this.anchors.set(p.to, anchorOf(p.to));
        newAnchors.push(p.to);
      }
    }
    // the cloths simulated so far go on where they are: the new one's particles come after theirs
    const carry: ParticleRange[] = this.model ? [{ from: 0, to: 0, count: this.model.particleCount }] : [];
    this.cloths.push(cloth);
    this.clothsAdded++;
    try {
      this.structureChanged(carry);
    } catch (e) {
      // refused by the simulation: nothing changes (the scene's colliders are the world's again: they follow meshes)
      this.cloths.pop();
      this.clothsAdded--;
      this.attached.splice(this.attached.length - attachedPins.length);
      for (const object of newAnchors) this.anchors.delete(object);
      if (meshName) this.meshes.delete(meshName);
      this.scene();
      cloth.disposeCloth();
      throw e;
    }
    return cloth;
  }

  /**
   * Makes a collider of one of your meshes: a sphere, box, capsule, cylinder or its triangles (`shape`, inferred by
   * default), where the mesh is now and following its world transform each update (unless `follow: false`).
   * Throws an error naming the option that is wrong; added while the world runs, it takes effect at once (a
   * collider cutting through a cloth is refused).
   */
  addCollider(mesh: Mesh, options: DrapeColliderOptions = {}): void {
    this.alive();
    if (!mesh || !(mesh as Mesh).isMesh) throw new TypeError(`${WHERE}.addCollider: the first argument must be a THREE.Mesh`);
    checkObject(`${WHERE}.addCollider`, 'options', options);
    checkOneOf(`${WHERE}.addCollider`, 'options.shape', options.shape, COLLIDER_SHAPE_OPTIONS);
    if (this.colliders.some((c) => c.object === mesh)) throw new Error(`${WHERE}.addCollider: this mesh is a collider already`);
    mesh.updateWorldMatrix(true, false);
    const meshName = `drape-three:collider-${this.names++}`;
    const made = colliderOfMesh(mesh, options.shape ?? 'auto', meshName);
    if (made.triangles) this.meshes.add({ name: meshName, mesh: made.triangles });
    const follower = options.follow === false ? null : new Follower(mesh, made.pivot);
    this.colliders.push({ object: mesh, spec: made.spec, follower, shape: options.shape ?? 'auto' });
    try {
      this.structureChanged();
    } catch (e) {
      // refused by the simulation: nothing changes (the scene's colliders are the world's again: they follow meshes)
      this.colliders.pop();
      this.meshes.delete(meshName);
      this.scene();
      throw e;
    }
  }

  /**
   * Takes a cloth out of the world: it is no longer simulated, its pins on objects go with it, and the geometry (and
   * the material) the world made for it is freed; remove the mesh from your scene yourself. While the world runs the
   * other cloths go on where they are, as with `addCloth` (with no cloth left the simulation stops, and starts again
   * when one is added). Throws when the cloth is not in this world.
   */
  removeCloth(cloth: DrapeCloth): void {
    this.alive();
    const k = this.cloths.indexOf(cloth);
    if (k < 0) throw new Error(`${WHERE}.removeCloth: this cloth is not in the world`);
    // particle numbers change with the model: a grab ends
    this.release();
    const attached = this.attached.filter((p) => p.cloth === cloth);
    // the other cloths go on where they are, each numbered from where the ones before it now end
    const carry: ParticleRange[] = [];
    if (this.model) {
      let to = 0;
      for (const c of this.cloths) {
        if (c === cloth) continue;
        carry.push({ from: c.start, to, count: c.particleCount });
        to += c.particleCount;
      }
    }
    this.cloths.splice(k, 1);
    for (const p of attached) this.attached.splice(this.attached.indexOf(p), 1);
    // the objects that carried only its pins need no anchor now
    for (const object of [...this.anchors.keys()]) if (!this.attached.some((p) => p.to === object)) this.anchors.delete(object);
    if (!this.cloths.length) {
      this.driver?.dispose();
      this.driver = null;
      this.starting = null;
      this.model = null;
      this.drawing?.dispose();
      this.drawing = null;
      this.scene();
    } else {
      this.structureChanged(carry);
    }
    const mesh = cloth.part.entry.cloth?.mesh;
    if (typeof mesh === 'string') this.meshes.delete(mesh);
    cloth.disposeCloth();
  }

  /**
   * Stops a mesh being a collider; it takes effect at once, and the cloths go on from where they are. Pins attached
   * to the mesh stay attached, following it. Throws when the mesh is no collider of this world.
   */
  removeCollider(mesh: Mesh): void {
    this.alive();
    const k = this.colliders.findIndex((c) => c.object === mesh);
    if (k < 0) throw new Error(`${WHERE}.removeCollider: this mesh is no collider of the world`);
    const [gone] = this.colliders.splice(k, 1);
    // its pins are carried by an anchor that follows the mesh, as pins on any other object are
    const anchored = this.attached.some((p) => p.to === mesh) && !this.anchors.has(mesh);
    if (anchored) this.anchors.set(mesh, anchorOf(mesh));
    try {
      this.structureChanged();
    } catch (e) {
      // refused by the simulation: nothing changes
      if (anchored) this.anchors.delete(mesh);
      this.colliders.splice(k, 0, gone);
      this.scene();
      throw e;
    }
    if (gone.spec.type === 'mesh') this.meshes.delete(gone.spec.mesh);
  }

  /**
   * Steps the world by `dt` seconds of wall time (default: the time since the last call), in whole 1/60 s frames
   * (what is left over waits for the next call; time the simulation cannot keep up with is dropped, never queued),
   * moves the colliders to where their meshes are, and refreshes the cloths. Call it once per displayed frame, before
   * rendering. The first call starts the simulation (asynchronously: the cloths keep their start pose meanwhile).
   */
  update(dt?: number): void {
    if (this.disposed) return;
    if (dt !== undefined && !(Number.isFinite(dt) && dt >= 0)) throw new RangeError(`${WHERE}.update: dt must be a finite number of seconds ≥ 0, got ${shownValue(dt)}`);
    const now = performance.now();
    const dtMs = dt !== undefined ? 1000 * dt : this.lastNow ? now - this.lastNow : 0;
    this.lastNow = now;
    const d = this.driver;
    if (!d) { void this.start(); return; }
    if (d instanceof GpuSim && d.lost) { this.fallBack('the WebGPU device was lost'); return; }
    this.follow(dtMs / 1000);
    d.tick(dtMs, now);
    this.draw();
  }

  /**
   * Steps `frames` frames of 1/60 s now, paused or not (starting the world first if need be); resolves once they
   * are done and the cloths' `positions` hold them (read back from the GPU there). Colliders move to where their
   * meshes are now, as having moved there over those frames.
   */
  async step(frames = 1): Promise<void> {
    if (!Number.isInteger(frames) || frames < 0) throw new RangeError(`${WHERE}.step: frames must be an integer ≥ 0, got ${shownValue(frames)}`);
    await this.start();
    const d = this.driver;
    if (!d) return;
    // the colliders' meshes moved over the time these frames simulate
    this.follow(frames * FRAME_DT);
    await d.step(frames);
    // the GPU fell back while these frames were on their way: the CPU steps them
    if (this.driver && this.driver !== d) await this.driver.step(frames);
    this.fresh = true;
    this.draw();
  }

  /**
   * Starts the simulation (the first `update` or `step` does): resolves once the backend is chosen and the cloths
   * loaded. A start that makes no simulation (no cloth yet, a scene refused and reported) is tried again once a cloth
   * or collider is added or taken out.
   */
  start(): Promise<void> {
    this.starting ??= this.begin();
    return this.starting;
  }

  /**
   * The cloth a ray meets first: a `THREE.Raycaster` (set from the camera and a pointer: `setFromCamera`) or an
   * origin and a direction [m]. Null when it meets none, or before the world has started.
   */
  pick(ray: Raycaster | { origin: Vector3; direction: Vector3 }): DrapeHit | null {
    // (a Raycaster by its shape: a page may hold another copy of three.js)
    const r = ray !== null && typeof ray === 'object' ? ('ray' in ray ? ray.ray : ray) : null;
    if (!isVector(r?.origin) || !isVector(r?.direction)) {
      throw new TypeError(`${WHERE}.pick: the ray must be a THREE.Raycaster or { origin, direction } of THREE.Vector3`);
    }
    const m = this.driver?.mirrors[0];
    if (!m || !this.model) return null;
    const dir = r.direction.clone().normalize();
    const hit = pickParticle(m.sim.model, m.sim.state, vec3(r.origin), vec3(dir));
    if (!hit) return null;
    const cloth = this.clothOf(hit.particle);
    if (!cloth) return null;
    return { cloth, particle: hit.particle - cloth.start, point: new Vector3(...hit.point), distance: hit.t };
  }

  /** Grabs a particle (a `pick` hit's), pulling it towards `target` [m] (default: the hit point) until `release`. */
  grab(hit: Pick<DrapeHit, 'cloth' | 'particle'> & { point?: Vector3 }, target?: Vector3): void {
    if (hit === null || typeof hit !== 'object') throw new TypeError(`${WHERE}.grab: hit must be a pick result, { cloth, particle }`);
    if (target !== undefined) checkTarget('grab', target);
    const d = this.driver;
    if (!d || !this.cloths.includes(hit.cloth)) return;
    if (!(Number.isInteger(hit.particle) && hit.particle >= 0 && hit.particle < hit.cloth.particleCount)) {
      throw new RangeError(`${WHERE}.grab: particle must be an integer 0…${hit.cloth.particleCount - 1}, got ${shownValue(hit.particle)}`);
    }
    this.grabbed = { cloth: hit.cloth, particle: hit.particle };
    const to = target ?? hit.point ?? new Vector3().fromArray(hit.cloth.positions, 3 * hit.particle);
    d.grab(0, hit.cloth.start + hit.particle, vec3(to));
  }

  /** Moves the grabbed particle's target [m]; nothing when none is grabbed. */
  drag(target: Vector3): void {
    checkTarget('drag', target);
    if (this.grabbed && this.driver) this.driver.grab(0, this.grabbed.cloth.start + this.grabbed.particle, vec3(target));
  }

  /** Lets the grabbed particle go (it keeps its velocity). */
  release(): void {
    if (this.grabbed && this.driver) this.driver.release(0);
    this.grabbed = null;
  }

  /** whether a particle is grabbed */
  get grabbing(): boolean {
    return this.grabbed !== null;
  }

  /** Puts every cloth back at its start pose, with its pins; colliders follow their meshes from where they are. */
  reset(): void {
    this.release();
    this.driver?.reset();
    for (const c of this.sceneColliders) c?.follower?.resend();
    this.fresh = true;
  }

  /**
   * Frees everything the world made: the worker (and its helper threads) or the GPU solvers and their buffers, the
   * cloths' geometries and the materials it made for them, its animation loop. Your meshes, materials and renderer
   * stay yours. The cloths stay in your scene until you remove them; the world is unusable after.
   */
  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    if (this.raf) cancelAnimationFrame(this.raf);
    this.driver?.dispose();
    this.driver = null;
    this.drawing?.dispose();
    this.drawing = null;
    for (const c of this.cloths) c.disposeCloth();
  }

  private alive(): void {
    if (this.disposed) throw new Error(`${WHERE}: the world was disposed`);
  }

  /**
   * A cloth or collider was added or taken out: a running world takes the new scene at once (a refusal throws, and
   * nothing changes); `carry`: the particles that go on where they are, where the model is rebuilt.
   */
  private structureChanged(carry: readonly ParticleRange[] = []): void {
    const scene = this.scene();
    const d = this.driver;
    if (!d) {
      if (this.startFailed) {
        this.startFailed = false;
        this.starting = null;
      }
      return;
    }
    // a scene the GPU does not take (cloths of different fabrics) goes on on the CPU: checked before the driver sees it
    const refusal = d.kind === 'gpu' ? GpuSim.supports(scene) : null;
    if (refusal) {
      // (the CPU driver checks the placement as it loads: a refusal there throws and changes nothing)
      this.fallBack(refusal, scene, carry);
      return;
    }
    try {
      d.setScene(0, scene, carry);
    } catch (e) {
      throw this.worldError(e);
    }
    for (const c of this.sceneColliders) c?.follower?.resend();
    this.draw();
  }

  /**
   * A core error about the world's scene as the world's: the option's name (optionError), and a collider by the
   * number you gave it (the scene counts the floor first and the objects pins follow last): `colliders[j]` of the
   * colliders added, with the mesh's name where it has one, 'the floor', or 'the object pins follow'.
   */
  private worldError(e: unknown): unknown {
    const error = optionError(e);
    if (!(error instanceof SceneError)) return error;
    // (a collider named as the subject, 'colliders[k] (sphere) …'; a path into one, 'colliders[k].pins', is left as it is)
    return new SceneError(error.message.replace(/colliders\[(\d+)\] \((\w+)\)/g, (whole, k: string, type: string) => {
      const c = this.sceneColliders[Number(k)];
      if (c === undefined) return whole;
      if (c === null) return 'the floor';
      const named = c.object.name ? ` '${plainText(c.object.name, 40)}'` : '';
      const j = this.colliders.findIndex((u) => u.object === c.object);
      return j >= 0 ? `colliders[${j}] (${type}${named})` : `the object${named} that pins follow`;
    }));
  }

  /** The world's scene (a world without cloths yet: with a stand-in one, to check the rest). */
  private scene(): Scene {
    try {
      const { scene, colliders } = worldScene(this.options, this.cloths, this.colliders, this.anchors, this.attached);
      this.sceneColliders = colliders;
      return scene;
    } catch (e) {
      throw optionError(e);
    }
  }

  private async begin(): Promise<void> {
    const r = this.options.renderer;
    try {
      if (r?.isWebGPURenderer && typeof r.init === 'function') await r.init();
    } catch {
      // a renderer that cannot start draws nothing; the simulation still runs on the CPU
    }
    if (this.disposed) return;
    if (!this.cloths.length) { this.startFailed = true; return; }
    let scene: Scene;
    try {
      scene = this.scene();
    } catch (e) {
      this.startFailed = true;
      this.report((e as Error).message);
      return;
    }
    const { kind, note } = this.choose(scene);
    this.backendNote = note;
    if (!this.load(kind, scene)) this.startFailed = true;
  }

  /** The backend the choice, the renderer and the scene allow, and why it is not the GPU. */
  private choose(scene: Scene): { kind: 'gpu' | 'cpu'; note: string } {
    const device = this.device();
    const offer = {
      missing: device ? null : 'no WebGPU device: the renderer is not a WebGPURenderer on WebGPU',
      software: !!device && isSoftwareAdapter((device as GPUDevice & { adapterInfo?: AdapterInfoLike }).adapterInfo),
    };
    return chooseBackend(this.options.backend ?? 'auto', scene, offer, { override: "backend: 'gpu' uses it anyway", explainAuto: true });
  }

  /** the renderer's WebGPU backend, when it is a WebGPURenderer on WebGPU */
  private webGpu(): WebGpuBackendLike | null {
    return webGpuBackend(this.options.renderer);
  }

  private device(): GPUDevice | null {
    const b = this.webGpu();
    return b?.device ?? null;
  }

  /** Makes the driver of `kind` and loads the scene into it; a scene the core refuses is reported. */
  private load(kind: 'gpu' | 'cpu', scene: Scene): SimDriver | null {
    const device = this.device();
    const d: SimDriver = kind === 'gpu' && device ? new GpuSim(device, this.meshes) : new SimClient(this.meshes);
    d.paused = this.pausedBeforeStart;
    d.onFrame = () => { this.fresh = true; };
    d.onError = (message) => {
      if (d.kind === 'gpu' && this.driver === d) this.fallBack(message);
      else this.report(message);
    };
    d.onUnstable = (_slot, frame) => this.report(`the simulation became unstable at frame ${frame} (positions no longer finite) and stopped at its last finite shape; reset() starts it again, more substeps or a softer fabric may help`);
    try {
      d.load([scene]);
    } catch (e) {
      d.dispose();
      this.report((this.worldError(e) as Error).message);
      return null;
    }
    this.driver = d;
    for (const c of this.sceneColliders) c?.follower?.resend();
    this.adopt(d.mirrors[0].sim.model);
    return d;
  }

  /**
   * The GPU cannot go on (an error, a lost device, a scene it does not take): the cloths go on on the CPU from the
   * last positions read back (or start again, for a new model: `scene`, a structure change the GPU refuses).
   */
  private fallBack(reason: string, scene?: Scene, carry: readonly ParticleRange[] = []): void {
    const old = this.driver;
    if (!old || old.kind !== 'gpu') return;
    const m = old.mirrors[0];
    const next = scene ?? m.sim.scene;
    if (scene) {
      // refused here, nothing changes: the GPU goes on with the scene it has
      try { new Simulation(next, { kernel: 'ts', meshes: this.meshes.resolve }).dispose(); } catch (e) { throw this.worldError(e); }
    }
    old.dispose();
    this.driver = null;
    this.backendNote = `GPU unavailable: ${reason}`;
    const d = this.load('cpu', next);
    // (refused there too: the next change to the cloths or colliders lets a start try again)
    if (!d) this.startFailed = true;
    const now = d?.mirrors[0];
    if (d && now && carry.length && m && m.unstableAt < 0) {
      // a cloth added or taken out as the world moved to the CPU: the cloths kept go on from the last readback
      copyCarried(m.sim.state, now.sim.state, carry);
      carryState(d, 0, now.sim.state, m.frame);
    } else if (d && !carry.length && carriable(m, now)) {
      carryState(d, 0, m.sim.state, m.frame);
    }
    this.grabbed = null;
  }

  /** The cloths' drawing for the world's model (a new model: every cloth restarts). */
  private adopt(model: ClothModel): void {
    this.model = model;
    // (the drawing before is freed first: with it, the buffers of a GPU solver that is gone)
    this.drawing?.dispose();
    this.drawing = new ClothDrawing(model, this.cloths, { gpu: this.driver instanceof GpuSim });
    this.drawing.update(this.driver!.mirrors[0].sim.state.positions);
    this.fresh = true;
  }

  /** Tells the simulation where each following collider's mesh is now (made again first where its scale changed). */
  private follow(dt: number): void {
    if (!this.driver) return;
    this.rescale();
    // (a rescale the GPU refuses moves the world to the CPU: the driver of now)
    const d = this.driver;
    if (!d) return;
    this.sceneColliders.forEach((c, k) => {
      if (!c?.follower) return;
      c.object.updateWorldMatrix(true, false);
      const pose = c.follower.look(dt);
      if (pose) d.setColliderPose(0, k, pose);
    });
  }

  /**
   * Makes each following collider whose mesh's world scale changed again at the new size, where the mesh is now, as
   * addCollider does (the cloths go on from where they are; one that the collider now overlaps is pushed out at
   * solver.depenetrationSpeed). One the simulation refuses keeps its size until the scale changes again, and the
   * refusal is reported (`error`, `onError`).
   */
  private rescale(): void {
    this.colliders.forEach((c, k) => {
      if (!c.follower || !(c.object as Mesh).isMesh) return;
      c.object.updateWorldMatrix(true, false);
      if (!c.follower.rescaled()) return;
      const mesh = c.object as Mesh, meshName = `drape-three:collider-${this.names++}`;
      const made = colliderOfMesh(mesh, c.shape ?? 'auto', meshName);
      if (made.triangles) this.meshes.add({ name: meshName, mesh: made.triangles });
      this.colliders[k] = { ...c, spec: made.spec, follower: new Follower(mesh, made.pivot) };
      try {
        this.structureChanged();
        if (c.spec.type === 'mesh') this.meshes.delete(c.spec.mesh);
      } catch (e) {
        this.colliders[k] = c;
        if (made.triangles) this.meshes.delete(meshName);
        c.follower.adoptScale();
        this.scene();
        this.report((e as Error).message);
      }
    });
  }

  /** Brings the cloths' geometries up to date with the driver (a rebuilt model, new positions, the GPU's buffers). */
  private draw(): void {
    const d = this.driver, m = d?.mirrors[0];
    if (!d || !m) return;
    if (m.sim.model !== this.model) this.adopt(m.sim.model);
    const solver = d instanceof GpuSim ? d.solverOf(0) : null;
    const backend = this.webGpu();
    if (solver && backend) this.drawing?.attach(backend, solver.positionBuffer, solver.normalBuffer);
    if (!this.fresh) return;
    this.fresh = false;
    this.drawing?.update(m.sim.state.positions);
  }

  private clothOf(particle: number): DrapeCloth | null {
    for (const c of this.cloths) if (particle >= c.start && particle < c.start + c.particleCount) return c;
    return null;
  }

  private report(message: string): void {
    this.error = message;
    (this.options.onError ?? ((m: string) => console.error(`Drape: ${m}`)))(message);
  }
}

/** The fields of `o` named in `keys` that are given. */
function pick<T extends object, K extends keyof T>(o: T, keys: readonly K[]): Partial<Pick<T, K>> {
  const out: Partial<Pick<T, K>> = {};
  for (const k of keys) if (o[k] !== undefined) out[k] = o[k];
  return out;
}
