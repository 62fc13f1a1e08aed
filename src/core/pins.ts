import type { ClothModel } from './model.js';
import type { PinPreset } from './scene.js';
import type { ClothState } from './state.js';

/**
 * Particle indices of a pin preset on a grid cloth. Row 0 is the 'top' (the far edge, -z, of a horizontal cloth;
 * the upper edge of a hanging one); column 0 is 'left' (-x).
 */
export function presetParticles(model: ClothModel, preset: PinPreset): number[] {
  const grid = model.grid;
  if (!grid) throw new Error(`pin preset '${preset}' needs a grid cloth`);
  const { nx, ny } = grid;
  const id = (i: number, j: number) => j * nx + i;
  const range = (count: number, f: (k: number) => number) => Array.from({ length: count }, (_, k) => f(k));
  switch (preset) {
    case 'top-left': return [id(0, 0)];
    case 'top-right': return [id(nx - 1, 0)];
    case 'bottom-left': return [id(0, ny - 1)];
    case 'bottom-right': return [id(nx - 1, ny - 1)];
    case 'center': {
      // the middle particle, or the 4 around the middle when the count is even
      const is = nx % 2 ? [(nx - 1) / 2] : [nx / 2 - 1, nx / 2];
      const js = ny % 2 ? [(ny - 1) / 2] : [ny / 2 - 1, ny / 2];
      return js.flatMap((j) => is.map((i) => id(i, j)));
    }
    case 'top-edge': return range(nx, (i) => id(i, 0));
    case 'bottom-edge': return range(nx, (i) => id(i, ny - 1));
    case 'left-edge': return range(ny, (j) => id(0, j));
    case 'right-edge': return range(ny, (j) => id(nx - 1, j));
  }
}

/** Resolves a scene's pin list (presets and indices) to particle indices, without duplicates. */
export function resolvePins(model: ClothModel, pins: readonly (PinPreset | number)[]): number[] {
  const set = new Set<number>();
  for (const p of pins) {
    if (typeof p === 'number') set.add(p);
    else for (const i of presetParticles(model, p)) set.add(i);
  }
  return [...set].sort((a, b) => a - b);
}

/** Sets exactly the given particles pinned, all others free. */
export function applyPins(state: ClothState, particles: readonly number[]): void {
  state.pinned.fill(0);
  for (const i of particles) state.pinned[i] = 1;
  state.tethersStale = true;
}
