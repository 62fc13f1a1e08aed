/**
 * The seeded waviness of a cloth's start pose (perturbation.ts, `cloth.perturbation`): where it moves the particles,
 * by how much, what it leaves alone, and that a seed is a specimen (the same every time, another for another seed).
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type SceneInput } from './scene.js';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';

/** The Cusick scene (a woven disc clamped on its pedestal) at `resolution` cells across, with `perturbation`. */
function cusick(resolution: number, perturbation: { amplitude?: number; seed?: number }): Simulation {
  const scene = builtinScene('cusick');
  return new Simulation(validateScene({ ...scene, cloth: { ...scene.cloth, resolution, perturbation } }), { kernel: 'ts' });
}

/** Largest relative change of a spring's length between the model's rest shape and the state [-]. */
function largestStrain(sim: Simulation): number {
  const { springs, restLengths } = sim.model, x = sim.state.positions;
  let most = 0;
  for (let s = 0; s < restLengths.length; s++) {
    const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
    const l = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
    most = Math.max(most, Math.abs(l / restLengths[s] - 1));
  }
  return most;
}

describe('cloth.perturbation', () => {
  it('is off by default: the cloth starts at its model\'s start pose exactly', () => {
    const sim = new Simulation(validateScene({ cloth: { shape: 'disc', resolution: 12 }, colliders: [] }), { kernel: 'ts' });
    expect(sim.scene.cloth.perturbation).toEqual({ amplitude: 0, seed: 1 });
    expect([...sim.state.positions]).toEqual([...sim.model.restPositions]);
  });

  it('moves the free particles along their normals by the amplitude (RMS), at rest; pins stay, and the springs start nearly unstretched', () => {
    for (const resolution of [48, 96]) {
      const sim = cusick(resolution, { amplitude: 0.001, seed: 1 });
      const x = sim.state.positions, x0 = sim.model.restPositions;
      let sum = 0, free = 0, most = 0;
      for (let i = 0; i < sim.model.particleCount; i++) {
        // the disc lies flat in xz: its normals are ±y
        expect(x[3 * i]).toBe(x0[3 * i]);
        expect(x[3 * i + 2]).toBe(x0[3 * i + 2]);
        const dy = x[3 * i + 1] - x0[3 * i + 1];
        if (sim.state.pinned[i]) { expect(dy).toBe(0); continue; }
        sum += dy * dy; free++;
        most = Math.max(most, Math.abs(dy));
      }
      expect(Math.sqrt(sum / free) / 0.001).toBeCloseTo(1, 3);
      expect(most).toBeGreaterThan(0.0015);
      expect([...sim.state.previousPositions]).toEqual([...x]);
      // grown from the clamp over half a wave: no spring starts more than 1 % long or short (seen: 0.48 % and 0.56 %;
      // a step of up to 2 mm at the clamp's edge would strain its 3 mm springs by up to 20 %)
      expect(largestStrain(sim)).toBeLessThan(0.01);
      sim.dispose();
    }
  });

  it('a seed is one specimen: the same seed gives the same start every time (a reset too), another seed another', () => {
    const a = cusick(24, { amplitude: 0.001, seed: 1 }), b = cusick(24, { amplitude: 0.001, seed: 1 }), c = cusick(24, { amplitude: 0.001, seed: 2 });
    const start = [...a.state.positions];
    expect([...b.state.positions]).toEqual(start);
    expect([...c.state.positions]).not.toEqual(start);
    a.advance(3);
    a.reset();
    expect([...a.state.positions]).toEqual(start);
    expect([...a.state.previousPositions]).toEqual(start);
    // a new seed rebuilds the cloth with it
    expect(a.set('cloth.perturbation.seed', 2)).toBe(true);
    expect([...a.state.positions]).toEqual([...c.state.positions]);
    for (const s of [a, b, c]) s.dispose();
  });

  it('on the WebAssembly kernel the cloth starts as on the reference', () => {
    const scene = builtinScene('cusick');
    const input = { ...scene, cloth: { ...scene.cloth, resolution: 24 } };
    const ts = new Simulation(input, { kernel: 'ts' }), wasm = new Simulation(input, { kernel: 'wasm' });
    expect(wasm.backend.kind).toBe('wasm');
    expect([...wasm.state.positions]).toEqual([...ts.state.positions]);
    expect([...ts.state.positions]).not.toEqual([...ts.model.restPositions]);
    ts.dispose(); wasm.dispose();
  });

  it('belongs to each cloth of a scene of several: one with it moves, one without does not', () => {
    const input: SceneInput = {
      colliders: [],
      cloths: [
        { cloth: { resolution: 8, position: [0, 1, 0] } },
        { cloth: { resolution: 8, position: [0, 2, 0], perturbation: { amplitude: 0.002, seed: 5 } } },
      ],
    };
    const sim = new Simulation(input, { kernel: 'ts' });
    const split = 3 * sim.model.clothStarts[1], x = sim.state.positions, x0 = sim.model.restPositions;
    expect([...x.subarray(0, split)]).toEqual([...x0.subarray(0, split)]);
    let sum = 0;
    for (let j = split + 1; j < x.length; j += 3) sum += (x[j] - x0[j]) ** 2;
    expect(Math.sqrt(sum / ((x.length - split) / 3)) / 0.002).toBeCloseTo(1, 3);
    sim.dispose();
  });

  it('a bad amplitude or seed is an error naming the field', () => {
    expect(() => validateScene({ cloth: { perturbation: { amplitude: -0.001 } } })).toThrow(/cloth\.perturbation\.amplitude/);
    expect(() => validateScene({ cloth: { perturbation: { seed: 1.5 } } })).toThrow(/cloth\.perturbation\.seed/);
    expect(() => validateScene({ cloth: { perturbation: { size: 1 } } })).toThrow(/cloth\.perturbation/);
  });
});
