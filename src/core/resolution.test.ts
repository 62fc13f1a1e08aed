import { describe, expect, it } from 'vitest';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';

describe('resolution independence (XPBD)', () => {
  it('cotton hanging from two corners sags the same at 32² and 128² faces, within 5% of its size', () => {
    const sag = (resolution: number) => {
      const sc = builtinScene('custom')!;
      sc.cloth = { ...sc.cloth, orientation: 'hanging', position: [0, 1.5, 0], resolution };
      sc.colliders = [];
      sc.pins = ['top-left', 'top-right'];
      // a sheet hanging from two corners never meets itself: self-contact's search would only cost (this test took 21 s with it, 1.9 s without)
      sc.solver.selfContact = false;
      const sim = new Simulation(sc);
      sim.advance(90);
      const mid = resolution / 2; // middle of the top edge (row 0)
      return 2.0 - sim.state.positions[3 * mid + 1];
    };
    const coarse = sag(32), fine = sag(128);
    expect(coarse).toBeGreaterThan(0.005); // it does sag
    expect(Math.abs(fine - coarse)).toBeLessThan(0.05 * 1.0);
  });
});
