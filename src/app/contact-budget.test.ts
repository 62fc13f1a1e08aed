import { describe, expect, it } from 'vitest';
import { ContactBudget, OVER_MS } from './contact-budget.js';

/** watches every 250 ms for `ms` from `t0`; true if it said to switch off at some look */
function run(b: ContactBudget, t0: number, ms: number, selfContact: boolean, paused: boolean, stepMs: number): boolean {
  let off = false;
  for (let t = t0; t <= t0 + ms; t += 250) off = b.watch(t, selfContact, paused, stepMs) || off;
  return off;
}

describe('the self-contact frame budget', () => {
  it('switches off once the simulation has needed more than a frame lasts for OVER_MS of running time', () => {
    const b = new ContactBudget();
    expect(run(b, 0, OVER_MS - 250, true, false, 30)).toBe(false);
    expect(b.watch(OVER_MS + 250, true, false, 30)).toBe(true);
  });

  it('leaves it on while the simulation keeps up (a slow display is not its fault), or before it is measured', () => {
    expect(run(new ContactBudget(), 0, 10_000, true, false, 14)).toBe(false);
    expect(run(new ContactBudget(), 0, 10_000, true, false, NaN)).toBe(false);
    expect(run(new ContactBudget(), 0, 10_000, true, false, Infinity)).toBe(false);
  });

  it('counts only running time, and starts over after a look that kept up', () => {
    const b = new ContactBudget();
    expect(run(b, 0, 10_000, true, true, 30)).toBe(false); // paused
    expect(run(b, 10_250, OVER_MS - 500, true, false, 30)).toBe(false);
    expect(b.watch(12_000, true, false, 10)).toBe(false);
    expect(run(b, 12_250, OVER_MS - 500, true, false, 30)).toBe(false);
  });

  it('never switches what was chosen by hand, or what is off; a new scene watches again', () => {
    const b = new ContactBudget();
    b.chosen = true;
    expect(run(b, 0, 10_000, true, false, 30)).toBe(false);
    expect(run(new ContactBudget(), 0, 10_000, false, false, 30)).toBe(false);
    b.reset();
    expect(run(b, 20_000, OVER_MS + 500, true, false, 30)).toBe(true);
  });

  it('says what it did in words, never NaN', () => {
    expect(ContactBudget.message(31.6)).toMatch(/^Self-contact switched off: with it the simulation needs 32 ms per 16\.7 ms frame/);
    expect(ContactBudget.message(NaN)).not.toMatch(/NaN/);
  });

  it('knows its own message (it is taken away when another scene loads: slots.ts)', () => {
    expect(ContactBudget.said(ContactBudget.message(24))).toBe(true);
    expect(ContactBudget.said('Imported scene.json')).toBe(false);
  });
});
