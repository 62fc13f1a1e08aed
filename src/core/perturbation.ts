/**
 * A cloth's seeded perturbation (`cloth.perturbation`): a smooth random waviness added to the start pose, not to the
 * rest shape, so that a specimen laid "flat" is as slightly uneven as a real one. The Cusick drape (BS 5058 /
 * ISO 9073-9) tests three specimens and reports their mean: the folds a disc forms depend on such small
 * differences, and on a perfectly flat disc they follow the mesh's own symmetry instead (docs/physics.md, "The
 * standard fabric tests"). Seeds 1, 2, 3 are three specimens of the same fabric.
 *
 * The field is a sum of WAVES plane waves cos(k·(x − centre) + φ) with random directions (uniform on the sphere),
 * phases and wavelengths between 1/4 and 1 of the cloth's size, so it is the same function of position at every
 * mesh density; each free particle moves along its vertex normal by it, scaled so that its root mean square over the
 * cloth's free particles is `amplitude`. Pinned particles do not move, and the waviness grows smoothly from 0 at a
 * pin to its full size half the shortest wavelength away along the springs (tethers.ts pinDistances), so a
 * clamp holds its specimen flat and no spring starts more than a fraction of a percent long at the clamp's edge.
 */
import { vertexNormals } from './mesh/normals.js';
import type { ClothModel } from './model.js';
import { mulberry32 } from './random.js';
import { clothEntries, type Scene } from './scene.js';
import type { ClothState } from './state.js';
import { pinDistances } from './tethers.js';

/** How many plane waves the waviness sums [-]. */
const WAVES = 8;

/**
 * Adds each cloth's `cloth.perturbation` (amplitude > 0) to the state's positions and previous positions (so it starts
 * at rest), leaving `pins` (particle indices of the merged model) where they are. Call it on a state at the model's
 * start pose (createState / resetState).
 */
export function perturbStart(model: ClothModel, scene: Scene, state: ClothState, pins: readonly number[]): void {
  const entries = clothEntries(scene);
  if (!entries.some((e) => e.cloth.perturbation.amplitude > 0)) return;
  const pinned = new Uint8Array(model.particleCount);
  for (const i of pins) pinned[i] = 1;
  const normals = vertexNormals(model.restPositions, model.triangles);
  const reach = pinDistances(model, pinned);
  entries.forEach((e, c) => {
    const { amplitude, seed } = e.cloth.perturbation;
    if (amplitude > 0) perturbCloth(model, state, normals, reach, model.clothStarts[c], model.clothStarts[c + 1], amplitude, seed);
  });
}

function perturbCloth(
  model: ClothModel, state: ClothState, normals: Float32Array, reach: Float64Array,
  from: number, to: number, amplitude: number, seed: number,
): void {
  const x = model.restPositions;
  // the cloth's centre and size, from its start pose
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = from; i < to; i++) {
    for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], x[3 * i + k]); hi[k] = Math.max(hi[k], x[3 * i + k]); }
  }
  const centre = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3);
  const random = mulberry32(seed);
  const waves = new Float64Array(4 * WAVES);
  let shortest = Infinity;
  for (let w = 0; w < WAVES; w++) {
    const cosTheta = 2 * random() - 1, sinTheta = Math.sqrt(1 - cosTheta * cosTheta), phi = 2 * Math.PI * random();
    const wavelength = size / (1 + 3 * random());
    shortest = Math.min(shortest, wavelength);
    const k = (2 * Math.PI) / wavelength;
    waves[4 * w] = k * sinTheta * Math.cos(phi);
    waves[4 * w + 1] = k * cosTheta;
    waves[4 * w + 2] = k * sinTheta * Math.sin(phi);
    waves[4 * w + 3] = 2 * Math.PI * random();
  }
  const ramp = shortest / 2;
  const offset = new Float64Array(to - from);
  let sumSquares = 0, free = 0;
  for (let i = from; i < to; i++) {
    if (reach[i] === 0) continue;
    const px = x[3 * i] - centre[0], py = x[3 * i + 1] - centre[1], pz = x[3 * i + 2] - centre[2];
    let f = 0;
    for (let w = 0; w < WAVES; w++) f += Math.cos(waves[4 * w] * px + waves[4 * w + 1] * py + waves[4 * w + 2] * pz + waves[4 * w + 3]);
    const t = Math.min(1, reach[i] / ramp);
    f *= t * t * (3 - 2 * t);
    offset[i - from] = f;
    sumSquares += f * f;
    free++;
  }
  if (!(sumSquares > 0)) return;
  const scale = amplitude / Math.sqrt(sumSquares / free);
  const p = state.positions, q = state.previousPositions;
  for (let i = from; i < to; i++) {
    const d = scale * offset[i - from];
    for (let k = 0; k < 3; k++) {
      p[3 * i + k] += d * normals[3 * i + k];
      q[3 * i + k] = p[3 * i + k];
    }
  }
}
