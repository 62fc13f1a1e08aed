import { describe, expect, it } from 'vitest';
import { countIntersections } from './intersections.js';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';
import { mulberry32 } from './random.js';

const tris = (...t: number[]) => Uint32Array.from(t);

describe('countIntersections: pairs of triangles that share no vertex and cross', () => {
  // triangle 0 in the plane z = 0; triangle 1 vertical, through it or beside it
  const flat = [0, 0, 0, 1, 0, 0, 0, 1, 0];
  it('a triangle through another is one pair; beside it, above it or parallel to it, none', () => {
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, 0.2, 0.2, -1, 0.2, 0.2, 1, 0.3, 0.6, 0])).toBe(1);
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, 2.2, 0.2, -1, 2.2, 0.2, 1, 2.3, 0.6, 0])).toBe(0);
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, 0.2, 0.2, 0.1, 0.2, 0.2, 1, 0.3, 0.6, 0.5])).toBe(0);
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, 0, 0, 0.01, 1, 0, 0.01, 0, 1, 0.01])).toBe(0);
    // crossing each other without a vertex inside the other: each pierces with an edge
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, 0.5, -0.5, -0.2, 0.5, 1.5, -0.2, 0.1, 0.5, 0.8])).toBe(1);
  });

  it('neighbours that share a vertex never count, whatever their angle', () => {
    // a wing folded through its neighbour along their shared edge, and one sharing a single corner
    expect(countIntersections(tris(0, 1, 2, 1, 0, 3), [...flat, 0.6, 0.3, -0.1])).toBe(0);
    expect(countIntersections(tris(0, 1, 2, 2, 3, 4), [...flat, 0.3, 0.2, -1, 0.3, 0.2, 1])).toBe(0);
  });

  it('a flat cloth and a cloth at rest on the sphere: none', () => {
    const sim = new Simulation(builtinScene('custom')!, { kernel: 'ts' });
    expect(countIntersections(sim.model.triangles, sim.state.positions)).toBe(0);
    expect(sim.report().intersections).toBe(0);
  });

  it('the grid finds every crossing pair that testing all pairs finds (a crumpled cloth)', () => {
    const scene = builtinScene('custom')!;
    scene.cloth.resolution = 10;
    const sim = new Simulation(scene, { kernel: 'ts' });
    const { triangles } = sim.model;
    const n = triangles.length / 3;
    const rnd = mulberry32(5);
    for (const amplitude of [0.02, 0.06, 0.15]) {
      const x = Float64Array.from(sim.state.positions, (v) => v + amplitude * (rnd() - 0.5));
      let brute = 0;
      for (let a = 0; a < n; a++) {
        for (let b = a + 1; b < n; b++) brute += countIntersections(tris(...triangles.subarray(3 * a, 3 * a + 3), ...triangles.subarray(3 * b, 3 * b + 3)), x);
      }
      expect(countIntersections(triangles, x), `amplitude ${amplitude}`).toBe(brute);
      if (amplitude > 0.1) expect(brute).toBeGreaterThan(10);
    }
  });

  it('NaN positions count nothing', () => {
    expect(countIntersections(tris(0, 1, 2, 3, 4, 5), [...flat, NaN, 0.2, -1, 0.2, 0.2, 1, 0.3, 0.6, 0])).toBe(0);
  });
});
