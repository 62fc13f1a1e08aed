/**
 * The fixed-timestep clock both simulation drivers (CPU worker, GPU) run on: display frames add wall time to an
 * accumulator that is spent in whole 1/60 s frames, and the real-time ratio is measured over the last second.
 * The app's HUD explains a ratio under 1 (app/slow-cause.ts).
 */
import { FRAME_DT } from '../../core/index.js';
import type { SimStats } from './sim-client.js';

export const FRAME_MS = FRAME_DT * 1000;
/** the accumulator never holds more than this many frames: a slow machine or a hidden tab builds no backlog */
const MAX_BACKLOG_FRAMES = 3;
/** most frames asked for in one go (catching up after a hiccup) */
const MAX_FRAMES_PER_REQUEST = 4;
/** longest wall-clock gap a single display frame may count for [ms] (tab switches, breakpoints) */
const MAX_TICK_MS = 100;
/** simulation time one display frame may take [ms] when choosing how many frames to step */
const FRAME_BUDGET_MS = 14;

/** Statistics of a driver before it has stepped anything. */
export function newStats(): SimStats {
  return { stepMs: 0, realTime: 1, measured: false, energy: { kinetic: 0, gravitational: 0, elastic: 0, bending: 0 }, maxStrain: 0, clamps: [], framesDone: 0, kernel: '', threads: 0 };
}

export class FrameClock {
  private acc = 0;
  /** (wall ms, simulated frames) samples over the last second, for the real-time ratio */
  private readonly history: [number, number][] = [];

  /** Forgets accumulated time (a new scene, a reset). */
  clear(): void {
    this.acc = 0;
  }

  /**
   * A new cloth (a scene loaded, a cloth rebuilt): its speed is not known yet. Forgets the accumulated time, the
   * real-time samples and the step time, and marks `stats` unmeasured until frames of the new cloth are timed.
   */
  restart(stats: SimStats): void {
    this.idle();
    stats.stepMs = 0;
    stats.measured = false;
  }

  /** Paused (or not ready): no time accumulates and the real-time measurement starts over. */
  idle(): void {
    this.acc = 0;
    this.history.length = 0;
  }

  /**
   * One running display frame, `dtMs` after the last, at `now`: how many whole frames to start now — as many as
   * have accumulated, at most what fits in about one display frame at `stepMs` each, none while `busy`. Time the
   * simulation cannot keep up with is dropped (slow motion), never queued.
   */
  tick(dtMs: number, now: number, busy: boolean, stepMs: number): number {
    this.acc += Math.min(Math.max(dtMs, 0), MAX_TICK_MS);
    let n = 0;
    if (!busy) {
      const budget = stepMs > 0 ? Math.max(1, Math.floor(FRAME_BUDGET_MS / stepMs)) : 1;
      n = Math.min(Math.floor(this.acc / FRAME_MS), MAX_FRAMES_PER_REQUEST, budget);
      this.acc -= n * FRAME_MS;
    }
    this.acc = Math.min(this.acc, MAX_BACKLOG_FRAMES * FRAME_MS);
    this.history.push([now, 0]);
    while (this.history.length > 2 && now - this.history[0][0] > 1000) this.history.shift();
    return n;
  }

  /** `frames` were stepped, `msPerFrame` each: updates the smoothed step time, the frame count and the real-time ratio. */
  account(stats: SimStats, frames: number, msPerFrame: number, paused: boolean): void {
    // no frame stepped (a step(0) that only waits for the backend): nothing was timed, and 0/0 or t/0 must not
    // become the smoothed step time for good
    if (!(frames > 0) || !Number.isFinite(msPerFrame)) return;
    stats.stepMs = stats.stepMs > 0 ? 0.8 * stats.stepMs + 0.2 * msPerFrame : msPerFrame;
    stats.framesDone += frames;
    const h = this.history;
    const last = h[h.length - 1];
    if (last && !paused) last[1] += frames;
    const span = h.length > 1 ? h[h.length - 1][0] - h[0][0] : 0;
    if (span > 500) {
      let n = 0;
      for (let i = 1; i < h.length; i++) n += h[i][1];
      stats.realTime = (n * FRAME_MS) / span;
      stats.measured = true;
    }
  }
}
