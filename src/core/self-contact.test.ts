import { describe, expect, it } from 'vitest';
import { countIntersections } from './intersections.js';
import { builtinScene } from './scenes.js';
import { selfContactBuilds, selfContactDistance } from './self-contact.js';
import { Simulation } from './simulation.js';
import { validateScene } from './scene.js';
import { copyState } from './state.js';

/** Rubber at 32² on the sphere: without self-contact it folds through itself from frame ~30 on (20 pairs). */
function rubber(selfContact: boolean, kernel: 'ts' | 'wasm'): Simulation {
  const scene = builtinScene('rubber-stretch')!;
  scene.cloth.resolution = 32;
  scene.solver.selfContact = selfContact;
  return new Simulation(scene, { kernel, threads: 1 });
}

/** The crossing pairs at every 10th frame of the first `frames`. */
function crossings(sim: Simulation, frames: number): number[] {
  const out: number[] = [];
  for (let f = 10; f <= frames; f += 10) {
    sim.advance(10);
    out.push(countIntersections(sim.model.triangles, sim.state.positions));
  }
  return out;
}

describe('self-contact (solver.selfContact)', () => {
  it('without it, rubber at 32² folds through itself on the sphere (what the tests below would see)', () => {
    const sim = rubber(false, 'ts');
    expect(Math.max(...crossings(sim, 60))).toBeGreaterThan(5);
    sim.dispose();
  });

  // every CPU kernel: the WebAssembly kernel runs the phase itself (its passes in the kernel, the candidate search in
  // TypeScript: wasm/self-contact-wasm.test.ts holds it to the reference bit for bit)
  it.each(['ts', 'wasm'] as const)('%s: with it, no two triangles cross at any 10th frame of 1.5 s, and the cloth stays on the sphere', (kernel) => {
    const sim = rubber(true, kernel);
    expect(crossings(sim, 90)).toEqual(Array(9).fill(0));
    const r = sim.report();
    expect(r.finite).toBe(true);
    expect(r.maxPenetration).toBeLessThanOrEqual(1e-3);
    expect(r.centroid[1]).toBeGreaterThan(0.3); // still draped on the sphere, not slid off to the floor
    // the candidate pairs are found ahead and again only when a particle leaves where they were found for: 90 frames
    // of 20 substeps found them 158 (wasm) and 160 (ts) times while it falls, lands and settles, not 1800
    const builds = selfContactBuilds(sim.model);
    expect(builds).toBeGreaterThanOrEqual(90);
    expect(builds).toBeLessThan(400);
    sim.dispose();
  });

  it('keeps a distance no more than the thickness and half the smallest rest altitude', () => {
    const coarse = rubber(true, 'ts'), fine = (() => {
      const s = builtinScene('rubber-stretch')!;
      s.cloth.resolution = 256;
      s.solver.selfContact = true;
      return new Simulation(s, { kernel: 'ts' });
    })();
    expect(selfContactDistance(coarse.model, coarse.params)).toBe(coarse.params.thickness);
    // 256 faces over 1 m: the right triangles' smallest altitude is (1/256)/√2
    expect(selfContactDistance(fine.model, fine.params)).toBeCloseTo(0.5 / 256 / Math.SQRT2, 6);
    coarse.dispose();
    fine.dispose();
  });

  // two thin strips crossing like an X, the upper one falling on the pinned lower one: every vertex stays far outside
  // the other strip's triangles, so only the edges meet (the particle–triangle test alone lets it fall through)
  it.each(['ts', 'wasm'] as const)('%s: edges that cross with no vertex near the other strip are kept apart (edge–edge contact)', (kernel) => {
    const scene = validateScene({
      name: 'crossed strips',
      solver: { selfContact: true },
      colliders: [{ type: 'floor', height: 0 }],
      cloths: [
        { cloth: { resolution: 1, width: 1, height: 0.02, position: [0, 0.3, 0] }, material: { fabric: 'cotton' }, pins: ['top-left', 'top-right', 'bottom-left', 'bottom-right'] },
        { cloth: { resolution: 1, width: 1, height: 0.02, position: [0, 0.33, 0], rotation: [0, 90, 0] }, material: { fabric: 'cotton' } },
      ],
    });
    const sim = new Simulation(scene, { kernel, threads: 1 });
    const h = selfContactDistance(sim.model, sim.params);
    expect(h).toBe(0.005);
    for (let f = 1; f <= 60; f++) {
      sim.advance(1);
      expect(countIntersections(sim.model.triangles, sim.state.positions), `frame ${f}`).toBe(0);
    }
    // the upper strip lies across the lower one, its ends tipping a little about the crossing (without edge–edge
    // contact it falls through to the floor)
    const x = sim.state.positions;
    let lowest = Infinity, highest = -Infinity;
    for (let i = 4; i < 8; i++) { lowest = Math.min(lowest, x[3 * i + 1]); highest = Math.max(highest, x[3 * i + 1]); }
    expect(lowest).toBeGreaterThan(0.25);
    expect(highest).toBeLessThan(0.33); // below where it started: it fell and stopped on the lower strip
    sim.dispose();
  });

  it('resolves the pairs in one order however the candidates were found: a cloth that found them frames ago steps as one that finds them now', () => {
    // fold landing at 32²: many particles meet several triangles in one substep, so the order shows
    const ahead = new Simulation(builtinScene('fold'), { kernel: 'ts' });
    ahead.advance(25);
    const fresh = new Simulation(builtinScene('fold'), { kernel: 'ts' });
    copyState(ahead.state, fresh.state);
    const built = selfContactBuilds(ahead.model);
    for (const sim of [ahead, fresh]) sim.advance(5);
    expect(selfContactBuilds(ahead.model) - built).toBeLessThan(100); // mostly the candidates found ahead: not every substep's
    expect([...fresh.state.positions]).toEqual([...ahead.state.positions]);
    ahead.dispose();
    fresh.dispose();
  });

  // the fold scene lands corner first in layers: without edge–edge contact 3–10 pairs crossed from frame 20 on
  it.each(['ts', 'wasm'] as const)('%s: the fold scene (32², corner first onto the floor) crosses itself at no 10th frame of 2 s', (kernel) => {
    const sim = new Simulation(builtinScene('fold'), { kernel, threads: 1 });
    expect(crossings(sim, 120)).toEqual(Array(12).fill(0));
    expect(sim.report().finite).toBe(true);
    // its layers lie on each other at the contact distance: nothing pressed them nearer
    expect(sim.report().squeezed).toBe(0);
    sim.dispose();
  });

  /**
   * A cotton sheet lying on the floor and a smaller one pinned all over above it, `gap` [m] above the lower one's
   * rest height (the floor's contact thickness): below the self-contact distance h, floor and pins hold the layers
   * nearer than h, since both run after self-contact (docs/physics.md).
   */
  function squeeze(gap: number, kernel: 'ts' | 'wasm'): Simulation {
    const t = 0.005;
    return new Simulation(validateScene({
      name: 'squeeze',
      solver: { selfContact: true },
      colliders: [{ type: 'floor', height: 0 }],
      cloths: [
        { name: 'lower', cloth: { resolution: 8, position: [0, t, 0], thickness: t }, material: { fabric: 'cotton' } },
        {
          name: 'upper', cloth: { resolution: 6, width: 0.6, height: 0.6, position: [0, t + gap, 0], thickness: t }, material: { fabric: 'cotton' },
          pins: [{ min: [-1, -1, -1], max: [1, 1, 1] }],
        },
      ],
    }), { kernel, threads: 1 });
  }

  it.each(['ts', 'wasm'] as const)('%s: where pins and a collider press two layers nearer than the contact distance, they win, and `squeezed` counts it', (kernel) => {
    const pressed = squeeze(0.0015, kernel);
    const h = selfContactDistance(pressed.model, pressed.params);
    expect(h).toBe(0.005);
    pressed.advance(30);
    const r = pressed.report();
    expect(r.finite).toBe(true);
    // the floor holds the lower sheet up (never below it), the pins hold the upper one where it is: 1.5 mm apart
    expect(r.bounds.min[1]).toBeGreaterThan(0);
    const x = pressed.state.positions, upper = pressed.model.clothStarts[1];
    expect(x[3 * upper + 1]).toBeCloseTo(0.0065, 6);
    // the upper sheet's 49 particles and the lower one's under it (0.6 m of its 1 m: 5 × 5 at least) lie 1.5 mm from the other layer
    expect(r.squeezed).toBeGreaterThanOrEqual(49 + 25);
    expect(r.squeezed).toBeLessThanOrEqual(pressed.model.particleCount);
    pressed.dispose();
    // 2 h above: nothing pressed; each layer rests where it is
    const free = squeeze(2 * 0.005, kernel);
    free.advance(30);
    expect(free.report().squeezed).toBe(0);
    free.dispose();
  });
});
