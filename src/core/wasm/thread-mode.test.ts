import { describe, expect, it } from 'vitest';
import { PROBE_AFTER, PROBE_EVERY, PROBE_FRAMES, ThreadModeChooser } from './thread-mode.js';

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
    expect(alone).toBeLessThanOrEqual(PROBE_FRAMES * Math.ceil(200 / PROBE_EVERY)); // one probe per PROBE_EVERY frames
  });

  it('runs alone when the helpers make frames slower (a busy machine), and goes back when they pay again', () => {
    const c = new ThreadModeChooser();
    let busy = true;
    const modes = drive(c, 200, (p) => (p ? (busy ? 0.5 : 0.1) : 0.18));
    expect(c.parallel).toBe(false);
    // parallel only during warm-up, the first window and one probe per PROBE_EVERY frames
    expect(modes.filter((p) => p).length).toBeLessThanOrEqual(PROBE_AFTER + 9 + PROBE_FRAMES * Math.ceil(200 / PROBE_EVERY));
    busy = false;
    drive(c, PROBE_EVERY + 12, (p) => (p ? (busy ? 0.5 : 0.1) : 0.18));
    expect(c.parallel).toBe(true);
  });

  it('is not fooled by single slow frames (a machine hiccup), nor switches for less than the margin', () => {
    const c = new ThreadModeChooser();
    let f = 0;
    drive(c, 400, (p) => (f++ % 7 === 0 ? 5 : p ? 0.1 : 0.18)); // every 7th frame 50× slower, in either mode
    expect(c.parallel).toBe(true);
    expect(c.framesAlone).toBeLessThanOrEqual(PROBE_FRAMES * Math.ceil(400 / PROBE_EVERY));
  });

  it('does not measure warm-up frames, nor switch for less than the margin', () => {
    const c = new ThreadModeChooser();
    const modes = drive(c, PROBE_AFTER, () => 1);
    expect(modes.every((p) => p)).toBe(true);
    drive(c, 200, (p) => (p ? 0.1 : 0.097)); // alone only 3 % faster: stays
    expect(c.parallel).toBe(true);
    const d = new ThreadModeChooser();
    drive(d, 200, (p) => (p ? 0.1 : 0.096)); // alone 4 % faster: stays (the margin to alone is 5 %)
    expect(d.parallel).toBe(true);
    drive(d, 200, (p) => (p ? 0.1 : 0.09)); // 10 % faster alone: goes
    expect(d.parallel).toBe(false);
    drive(d, 300, (p) => (p ? 0.08 : 0.09)); // helpers 11 % faster: not enough to go back (15 %)
    expect(d.parallel).toBe(false);
  });

  it('hold() fixes the mode until released', () => {
    const c = new ThreadModeChooser();
    c.hold(true);
    expect(drive(c, 200, (p) => (p ? 1 : 0.1)).every((p) => p)).toBe(true);
    c.hold(false);
    expect(drive(c, 10, () => 0.1).every((p) => !p)).toBe(true);
    c.hold(undefined);
    drive(c, 200, (p) => (p ? 1 : 0.1));
    expect(c.parallel).toBe(false);
  });
});
