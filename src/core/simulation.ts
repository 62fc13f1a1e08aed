/**
 * Wiring for front ends (CLI, app, benchmarks): a scene → model → state → params, and the rules for what a change
 * rebuilds. Geometry (cloth.*, material.scaleWithResolution) rebuilds the model and restarts the cloth; everything
 * else (stiffness, damping, mass, wind, gravity, solver, colliders, pins) applies on the next step.
 */
import { countIntersections } from './intersections.js';
import { selfContacts } from './contacts.js';
import { smallestSelfContactDistance } from './self-contact.js';
import type { ClothModel } from './model.js';
import { modelFor, type MeshResolver } from './cloth-shape.js';
import { bounds, centroid, energy, isFinite3, maxPenetration, maxStructuralStrain, type Bounds, type Energy } from './metrics.js';
import { FRAME_DT, resolveParams, type SimParams } from './params.js';
import { perturbStart } from './perturbation.js';
import { applyPins, scenePins } from './pins.js';
import { clothEntries, clothName, setScenePath, validateScene, type Scene, type SceneInput } from './scene.js';
import { plainText, shownValue } from './text.js';
import { checkPlacement } from './placement.js';
import { copyState, resetState, type ClothState } from './state.js';
import type { HelperSpawner } from './wasm/xpbd-wasm.js';
import { TsBackend, WasmBackend, type Backend } from './backend.js';
import type { ColliderPose } from './colliders/pose.js';
import { checkTest, measureTest, type TestResult } from './textile-tests.js';

/** Where a Simulation runs the XPBD substeps on the CPU. */
export type CpuKernel = 'wasm' | 'ts';

export interface SimulationOptions {
  /**
   * 'wasm': the WebAssembly SIMD kernel (wasm/xpbd-wasm.ts); 'ts': the TypeScript solver; 'auto' (default): wasm
   * where the runtime can run it, else ts. Both compute the same phases; wasm is f32 in the constraint passes.
   */
  kernel?: CpuKernel | 'auto';
  /**
   * threads sharing each substep of the wasm kernel: an integer ≥ 1, or 'auto' (the default): the spawner's cores
   * (at most 8), but one thread for cloths under AUTO_THREADS_MIN_PARTICLES particles, where threads do not pay.
   * More than one needs `spawnHelper`, and never more than its `cores` are used.
   */
  threads?: number | 'auto';
  /** starts a helper thread of the wasm kernel (Node: spawnNodeHelper from drape/threads) */
  spawnHelper?: HelperSpawner;
  /**
   * reads the mesh file a scene's cloth.mesh names (Node: loadSceneFile or meshReader from drape/node; the app:
   * its imported file); needed only for cloth.shape 'mesh'
   */
  meshes?: MeshResolver;
}

export interface Report {
  particles: number;
  triangles: number;
  /** springs of all kinds */
  constraints: number;
  finite: boolean;
  maxStrain: number;
  maxPenetration: number;
  /** pairs of triangles that share no vertex and cross each other now (intersections.ts): 0 without self-intersection */
  intersections: number;
  /**
   * particles nearer than half the self-contact distance (the smallest of any pair, self-contact.ts) to a triangle
   * not their own, now: layers pressed together harder than self-contact holds them apart. Colliders and pins run
   * after self-contact and win where they squeeze cloth, so with self-contact on this counts what they squeezed
   * (0 on a cloth left to itself); without it, every layer lying on another
   */
  squeezed: number;
  centroid: [number, number, number];
  bounds: Bounds;
  energy: Energy;
  /** the scene's standard fabric test measured now (textile-tests.ts), when the scene is one */
  test?: TestResult;
  /** each cloth's own figures, in the scene's order, when the scene has a list of cloths (`cloths`) */
  cloths?: ClothReport[];
}

/** One cloth of a scene of several (Report.cloths): its particles are first … first + particles − 1 of the whole. */
export interface ClothReport {
  /** cloths[k].name, or 'cloth k' */
  name: string;
  /** its first particle in the scene's numbering (reports, exports, colliders[k].pins) */
  first: number;
  particles: number;
  triangles: number;
  centroid: [number, number, number];
  bounds: Bounds;
}

/** Whether going from scene `prev` to `next` needs a new model (and so restarts the cloth): a change of geometry. */
export function needsRebuild(prev: Scene, next: Scene): boolean {
  const geometry = (s: Scene) => JSON.stringify(clothEntries(s).map((e) => [e.cloth, e.material.scaleWithResolution]));
  return geometry(prev) !== geometry(next);
}

/**
 * Smallest cloth [particles] that 'auto' gives more than one thread: below it one thread is as fast (measured with
 * `drape bench --sizes …`, docs/performance.md).
 */
export const AUTO_THREADS_MIN_PARTICLES = 2500;

/** Threads for a kernel: the request, or 'auto' by cloth size, and never more than the cores or 8. */
function threadsFor(request: number | 'auto', cores: number, particles: number): number {
  const most = Math.min(8, cores);
  if (request === 'auto') return particles < AUTO_THREADS_MIN_PARTICLES ? 1 : most;
  return Math.min(request, most);
}

/** How errors about a whole scene name it. */
const sceneLabel = (scene: Scene) => `scene '${plainText(scene.name, 100)}'`;

/** Whether every value is finite: one sum (NaN and ±∞ survive it; f32 values cannot overflow an f64 sum). */
function allFinite(x: Float32Array): boolean {
  let s = 0;
  for (let j = 0; j < x.length; j++) s += x[j];
  return s - s === 0;
}

/** Throws a TypeError naming the field of a collider pose that is not a finite 3-vector. */
function checkPose(pose: ColliderPose): void {
  if (pose === null || typeof pose !== 'object') throw new TypeError('Simulation.setColliderPose: pose must be an object or null');
  for (const key of ['translation', 'rotation', 'velocity', 'angularVelocity'] as const) {
    const v = pose[key];
    if (v === undefined) continue;
    if (!Array.isArray(v) && !ArrayBuffer.isView(v) || (v as ArrayLike<number>).length !== 3 ||
        !Array.from(v as ArrayLike<number>).every((c) => typeof c === 'number' && Number.isFinite(c) && Math.abs(c) <= 1e6)) {
      throw new TypeError(`Simulation.setColliderPose: pose.${key} must be three finite numbers (|value| ≤ 1e6)`);
    }
  }
}

/** The options as given, or an Error naming the one that is wrong. */
function checkOptions(options: SimulationOptions): SimulationOptions {
  if (options === null || typeof options !== 'object') throw new TypeError('Simulation: options must be an object');
  const { kernel, threads, spawnHelper } = options;
  if (kernel !== undefined && kernel !== 'auto' && kernel !== 'wasm' && kernel !== 'ts') {
    throw new TypeError(`Simulation: options.kernel must be 'auto', 'wasm' or 'ts', got ${JSON.stringify(kernel)}`);
  }
  if (threads !== undefined && threads !== 'auto' && !(Number.isInteger(threads) && threads >= 1)) {
    throw new RangeError(`Simulation: options.threads must be 'auto' or an integer ≥ 1, got ${String(threads)}`);
  }
  if (spawnHelper !== undefined && typeof spawnHelper !== 'function') {
    throw new TypeError('Simulation: options.spawnHelper must be a function (e.g. spawnNodeHelper from drape/threads)');
  }
  if (options.meshes !== undefined && typeof options.meshes !== 'function') {
    throw new TypeError('Simulation: options.meshes must be a function from a cloth.mesh path to a mesh (e.g. meshReader from drape/node)');
  }
  if (spawnHelper !== undefined && !(Number.isInteger(spawnHelper.cores) && spawnHelper.cores >= 1)) {
    throw new TypeError('Simulation: options.spawnHelper.cores must be the number of cores its threads can use (an integer ≥ 1)');
  }
  return options;
}

export class Simulation {
  scene: Scene;
  model: ClothModel;
  params: SimParams;
  /** where the frames run; it holds the state (see backend.ts) */
  private backendNow: Backend;
  /** frames stepped since the last (re)start */
  frame = 0;
  /**
   * the frame at whose end some position was first not finite (the cloth blew up), or null while every position
   * is finite; advance() steps no further once it is set (reset() or a rebuild clears it). On a backend whose
   * state is read back (the GPU), it is found by sync(): the frame of that read
   */
  unstableFrame: number | null = null;
  private readonly options: SimulationOptions;
  private disposed = false;

  constructor(scene: SceneInput, options: SimulationOptions = {}) {
    this.options = checkOptions(options);
    this.scene = validateScene(scene);
    this.model = modelFor(this.scene, this.options.meshes);
    this.params = resolveParams(this.model, this.scene, FRAME_DT, this.options.meshes);
    const pins = scenePins(this.model, this.scene);
    checkPlacement(this.model, this.params.colliders, pins, this.scene.material.stretchFactor, sceneLabel(this.scene));
    checkTest(this.model, this.scene, sceneLabel(this.scene));
    this.backendNow = this.newBackend();
    applyPins(this.state, pins);
    perturbStart(this.model, this.scene, this.state, pins);
  }

  /** the backend the frames run on */
  get backend(): Backend {
    return this.backendNow;
  }

  /**
   * the cloth's state (on the GPU: as of the last sync()). Its arrays belong to the cloth of now: a rebuild (`set` or
   * `setScene` returning true) or `useBackend` gives a new state with new arrays, so read `sim.state.positions`
   * afresh after one (or each frame) rather than keeping the array
   */
  get state(): ClothState {
    return this.backendNow.state;
  }

  /**
   * what the simulation does differently from what the scene asks, in words: the params' clamps (params.ts: a
   * softened spring, substeps raised for self-contact) and the backend's (the GPU's self-contact list overflowing
   * in some pass since the last reset, as far as synced)
   */
  get notes(): string[] {
    return [...this.params.clamps, ...(this.backendNow.notes ?? [])];
  }

  /** the CPU kernel the substeps run in: 'wasm' only for XPBD (mass-spring always steps in TypeScript) */
  get kernel(): CpuKernel {
    return this.backendNow.kind === 'wasm' ? 'wasm' : 'ts';
  }

  /** threads sharing each substep now (1 until a wasm kernel's helpers have started) */
  get threads(): number {
    return this.backendNow.threads;
  }

  /** Resolves once the backend runs at full strength (the wasm kernel's helper threads started). */
  whenReady(): Promise<void> {
    return this.backendNow.whenReady();
  }

  /** Stops the wasm kernel's helper threads (and frees a GPU backend) for good: the state stays readable. */
  dispose(): void {
    this.disposed = true;
    this.backendNow.dispose();
  }

  /**
   * Moves the cloth, as it is, onto another backend built for this model (e.g. the GPU's, src/gpu/backend.ts); the
   * old one is disposed. A rebuild of the model (a geometry change) comes back to a CPU backend.
   */
  useBackend(next: Backend): void {
    if (next === this.backendNow) return;
    if (next.state.positions.length !== this.state.positions.length) {
      throw new RangeError(`Simulation.useBackend: the backend holds ${next.state.positions.length / 3} particles, the cloth ${this.model.particleCount}`);
    }
    if (!this.backendNow.current) {
      throw new Error(`Simulation.useBackend: the ${this.backendNow.kind} backend has stepped frames the state does not hold yet; await sync() first`);
    }
    copyState(this.state, next.state);
    next.stateChanged('all');
    this.backendNow.dispose();
    this.backendNow = next;
  }

  /** Brings the state up to date with the frames stepped (the GPU reads back) and checks it is finite. */
  async sync(): Promise<void> {
    await this.backendNow.sync();
    if (this.unstableFrame === null && !allFinite(this.state.positions)) this.unstableFrame = this.frame;
  }

  /** A backend for the current model and solver: the wasm kernel for XPBD (unless asked not to), else TypeScript. */
  private newBackend(): Backend {
    const { kernel = 'auto', threads = 'auto' } = this.options;
    const spawnHelper = this.disposed ? undefined : this.options.spawnHelper;
    if (kernel !== 'ts' && this.scene.solver.type === 'xpbd') {
      const t = spawnHelper ? threadsFor(threads, spawnHelper.cores, this.model.particleCount) : 1;
      // self-contact's memory only for a scene with it on (setScene makes a new kernel when it is switched on)
      const self = this.scene.solver.selfContact;
      const backend = WasmBackend.create(this.model, t, spawnHelper, self) ?? (t > 1 ? WasmBackend.create(this.model, 1, undefined, self) : null);
      if (backend) return backend;
      if (kernel === 'wasm') throw new Error('the WebAssembly kernel needs WebAssembly SIMD, which this runtime lacks');
    }
    return new TsBackend(this.model);
  }

  /**
   * Advances `frames` frames of 1/60 s; returns false (stepping no further) once a position is not finite, with
   * `unstableFrame` saying at which frame.
   */
  advance(frames = 1): boolean {
    if (!Number.isInteger(frames) || frames < 0) throw new RangeError(`Simulation.advance: frames must be an integer ≥ 0, got ${shownValue(frames)}`);
    const live = this.backendNow.kind !== 'gpu'; // a GPU state is checked when it is read back (sync)
    for (let f = 0; f < frames && this.unstableFrame === null; f++) {
      this.backendNow.frame(this.model, this.params, FRAME_DT);
      this.frame++;
      if (live && !allFinite(this.state.positions)) this.unstableFrame = this.frame;
    }
    return this.unstableFrame === null;
  }

  /** Back to the start pose with the scene's pins. */
  reset(): void {
    resetState(this.model, this.state);
    const pins = scenePins(this.model, this.scene);
    applyPins(this.state, pins);
    perturbStart(this.model, this.scene, this.state, pins);
    for (const c of this.params.colliders) c.setDrive(0, null);
    this.backendNow.stateChanged('all');
    this.frame = 0;
    this.unstableFrame = null;
  }

  /**
   * Changes one scene path (validated; throws SceneError naming the field). Returns true when the cloth had to
   * be rebuilt (and so restarted).
   */
  set(path: string, value: unknown): boolean {
    if (typeof path !== 'string') throw new TypeError(`Simulation.set: path must be a string such as 'material.damping', got ${typeof path}`);
    return this.setScene(setScenePath(this.scene, path, value, `Simulation.set('${plainText(path, 100)}')`));
  }

  /**
   * Replaces the whole scene, rebuilding only what the change needs. Returns true when the cloth was rebuilt: it
   * restarts from its start pose, but for the particles `carry` names (old particle numbers to new ones: a
   * cloth of the old scene's list that is also in the new one), which go on where they were, as they were moving,
   * and the clock with them (state.time, state.substeps, frame; so a cloth added this way takes its first substep
   * as any later one, without the half step a start takes: ½·g·h² more fall, ~4 mm/s at 20 substeps).
   */
  setScene(input: SceneInput, carry: readonly ParticleRange[] = []): boolean {
    if (!Array.isArray(carry)) throw new TypeError(`Simulation.setScene: carry must be an array of { from, to, count }, got ${shownValue(carry)}`);
    const next = validateScene(input);
    const prev = this.scene;
    const rebuild = needsRebuild(prev, next);
    const model = rebuild ? modelFor(next, this.options.meshes) : this.model;
    const params = resolveParams(model, next, FRAME_DT, this.options.meshes);
    const pins = scenePins(model, next);
    const pinsChanged = rebuild || JSON.stringify(pins) !== JSON.stringify(scenePins(this.model, prev));
    // a scene whose cloth cannot start outside its colliders is refused, and nothing changes
    if (rebuild || pinsChanged || JSON.stringify(prev.colliders) !== JSON.stringify(next.colliders) ||
        prev.material.stretchFactor !== next.material.stretchFactor) {
      checkPlacement(model, params.colliders, pins, next.material.stretchFactor, sceneLabel(next));
    }
    checkTest(model, next, sceneLabel(next));
    // (a carry outside either cloth is refused here too, before anything changes)
    const kept = rebuild && carry.length ? carried(this.state, carry, model.particleCount) : null;
    this.scene = next;
    if (rebuild) {
      this.backendNow.dispose();
      this.model = model;
      this.backendNow = this.newBackend();
      perturbStart(model, next, this.state, pins);
      if (kept) {
        kept.into(this.state);
      } else {
        this.frame = 0;
      }
      this.unstableFrame = null;
    } else if ((prev.solver.type === 'xpbd') !== (next.solver.type === 'xpbd') && this.backendNow.kind !== 'gpu') {
      // XPBD steps in the kernel's memory, mass-spring in plain arrays: move the cloth over, as it is
      const moved = this.newBackend();
      if (moved.kind !== this.backendNow.kind) this.useBackend(moved);
      else moved.dispose();
    } else if (next.solver.selfContact && this.backendNow instanceof WasmBackend && !this.backendNow.kernel.hasSelfContact) {
      // self-contact switched on over a kernel made without its memory: a kernel with it takes the cloth as it is
      const moved = this.newBackend();
      if (moved instanceof WasmBackend) this.useBackend(moved);
      else moved.dispose();
    }
    // colliders the library drives keep their drive while the scene keeps them
    if (!rebuild) {
      params.colliders.forEach((c, k) => {
        const was = this.params.colliders[k];
        if (was?.driven && next.colliders[k].type === prev.colliders[k].type) c.takeDrive(was);
      });
    }
    this.params = params;
    if (rebuild || pinsChanged) {
      applyPins(this.state, pins);
      this.backendNow.stateChanged(rebuild ? 'all' : 'pins');
    }
    return rebuild;
  }

  /**
   * Drives collider `index` from now on (without revalidating the scene): its pose now — translation from the
   * scene's placement [m] and rotation about its pivot, Euler XYZ [degrees] — and the velocity [m/s] and angular
   * velocity [rad/s, world axes, about the pivot] it keeps over the next frames, until the next call. Call it each
   * frame with the pose and velocity of whatever moves the collider (an animated body); the substeps move it on at
   * that velocity, and friction drags the cloth with the moving surface. `null` gives the collider back to its
   * scene motion (reset() does that for every collider). Every backend reads the drive from params.colliders each
   * frame (the GPU backend puts the collider's pose of each substep in the frame it submits).
   */
  setColliderPose(index: number, pose: ColliderPose | null): void {
    const colliders = this.params.colliders;
    if (!Number.isInteger(index) || index < 0 || index >= colliders.length) {
      throw new RangeError(`Simulation.setColliderPose: index must be an integer 0…${colliders.length - 1} (the scene has ${colliders.length} colliders), got ${String(index)}`);
    }
    if (pose !== null) checkPose(pose);
    colliders[index].setDrive(this.state.time, pose);
  }

  report(): Report {
    const { model, state, params } = this;
    return {
      particles: model.particleCount,
      triangles: model.triangles.length / 3,
      constraints: model.restLengths.length,
      finite: isFinite3(state),
      maxStrain: maxStructuralStrain(model, state),
      maxPenetration: maxPenetration(model, state, params),
      intersections: countIntersections(model.triangles, state.positions),
      squeezed: selfContacts(model.triangles, state.positions, model.particleCount, 0.5 * smallestSelfContactDistance(model, params)),
      centroid: centroid(state),
      bounds: bounds(state),
      energy: energy(model, state, params),
      ...(this.scene.test ? { test: measureTest(model, state, this.scene) } : {}),
      ...(this.scene.cloths ? { cloths: this.clothReports() } : {}),
    };
  }

  /** Report.cloths: each cloth's figures. */
  private clothReports(): ClothReport[] {
    const { model, state } = this, starts = model.clothStarts;
    return clothEntries(this.scene).map((e, c) => ({
      name: clothName(e, c),
      first: starts[c],
      particles: starts[c + 1] - starts[c],
      triangles: (model.clothParts?.[c] ?? model).triangles.length / 3,
      centroid: centroid(state, starts[c], starts[c + 1]),
      bounds: bounds(state, starts[c], starts[c + 1]),
    }));
  }
}

/** Particles `count` from `from` of one model that are `to`… of another: a cloth kept across a rebuild (Simulation.setScene). */
export interface ParticleRange {
  readonly from: number;
  readonly to: number;
  readonly count: number;
}

/** Per-particle state, stride 3, that a carried particle keeps across a rebuild. */
const CARRIED = ['positions', 'previousPositions', 'residuals', 'previousResiduals', 'velocities'] as const;

/** What of a state a carry copies: the per-particle arrays above and the clock. */
export type CarriedState = Pick<ClothState, (typeof CARRIED)[number] | 'time' | 'substeps'>;

/** Copies the particles `carry` names from `from` into `to` (ranges already checked), and the clock. */
export function copyCarried(from: CarriedState, to: ClothState, carry: readonly ParticleRange[]): void {
  for (const k of CARRIED) for (const r of carry) to[k].set(from[k].subarray(3 * r.from, 3 * (r.from + r.count)), 3 * r.to);
  to.time = from.time;
  to.substeps = from.substeps;
}

/**
 * What `carry` keeps of `state` (copied now: the old backend's memory goes), to put into a new model's state of `n`
 * particles; throws a RangeError for a range outside either.
 */
function carried(state: ClothState, carry: readonly ParticleRange[], n: number): { into(next: ClothState): void } {
  const old = state.positions.length / 3;
  for (const r of carry) {
    if (!(Number.isInteger(r.from) && Number.isInteger(r.to) && Number.isInteger(r.count) && r.from >= 0 && r.to >= 0 && r.count >= 0 && r.from + r.count <= old && r.to + r.count <= n)) {
      throw new RangeError(`Simulation.setScene: carry ${JSON.stringify(r)} is outside the old cloth (${old} particles) or the new one (${n})`);
    }
  }
  const copy: CarriedState = {
    positions: state.positions.slice(), previousPositions: state.previousPositions.slice(), residuals: state.residuals.slice(),
    previousResiduals: state.previousResiduals.slice(), velocities: state.velocities.slice(), time: state.time, substeps: state.substeps,
  };
  return { into: (next) => copyCarried(copy, next, carry) };
}
