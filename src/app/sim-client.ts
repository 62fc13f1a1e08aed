/**
 * The page's side of the simulation: a fixed-timestep clock that asks the worker for whole 1/60 s frames, and a
 * mirror of each slot's cloth for drawing and picking.
 *
 * The mirror of a slot is a core Simulation that is never stepped: it holds the model (built from the same scene
 * by the same code as the worker's, so the two agree particle for particle) and a state whose positions and pins
 * are overwritten by each frame from the worker. Changing its scene with `setScene` tells us, by the core's own
 * rule, whether the worker is rebuilding the cloth; frames of an older cloth are then dropped.
 */
import { FRAME_DT, Simulation, type ClothState, type Energy, type Scene } from '../core/index.js';
import type { FromWorker, ToWorker } from './protocol.js';

export const FRAME_MS = FRAME_DT * 1000;
/** the accumulator never holds more than this many frames: a slow machine or a hidden tab builds no backlog */
const MAX_BACKLOG_FRAMES = 3;
/** most frames asked for in one go (catching up after a hiccup) */
const MAX_FRAMES_PER_REQUEST = 4;
/** longest wall-clock gap a single display frame may count for [ms] (tab switches, breakpoints) */
const MAX_TICK_MS = 100;

export interface Mirror {
  sim: Simulation;
  /** generation of the current model; frames of older generations are dropped */
  modelGen: number;
  frame: number;
  grabbed: number;
}

export interface SimStats {
  /** worker time per simulated frame, summed over slots, smoothed [ms] */
  stepMs: number;
  /** simulated time / wall time over the last second while running (1 = real time) */
  realTime: number;
  energy: Energy;
  maxStrain: number;
  clamps: string[];
  /** frames answered by the worker since the page loaded */
  framesDone: number;
}

/** What the app drives: the CPU backend (SimClient, a worker) or the GPU backend (GpuSim, on the page's device). */
export interface SimDriver {
  readonly kind: 'cpu' | 'gpu';
  readonly mirrors: Mirror[];
  paused: boolean;
  readonly stats: SimStats;
  onFrame: (() => void) | null;
  onError: ((message: string) => void) | null;
  load(scenes: Scene[]): void;
  setScene(slot: number, scene: Scene): boolean;
  reset(): void;
  resetSlot(slot: number): void;
  grab(slot: number, particle: number, target: [number, number, number]): void;
  release(slot: number): void;
  step(frames?: number): Promise<void>;
  tick(dtMs: number, now: number): void;
  dispose(): void;
}

export class SimClient implements SimDriver {
  readonly kind = 'cpu' as const;
  readonly mirrors: Mirror[] = [];
  paused = false;
  readonly stats: SimStats = {
    stepMs: 0, realTime: 1, energy: { kinetic: 0, gravitational: 0, elastic: 0 }, maxStrain: 0, clamps: [], framesDone: 0,
  };
  /** called after each frame from the worker has been applied to the mirrors */
  onFrame: (() => void) | null = null;
  /** called with a worker error message */
  onError: ((message: string) => void) | null = null;

  private worker: Worker;
  private gen = 0;
  private acc = 0;
  private nextId = 1;
  private loopInFlight = 0;
  private pending = new Map<number, () => void>();
  /** (wall ms, simulated frames) samples for the real-time ratio */
  private history: [number, number][] = [];

  constructor() {
    this.worker = new Worker(new URL('./sim.worker.ts', import.meta.url), { type: 'module', name: 'drape-sim' });
    this.worker.onmessage = (e: MessageEvent<FromWorker>) => this.receive(e.data);
    this.worker.onerror = (e) => this.onError?.(`simulation worker: ${e.message || 'failed to start'}`);
  }

  private post(msg: ToWorker): void {
    this.worker.postMessage(msg);
  }

  /** Replaces every cloth (a new scene, or a different number of slots). */
  load(scenes: Scene[]): void {
    const gen = ++this.gen;
    this.mirrors.length = 0;
    for (const scene of scenes) this.mirrors.push({ sim: new Simulation(scene), modelGen: gen, frame: 0, grabbed: -1 });
    this.post({ type: 'load', gen, scenes: this.mirrors.map((m) => m.sim.scene) });
    this.acc = 0;
  }

  /** Changes one slot's scene, live. Returns true when the cloth is rebuilt (and restarts). */
  setScene(slot: number, scene: Scene): boolean {
    const m = this.mirrors[slot];
    const gen = ++this.gen;
    const rebuilt = m.sim.setScene(scene);
    if (rebuilt) { m.modelGen = gen; m.frame = 0; m.grabbed = -1; }
    this.post({ type: 'setScene', gen, slot, scene: m.sim.scene });
    return rebuilt;
  }

  reset(): void {
    for (const m of this.mirrors) { m.sim.reset(); m.frame = 0; m.grabbed = -1; }
    this.post({ type: 'reset' });
    this.acc = 0;
  }

  resetSlot(slot: number): void {
    const m = this.mirrors[slot];
    m.sim.reset(); m.frame = 0; m.grabbed = -1;
    this.post({ type: 'reset', slot });
  }

  grab(slot: number, particle: number, target: [number, number, number]): void {
    this.mirrors[slot].grabbed = particle;
    this.post({ type: 'grab', slot, particle, target });
  }

  release(slot: number): void {
    this.mirrors[slot].grabbed = -1;
    this.post({ type: 'release', slot });
  }

  /**
   * Continues a slot from a state of another backend (positions, previous positions, velocities, time; pins are
   * the scene's): the mirror shows it at once and the worker steps on from it.
   */
  setState(slot: number, state: ClothState, frame: number): void {
    const m = this.mirrors[slot];
    m.sim.state.positions.set(state.positions);
    m.frame = frame;
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
   * Called once per displayed frame with the wall time since the last one. Asks the worker for as many whole
   * frames as have accumulated, at most what it can step in about one display frame, and at most one request
   * at a time; time the worker cannot keep up with is dropped (slow motion), never queued.
   */
  tick(dtMs: number, now: number): void {
    dtMs = Math.min(Math.max(dtMs, 0), MAX_TICK_MS);
    if (this.paused) {
      this.acc = 0;
      this.history.length = 0;
      return;
    }
    this.acc += dtMs;
    if (this.loopInFlight === 0) {
      const budget = this.stats.stepMs > 0 ? Math.max(1, Math.floor(14 / this.stats.stepMs)) : 1;
      const n = Math.min(Math.floor(this.acc / FRAME_MS), MAX_FRAMES_PER_REQUEST, budget);
      if (n > 0) {
        this.acc -= n * FRAME_MS;
        const id = this.nextId++;
        this.loopInFlight++;
        this.pending.set(id, () => { this.loopInFlight--; });
        this.post({ type: 'advance', id, frames: n });
      }
    }
    this.acc = Math.min(this.acc, MAX_BACKLOG_FRAMES * FRAME_MS);
    this.history.push([now, 0]);
    while (this.history.length > 2 && now - this.history[0][0] > 1000) this.history.shift();
  }

  private receive(msg: FromWorker): void {
    if (msg.type === 'error') {
      this.onError?.(msg.message);
      return;
    }
    msg.slots.forEach((f, k) => {
      const m = this.mirrors[k];
      if (!m || f.gen < m.modelGen || f.positions.length !== m.sim.state.positions.length) return;
      m.sim.state.positions.set(f.positions);
      m.sim.state.pinned.set(f.pinned);
      m.frame = f.frame;
      m.grabbed = f.grabbed;
    });
    const s = this.stats;
    if (msg.frames > 0) {
      s.stepMs = s.stepMs > 0 ? 0.8 * s.stepMs + 0.2 * msg.stepMs : msg.stepMs;
      s.framesDone += msg.frames;
      const last = this.history[this.history.length - 1];
      if (last && !this.paused) last[1] += msg.frames;
      const span = this.history.length > 1 ? this.history[this.history.length - 1][0] - this.history[0][0] : 0;
      if (span > 500) {
        let frames = 0;
        for (let i = 1; i < this.history.length; i++) frames += this.history[i][1];
        s.realTime = (frames * FRAME_MS) / span;
      }
    }
    s.energy = msg.energy;
    s.maxStrain = msg.maxStrain;
    s.clamps = msg.clamps;
    const done = this.pending.get(msg.id);
    this.pending.delete(msg.id);
    done?.();
    this.onFrame?.();
  }
}
