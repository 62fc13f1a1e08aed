import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { builtinScene, SCENE_NAMES, Simulation } from './index.js';

/** Every built-in grid scene, 120 frames on the TypeScript kernel, against the result recorded before meshes. */
const fixture = JSON.parse(readFileSync(new URL('./fixtures/grid-parity.json', import.meta.url), 'utf8')) as {
  scenes: Record<string, { particles: number; centroid: number[]; min: number[]; max: number[] }>;
};

describe('built-in scenes give the result recorded in the fixture (first recorded before cloths became triangle meshes)', () => {
  it('the fixture covers every built-in scene', () => {
    expect(Object.keys(fixture.scenes).sort()).toEqual([...SCENE_NAMES].sort());
  });
  it.each([...SCENE_NAMES])('%s', (name) => {
    const scene = builtinScene(name);
    delete scene.resolutionSweep;
    const sim = new Simulation(scene, { kernel: 'ts' });
    sim.advance(120);
    const r = sim.report(), want = fixture.scenes[name];
    expect(r.particles).toBe(want.particles);
    // the same arithmetic in the same order: equal to the fixture's 9 digits
    for (let k = 0; k < 3; k++) {
      expect(r.centroid[k]).toBeCloseTo(want.centroid[k], 7);
      expect(r.bounds.min[k]).toBeCloseTo(want.min[k], 7);
      expect(r.bounds.max[k]).toBeCloseTo(want.max[k], 7);
    }
  });
});
