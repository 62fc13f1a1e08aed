/**
 * The Ten Minute Physics 15 method (particle-hash.ts), the self-contact bench's peer: its demo's strip falls into a
 * pile on the floor that stays above the floor, at its thickness apart, with few crossing triangles, while the same
 * strip with its contacts off piles through itself.
 */
import { describe, expect, it } from 'vitest';
import { countIntersections } from '../../core/intersections.js';
import { hangingStrip, ParticleHashCloth, PARTICLE_HASH_DEFAULTS } from './particle-hash.js';

describe('the particle-hash peer (Ten Minute Physics 15)', () => {
  it('the demo strip (10 × 60 here) piles on the floor with its particles apart; without contact it crosses itself', () => {
    const grid = hangingStrip(10, 60, 0.01, 0.01, 0.004);
    expect(countIntersections(grid.triangles, grid.positions)).toBe(0);
    const run = (contact: boolean) => {
      const cloth = new ParticleHashCloth(grid, { ...PARTICLE_HASH_DEFAULTS, contact });
      for (let f = 0; f < 90; f++) cloth.step(1 / 60);
      return cloth.positions;
    };
    const x = run(true);
    expect(x.every(Number.isFinite)).toBe(true);
    let top = -Infinity, bottom = Infinity;
    for (let i = 1; i < x.length; i += 3) { top = Math.max(top, x[i]); bottom = Math.min(bottom, x[i]); }
    // a pile some layers deep, resting on the floor (radius 5 mm)
    expect(bottom).toBeGreaterThanOrEqual(0.005 - 1e-6);
    expect(top).toBeLessThan(0.1);
    expect(top).toBeGreaterThan(0.02);
    // particles that are not mesh neighbours keep (nearly) a thickness apart
    const r = grid.positions, n = x.length / 3;
    let nearest = Infinity;
    for (let i = 0; i < n; i++) for (let j = i + 1; j < n; j++) {
      if (Math.hypot(r[3 * i] - r[3 * j], r[3 * i + 1] - r[3 * j + 1], r[3 * i + 2] - r[3 * j + 2]) < 0.0101) continue;
      nearest = Math.min(nearest, Math.hypot(x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]));
    }
    expect(nearest).toBeGreaterThan(0.005);
    const with_ = countIntersections(grid.triangles, x), without = countIntersections(grid.triangles, run(false));
    expect(with_).toBeLessThan(20);
    expect(without).toBeGreaterThan(10 * Math.max(with_, 10));
  });
});
