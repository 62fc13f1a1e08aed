/** selfContacts (contacts.ts): what the HUD counts and the contact view marks. */
import { describe, expect, it } from 'vitest';
import { closestPointOnTriangle } from './colliders/sphere.js';
import { selfContacts } from './contacts.js';
import { builtinScene } from './scenes.js';
import { selfContactDistance } from './self-contact.js';
import { Simulation } from './simulation.js';

describe('selfContacts', () => {
  it('sheets apart have none; the layers scene landed has them where a cloth lies on another, and flags mark exactly those', () => {
    const scene = builtinScene('layers');
    for (const entry of [scene.cloth, ...(scene.cloths ?? []).map((c) => c.cloth)]) entry.resolution = 8;
    const sim = new Simulation(scene, { kernel: 'ts' });
    const d = 1.5 * selfContactDistance(sim.model, sim.params);
    const n = sim.model.particleCount, flags = new Uint8Array(n);
    expect(selfContacts(sim.model.triangles, sim.state.positions, n, d, flags)).toBe(0);
    sim.advance(120);
    const count = selfContacts(sim.model.triangles, sim.state.positions, n, d, flags);
    expect(flags.reduce((a, b) => a + b, 0)).toBe(count);
    // the upper two cloths (two thirds of the particles) lie on the ones below, partly: measured 49 of 243
    expect(count).toBeGreaterThan(n / 10);
    expect(count).toBeLessThan((2 * n) / 3);
    // a particle is flagged exactly when it is within d of a triangle not its own (every triangle tried)
    const x = sim.state.positions, tri = sim.model.triangles, bary = new Float64Array(3);
    const nearest = (p: number) => {
      let best = Infinity;
      for (let t = 0; t < tri.length; t += 3) {
        if (tri[t] === p || tri[t + 1] === p || tri[t + 2] === p) continue;
        const [a, b, c] = [3 * tri[t], 3 * tri[t + 1], 3 * tri[t + 2]];
        closestPointOnTriangle(x[3 * p], x[3 * p + 1], x[3 * p + 2], x[a], x[a + 1], x[a + 2], x[b], x[b + 1], x[b + 2], x[c], x[c + 1], x[c + 2], bary);
        best = Math.min(best, Math.hypot(...[0, 1, 2].map((k) => bary[0] * x[a + k] + bary[1] * x[b + k] + bary[2] * x[c + k] - x[3 * p + k])));
      }
      return best;
    };
    for (let p = 0; p < n; p++) expect(flags[p], `particle ${p}`).toBe(nearest(p) < d ? 1 : 0);
    expect(selfContacts(sim.model.triangles, sim.state.positions, n, 0)).toBe(0);
  });
});
