import { describe, expect, it } from 'vitest';
import { FRAME_MS, FrameClock, newStats } from '../three/sim/frame-clock.js';
import { slowCause } from './slow-cause.js';

describe('slowCause: the HUD blames what limits the page', () => {
  it('a simulation that keeps up while drawing runs at 1 fps: drawing is to blame, not the simulation', () => {
    // software rendering: one display frame a second, the worker steps a frame in 2.1 ms
    const c = slowCause(0.07, 2.1, 1);
    expect(c.by).toBe('drawing');
    expect(c.text).toContain('drawing holds it back');
    expect(c.text).toContain('1.0 frames drawn per second');
    expect(c.text).toContain('2.1 ms per 16.7 ms frame');
    expect(c.text).not.toContain('lower resolution');
  });

  it('a simulation that needs more than a frame lasts is to blame, whatever the display does', () => {
    const c = slowCause(0.6, 21, 60);
    expect(c.by).toBe('simulation');
    expect(c.text).toBe('slow motion: 60% of real time — the simulation needs 21 ms per 16.7 ms frame; try a lower resolution or fewer substeps');
  });

  it('the clock it explains: at 1 display frame a second a 2 ms simulation runs at 1/15 of real time', () => {
    // what the loop does at 1 fps: ticks 1000 ms apart, each counted as at most 100 ms
    const clock = new FrameClock();
    const stats = newStats();
    let frames = 0;
    for (let k = 0; k < 5; k++) {
      const n = clock.tick(1000, 1000 * k, false, 2);
      frames += n;
      clock.account(stats, n, 2, false);
    }
    expect(frames * FRAME_MS / 5000).toBeLessThan(0.1);
    expect(stats.realTime).toBeLessThan(0.1);
    expect(slowCause(stats.realTime, stats.stepMs, 1).by).toBe('drawing');
  });

  it('a step of no frames (one that only waits for the backend) times nothing: the step time stays what it was', () => {
    const clock = new FrameClock();
    const stats = newStats();
    clock.account(stats, 0, 12 / 0, false);
    expect(stats.stepMs).toBe(0);
    clock.account(stats, 2, 20, false);
    clock.account(stats, 0, NaN, false);
    expect(stats.stepMs).toBe(20);
    expect(stats.framesDone).toBe(2);
  });

  it('never shows NaN: an unmeasured step time or frame rate', () => {
    expect(slowCause(0.5, NaN, 30).text).not.toMatch(/NaN|Infinity/);
    // nothing drawn for half a second while running: a display frame takes longer than that
    expect(slowCause(0.5, 3, 0).text).toContain('less than one frame drawn per second');
  });
});
