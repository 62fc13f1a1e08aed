import { clothPath } from './cloth-paths.js';
import type { ClothModel } from './model.js';
import { SceneError, clothEntries, type PinEntry, type PinPreset, type Scene } from './scene.js';
import type { ClothState } from './state.js';

/**
 * Particle indices of a pin preset. On a rectangle (a grid), row 0 is the 'top' (the far edge, -z, of a horizontal
 * cloth; the upper edge of a hanging one) and column 0 is 'left' (-x). Any other cloth has only 'center': the
 * particle nearest the middle of its rest shape's bounding box; the corner and edge presets throw a SceneError
 * saying they need a rectangle.
 */
export function presetParticles(model: ClothModel, preset: PinPreset): number[] {
  const grid = model.grid;
  if (!grid) {
    if (preset === 'center') return [nearestToMiddle(model)];
    throw new SceneError(`pin preset '${preset}' names a corner or an edge of a rectangle, and this cloth is not one`);
  }
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

/** The particle nearest the middle of the rest shape's bounding box (the lowest index on a tie). */
function nearestToMiddle(model: ClothModel): number {
  const p = model.restPositions;
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i += 3) for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], p[i + k]); hi[k] = Math.max(hi[k], p[i + k]); }
  let best = 0, bestD = Infinity;
  for (let i = 0; i < model.particleCount; i++) {
    let d = 0;
    for (let k = 0; k < 3; k++) d += (p[3 * i + k] - (lo[k] + hi[k]) / 2) ** 2;
    if (d < bestD) { bestD = d; best = i; }
  }
  return best;
}

/**
 * Resolves a scene's pin list (presets, indices and regions) to particle indices, without duplicates. Throws a
 * SceneError naming the entry (pins[k]) for an index the cloth does not have, a preset it cannot take or a region
 * no particle starts in.
 */
export function resolvePins(model: ClothModel, pins: readonly PinEntry[], field = 'pins'): number[] {
  const set = new Set<number>();
  const n = model.particleCount;
  pins.forEach((p, k) => {
    if (typeof p === 'number') {
      if (!(Number.isInteger(p) && p >= 0 && p < n)) throw new SceneError(`${field}[${k}]: particle ${p} does not exist (cloth has ${n} particles, 0…${n - 1})`);
      set.add(p);
      return;
    }
    if (typeof p === 'object') {
      // (a library caller's region is checked here: a scene's by the schema)
      const corner = (v: unknown) => Array.isArray(v) && v.length === 3 && v.every(Number.isFinite);
      const x = model.restPositions;
      let found = 0;
      if (p !== null && 'center' in p) {
        if (!corner(p.center) || !(Number.isFinite(p.radius) && p.radius >= 0)) throw new SceneError(`${field}[${k}]: a round region is { center: [x, y, z], radius: r } of finite numbers, r ≥ 0 [m]`);
        const [cx, cy, cz] = p.center;
        for (let i = 0; i < n; i++) {
          if (Math.hypot(x[3 * i] - cx, x[3 * i + 1] - cy, x[3 * i + 2] - cz) <= p.radius) { set.add(i); found++; }
        }
        if (found === 0) throw new SceneError(`${field}[${k}]: no particle starts within ${p.radius} m of [${p.center.join(', ')}] m`);
        return;
      }
      if (p === null || !corner(p.min) || !corner(p.max)) throw new SceneError(`${field}[${k}]: a region is { min: [x, y, z], max: [x, y, z] } or { center: [x, y, z], radius: r } of finite numbers [m]`);
      for (let i = 0; i < n; i++) {
        let inside = true;
        for (let d = 0; d < 3; d++) if (!(x[3 * i + d] >= p.min[d] && x[3 * i + d] <= p.max[d])) inside = false;
        if (inside) { set.add(i); found++; }
      }
      if (found === 0) throw new SceneError(`${field}[${k}]: no particle starts in the region from [${p.min.join(', ')}] to [${p.max.join(', ')}] m`);
      return;
    }
    try {
      for (const i of presetParticles(model, p)) set.add(i);
    } catch (e) {
      // what to do instead: a cloth's own pins can be clicked with the app's pin tool, a collider's cannot
      const instead = field.startsWith('colliders[') ? 'give the collider\'s pins as particle indices or regions'
        : 'pin particles by index (in the app: click them with the pin tool)';
      if (e instanceof SceneError) throw new SceneError(`${field}[${k}]: ${e.message}; ${instead}`);
      throw e;
    }
  });
  return [...set].sort((a, b) => a - b);
}

/**
 * Every pinned particle of a scene: each cloth's `pins` (on a model of several cloths, resolved on that cloth's own
 * model and counted from its first particle) and those its colliders carry (`colliders[k].pins`), in order.
 */
export function scenePins(model: ClothModel, scene: Scene): number[] {
  const set = new Set<number>();
  clothEntries(scene).forEach((e, c) => {
    const part = model.clothParts?.[c];
    // named as the scene names them: 'pins' in a one-cloth scene, 'cloths[0].pins' in a list of one
    const path = clothPath(scene, c, 'pins');
    if (!part) { for (const i of resolvePins(model, e.pins, path)) set.add(i); return; }
    for (const i of resolvePins(part, e.pins, path)) set.add(i + model.clothStarts[c]);
  });
  scene.colliders.forEach((c, k) => { for (const i of resolvePins(model, c.pins ?? [], `colliders[${k}].pins`)) set.add(i); });
  return [...set].sort((a, b) => a - b);
}

/** Sets exactly the given particles pinned, all others free. */
export function applyPins(state: ClothState, particles: readonly number[]): void {
  state.pinned.fill(0);
  for (const i of particles) state.pinned[i] = 1;
  state.tethersStale = true;
}
