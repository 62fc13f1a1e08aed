/**
 * The HUD's self-contact count: the particles lying on another part of their cloth (core selfContacts, within
 * `contactDistance`), measured on the main thread from the slots' CPU mirrors, at most as often as keeps it under
 * a twentieth of the page's time (a 256² cloth takes tens of ms), and at least every quarter second.
 */
import { selfContactDistance, selfContacts, type Simulation } from '../core/index.js';

/** How near another part of the cloth a particle must be to count as in contact [m]: 1.5 × the self-contact distance. */
export function contactDistance(sim: Simulation): number {
  return 1.5 * selfContactDistance(sim.model, sim.params);
}

export class ContactMeter {
  private last = -Infinity;
  private cost = 0;
  private value = 0;

  /** The count over these simulations now (or as last measured, when measuring again would cost too much). */
  count(sims: readonly Simulation[], now: number): number {
    if (now - this.last < Math.max(250, 20 * this.cost)) return this.value;
    const t0 = performance.now();
    let n = 0;
    for (const sim of sims) n += selfContacts(sim.model.triangles, sim.state.positions, sim.model.particleCount, contactDistance(sim));
    this.cost = performance.now() - t0;
    this.last = now;
    return (this.value = n);
  }
}
