/**
 * Self-contact "on by default where the frame budget allows" (issue 12). The built-in scenes come with
 * `solver.selfContact` on; the page keeps it on while the simulation keeps real time. When the simulation itself
 * cannot keep up (slow-cause.ts cannotKeepUp: its own frame takes longer than the frame lasts) for OVER_MS of
 * running time with self-contact on, and nobody chose self-contact on this page (the panel's switch), the app turns
 * it off and says so; switched on again by hand it stays on. A new scene starts the watch afresh.
 */
import { FRAME_MS } from '../three/sim/frame-clock.js';
import { cannotKeepUp } from './slow-cause.js';

/** how long the simulation must hold the page back before self-contact goes off [ms of running wall time] */
export const OVER_MS = 2000;

const SWITCHED_OFF = 'Self-contact switched off:';

export class ContactBudget {
  /** self-contact was set by hand on this page (the panel): the budget leaves it alone until the next scene */
  chosen = false;
  /** running wall time over budget so far [ms] */
  private over = 0;
  private last = -1;

  /** A new scene (built-in, file, link): the watch starts again and nobody has chosen yet. */
  reset(): void {
    this.chosen = false;
    this.over = 0;
    this.last = -1;
  }

  /**
   * One look at `now` [ms]: true (once) when self-contact should go off — it is on, the page runs (not paused),
   * nobody chose it, and the simulation, needing `stepMs` per frame (smoothed), has been too slow for OVER_MS.
   */
  watch(now: number, selfContact: boolean, paused: boolean, stepMs: number): boolean {
    const dt = this.last < 0 ? 0 : Math.min(now - this.last, 500);
    this.last = now;
    if (!selfContact || paused || this.chosen) { this.over = 0; return false; }
    this.over = cannotKeepUp(stepMs) ? this.over + dt : 0;
    if (this.over < OVER_MS) return false;
    this.over = 0;
    return true;
  }

  /** Whether `text` is the budget's message (it belongs to the scene it was said of). */
  static said(text: string): boolean {
    return text.startsWith(SWITCHED_OFF);
  }

  /** What the page says when it switched self-contact off, from the simulation's time per frame [ms]. */
  static message(stepMs: number): string {
    const step = Number.isFinite(stepMs) ? stepMs.toFixed(0) : '?';
    return `${SWITCHED_OFF} with it the simulation needs ${step} ms per ${FRAME_MS.toFixed(1)} ms frame here. ` +
      'Switch it on again under Solver (it then stays on), or lower the resolution.';
  }
}
