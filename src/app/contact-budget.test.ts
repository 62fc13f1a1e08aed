import { describe, expect, it } from 'vitest';
import { ContactBudget, OVER_MS } from './contact-budget.js';
import { newStats } from '../three/sim/frame-clock.js';

/** stats of a simulation that needs `stepMs` per 16.7 ms frame and runs at `realTime` of real time */
const stats = (stepMs: number, realTime: number) => ({ ...newStats(), stepMs, realTime });

/** watches every 250 ms for `ms`; true if it said to switch off at some look */
function run(b: ContactBudget, t0: number, ms: number, ...args: [boolean, boolean, ReturnType<typeof stats>, number]): boolean {
  let off = false;
  for (let t = t0; t <= t0 + ms; t += 250) off = b.watch(t, ...args) || off;
  return off;
}

describe('the self-contact frame budget', () => {
  it('switches off once the simulation has held the page back for OVER_MS of running time', () => {
    const b = new ContactBudget();
    expect(run(b, 0, OVER_MS - 250, true, false, stats(30, 0.5), 60)).toBe(false);
    expect(b.watch(OVER_MS + 250, true, false, stats(30, 0.5), 60)).toBe(true);
  });

  it('leaves it on while the simulation keeps up, or when drawing is what is slow', () => {
    expect(run(new ContactBudget(), 0, 10_000, true, false, stats(12, 1), 60)).toBe(false);
    expect(run(new ContactBudget(), 0, 10_000, true, false, stats(4, 0.4), 8)).toBe(false);
  });

  it('counts only running time, and starts over after a frame that kept up', () => {
    const b = new ContactBudget();
    expect(run(b, 0, 10_000, true, true, stats(30, 0.5), 60)).toBe(false); // paused
    expect(run(b, 10_250, OVER_MS - 500, true, false, stats(30, 0.5), 60)).toBe(false);
    expect(b.watch(12_000, true, false, stats(10, 1), 60)).toBe(false);
    expect(run(b, 12_250, OVER_MS - 500, true, false, stats(30, 0.5), 60)).toBe(false);
  });

  it('never switches what was chosen by hand, or what is off; a new scene watches again', () => {
    const b = new ContactBudget();
    b.chosen = true;
    expect(run(b, 0, 10_000, true, false, stats(30, 0.5), 60)).toBe(false);
    expect(run(new ContactBudget(), 0, 10_000, false, false, stats(30, 0.5), 60)).toBe(false);
    b.reset();
    expect(run(b, 20_000, OVER_MS + 500, true, false, stats(30, 0.5), 60)).toBe(true);
  });

  it('says what it did in words, never NaN', () => {
    expect(ContactBudget.message(31.6)).toMatch(/^Self-contact switched off: with it the simulation needs 32 ms per 16\.7 ms frame/);
    expect(ContactBudget.message(NaN)).not.toMatch(/NaN/);
  });
});
