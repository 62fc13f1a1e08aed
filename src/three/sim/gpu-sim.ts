/**
 * The GPU backend of the page: one core Simulation per slot, running on a core GpuBackend (src/gpu/backend.ts:
 * the same Backend interface the CLI and the library use; the Simulation's state is its CPU mirror), one per
 * slot, on the renderer's own GPUDevice, on the main thread. A frame is one command buffer the CPU only encodes;
 * the cloth is drawn straight from the solver's position and normal buffers (ClothView.attachGpu). Positions come
 * back to the CPU only asynchronously, at most ~10 times a second (every frame while a CPU-drawn view — springs,
 * particles, strain — is showing), for picking, the HUD numbers, the exports and the device-loss fallback.
 *
 * Same interface and clock as the worker's SimClient: whole 1/60 s frames, at most one batch of frames in flight
 * on the GPU queue, time it cannot keep up with dropped.
 */
import {
  Simulation, energy, grab, isFinite3, maxStructuralStrain, release, type ClothModel, type ColliderPose, type ParticleRange, type Scene,
} from '../../core/index.js';
import { GpuBackend, sceneRefusal, type GpuClothSolver } from '../../gpu/index.js';
import { FrameClock, newStats } from './frame-clock.js';
import type { MeshStore } from './meshes.js';
import type { Mirror, SimDriver, SimStats } from './sim-client.js';

/** background readback period [ms] (picking, HUD, fallback state) */
const READBACK_MS = 100;

interface GpuSlot {
  /** the slot's GPU backend (its Simulation runs on it once made) */
  backend: GpuBackend | null;
  /** model the backend was made for */
  model: ClothModel | null;
  /** creation in progress (for this model) */
  creating: ClothModel | null;
  /** a newer readback is wanted before positions are trusted (after a reset or upload) */
  stale: boolean;
  /** the last positions read back that were all finite (what an unstable cloth goes back to and shows) */
  lastGood: Float32Array | null;
}

export class GpuSim implements SimDriver {
  readonly kind = 'gpu' as const;
  readonly mirrors: Mirror[] = [];
  private slots: GpuSlot[] = [];
  paused = false;
  readonly stats: SimStats = newStats();
  onFrame: (() => void) | null = null;
  onPositions: ((frames: readonly number[]) => void) | null = null;
  onError: ((message: string) => void) | null = null;
  onUnstable: ((slot: number, frame: number) => void) | null = null;
  /** true: read back every frame (a view drawn from CPU positions is showing) */
  eagerReadback = false;
  /** the device was lost: nothing is stepped or read any more; mirrors keep the last readback */
  lost = false;
  private readonly clock = new FrameClock();
  private inFlight = false;
  private reading = false;
  private lastRead = 0;
  private readGen = 0;
  private disposed = false;

  /** `meshes`: the page's imported mesh files, for the scenes that name them (cloth, mesh colliders) */
  constructor(readonly device: GPUDevice, private readonly meshes: MeshStore) {
    void device.lost.then(() => { this.lost = true; });
  }

  /** the solver of a slot once compiled for its current model (views attach to its buffers) */
  solverOf(slot: number): GpuClothSolver | null {
    const s = this.slots[slot], m = this.mirrors[slot];
    return s && m && s.backend && s.model === m.sim.model ? s.backend.solver : null;
  }

  /** all solvers compiled for their current models */
  get ready(): boolean {
    return this.mirrors.every((_, k) => this.solverOf(k) !== null);
  }

  /** Replaces every cloth; a scene the core refuses throws before anything changes. */
  load(scenes: Scene[]): void {
    // the mirror holds scene, model and read-back positions; the GPU steps, so no kernel memory
    const sims = scenes.map((scene) => new Simulation(scene, { kernel: 'ts', meshes: this.meshes.resolve }));
    this.destroySolvers();
    this.mirrors.length = 0;
    for (const sim of sims) {
      this.mirrors.push({ sim, modelGen: 0, frame: 0, grabbed: -1, unstableAt: -1 });
      this.slots.push({ backend: null, model: null, creating: null, stale: false, lastGood: sim.state.positions.slice() });
    }
    this.readGen++;
    this.clock.restart(this.stats);
    this.mirrors.forEach((_, k) => this.ensureSolver(k));
  }

  /** Fails for what the GPU solver does not support (mass-spring, a collider shape it lacks: gpu/encoder.ts sceneRefusal): the caller falls back. */
  static supports(scene: Scene): string | null {
    return sceneRefusal(scene);
  }

  private ensureSolver(k: number): void {
    const slot = this.slots[k], m = this.mirrors[k];
    const model = m.sim.model;
    if (slot.model === model || slot.creating === model || this.lost) return;
    slot.creating = model;
    GpuBackend.create(this.device, model).then((backend) => {
      if (this.disposed || this.slots[k] !== slot || this.mirrors[k]?.sim.model !== model) { backend.dispose(); return; }
      slot.creating = null;
      try {
        backend.solver.setParams(m.sim.params);
        // the cloth moves onto the GPU as the mirror has it (the CPU backend it was built with is let go)
        m.sim.useBackend(backend);
      } catch (e) {
        backend.dispose();
        this.onError?.(`GPU solver: ${(e as Error).message}`);
        return;
      }
      slot.backend = backend;
      slot.model = model;
      this.onFrame?.();
    }, (e: unknown) => {
      if (slot.creating === model) slot.creating = null;
      if (!this.lost && !this.disposed) this.onError?.((e as Error).message ?? String(e));
    });
  }

  setScene(slot: number, scene: Scene, carry: readonly ParticleRange[] = []): boolean {
    const m = this.mirrors[slot];
    // (the carried particles as last read back: up to READBACK_MS old)
    const rebuilt = m.sim.setScene(scene, carry);
    if (rebuilt) {
      m.frame = carry.length ? m.frame : 0; m.grabbed = -1; m.unstableAt = -1;
      this.readGen++;
      const s = this.slots[slot];
      s.lastGood = m.sim.state.positions.slice();
      // (the Simulation let the old backend go when it rebuilt)
      s.backend = null; s.model = null;
      this.ensureSolver(slot);
      this.clock.restart(this.stats);
    }
    return rebuilt;
  }

  reset(): void {
    this.mirrors.forEach((_, k) => this.resetSlot(k));
    this.clock.clear();
  }

  resetSlot(slot: number): void {
    const m = this.mirrors[slot];
    m.sim.reset(); m.frame = 0; m.grabbed = -1; m.unstableAt = -1; // (the backend sends the reset cloth at once)
    this.slots[slot].lastGood = m.sim.state.positions.slice();
    this.readGen++;
    this.onFrame?.();
  }

  /** Test hook: NaN into one particle's position on the GPU; the next readback finds it (see readback). */
  poison(slot: number): void {
    const solver = this.solverOf(slot), m = this.mirrors[slot];
    if (!solver || !m) return;
    const i = m.sim.model.particleCount >> 1;
    this.device.queue.writeBuffer(solver.positionBuffer, 16 * i, new Float32Array([NaN, NaN, NaN, 0]));
  }

  /** Puts a state (from another backend) into a slot: positions, velocities, time, pins; and its frame count. */
  upload(slot: number, frame: number): void {
    const m = this.mirrors[slot];
    m.frame = frame;
    m.sim.frame = frame;
    m.sim.unstableFrame = null;
    m.unstableAt = -1;
    this.slots[slot].lastGood = m.sim.state.positions.slice();
    this.readGen++;
    m.sim.backend.stateChanged('all');
  }

  grab(slot: number, particle: number, target: [number, number, number]): void {
    const m = this.mirrors[slot];
    m.grabbed = particle;
    grab(m.sim.state, particle, target);
    // the CPU copy of the grabbed particle follows the target at once (picking and the marker need no readback)
    m.sim.state.positions.set(target, 3 * particle);
  }

  release(slot: number): void {
    const m = this.mirrors[slot];
    m.grabbed = -1;
    release(m.sim.state);
  }

  /** (the GPU backend reads the drive from the Simulation's params each frame) */
  setColliderPose(slot: number, index: number, pose: ColliderPose | null): void {
    this.mirrors[slot].sim.setColliderPose(index, pose);
  }

  /** Steps `frames` frames now (paused or not); resolves once they are done and read back into the mirrors. */
  async step(frames = 1): Promise<void> {
    await this.whenReady();
    if (this.lost || this.disposed) return;
    const t0 = performance.now();
    if (!this.encode(frames)) return;
    await this.device.queue.onSubmittedWorkDone();
    this.clock.account(this.stats, frames, (performance.now() - t0) / frames, this.paused);
    await this.readback(true);
  }

  private async whenReady(): Promise<void> {
    for (let k = 0; !this.ready && !this.lost && !this.disposed && k < 600; k++) await new Promise((r) => setTimeout(r, 50));
  }

  /**
   * Encodes `frames` frames of every slot; false, said through onError, where the GPU refuses one when it meets it
   * (self-contact switched on for a cloth whose lists this device cannot bind, a mesh collider's tables over its
   * limit): the page then moves the cloths to the CPU, saying why.
   */
  private encode(frames: number): boolean {
    try {
      for (let f = 0; f < frames; f++) {
        this.mirrors.forEach((m, k) => {
          if (!this.solverOf(k) || m.unstableAt >= 0) return;
          m.sim.advance(1);
          m.frame = m.sim.frame;
        });
      }
    } catch (e) {
      this.onError?.((e as Error).message ?? String(e));
      return false;
    }
    this.onFrame?.();
    return true;
  }

  tick(dtMs: number, now: number): void {
    if (this.lost || this.disposed) return;
    if (!this.paused && this.ready) {
      const n = this.clock.tick(dtMs, now, this.inFlight, this.stats.stepMs);
      if (n > 0) {
        const t0 = performance.now();
        if (!this.encode(n)) return;
        this.inFlight = true;
        this.device.queue.onSubmittedWorkDone().then(() => {
          this.inFlight = false;
          this.clock.account(this.stats, n, (performance.now() - t0) / n, this.paused);
        }, () => { this.inFlight = false; });
      }
    } else {
      this.clock.idle();
    }
    if (!this.reading && this.ready && (this.eagerReadback || now - this.lastRead >= READBACK_MS)) void this.readback(false);
  }

  /**
   * Reads every slot's cloth back into its mirror (positions, velocities, λ) and recomputes the HUD numbers.
   * A lost device cannot be read: the mirrors then keep the last completed readback.
   */
  private async readback(force: boolean): Promise<void> {
    if (this.lost || (this.reading && !force)) return;
    this.reading = true;
    const gen = this.readGen;
    // the read is queued after the frames encoded so far: the positions are of these frames
    const frames = this.mirrors.map((m) => m.frame);
    try {
      await Promise.all(this.mirrors.map(async (m, k) => {
        if (!this.solverOf(k) || m.unstableAt >= 0) return;
        await m.sim.sync();
        // a load, reset or rebuild since the read began: its cloths are not these (stopUnstable and lastGood are theirs)
        if (gen !== this.readGen) return;
        // (synchronously after the read: nothing is drawn in between)
        const slot = this.slots[k];
        if (!isFinite3(m.sim.state)) {
          this.stopUnstable(k);
          return;
        }
        if (m.grabbed >= 0) m.sim.state.positions.set(m.sim.state.grabTarget, 3 * m.grabbed);
        if (slot.lastGood?.length === m.sim.state.positions.length) slot.lastGood.set(m.sim.state.positions);
        else slot.lastGood = m.sim.state.positions.slice();
      }));
    } catch (e) {
      // a read of solvers let go meanwhile (a load or a rebuild destroyed their buffers) is moot, not a failure
      if (!this.lost && !this.disposed && gen === this.readGen) this.onError?.(`GPU readback: ${(e as Error).message}`);
      return;
    } finally {
      this.reading = false;
      this.lastRead = performance.now();
    }
    if (gen !== this.readGen) return;
    const s = this.stats;
    const total = { kinetic: 0, gravitational: 0, elastic: 0, bending: 0 };
    let maxStrain = 0;
    const clamps = new Set<string>();
    for (const m of this.mirrors) {
      if (m.unstableAt >= 0) continue;
      const e = energy(m.sim.model, m.sim.state, m.sim.params);
      total.kinetic += e.kinetic; total.gravitational += e.gravitational; total.elastic += e.elastic; total.bending += e.bending;
      maxStrain = Math.max(maxStrain, maxStructuralStrain(m.sim.model, m.sim.state));
      for (const c of m.sim.notes) clamps.add(c);
    }
    s.energy = total;
    s.maxStrain = maxStrain;
    s.clamps = [...clamps];
    this.onPositions?.(frames);
    this.onFrame?.();
  }

  /**
   * A cloth whose positions read back are not finite: it is no longer stepped, and goes back to the last finite
   * positions read back, on the CPU and on the GPU (which the views draw from), so nothing NaN is drawn (at most
   * the one readback period, ~0.1 s, in between), picked or exported. Reset starts it again.
   */
  private stopUnstable(k: number): void {
    const m = this.mirrors[k], slot = this.slots[k];
    m.unstableAt = m.frame;
    const st = m.sim.state;
    const good = slot.lastGood?.length === st.positions.length ? slot.lastGood : m.sim.model.restPositions;
    st.positions.set(good);
    st.previousPositions.set(good);
    st.velocities.fill(0);
    st.residuals.fill(0);
    st.previousResiduals.fill(0);
    st.lambdas.fill(0);
    m.grabbed = -1;
    release(st);
    m.sim.backend.stateChanged('all');
    this.onUnstable?.(k, m.frame);
  }

  private destroySolvers(): void {
    for (const s of this.slots) { s.backend?.dispose(); s.backend = null; s.creating = null; }
    this.slots = [];
  }

  dispose(): void {
    this.disposed = true;
    if (!this.lost) this.destroySolvers();
  }
}
