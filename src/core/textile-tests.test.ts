/**
 * The standard fabric tests (textile-tests.ts): the heavy elastica behind the cantilever's bending length, the
 * Cusick measurement on shapes whose answer is known, the scenes, and pins by region that hold a clamp at any
 * resolution.
 */
import { describe, expect, it } from 'vitest';
import { modelFor } from './cloth-shape.js';
import { resolvePins } from './pins.js';
import { validateScene } from './scene.js';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';
import { countFolds, elasticaChordAngle, elasticaLoad, measureTest, type CantileverResult, type CusickResult } from './textile-tests.js';

const deg = (r: number) => (r * 180) / Math.PI;

describe('the heavy elastica', () => {
  it('gives Peirce\'s 41.5° at an overhang of twice the bending length (λ = 8), as ASTM D1388 rests on', () => {
    expect(deg(elasticaChordAngle(8))).toBeCloseTo(41.5, 1);
    expect(elasticaLoad((41.5 * Math.PI) / 180)).toBeCloseTo(8, 1);
  });
  it('is the small-deflection beam for a light load: tip drop wL⁴/(8B), a chord of atan(λ/8)', () => {
    for (const lambda of [0.001, 0.01]) expect(elasticaChordAngle(lambda) / Math.atan(lambda / 8)).toBeCloseTo(1, 3);
  });
  it('the chord falls further as the load grows, and elasticaLoad inverts it', () => {
    let prev = 0;
    for (const lambda of [0.1, 1, 4, 8, 20, 60, 200, 1000]) {
      const t = elasticaChordAngle(lambda);
      expect(t).toBeGreaterThan(prev);
      prev = t;
      expect(elasticaLoad(t) / lambda).toBeCloseTo(1, 4);
    }
  });
});

describe('what the tests measure', () => {
  it('a cantilever strip held straight at α below the edge reads a chord of α and the bending length that gives', () => {
    const sim = new Simulation(builtinScene('cantilever'), { kernel: 'ts' });
    const edge = sim.scene.test!.type === 'cantilever' ? sim.scene.test!.edge : [0, 0, 0];
    const x = sim.state.positions, alpha = (30 * Math.PI) / 180;
    for (let i = 0; i < sim.model.particleCount; i++) {
      const out = x[3 * i + 2] - edge[2];
      if (sim.state.pinned[i] || out <= 0) continue;
      x[3 * i + 1] = edge[1] - out * Math.sin(alpha);
      x[3 * i + 2] = edge[2] + out * Math.cos(alpha);
    }
    const r = sim.report().test as CantileverResult;
    expect(r.overhang).toBeCloseTo(0.04, 6);
    expect(r.chordAngle).toBeCloseTo(30, 3);
    expect(r.bendingLength! / (0.04 / Math.cbrt(elasticaLoad(alpha)))).toBeCloseTo(1, 5);
  });

  it('a strip that has not bent yet (its start, flat) has no bending length to read: null, not Infinity', () => {
    const sim = new Simulation(builtinScene('cantilever'), { kernel: 'ts' });
    const r = sim.report().test as CantileverResult;
    expect(r.chordAngle).toBe(0);
    expect(r.bendingLength).toBeNull();
  });

  it('where no row lies on the edge, the strip overhangs from the last clamped row behind it, and is measured from there', () => {
    // 15 faces along 8 cm: rows every 5.33 mm, the clamp's last at z = −2.67 mm, the first free one at +2.67 mm
    const scene = builtinScene('cantilever');
    const sim = new Simulation(validateScene({ ...scene, cloth: { ...scene.cloth, resolution: 15 } }), { kernel: 'ts' });
    const x = sim.state.positions, alpha = (40 * Math.PI) / 180;
    let clamp = -Infinity;
    for (let i = 0; i < sim.model.particleCount; i++) if (sim.state.pinned[i]) clamp = Math.max(clamp, x[3 * i + 2]);
    expect(clamp).toBeCloseTo(-0.08 / 30, 6);
    for (let i = 0; i < sim.model.particleCount; i++) {
      if (sim.state.pinned[i]) continue;
      const out = x[3 * i + 2] - clamp;
      x[3 * i + 1] = 0.5 - out * Math.sin(alpha);
      x[3 * i + 2] = clamp + out * Math.cos(alpha);
    }
    const r = sim.report().test as CantileverResult;
    expect(r.overhang).toBeCloseTo(0.04 - clamp, 6);
    expect(r.chordAngle).toBeCloseTo(40, 3);
    expect(r.bendingLength! / (r.overhang / Math.cbrt(elasticaLoad(alpha)))).toBeCloseTo(1, 5);
  });

  it('a Cusick disc lying flat covers its own area (coefficient 1, no folds); one hanging as a cylinder at the pedestal\'s edge, none', () => {
    const scene = builtinScene('cusick');
    const sim = new Simulation(validateScene({ ...scene, cloth: { ...scene.cloth, perturbation: { amplitude: 0 } } }), { kernel: 'ts' });
    const flat = sim.report().test as CusickResult;
    expect(flat.projectedArea / sim.model.area).toBeCloseTo(1, 2);
    expect(flat.drapeCoefficient).toBeCloseTo(1, 2);
    expect(flat.folds).toBe(0);
    // every particle moved in to the pedestal's radius: the shadow is the pedestal's
    const x = sim.state.positions;
    for (let i = 0; i < sim.model.particleCount; i++) {
      const r = Math.hypot(x[3 * i], x[3 * i + 2]);
      if (r > 0.09) { x[3 * i] *= 0.09 / r; x[3 * i + 2] *= 0.09 / r; }
    }
    const hanging = measureTest(sim.model, sim.state, sim.scene) as CusickResult;
    expect(Math.abs(hanging.drapeCoefficient)).toBeLessThan(0.01);
  });

  it('a cloth spread wider than 4 m is measured on coarser cells, not reported as NaN; a pedestal as large as the cloth, or a strip with no horizontal direction, is refused', () => {
    const wide = new Simulation({ cloth: { width: 5, height: 5, resolution: 4 }, colliders: [], test: { type: 'cusick' } }, { kernel: 'ts' });
    const t = wide.report().test as CusickResult;
    expect(t.projectedArea / 25).toBeCloseTo(1, 3);
    expect(t.drapeCoefficient).toBeCloseTo(1, 3);
    wide.dispose();
    const r = 1.01 * Math.sqrt(1.5 * 1.5 / Math.PI);
    expect(() => new Simulation({ cloth: { width: 1.5, height: 1.5, resolution: 4 }, colliders: [], test: { type: 'cusick', pedestalRadius: r } }, { kernel: 'ts' }))
      .toThrow(/test\.pedestalRadius: the pedestal's top \(2\.30 m²\) must be smaller than the cloth \(2\.25 m²\)/);
    expect(() => validateScene({ test: { type: 'cantilever', direction: [0, 1, 0] } })).toThrow(/test\.direction: must have a horizontal part/);
    expect(() => validateScene({ test: { type: 'cantilever', direction: [0, 0, 0] } })).toThrow(/test\.direction: must have a horizontal part/);
  });

  it('folds are the peaks of the silhouette\'s radius round the rim', () => {
    const profile = (k: number, amplitude: number, noise = 0) => Float64Array.from({ length: 360 }, (_, d) =>
      0.12 + amplitude * Math.cos((k * d * Math.PI) / 180) + noise * Math.sin(d * 1.7) * Math.cos(d * 2.9));
    for (const k of [4, 6, 9, 12]) expect(countFolds(profile(k, 0.01, 3e-4))).toBe(k);
    expect(countFolds(profile(8, 5e-4))).toBe(0); // ripples under 2 mm are not folds
  });
});

describe('the scenes run to their duration and report their test', () => {
  it.each(['cantilever', 'cusick'])('%s', (name) => {
    const scene = builtinScene(name);
    expect(scene.duration).toBeGreaterThan(3);
    const sim = new Simulation(validateScene({ ...scene, cloth: { ...scene.cloth, resolution: 12 } }), { kernel: 'ts' });
    sim.advance(20);
    const t = sim.report().test!;
    expect(t.type).toBe(name);
    for (const v of Object.values(t)) if (typeof v === 'number') expect(Number.isFinite(v)).toBe(true);
  });
});

describe('the standard fabric tests as the scenes set them up', () => {
  // the scenes' own bending, the hinges solved together: cotton's strip as `drape run cantilever` runs it (32 faces,
  // 6 s) reads 0.99 of its bending length; with the default skip-one springs it hangs straight down, 0.21, and with
  // the hinges swept one at a time 0.65 (docs/physics.md "The standard fabric tests"). The issue asks for 10 %.
  it('the cantilever scene, run as it is, reads cotton\'s bending length within 3 %', () => {
    const scene = builtinScene('cantilever');
    expect(scene.solver).toMatchObject({ bending: 'hinges', bendingSolve: 'global' });
    const sim = new Simulation(scene);
    sim.advance(Math.round(scene.duration * 60));
    const t = sim.report().test as CantileverResult;
    sim.dispose();
    expect(Math.abs(t.bendingLength! / Math.cbrt(7.85e-6 / (0.12 * 9.81)) - 1)).toBeLessThan(0.03);
  });
});

describe('the Cusick scene, as it is set up', () => {
  // the woven disc clamped on the pedestal, the hinges solved together, the springs' coarse correction (the default
  // since 2026-12-06), the scene's specimen (seed 1 of its 1 mm waviness): cotton at 2 s 0.481 at 48 cells (the
  // scene's) and 0.513 at 96, 6 folds each; silk at 4 s 0.347; leather 0.983 (docs/physics.md, "The standard fabric
  // tests"). Laid flat, cotton read 0.476 and 0.489 (at rest by 2 s, kinetic energy 3·10⁻¹⁰ J); silk, lighter, was
  // still sinking then (0.451 at 2 s, 0.429 at 3 s, 0.377 at 4 s, 0.353 at 6 s). The sweep alone read 0.466, 0.441;
  // silk 0.435, 0.386 at 2 and 3 s; leather 0.967. Unclamped on a disc of rings (before 2026-12-06) cotton read 0.51
  // at 24 cells and 0.39 at 48.
  const drape = (fabric: string, resolution: number, frames = 120) => {
    const scene = validateScene({ ...builtinScene('cusick'), material: { fabric }, cloth: { ...builtinScene('cusick').cloth, resolution } });
    const sim = new Simulation(scene);
    sim.advance(frames);
    const t = sim.report().test as CusickResult;
    sim.dispose();
    return t.drapeCoefficient;
  };
  // Source 16's polyester tropical has cotton's B and ρ_A within 4 % and measured 0.507 (docs/materials.md §3.6): the
  // issue's ±0.10 of a real fabric of similar B and ρ_A, here at 2 s (the scene's 6 s reads 0.477 and 0.49 as the
  // mean of three specimens).
  it('reads the same drape coefficient at 48 and 96 cells across (within 0.05), and orders silk < cotton < leather; cotton within 0.10 of a measured fabric of its B and ρ_A', () => {
    const cotton = drape('cotton', 48), fine = drape('cotton', 96);
    expect(Math.abs(fine - cotton)).toBeLessThan(0.05);
    for (const dc of [cotton, fine]) expect(Math.abs(dc - 0.507)).toBeLessThan(0.1);
    expect(drape('silk', 48, 240)).toBeLessThan(cotton - 0.05);
    expect(drape('leather', 48)).toBeGreaterThan(cotton + 0.3);
  });
  // `wool` is a real fabric whose areal density, stiffnesses and drape coefficient were measured together (source
  // 17's M3, a wool-blend twill whose warp and weft bend alike: docs/materials.md §3.7; scripts/cusick-measured.mjs
  // runs it among ten such fabrics). Measured 0.349; the scene reads 0.265 (seed 1, 48 cells, at its 6 s), solved
  // closely 0.358. At 96 cells the three specimens' mean is 0.235, 0.11 below: the issue's ±0.10 holds at 48 only.
  it('reads wool, a fabric measured whole, within 0.10 of its measured drape coefficient at the scene\'s settings', () => {
    expect(Math.abs(drape('wool', 48, Math.round(builtinScene('cusick').duration * 60)) - 0.349)).toBeLessThan(0.1);
  });
});

describe('a cantilever held everywhere', () => {
  it('measures no overhang and no drop (not NaN), whose bending length is unknown', () => {
    const scene = builtinScene('cantilever');
    scene.cloth.resolution = 1;
    scene.pins = [{ min: [-9, -9, -9], max: [9, 9, 9] }];
    const sim = new Simulation(validateScene(scene), { kernel: 'ts' });
    sim.advance(2);
    expect(sim.report().test).toEqual({ type: 'cantilever', overhang: 0, chordAngle: 0, bendingLength: null });
  });
});

describe('pins by region', () => {
  it('hold the particles that start in the box, at any resolution and on any shape; an empty box is an error naming it', () => {
    const clamp = { min: [-1, 0, -1] as [number, number, number], max: [1, 2, 0] as [number, number, number] };
    for (const resolution of [4, 8, 16]) {
      const sim = new Simulation(validateScene({ cloth: { resolution, position: [0, 1, 0] }, colliders: [], pins: [clamp] }), { kernel: 'ts' });
      const pinned = resolvePins(sim.model, sim.scene.pins);
      // every particle with z ≤ 0: rows 0 … resolution/2 of the grid
      expect(pinned.length).toBe((resolution / 2 + 1) * (resolution + 1));
      for (const i of pinned) expect(sim.model.restPositions[3 * i + 2]).toBeLessThanOrEqual(0);
    }
    const disc = new Simulation(validateScene({ cloth: { shape: 'disc', position: [0, 1, 0] }, colliders: [], pins: [clamp] }), { kernel: 'ts' });
    expect(disc.state.pinned.reduce((a, b) => a + b, 0)).toBeGreaterThan(10);
    expect(() => new Simulation(validateScene({ colliders: [], pins: ['center', { min: [5, 5, 5], max: [6, 6, 6] }] }), { kernel: 'ts' }))
      .toThrow('pins[1]: no particle starts in the region from [5, 5, 5] to [6, 6, 6] m');
    expect(() => validateScene({ pins: [{ min: [0, 0, 0] }] })).toThrow(/pins\[0\]/);
    // a library caller's pins, which no schema checked: a particle that is not one, a region that is not one
    for (const p of [-1, 2.5, NaN]) expect(() => resolvePins(disc.model, [p])).toThrow(/^pins\[0\]: particle .* does not exist/);
    expect(() => resolvePins(disc.model, [{ min: [0, 0, 0] } as never])).toThrow(/^pins\[0\]: a region is \{ min: \[x, y, z\], max: \[x, y, z\] \}/);
  });

  it('a round region holds the particles that start within its radius of its centre (the Cusick clamp); an empty one is an error naming it', () => {
    const ball = { center: [0.1, 1, 0] as [number, number, number], radius: 0.2 };
    for (const lattice of ['rings', 'weave'] as const) {
      const sim = new Simulation(validateScene({ cloth: { shape: 'disc', lattice, resolution: 24, position: [0, 1, 0] }, colliders: [], pins: [ball] }), { kernel: 'ts' });
      const x = sim.model.restPositions, pinned = new Set(resolvePins(sim.model, sim.scene.pins));
      expect(pinned.size).toBeGreaterThan(20);
      for (let i = 0; i < sim.model.particleCount; i++) {
        expect(pinned.has(i)).toBe(Math.hypot(x[3 * i] - 0.1, x[3 * i + 1] - 1, x[3 * i + 2]) <= 0.2);
      }
    }
    expect(() => new Simulation(validateScene({ colliders: [], pins: [{ center: [5, 5, 5], radius: 0.5 }] }), { kernel: 'ts' }))
      .toThrow('pins[0]: no particle starts within 0.5 m of [5, 5, 5] m');
    expect(() => validateScene({ pins: [{ center: [0, 0, 0], radius: -1 }] })).toThrow(/pins\[0\]/);
    const disc = modelFor(validateScene({ cloth: { shape: 'disc' } }));
    expect(() => resolvePins(disc, [{ center: [0, 0, 0], radius: NaN } as never])).toThrow(/^pins\[0\]: a round region is \{ center: \[x, y, z\], radius: r \}/);
  });
});
