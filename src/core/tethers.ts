/**
 * Long-range attachments (Kim, Chentanez & Müller 2012, "Long Range Attachments — A Method to Simulate
 * Inextensible Clothing in Computer Games"): every free particle is tethered to its nearest pinned particle and
 * may not get farther from it than stretchFactor × their rest distance. A hanging cloth then cannot stretch more
 * than its material allows, however fine the mesh, at the cost of one check per particle per substep.
 */
import { BEND, type ClothModel } from './model.js';
import type { SimParams } from './params.js';
import type { ClothState } from './state.js';

/**
 * Recomputes each particle's anchor: the pinned particle nearest along the structural and shear springs
 * (pinDistances), and the rest distance to it (straight-line; exact for the flat rest shapes the grid builder
 * makes, and never longer than the path along the cloth).
 */
export function updateTethers(model: ClothModel, state: ClothState): void {
  state.tethersStale = false;
  const n = model.particleCount;
  const anchors = state.tetherAnchors, lengths = state.tetherLengths;
  anchors.fill(-1);
  lengths.fill(0);
  if (!state.pinned.includes(1)) return;
  pinDistances(model, state.pinned, anchors);
  const x0 = model.restPositions;
  for (let i = 0; i < n; i++) {
    const a = anchors[i];
    if (a < 0 || a === i) { anchors[i] = -1; continue; }
    lengths[i] = Math.hypot(x0[3 * i] - x0[3 * a], x0[3 * i + 1] - x0[3 * a + 1], x0[3 * i + 2] - x0[3 * a + 2]);
  }
}

/**
 * Each particle's distance from the nearest pinned one (`pinned[i]` nonzero) along the structural and shear springs
 * at their rest lengths [m] (Infinity where no pin is reached), by Dijkstra from every pin at once; `anchors`, if
 * given, gets that nearest pin (-1 where none).
 */
export function pinDistances(model: ClothModel, pinned: ArrayLike<number>, anchors?: Int32Array): Float64Array {
  const n = model.particleCount;
  // adjacency (CSR) over structural + shear springs
  const sp = model.springs, rest = model.restLengths, kinds = model.springKinds;
  const degree = new Uint32Array(n + 1);
  for (let s = 0; s < rest.length; s++) {
    if (kinds[s] === BEND) continue;
    degree[sp[2 * s] + 1]++;
    degree[sp[2 * s + 1] + 1]++;
  }
  for (let i = 0; i < n; i++) degree[i + 1] += degree[i];
  const fill = degree.slice(0, n);
  const nbr = new Uint32Array(degree[n]);
  const len = new Float32Array(degree[n]);
  for (let s = 0; s < rest.length; s++) {
    if (kinds[s] === BEND) continue;
    const a = sp[2 * s], b = sp[2 * s + 1];
    nbr[fill[a]] = b; len[fill[a]++] = rest[s];
    nbr[fill[b]] = a; len[fill[b]++] = rest[s];
  }

  // binary heap of (distance, particle) with lazy deletion
  const dist = new Float64Array(n).fill(Infinity);
  anchors?.fill(-1);
  const heapD = new Float64Array(degree[n] + n);
  const heapP = new Uint32Array(degree[n] + n);
  let size = 0;
  const push = (d: number, p: number) => {
    let i = size++;
    while (i > 0) {
      const parent = (i - 1) >> 1;
      if (heapD[parent] <= d) break;
      heapD[i] = heapD[parent]; heapP[i] = heapP[parent];
      i = parent;
    }
    heapD[i] = d; heapP[i] = p;
  };
  const pop = () => {
    const d = heapD[--size], p = heapP[size];
    let i = 0;
    for (;;) {
      let c = 2 * i + 1;
      if (c >= size) break;
      if (c + 1 < size && heapD[c + 1] < heapD[c]) c++;
      if (heapD[c] >= d) break;
      heapD[i] = heapD[c]; heapP[i] = heapP[c];
      i = c;
    }
    heapD[i] = d; heapP[i] = p;
  };
  for (let i = 0; i < n; i++) {
    if (pinned[i]) { dist[i] = 0; if (anchors) anchors[i] = i; push(0, i); }
  }
  while (size > 0) {
    const d = heapD[0], p = heapP[0];
    pop();
    if (d > dist[p]) continue;
    for (let e = degree[p]; e < degree[p + 1]; e++) {
      const q = nbr[e];
      const nd = d + len[e];
      if (nd < dist[q]) { dist[q] = nd; if (anchors) anchors[q] = anchors[p]; push(nd, q); }
    }
  }
  return dist;
}

/** Pulls every particle that is farther than stretchFactor × its tether length from its anchor back onto it. */
export function solveTethers(state: ClothState, params: SimParams): void {
  const x = state.positions, w = state.invMass, anchors = state.tetherAnchors, lengths = state.tetherLengths;
  const owner = params.owner, stretch = params.perCloth.stretchFactor;
  for (let i = 0; i < anchors.length; i++) {
    const a = anchors[i];
    if (a < 0 || w[i] === 0) continue;
    const sf = stretch[owner[i]];
    const j = 3 * i, k = 3 * a;
    const dx = x[j] - x[k], dy = x[j + 1] - x[k + 1], dz = x[j + 2] - x[k + 2];
    const d2 = dx * dx + dy * dy + dz * dz;
    const max = sf * lengths[i];
    if (d2 <= max * max) continue;
    const s = max / Math.sqrt(d2);
    x[j] = x[k] + dx * s; x[j + 1] = x[k + 1] + dy * s; x[j + 2] = x[k + 2] + dz * s;
  }
}
