import { readFileSync, writeFileSync } from 'node:fs';
import { afterAll, describe, expect, it } from 'vitest';
import { builtinScene, SCENE_NAMES, Simulation } from './index.js';

/**
 * Every built-in grid scene, 120 frames on the TypeScript kernel, against the result recorded before meshes.
 * To measure it again, where a change moves the results on purpose (say why in the fixture's $comment, which is
 * kept): `DRAPE_RECORD_GRID_PARITY=1 npx vitest run src/core/grid-parity.test.ts` rewrites its scenes from today's
 * code (9 significant digits), then run the test again without it.
 */
const FIXTURE = new URL('./fixtures/grid-parity.json', import.meta.url);
type Entry = { particles: number; centroid: number[]; min: number[]; max: number[] };
const fixture = JSON.parse(readFileSync(FIXTURE, 'utf8')) as { $comment: string; scenes: Record<string, Entry> };
const record = process.env.DRAPE_RECORD_GRID_PARITY === '1';
const recorded: Record<string, Entry> = {};
afterAll(() => {
  if (!record) return;
  const scenes: Record<string, Entry> = {};
  for (const name of Object.keys(fixture.scenes)) scenes[name] = recorded[name] ?? fixture.scenes[name];
  for (const name of PARITY_SCENES) if (recorded[name]) scenes[name] = recorded[name];
  writeFileSync(FIXTURE, JSON.stringify({ $comment: fixture.$comment, scenes }, null, 1) + '\n');
});
const digits = (v: readonly number[]) => v.map((x) => Number(x.toPrecision(9)));
/**
 * The scenes held to the fixture: every built-in but the two made for self-contact (fold, layers), which are held to
 * their crossings instead (self-contact.test.ts, cloths.test.ts) and cost the most to step in TypeScript. Each runs
 * with self-contact off, the springs swept alone (solver.stretch 'gauss-seidel') and the cloth laid flat (no
 * cloth.perturbation), as the fixture was recorded: the built-in scenes have self-contact on since, the coarse
 * correction by default since 2026-12-06 and the Cusick specimen its waviness since that day, and what they change is
 * held to their own tests; this one holds every other phase to its recorded result.
 */
const SELF_CONTACT_SCENES = ['fold', 'layers'];
const PARITY_SCENES = SCENE_NAMES.filter((name) => !SELF_CONTACT_SCENES.includes(name));

describe('built-in scenes give the result recorded in the fixture (first recorded before cloths became triangle meshes)', () => {
  it('the fixture covers every built-in scene but fold and layers', () => {
    expect(Object.keys(fixture.scenes).sort()).toEqual([...PARITY_SCENES].sort());
  });
  it.each([...PARITY_SCENES])('%s', (name) => {
    const scene = builtinScene(name);
    delete scene.resolutionSweep;
    scene.solver.selfContact = false;
    scene.solver.stretch = 'gauss-seidel';
    scene.cloth.perturbation.amplitude = 0;
    const sim = new Simulation(scene, { kernel: 'ts' });
    sim.advance(120);
    const r = sim.report(), want = fixture.scenes[name];
    if (record) {
      recorded[name] = { particles: r.particles, centroid: digits(r.centroid), min: digits(r.bounds.min), max: digits(r.bounds.max) };
      return;
    }
    expect(r.particles).toBe(want.particles);
    // the same arithmetic in the same order: equal to the fixture's 9 digits
    for (let k = 0; k < 3; k++) {
      expect(r.centroid[k]).toBeCloseTo(want.centroid[k], 7);
      expect(r.bounds.min[k]).toBeCloseTo(want.min[k], 7);
      expect(r.bounds.max[k]).toBeCloseTo(want.max[k], 7);
    }
  });
});
