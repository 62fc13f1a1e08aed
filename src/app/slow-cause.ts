/** What holds a page back from real time, in words for the HUD (the clock's numbers: three/sim/frame-clock.ts). */
import { FRAME_MS } from '../three/sim/frame-clock.js';

/**
 * Whether a simulation that needs `stepMs` per 1/60 s frame cannot keep real time however the display goes: its
 * frame takes longer than the frame lasts (with a tenth's margin for the messages that carry it). Unmeasured: no.
 */
export function cannotKeepUp(stepMs: number): boolean {
  return Number.isFinite(stepMs) && stepMs > 0.9 * FRAME_MS;
}

/** What keeps a page from real time, and what to try. */
export interface SlowCause {
  /** 'simulation': stepping a frame takes longer than it lasts; 'drawing': the simulation keeps up, but display
   * frames come too rarely to ask it for all the frames the time needs */
  by: 'simulation' | 'drawing';
  /** one line for the HUD, in words, with the fix that fits */
  text: string;
}

/**
 * Why the page runs at `realTime` (< 1) of real time: the simulation needs `stepMs` per 1/60 s frame, and `fps`
 * display frames are drawn per second. A display frame asks for at most MAX_FRAMES_PER_REQUEST frames and counts at
 * most MAX_TICK_MS of wall time, so at few display frames per second the simulation idles however fast it is: that
 * is drawing's fault, not the simulation's. The simulation is to blame only when its own frame takes longer than
 * the frame lasts (with a tenth's margin for the messages that carry it).
 */
export function slowCause(realTime: number, stepMs: number, fps: number): SlowCause {
  const pct = `${(100 * realTime).toFixed(0)}% of real time`;
  const step = Number.isFinite(stepMs) ? stepMs : 0;
  if (cannotKeepUp(step)) {
    return { by: 'simulation', text: `slow motion: ${pct} — the simulation needs ${step.toFixed(0)} ms per ${FRAME_MS.toFixed(1)} ms frame; try a lower resolution or fewer substeps` };
  }
  return {
    by: 'drawing',
    text: `slow motion: ${pct} — drawing holds it back (${drawn(fps)}; the simulation needs only ${step.toFixed(1)} ms per ${FRAME_MS.toFixed(1)} ms frame); try a smaller window, the wireframe view, or ?lite in the address`,
  };
}

function drawn(fps: number): string {
  if (!(fps >= 1)) return 'less than one frame drawn per second';
  return `${fps < 10 ? fps.toFixed(1) : fps.toFixed(0)} frames drawn per second`;
}
