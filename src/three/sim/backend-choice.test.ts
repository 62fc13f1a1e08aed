import { describe, expect, it } from 'vitest';
import { Simulation, builtinScene, validateScene } from '../../core/index.js';
import { carriable, chooseBackend } from './backend-choice.js';
import type { Mirror } from './sim-client.js';

const hardware = { missing: null, software: false };
const software = { missing: null, software: true };
const none = { missing: 'no WebGPU device', software: false };
const app = { override: 'choose GPU to use it anyway', explainAuto: false };
const addon = { override: "backend: 'gpu' uses it anyway", explainAuto: true };

describe('the backend choice the app and DrapeWorld share', () => {
  const scene = builtinScene('cotton-basic');
  const massSpring = validateScene({ solver: { type: 'mass-spring' } });

  it('cpu is the CPU; gpu takes any device; auto passes a software one by, saying how to take it anyway', () => {
    for (const gpu of [hardware, software, none]) expect(chooseBackend('cpu', scene, gpu, app)).toEqual({ kind: 'cpu', note: '' });
    expect(chooseBackend('auto', scene, hardware, app)).toEqual({ kind: 'gpu', note: '' });
    expect(chooseBackend('gpu', scene, software, app)).toEqual({ kind: 'gpu', note: '' });
    expect(chooseBackend('auto', scene, software, app)).toEqual({ kind: 'cpu', note: expect.stringMatching(/^auto: the WebGPU device is a software fallback .*; choose GPU to use it anyway$/) });
    expect(chooseBackend('auto', scene, software, addon).note).toMatch(/; backend: 'gpu' uses it anyway$/);
  });

  it("says what the scene needs on any machine, and the missing device where it was asked for (or the wording explains auto)", () => {
    const why = chooseBackend('gpu', massSpring, hardware, app);
    expect(why.kind).toBe('cpu');
    expect(why.note).toMatch(/^GPU unavailable: .*mass-spring/);
    // the scene's reason comes before the machine's
    expect(chooseBackend('auto', massSpring, none, app)).toEqual(why);
    expect(chooseBackend('gpu', scene, none, app)).toEqual({ kind: 'cpu', note: 'GPU unavailable: no WebGPU device' });
    expect(chooseBackend('auto', scene, none, app)).toEqual({ kind: 'cpu', note: '' });
    expect(chooseBackend('auto', scene, none, addon)).toEqual({ kind: 'cpu', note: 'GPU unavailable: no WebGPU device' });
  });

  it('carries a mirror only into one of the same particles, and only while it is finite', () => {
    const mirror = (resolution: number, unstableAt = -1): Mirror =>
      ({ sim: new Simulation({ cloth: { resolution } }, { kernel: 'ts' }), modelGen: 0, frame: 0, grabbed: -1, unstableAt });
    const a = mirror(8), b = mirror(8), c = mirror(9);
    expect(carriable(a, b)).toBe(true);
    expect(carriable(a, c)).toBe(false);
    expect(carriable(mirror(8, 12), b)).toBe(false);
    expect(carriable(undefined, b)).toBe(false);
    expect(carriable(a, undefined)).toBe(false);
    for (const m of [a, b, c]) m.sim.dispose();
  });
});
