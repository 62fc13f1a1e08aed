import { describe, expect, it } from 'vitest';
import { PROBE_AFTER, PROBE_EVERY, ThreadModeChooser } from './thread-mode.js';

/** Runs `frames` frames where a frame costs `ms(parallel)` per substep; returns the modes chosen. */
function drive(chooser: ThreadModeChooser, frames: number, ms: (parallel: boolean) => number): boolean[] {
  const modes: boolean[] = [];
  for (let f = 0; f < frames; f++) {
    const parallel = chooser.next();
    modes.push(parallel);
    chooser.record(ms(parallel));
  }
  return modes;
}

describe('thread mode', () => {
  it('keeps the helpers while they make frames faster, probing alone now and then', () => {
    const c = new ThreadModeChooser();
    const modes = drive(c, 200, (p) => (p ? 0.1 : 0.18));
    expect(c.parallel).toBe(true);
    const alone = modes.filter((p) => !p).length;
    expect(alone).toBeGreaterThan(0);
    expect(alone).toBeLessThanOrEqual(Math.ceil(200 / PROBE_EVERY)); // one probe per PROBE_EVERY frames
  });

  it('runs alone when the helpers make frames slower (a busy machine), and goes back when they pay again', () => {
    const c = new ThreadModeChooser();
    let busy = true;
    const modes = drive(c, 120, (p) => (p ? (busy ? 0.5 : 0.1) : 0.18));
    expect(c.parallel).toBe(false);
    expect(modes.slice(PROBE_AFTER + 2).filter((p) => p).length).toBeLessThanOrEqual(Math.ceil(120 / PROBE_EVERY));
    busy = false;
    drive(c, 2 * PROBE_EVERY + 2, (p) => (p ? (busy ? 0.5 : 0.1) : 0.18));
    expect(c.parallel).toBe(true);
  });

  it('does not measure warm-up frames, nor switch for less than the margin', () => {
    const c = new ThreadModeChooser();
    const modes = drive(c, PROBE_AFTER, () => 1);
    expect(modes.every((p) => p)).toBe(true);
    drive(c, 200, (p) => (p ? 0.1 : 0.095)); // alone only 5 % faster: stays
    expect(c.parallel).toBe(true);
  });
});
