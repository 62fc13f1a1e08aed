import { describe, expect, it } from 'vitest';
import { FRAME_MS, FrameClock, newStats } from './frame-clock.js';

describe('FrameClock: the fixed-step accumulator both drivers run on', () => {
  it('spends wall time in whole 1/60 s frames and carries the rest over', () => {
    const clock = new FrameClock();
    // 10 ms, 10 ms, 10 ms: 30 ms is one frame of 16.7 ms and 13.3 ms left
    expect(clock.tick(10, 10, false, 1)).toBe(0);
    expect(clock.tick(10, 20, false, 1)).toBe(1);
    expect(clock.tick(10, 30, false, 1)).toBe(0);
    expect(clock.tick(10, 40, false, 1)).toBe(1);
    // 60 display frames of 1/60 s each step 60 frames
    let n = 0;
    for (let k = 0; k < 60; k++) n += clock.tick(FRAME_MS, 100 + k * FRAME_MS, false, 1);
    expect(Math.abs(n - 60)).toBeLessThanOrEqual(1);
  });

  it('builds no backlog: a long gap counts as at most 100 ms, and at most 3 frames wait', () => {
    const clock = new FrameClock();
    // a hidden tab: 5 s in one display frame
    expect(clock.tick(5000, 5000, false, 1)).toBe(4);
    expect(clock.tick(0, 5001, false, 1)).toBeLessThanOrEqual(3);
    // while a batch is in flight nothing starts; the time waiting is capped at three frames
    const busy = new FrameClock();
    for (let k = 0; k < 10; k++) expect(busy.tick(50, 50 * k, true, 1)).toBe(0);
    expect(busy.tick(0, 600, false, 1)).toBe(3);
  });

  it('asks for no more frames than fit in a display frame at the measured step time', () => {
    const clock = new FrameClock();
    // 10 ms per frame: one frame per request however much time is due
    expect(clock.tick(100, 100, false, 10)).toBe(1);
    expect(clock.tick(0, 101, false, 10)).toBe(1);
  });

  it('measures the real-time ratio over the last second', () => {
    const clock = new FrameClock();
    const stats = newStats();
    // half the frames due are stepped: every other display frame of 1/60 s steps one
    for (let k = 0; k < 120; k++) {
      clock.tick(FRAME_MS, k * FRAME_MS, false, 1);
      if (k % 2 === 0) clock.account(stats, 1, 1, false);
    }
    expect(stats.realTime).toBeGreaterThan(0.4);
    expect(stats.realTime).toBeLessThan(0.6);
    expect(stats.framesDone).toBe(60);
    expect(stats.measured).toBe(true);
    // forgetting the accumulator: nothing is due at once after clear()
    clock.tick(15, 3000, false, 1);
    clock.clear();
    expect(clock.tick(5, 3005, false, 1)).toBe(0);
  });

  it('a new cloth is unmeasured until its frames have run for half a second: the HUD does not say real time before', () => {
    const clock = new FrameClock();
    const stats = newStats();
    expect(stats.measured).toBe(false);
    for (let k = 0; k < 60; k++) { clock.tick(FRAME_MS, k * FRAME_MS, false, 1); clock.account(stats, 1, 1, false); }
    expect([stats.measured, stats.stepMs]).toEqual([true, 1]);
    // a heavier cloth is loaded: its first frame takes 2 s, and until it is timed nothing is known
    clock.restart(stats);
    expect([stats.measured, stats.stepMs]).toEqual([false, 0]);
    for (let k = 0; k < 120; k++) clock.tick(FRAME_MS, 1000 + k * FRAME_MS, true, stats.stepMs);
    expect(stats.measured).toBe(false);
    clock.account(stats, 1, 2000, false);
    expect(stats.measured).toBe(true);
    expect(stats.realTime).toBeLessThan(0.02); // one frame of 16.7 ms in the last second
    expect(stats.stepMs).toBe(2000);
  });
});
