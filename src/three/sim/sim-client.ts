/**
 * The page's side of the simulation: a fixed-timestep clock that asks the worker for whole 1/60 s frames, and a
 * mirror of each slot's cloth for drawing and picking.
 *
 * The mirror of a slot is a core Simulation that is never stepped: it holds the model (built from the same scene
 * by the same code as the worker's, so the two agree particle for particle) and a state whose positions and pins
 * are overwritten by each frame from the worker. Changing its scene with `setScene` tells us, by the core's own
 * rule, whether the worker is rebuilding the cloth; frames of an older cloth are then dropped.
 */
import { Simulation, type ClothState, type ColliderPose, type Energy, type ParticleRange, type Scene, type TriangleMesh } from '../../core/index.js';
import { FrameClock, newStats } from './frame-clock.js';
import { sceneMeshes, type MeshStore } from './meshes.js';
import type { FromWorker, ToWorker } from './protocol.js';


export interface Mirror {
  sim: Simulation;
  /** generation of the current model; frames of older generations are dropped */
  modelGen: number;
  frame: number;
  grabbed: number;
  /**
   * frame at which the cloth stopped being finite (-1: it is finite). The mirror then keeps the last finite
   * positions: nothing NaN is drawn, picked or exported; the slot is no longer stepped until a reset or rebuild.
   */
  unstableAt: number;
}

export interface SimStats {
  /** worker time per simulated frame, summed over slots, smoothed [ms] */
  stepMs: number;
  /** simulated time / wall time over the last second while running (1 = real time) */
  realTime: number;
  /** whether realTime and stepMs have been measured on the cloth now (false from a load or rebuild until they are) */
  measured: boolean;
  energy: Energy;
  maxStrain: number;
  clamps: string[];
  /** frames answered by the worker since the page loaded */
  framesDone: number;
  /** where the CPU worker runs the XPBD substeps ('wasm': WebAssembly SIMD; 'ts': TypeScript); '' on the GPU */
  kernel: string;
  /** threads sharing each of the CPU worker's substeps (more than 1 only where the page is cross-origin isolated); 0 on the GPU */
  threads: number;
}

/** What the app drives: the CPU backend (SimClient, a worker) or the GPU backend (GpuSim, on the page's device). */
export interface SimDriver {
  readonly kind: 'cpu' | 'gpu';
  readonly mirrors: Mirror[];
  paused: boolean;
  readonly stats: SimStats;
  onFrame: (() => void) | null;
  /**
   * called when the mirrors hold new positions from the simulation, `frames[k]` the frame mirror k's are of (the
   * worker's frames as they arrive; on the GPU, each readback)
   */
  onPositions: ((frames: readonly number[]) => void) | null;
  onError: ((message: string) => void) | null;
  /** a slot's cloth stopped being finite at `frame` (called once; see Mirror.unstableAt) */
  onUnstable: ((slot: number, frame: number) => void) | null;
  load(scenes: Scene[]): void;
  /** `carry`: the particles that go on where they are when the cloth is rebuilt (Simulation.setScene) */
  setScene(slot: number, scene: Scene, carry?: readonly ParticleRange[]): boolean;
  reset(): void;
  resetSlot(slot: number): void;
  grab(slot: number, particle: number, target: [number, number, number]): void;
  release(slot: number): void;
  /**
   * Drives collider `index` of a slot from now on: its pose and velocity (Simulation.setColliderPose; null gives it
   * back to its scene motion). The mirror's collider moves with it, for drawing.
   */
  setColliderPose(slot: number, index: number, pose: ColliderPose | null): void;
  step(frames?: number): Promise<void>;
  tick(dtMs: number, now: number): void;
  /** test hook only: makes one particle's position NaN, as a blown-up solver would */
  poison(slot: number): void;
  dispose(): void;
}

export class SimClient implements SimDriver {
  readonly kind = 'cpu' as const;
  readonly mirrors: Mirror[] = [];
  paused = false;
  readonly stats: SimStats = newStats();
  /** called after each frame from the worker has been applied to the mirrors */
  onFrame: (() => void) | null = null;
  onPositions: ((frames: readonly number[]) => void) | null = null;
  /** called with a worker error message */
  onError: ((message: string) => void) | null = null;
  onUnstable: ((slot: number, frame: number) => void) | null = null;

  private worker: Worker;
  private gen = 0;
  private readonly clock = new FrameClock();
  private nextId = 1;
  private loopInFlight = 0;
  private pending = new Map<number, () => void>();
  /** the mesh files sent to the worker, by name (a newer import of the same name is sent again) */
  private readonly sent = new Map<string, TriangleMesh>();

  /** `meshes`: the page's imported mesh files, for scenes that name them (sent to the worker as needed) */
  constructor(private readonly meshes: MeshStore) {
    // the one form bundlers (Vite, webpack, Parcel) find a worker by: keep the URL inside `new Worker(…)`. A page
    // that enforces Trusted Types lets it through with a default policy (app/security.ts; docs/three.md)
    this.worker = new Worker(new URL('./sim.worker.js', import.meta.url), { type: 'module', name: 'drape-sim' });
    this.worker.onmessage = (e: MessageEvent<FromWorker>) => this.receive(e.data);
    this.worker.onerror = (e) => this.onError?.(`simulation worker: ${e.message || 'failed to start'}`);
  }

  private post(msg: ToWorker): void {
    this.worker.postMessage(msg);
  }

  /**
   * Sends the worker the mesh files a scene names (its cloth's, its mesh colliders'), before the scene, unless it has
   * them already.
   */
  private sendMeshes(scene: Scene): void {
    for (const { path } of sceneMeshes(scene)) {
      const entry = this.meshes.find(path);
      if (!entry || this.sent.get(entry.name) === entry.mesh) continue;
      this.sent.set(entry.name, entry.mesh);
      this.post({ type: 'mesh', entry });
    }
  }

  /**
   * Replaces every cloth (a new scene, or a different number of slots). A scene the core refuses (SceneError, e.g.
   * a collider cutting through the cloth) throws before anything changes.
   */
  load(scenes: Scene[]): void {
    // mirrors hold the scene and model for picking and the panel; they never step, so no kernel memory
    const sims = scenes.map((scene) => new Simulation(scene, { kernel: 'ts', meshes: this.meshes.resolve }));
    const gen = ++this.gen;
    this.mirrors.length = 0;
    for (const sim of sims) this.mirrors.push({ sim, modelGen: gen, frame: 0, grabbed: -1, unstableAt: -1 });
    for (const sim of sims) this.sendMeshes(sim.scene);
    this.post({ type: 'load', gen, scenes: this.mirrors.map((m) => m.sim.scene) });
    this.clock.restart(this.stats);
  }

  /**
   * Changes one slot's scene, live. Returns true when the cloth is rebuilt: it restarts, but for the particles
   * `carry` keeps (Simulation.setScene). Refused: throws, changes nothing.
   */
  setScene(slot: number, scene: Scene, carry: readonly ParticleRange[] = []): boolean {
    const m = this.mirrors[slot];
    const gen = ++this.gen;
    const rebuilt = m.sim.setScene(scene, carry);
    if (rebuilt) { m.modelGen = gen; m.frame = carry.length ? m.frame : 0; m.grabbed = -1; m.unstableAt = -1; this.clock.restart(this.stats); }
    this.sendMeshes(m.sim.scene);
    this.post({ type: 'setScene', gen, slot, scene: m.sim.scene, carry: [...carry] });
    return rebuilt;
  }

  /** frames stepped before a reset (still on their way) are dropped: a newer generation */
  reset(): void {
    const gen = ++this.gen;
    for (const m of this.mirrors) { m.sim.reset(); m.frame = 0; m.grabbed = -1; m.unstableAt = -1; m.modelGen = gen; }
    this.post({ type: 'reset', gen });
    this.clock.clear();
  }

  resetSlot(slot: number): void {
    const gen = ++this.gen;
    const m = this.mirrors[slot];
    m.sim.reset(); m.frame = 0; m.grabbed = -1; m.unstableAt = -1; m.modelGen = gen;
    this.post({ type: 'reset', gen, slot });
  }

  poison(slot: number): void {
    this.post({ type: 'poison', slot });
  }

  grab(slot: number, particle: number, target: [number, number, number]): void {
    this.mirrors[slot].grabbed = particle;
    this.post({ type: 'grab', slot, particle, target });
  }

  release(slot: number): void {
    this.mirrors[slot].grabbed = -1;
    this.post({ type: 'release', slot });
  }

  setColliderPose(slot: number, index: number, pose: ColliderPose | null): void {
    this.mirrors[slot].sim.setColliderPose(index, pose);
    this.post({ type: 'colliderPose', slot, index, pose });
  }

  /**
   * Continues a slot from a state of another backend (positions, previous positions, velocities, time; pins are
   * the scene's): the mirror shows it at once and the worker steps on from it.
   */
  setState(slot: number, state: ClothState, frame: number): void {
    const m = this.mirrors[slot];
    m.sim.state.positions.set(state.positions);
    m.frame = frame;
    m.unstableAt = -1;
    this.post({
      type: 'setState', slot, frame, time: state.time, substeps: state.substeps,
      positions: state.positions.slice(), previous: state.previousPositions.slice(), velocities: state.velocities.slice(),
    });
  }

  dispose(): void {
    this.worker.terminate();
    for (const done of this.pending.values()) done();
    this.pending.clear();
  }

  /** Steps `frames` frames now (paused or not); resolves once they are in the mirrors. */
  step(frames = 1): Promise<void> {
    return new Promise((resolve) => {
      const id = this.nextId++;
      this.pending.set(id, resolve);
      this.post({ type: 'advance', id, frames });
    });
  }

  /**
   * Called once per displayed frame with the wall time since the last one: asks the worker for the whole frames
   * the clock says are due, at most one request at a time (see FrameClock).
   */
  tick(dtMs: number, now: number): void {
    if (this.paused) {
      this.clock.idle();
      return;
    }
    const n = this.clock.tick(dtMs, now, this.loopInFlight > 0, this.stats.stepMs);
    if (n > 0) {
      const id = this.nextId++;
      this.loopInFlight++;
      this.pending.set(id, () => { this.loopInFlight--; });
      this.post({ type: 'advance', id, frames: n });
    }
  }

  private receive(msg: FromWorker): void {
    if (msg.type === 'error') {
      this.onError?.(msg.message);
      return;
    }
    msg.slots.forEach((f, k) => {
      const m = this.mirrors[k];
      if (!m || f.gen < m.modelGen || f.positions.length !== m.sim.state.positions.length) return;
      if (f.unstableAt >= 0) {
        // keep the last finite positions on screen; say so once
        m.frame = f.frame;
        if (m.unstableAt < 0) { m.unstableAt = f.unstableAt; this.onUnstable?.(k, f.unstableAt); }
        return;
      }
      m.sim.state.positions.set(f.positions);
      m.sim.state.pinned.set(f.pinned);
      m.frame = f.frame;
      m.grabbed = f.grabbed;
    });
    const s = this.stats;
    // frames of a cloth loaded or rebuilt since (still on their way) time that cloth, not this one
    const current = msg.slots.every((f, k) => !this.mirrors[k] || f.gen >= this.mirrors[k].modelGen);
    if (msg.frames > 0 && current) this.clock.account(s, msg.frames, msg.stepMs, this.paused);
    s.energy = msg.energy;
    s.maxStrain = msg.maxStrain;
    s.clamps = msg.clamps;
    s.kernel = msg.kernel;
    s.threads = msg.threads;
    const done = this.pending.get(msg.id);
    this.pending.delete(msg.id);
    done?.();
    if (msg.frames > 0) this.onPositions?.(this.mirrors.map((m) => m.frame));
    this.onFrame?.();
  }
}
