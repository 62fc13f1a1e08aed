/**
 * How big a cloth each simulation backend takes (README, "The app"): the CPU worker up to 256 faces per side, the
 * GPU up to 1024. The scene schema allows 1024 everywhere (the CLI and the GPU run it), so a link, a file or a
 * backend switch can ask the CPU for a million-particle cloth — which would freeze the tab building it. The app
 * clamps such a scene to the backend's cap and says so. A rectangle is capped by its resolution; a disc or a tube
 * by its particles (the same count as the largest rectangle: 257² on the CPU, 1025² on the GPU), its resolution
 * lowered until it fits; a mesh file has its own particles, so a mesh over the cap is refused, not clamped. The
 * cloths of a scene of several share the cap: when together over it, each generated cloth over its share is lowered.
 * No DOM here: unit-tested in limits.test.ts.
 */
import { MAX_INPUT_BYTES, SceneError, wovenDiscParticles, clothEntries, clothName, editCloth, plainText, type ClothSpec, type PinEntry, type Scene } from '../core/index.js';

export type BackendKind = 'cpu' | 'gpu';

/** largest resolution per simulation backend [faces per side] */
export const MAX_RESOLUTION: Readonly<Record<BackendKind, number>> = { cpu: 256, gpu: 1024 };

/** particles of all the cloths on screen together, at most: one cloth at the backend's largest resolution */
export const MAX_PARTICLES: Readonly<Record<BackendKind, number>> = {
  cpu: (MAX_RESOLUTION.cpu + 1) ** 2,
  gpu: (MAX_RESOLUTION.gpu + 1) ** 2,
};

const NAMES: Record<BackendKind, string> = { cpu: 'CPU', gpu: 'GPU' };

export interface Capped {
  scene: Scene;
  /** one line saying what was clamped ('' when nothing was) */
  note: string;
}

/**
 * The scene with its resolution (and each resolution of a sweep) at most the backend's cap. The same scene object
 * when nothing is over it.
 */
export function capResolution(scene: Scene, kind: BackendKind): Capped {
  const max = MAX_RESOLUTION[kind];
  const over: string[] = [];
  let next = scene;
  if (scene.cloth.resolution > max) {
    over.push(`resolution ${scene.cloth.resolution}`);
    // (a particle index names a particle of the old resolution: dropped, as a new resolution from the panel drops it)
    next = { ...next, cloth: { ...next.cloth, resolution: max }, pins: resolutionPins(next.pins) };
  }
  const sweep = scene.resolutionSweep;
  if (sweep?.some((r) => r > max)) {
    over.push(`sweep resolutions ${sweep.filter((r) => r > max).join(', ')}`);
    const capped: number[] = [];
    for (const r of sweep) if (!capped.includes(Math.min(r, max))) capped.push(Math.min(r, max));
    next = { ...next, resolutionSweep: capped };
  }
  if (!over.length) return { scene, note: '' };
  const more = kind === 'cpu' ? `; the GPU backend goes to ${MAX_RESOLUTION.gpu}` : '';
  const dropped = droppedNote(next.pins, scene.pins);
  return {
    scene: next,
    note: `${over.join(' and ')} faces per side: more than the ${NAMES[kind]} backend takes, clamped to ${max}${dropped}${more}`,
  };
}

/**
 * The pins that mean the same on a cloth of another resolution or mesh: the presets and the regions (a box in space),
 * not the particle indices, which name particles of one mesh.
 */
export function resolutionPins(pins: readonly PinEntry[]): PinEntry[] {
  return pins.filter((p) => typeof p !== 'number');
}

/** The clamp note's words for the pins resolutionPins left out ('' when it kept them all). */
function droppedNote(kept: readonly PinEntry[], pins: readonly PinEntry[]): string {
  return kept.length < pins.length ? '; the pins on particle numbers are dropped' : '';
}

/** particles of a cloth of `resolution` faces per side */
export const particlesOf = (resolution: number): number => (resolution + 1) ** 2;

/**
 * Particles of a generated cloth (rectangle, disc, tube) of the scene's size at `resolution`, without building it:
 * the generators' own counts (core/mesh/generators.ts; limits.test.ts holds them to the models they build).
 */
export function shapeParticles(cloth: Scene['cloth'], resolution = cloth.resolution): number {
  switch (cloth.shape) {
    case 'disc': {
      if (cloth.lattice === 'weave') return wovenDiscParticles(resolution);
      // a centre vertex and K rings of 6k vertices
      const K = Math.max(1, Math.ceil(resolution / 2));
      return 1 + 3 * K * (K + 1);
    }
    case 'tube': {
      // rings of M vertices, L + 1 of them, cells about square with `resolution` along the longer direction
      const circumference = Math.PI * cloth.width;
      const cell = Math.max(circumference, cloth.height) / resolution;
      const M = Math.max(3, Math.round(circumference / cell));
      const L = Math.max(1, Math.round(cloth.height / cell));
      return M * (L + 1);
    }
    default:
      // the seed's grid
      return particlesOf(resolution);
  }
}

const count = (n: number): string => n.toLocaleString('en');

/**
 * The scene with its cloth within what the backend takes: a rectangle by resolution (capResolution); a disc or a
 * tube by particles, its resolution lowered to the largest that fits; a mesh file (its particles: `meshParticles`
 * of its name) refused with a SceneError when over, since a mesh cannot be made coarser. The same scene object when
 * nothing is over the cap.
 */
export function capCloth(scene: Scene, kind: BackendKind, meshParticles: (path: string) => number): Capped {
  if (scene.cloths) return capCloths(scene, kind, meshParticles);
  const c = scene.cloth, max = MAX_PARTICLES[kind];
  const more = kind === 'cpu' ? `; the GPU backend takes ${count(MAX_PARTICLES.gpu)}` : '';
  if (c.shape === 'rectangle') return capResolution(scene, kind);
  if (c.shape === 'mesh') {
    const n = meshParticles(c.mesh ?? '');
    if (n <= max) return { scene, note: '' };
    throw new SceneError(`${plainText(c.mesh ?? '', 200)}: ${count(n)} particles, more than the ${NAMES[kind]} backend takes (${count(max)})${more}`);
  }
  const n = shapeParticles(c);
  if (n <= max) return { scene, note: '' };
  const r = largestFitting(c, max);
  const pins = resolutionPins(scene.pins);
  const dropped = droppedNote(pins, scene.pins);
  return {
    scene: { ...scene, cloth: { ...c, resolution: r }, pins },
    note: `${c.shape} of resolution ${c.resolution}: ${count(n)} particles, more than the ${NAMES[kind]} backend takes (${count(max)}), ` +
      `clamped to resolution ${r} (${count(shapeParticles(c, r))} particles)${dropped}${more}`,
  };
}

/** The largest resolution of a generated cloth (at most its own) with at most `max` particles (the counts grow with it). */
function largestFitting(c: ClothSpec, max: number): number {
  let lo = 1, hi = c.resolution;
  while (lo < hi) {
    const mid = Math.ceil((lo + hi) / 2);
    if (shapeParticles(c, mid) <= max) lo = mid; else hi = mid - 1;
  }
  return lo;
}

/**
 * capCloth for a scene of several cloths (`cloths`): together they take what one cloth may. When over it, the mesh
 * files keep their particles (a SceneError when they alone are over), and every generated cloth over an equal share
 * of the rest is lowered to the largest resolution that fits in it, its particle pins dropped (their numbers belong
 * to the old resolution).
 */
function capCloths(scene: Scene, kind: BackendKind, meshParticles: (path: string) => number): Capped {
  const entries = clothEntries(scene), max = MAX_PARTICLES[kind];
  const more = kind === 'cpu' ? `; the GPU backend takes ${count(MAX_PARTICLES.gpu)}` : '';
  const counts = entries.map((e) => (e.cloth.shape === 'mesh' ? meshParticles(e.cloth.mesh ?? '') : shapeParticles(e.cloth)));
  const total = counts.reduce((a, b) => a + b, 0);
  if (total <= max) return { scene, note: '' };
  const meshes = entries.reduce((n, e, k) => n + (e.cloth.shape === 'mesh' ? counts[k] : 0), 0);
  const generated = entries.filter((e) => e.cloth.shape !== 'mesh').length;
  if (meshes > max || generated === 0) {
    throw new SceneError(`the cloths' mesh files: ${count(meshes)} particles together, more than the ${NAMES[kind]} backend takes (${count(max)})${more}`);
  }
  const share = Math.floor((max - meshes) / generated);
  let next = scene;
  const lowered: string[] = [];
  entries.forEach((e, k) => {
    if (e.cloth.shape === 'mesh' || counts[k] <= share) return;
    const r = largestFitting(e.cloth, share);
    next = editCloth(next, k, (one) => ({ ...one, cloth: { ...one.cloth, resolution: r }, pins: resolutionPins(one.pins) }));
    lowered.push(`cloths[${k}] (${plainText(clothName(e, k), 40)}) resolution ${e.cloth.resolution} → ${r}`);
  });
  return {
    scene: next,
    note: `${entries.length} cloths of ${count(total)} particles together: more than the ${NAMES[kind]} backend takes (${count(max)}), ` +
      `clamped: ${lowered.join(', ')}${more}`,
  };
}

/**
 * The resolutions of a sweep laid side by side that the backend takes together: the leading ones while the sum of
 * their particles stays within MAX_PARTICLES (at least the first), and a note when some were left out.
 */
export function fitSideBySide(resolutions: readonly number[], kind: BackendKind): { list: number[]; note: string } {
  const list: number[] = [];
  let total = 0;
  for (const r of resolutions) {
    if (list.length && total + particlesOf(r) > MAX_PARTICLES[kind]) break;
    list.push(r);
    total += particlesOf(r);
  }
  if (list.length === resolutions.length) return { list, note: '' };
  return {
    list,
    note: `side by side: ${list.length} of ${resolutions.length} cloths shown — the ${NAMES[kind]} backend simulates at most ` +
      `${MAX_PARTICLES[kind].toLocaleString('en')} particles at once`,
  };
}

/**
 * Why a file of `bytes` is not read as a scene or mesh ('' when it may be): larger than the core's MAX_INPUT_BYTES (the
 * CLI's limit too), which reading would only spend the tab's memory on.
 */
export function importSizeProblem(bytes: number, what = 'scene file'): string {
  if (bytes <= MAX_INPUT_BYTES) return '';
  return `${(bytes / 2 ** 20).toFixed(1)} MiB, more than the ${MAX_INPUT_BYTES / 2 ** 20} MiB a ${what} may be`;
}
