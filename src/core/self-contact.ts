/**
 * Self-contact (solver.selfContact, the `selfContact` phase): the cloth kept from passing through itself, particle
 * against triangle, every substep after the solver's constraints and before collider contact (so a collider wins
 * where the two disagree). Proximity with side memory, after Bridson, Fedkiw & Anderson 2002 ("Robust Treatment of
 * Collisions, Contact and Friction for Cloth Animation", their repulsion step) in position-based form (Müller et al.
 * 2007; Macklin et al. 2014 for the friction):
 *
 * - Each particle p (a pinned or grabbed one too: moved by a pin's collider or the grab, it pushes the cloth it
 *   meets) is tested against every triangle t not having it as a corner whose box — over the
 *   substep's start and end positions, widened by the self-contact distance h — meets p's own. The candidates are
 *   found ahead (findCandidates: bounding-box trees over boxes of where each particle can be until the frame's end,
 *   in a frame moving with the cloth where it moves as one (movingFrame), less the pairs too far apart to come
 *   within h by then), and found again only when some particle leaves its box — for those particles alone where
 *   they are few (updateCandidates), else whole: every pair that can come within h in a substep is among them; and
 *   they are resolved in
 *   (particle, triangle) order, ascending, whenever they were found (so when they were found does not change their
 *   order). (Leaving out its whole
 *   neighbourhood, the triangles touching its one-ring, saved a tenth of the time and let 8× as many tight folds
 *   through at 64²: not done.)
 * - **Passed through** (side memory): p was on one side of t's plane at the substep's start and is on the other
 *   now, its projection onto the plane falls inside t (now or then), and it is nearer t now than h or than the two
 *   moved over the substep (resolvePair): p and t's corners are moved, by inverse mass and barycentric weight, until
 *   p is back on its side at distance h.
 * - **Too near**: on its side but nearer t than h (closest point of t, Ericson 2005 §5.1.5): moved apart to h.
 * - **Friction**: the tangential motion of p relative to t's point over the substep is removed while within the
 *   static cone (|d_t| < μ_s·depth), else reduced by μ_k·depth — the cloth's own friction and static friction
 *   within one cloth; between two cloths (a scene's `cloths`) the geometric mean of theirs, √(μ_p·μ_t), each of
 *   the two coefficients (the rule of Bullet and Jolt: a slippery cloth slides on any other).
 *
 * h is the contact thickness (between two cloths the mean of theirs: each keeps half its own thickness), but never
 * more than half the smallest altitude of the rest triangles, so a particle
 * at rest is never "too near" a triangle of its own neighbourhood (on a fine mesh the layers then keep closer than
 * the thickness). Then edge against edge (collideEdges): two edges crossing while every vertex stays outside the
 * other's triangles, kept h/2 apart at rest and up to h in motion (SELF_EDGE_SHARE). Not handled: a particle or an
 * edge that starts a substep already on the wrong side stays there (side memory keeps, it does not untangle). Most
 * listed pairs are neighbours that are not near: each
 * triangle's normals (now and at the substep's start), centroid and radius, and each edge's midpoint and half
 * vector, are computed once per substep (again only after a correction moved a corner), and the pairs they prove
 * apart cost a few products each; an edge pair keeps its last measured distance, which bounds it until its particles
 * have travelled that far (their path lengths since the candidates were found) — exact skips: what they skip would
 * have changed nothing.
 * One Gauss–Seidel pass in particle order, then one in edge order;
 * the trees are built when a model is first seen and refitted after; the pair lists grow only when a search finds
 * more pairs than ever before.
 */
import { BoxTree } from './box-tree.js';
import { SELF_EDGE_SHARE, SELF_FRAME_SHARE, SELF_REACH_MARGIN, SELF_SKIP_MARGIN } from './layout.generated.js';
import type { ClothModel } from './model.js';
import type { SimParams } from './params.js';
import type { ClothState } from './state.js';

/** What one model's self-contact keeps between substeps. */
interface SelfScratch {
  /** the smallest altitude of the rest triangles [m]: the self-contact distance is at most half of it */
  minAltitude: number;
  /** the mean rest edge length [m]: a reach box spans at most REACH_SPAN of it of predicted motion (findCandidates) */
  meanEdge: number;
  /** triangle boxes over the substep (start ∪ end), widened by h: minx, miny, minz, maxx, maxy, maxz */
  boxes: Float64Array;
  /** edge boxes over the substep, widened by h/2, as `boxes` */
  edgeBoxes: Float64Array;
  /**
   * where each particle can be until the candidates are found again: its box over the substeps left in the frame
   * (its motion so far carried on, and gravity), with a margin; the candidates hold while every particle's box over
   * a substep stays inside its own
   */
  reach: Float64Array;
  /**
   * how far each particle can be from where it was when the candidates were found (`seen`) while they hold: the
   * farthest corner of its reach box from there [m]
   */
  reachRadius: Float64Array;
  /** each particle's box over the substep (x_prev to x, as of the last substepBoxes), as `boxes` */
  particleBoxes: Float64Array;
  /** the triangles' and edges' reach boxes (their corners' reach boxes, widened by h; an edge's by SELF_EDGE_SHARE·h/2) */
  triangleReach: Float64Array;
  edgeReach: Float64Array;
  /** candidate pairs (particle, triangle) and (edge, edge) whose reach boxes meet, in the order they are resolved */
  pairs: Int32Array;
  pairCount: number;
  edgePairs: Int32Array;
  edgePairCount: number;
  /** sortPairs' counts per first entry and its sorted copy */
  bucket: Int32Array;
  sorted: Int32Array;
  /**
   * per triangle, what its pairs' tests share within a substep (triangleFrame): the unit normal now and at the
   * substep's start (unitNormal; NaN for a degenerate triangle), the centroid now [m] and the largest
   * distance of a corner from it [m]: nx, ny, nz, n0x, n0y, n0z, cx, cy, cz, r
   */
  triFrame: Float64Array;
  /** per edge (edgeFrame): its midpoint now [m], half its vector b − a now [m] */
  edgeFrame: Float64Array;
  /** the clock (below) when each triangle's and each edge's frame was computed */
  triFrameAt: Float64Array;
  edgeFrameAt: Float64Array;
  /** the clock when each particle was last moved by a correction */
  movedAt: Float64Array;
  /**
   * how far each particle can have moved since the candidates were found [m]: the sum of its moves between the
   * times self-contact looked at it (the start of each substep's phase, and each correction that moved it), and
   * where it was the last time (`seen`)
   */
  travel: Float64Array;
  seen: Float32Array;
  /** each particle's move over the substep so far, |x − x_prev| [m] */
  move: Float64Array;
  /**
   * per edge pair of `edgePairs`: a lower bound on its distance [m] once measured (−∞ before), and the sum of its
   * four particles' travel then [m]: it is now at least the bound less what they travelled since
   */
  edgeMemo: Float64Array;
  /**
   * counts corrections and substeps [-]: a frame is current while it was computed in this substep (at or after
   * `substepAt`) and none of its particles moved after it
   */
  clock: number;
  substepAt: number;
  /** the distance h the reach boxes were widened by (NaN: none found yet) */
  builtFor: number;
  /** each particle's triangles and edges (compressed rows: particle p's are list[start[p]…start[p+1]−1]) */
  particleTriangles: { start: Int32Array; list: Int32Array };
  particleEdges: { start: Int32Array; list: Int32Array };
  /**
   * the frame the reach boxes are made in (movingFrame): its motion per substep u [m] (x, y, z) and the substeps
   * since the last search j [-]; a point x at the end of this substep is at x − j·u in it, at its start x − (j − 1)·u
   */
  frame: Float64Array;
  /** substeps since the last whole search (this one included), and how many the one before it held (∞: none yet) */
  since: number;
  lasted: number;
  /** the particles out of their reach boxes at the last substepBoxes (the first escapedCount) */
  escaped: Int32Array;
  escapedCount: number;
  /** updateCandidates: the triangles and edges of the escaped particles, listed, and all three marked */
  touchedTriangles: Int32Array;
  touchedEdges: Int32Array;
  escapedMark: Uint8Array;
  triangleMark: Uint8Array;
  edgeMark: Uint8Array;
}
const scratchOf = new WeakMap<ClothModel, SelfScratch>();
const restOf = new WeakMap<ClothModel, { minAltitude: number; meanEdge: number }>();

/** `model`'s smallest rest altitude of a triangle and mean rest edge length [m] (computed once per model). */
function restMeasures(model: ClothModel): { minAltitude: number; meanEdge: number } {
  let r = restOf.get(model);
  if (r) return r;
  const tri = model.triangles, x = model.restPositions, n = tri.length / 3;
  let minAltitude = Infinity;
  for (let t = 0; t < n; t++) {
    const a = 3 * tri[3 * t], b = 3 * tri[3 * t + 1], c = 3 * tri[3 * t + 2];
    const ux = x[b] - x[a], uy = x[b + 1] - x[a + 1], uz = x[b + 2] - x[a + 2];
    const vx = x[c] - x[a], vy = x[c + 1] - x[a + 1], vz = x[c + 2] - x[a + 2];
    const area2 = Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
    const longest = Math.max(Math.hypot(ux, uy, uz), Math.hypot(vx, vy, vz), Math.hypot(x[c] - x[b], x[c + 1] - x[b + 1], x[c + 2] - x[b + 2]));
    if (longest > 0) minAltitude = Math.min(minAltitude, area2 / longest);
  }
  let edgeSum = 0;
  const ed = model.edges;
  for (let e = 0; e < ed.length; e += 2) {
    const a = 3 * ed[e], b = 3 * ed[e + 1];
    edgeSum += Math.hypot(x[b] - x[a], x[b + 1] - x[a + 1], x[b + 2] - x[a + 2]);
  }
  r = { minAltitude, meanEdge: ed.length > 0 ? edgeSum / (ed.length / 2) : 0 };
  restOf.set(model, r);
  return r;
}

/** For each of `np` particles, the primitives (of `k` particles each, in `ids`) it is one of, as compressed rows. */
export function rowsOf(ids: Uint32Array, k: number, np: number): { start: Int32Array; list: Int32Array } {
  const start = new Int32Array(np + 1), list = new Int32Array(ids.length);
  for (let i = 0; i < ids.length; i++) start[ids[i] + 1]++;
  for (let p = 0; p < np; p++) start[p + 1] += start[p];
  const at = start.slice(0, np);
  for (let i = 0; i < ids.length; i++) list[at[ids[i]]++] = Math.floor(i / k);
  return { start, list };
}

function scratch(model: ClothModel): SelfScratch {
  let s = scratchOf.get(model);
  if (s) return s;
  const n = model.triangles.length / 3;
  s = {
    ...restMeasures(model),
    boxes: new Float64Array(6 * n),
    edgeBoxes: new Float64Array(3 * model.edges.length),
    reach: new Float64Array(6 * model.particleCount),
    reachRadius: new Float64Array(model.particleCount),
    particleBoxes: new Float64Array(6 * model.particleCount),
    triangleReach: new Float64Array(6 * n),
    edgeReach: new Float64Array(3 * model.edges.length),
    pairs: new Int32Array(0),
    pairCount: 0,
    edgePairs: new Int32Array(0),
    edgePairCount: 0,
    bucket: new Int32Array(0),
    sorted: new Int32Array(0),
    triFrame: new Float64Array(10 * n),
    edgeFrame: new Float64Array(6 * (model.edges.length / 2)),
    triFrameAt: new Float64Array(n).fill(-1),
    edgeFrameAt: new Float64Array(model.edges.length / 2).fill(-1),
    movedAt: new Float64Array(model.particleCount),
    travel: new Float64Array(model.particleCount),
    seen: new Float32Array(3 * model.particleCount),
    move: new Float64Array(model.particleCount),
    edgeMemo: new Float64Array(0),
    clock: 0,
    substepAt: 0,
    builtFor: NaN,
    particleTriangles: rowsOf(model.triangles, 3, model.particleCount),
    particleEdges: rowsOf(model.edges, 2, model.particleCount),
    frame: new Float64Array(4),
    since: Infinity,
    lasted: Infinity,
    escaped: new Int32Array(model.particleCount),
    escapedCount: 0,
    touchedTriangles: new Int32Array(n),
    touchedEdges: new Int32Array(model.edges.length / 2),
    escapedMark: new Uint8Array(model.particleCount),
    triangleMark: new Uint8Array(n),
    edgeMark: new Uint8Array(model.edges.length / 2),
  };
  scratchOf.set(model, s);
  return s;
}

/**
 * The self-contact distance on `model` [m]: the contact thickness, at most half the smallest rest altitude (with
 * several cloths the largest such distance: the thickest cloth's thickness, at most half the smallest rest altitude
 * of any cloth).
 */
export function selfContactDistance(model: ClothModel, params: SimParams): number {
  return Math.min(params.thickness, 0.5 * restMeasures(model).minAltitude);
}

/**
 * The smallest self-contact distance of any pair on `model` [m]: each cloth's own thickness (between two cloths
 * the mean of theirs, never below the thinner one's), at most half the smallest rest altitude.
 */
export function smallestSelfContactDistance(model: ClothModel, params: SimParams): number {
  return contactDistanceFor(model, params.perCloth.thickness);
}

/**
 * The smallest self-contact distance on `model` for cloths of these thicknesses [m] (one per cloth): the thinnest,
 * at most half the smallest rest altitude of a triangle (smallestSelfContactDistance, before the params exist).
 */
export function contactDistanceFor(model: ClothModel, thickness: ArrayLike<number>): number {
  let h = 0.5 * restMeasures(model).minAltitude;
  for (let c = 0; c < thickness.length; c++) h = Math.min(h, thickness[c]);
  return h;
}

/**
 * The fewest substeps in a frame of dt [s] at which cloth moving at `speed` [m/s] (solver.selfContactSpeed) moves at
 * most the contact distance h [m] in one substep; 0 when there is no such distance (a zero thickness: no
 * self-contact) or no speed.
 */
export function selfContactSubsteps(h: number, speed: number, dt: number): number {
  return h > 0 && Number.isFinite(h) && speed > 0 ? Math.ceil((speed * dt) / h - 1e-9) : 0;
}

/** scratch for one pair's correction: barycentric weights of the triangle's point, the direction */
const bary = new Float64Array(3);
const dir = new Float64Array(3);
/**
 * what the passes hand resolvePair and resolveEdges: the pair's distance h [m] and friction μ, μs [-]; and what
 * closestPoint and segmentClosest answer, the distance [m]. Through arrays, not as arguments and return values: a
 * number passed to or returned from a call V8 does not inline is boxed on the heap (colliders/shape.ts)
 */
const pairOf = new Float64Array(3);
const PAIR_H = 0, PAIR_MU = 1, PAIR_MU_S = 2;
const nearest = new Float64Array(1);

/** how many times each model's candidates were found, by either CPU kernel (for the tests: about once a frame on a falling cloth) */
const buildsOf = new WeakMap<ClothModel, number>();

/** How many times `model`'s self-contact candidates have been found (the tests check it is not every substep). */
export function selfContactBuilds(model: ClothModel): number {
  return buildsOf.get(model) ?? 0;
}

const updatesOf = new WeakMap<ClothModel, number>();

/** How many times `model`'s candidates were updated for the particles that left their boxes (updateCandidates). */
export function selfContactUpdates(model: ClothModel): number {
  return updatesOf.get(model) ?? 0;
}

/** Counts an update of `model`'s candidates (updateCandidates here, or the WebAssembly kernel's own). */
export function countSelfUpdate(model: ClothModel): void {
  updatesOf.set(model, selfContactUpdates(model) + 1);
}

/** Counts a search for `model`'s candidates (findCandidates here, or the WebAssembly kernel's own). */
export function countSelfSearch(model: ClothModel): void {
  buildsOf.set(model, selfContactBuilds(model) + 1);
}

/** Candidate pairs found ahead in TypeScript, as the WebAssembly kernel's self-contact takes them where its own search overflows (self-contact-wasm.ts). */
export interface SelfCandidates {
  /** each particle's reach box: min x, y, z, max x, y, z [m], in the frame of `frame` */
  readonly reach: Float64Array;
  /** the frame the reach boxes are in (movingFrame): its motion per substep [m] (x, y, z), then 0 substeps since */
  readonly frame: Float64Array;
  /** (particle, triangle) pairs, the first pairCount, in the order they are resolved */
  readonly pairs: Int32Array;
  readonly pairCount: number;
  /** (edge, edge) pairs, the first edgePairCount */
  readonly edgePairs: Int32Array;
  readonly edgePairCount: number;
}

/**
 * Finds `model`'s candidate pairs for the substeps left in the frame, as collideSelf does (substep length h [s],
 * `left` substeps left, this one included), for a backend that runs the narrow phase itself; null when a box is
 * not finite (an unstable cloth: nothing to keep apart).
 */
export function findSelfCandidates(model: ClothModel, state: ClothState, params: SimParams, h: number, left: number): SelfCandidates | null {
  const s = scratch(model);
  return findCandidates(model, state, params, s, selfContactDistance(model, params), h, left) ? s : null;
}

/** `model`'s candidate pairs as the reference's last search left them (tests), or null before the first. */
export function lastSelfCandidates(model: ClothModel): SelfCandidates | null {
  const s = scratchOf.get(model);
  return s && s.builtFor === s.builtFor ? s : null;
}

/**
 * One substep of self-contact (see the file's comment): substep length h [s], `left` substeps of the frame left
 * (this one included), for how far ahead the candidates are found.
 */
export function collideSelf(model: ClothModel, state: ClothState, params: SimParams, h: number, left: number): void {
  const tri = model.triangles, nt = tri.length / 3, np = model.particleCount;
  if (nt < 2) return;
  const s = scratch(model);
  // the largest distance of any pair: the boxes are made for it
  const hMax = Math.min(params.thickness, 0.5 * s.minAltitude);
  if (!(hMax > 0)) return;
  const owner = params.owner, { thickness, friction, staticFriction } = params.perCloth;
  const x = state.positions, xp = state.previousPositions, w = state.invMass;

  // the candidates hold while every particle's box over this substep is inside its reach box
  s.frame[FRAME_J]++;
  s.since++;
  const ahead = searchAhead(left, s.lasted);
  const within = substepBoxes(s, x, xp, np, true);
  if (!(s.builtFor === hMax && within) && !updateCandidates(model, state, params, s, hMax, h, ahead) && !searchWhole(model, state, params, s, hMax, h, ahead)) return; // an unstable cloth: nothing to keep apart

  // triangle boxes over the substep (their corners'), widened by h
  const boxes = s.boxes, pb = s.particleBoxes;
  for (let t = 0; t < nt; t++) {
    const b = 6 * t, i = 6 * tri[3 * t], j = 6 * tri[3 * t + 1], k = 6 * tri[3 * t + 2];
    boxes[b] = Math.min(pb[i], pb[j], pb[k]) - hMax;
    boxes[b + 1] = Math.min(pb[i + 1], pb[j + 1], pb[k + 1]) - hMax;
    boxes[b + 2] = Math.min(pb[i + 2], pb[j + 2], pb[k + 2]) - hMax;
    boxes[b + 3] = Math.max(pb[i + 3], pb[j + 3], pb[k + 3]) + hMax;
    boxes[b + 4] = Math.max(pb[i + 4], pb[j + 4], pb[k + 4]) + hMax;
    boxes[b + 5] = Math.max(pb[i + 5], pb[j + 5], pb[k + 5]) + hMax;
  }
  // a new substep: every triangle's and edge's frame is to be computed again
  s.substepAt = ++s.clock;
  const pairs = s.pairs;
  for (let q = 0; q < s.pairCount; q++) {
    const p = pairs[2 * q], t = pairs[2 * q + 1];
    const jp = 3 * p, bb = 6 * t;
    const px = x[jp], py = x[jp + 1], pz = x[jp + 2];
    if (px < boxes[bb] || px > boxes[bb + 3] || py < boxes[bb + 1] || py > boxes[bb + 4] || pz < boxes[bb + 2] || pz > boxes[bb + 5]) {
      const qx = xp[jp], qy = xp[jp + 1], qz = xp[jp + 2];
      if (qx < boxes[bb] || qx > boxes[bb + 3] || qy < boxes[bb + 1] || qy > boxes[bb + 4] || qz < boxes[bb + 2] || qz > boxes[bb + 5]) continue;
    }
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    // the pair's distance and friction: one cloth's own, or between two cloths the mean thickness and the
    // geometric mean of the coefficients
    const cp = owner[p], ct = owner[a];
    const k = pairOf;
    if (cp === ct) {
      k[PAIR_H] = Math.min(thickness[cp], hMax); k[PAIR_MU] = friction[cp]; k[PAIR_MU_S] = staticFriction[cp];
    } else {
      k[PAIR_H] = Math.min(0.5 * (thickness[cp] + thickness[ct]), hMax);
      k[PAIR_MU] = Math.sqrt(friction[cp] * friction[ct]); k[PAIR_MU_S] = Math.sqrt(staticFriction[cp] * staticFriction[ct]);
    }
    resolvePair(s, x, xp, w, p, t, a, b, c);
  }
  // the particle pass may have pushed a particle out of its reach box: the edges' candidates must hold for where
  // the particles are now
  if (!substepBoxes(s, x, xp, np, false) && !updateCandidates(model, state, params, s, hMax, h, ahead) && !searchWhole(model, state, params, s, hMax, h, ahead)) return;
  collideEdges(model, state, params, s, hMax);
}

/** collideSelf's whole search (findCandidates), which then counts how long the lists before it held (searchAhead). */
function searchWhole(model: ClothModel, state: ClothState, params: SimParams, s: SelfScratch, hMax: number, h: number, left: number): boolean {
  if (!findCandidates(model, state, params, s, hMax, h, left)) return false;
  s.lasted = s.since;
  s.since = 0;
  return true;
}

/**
 * Each particle's box over the substep (x_prev to x) into particleBoxes, and (`start`: the phase's start) its
 * travel and move (track); the particles whose box is not inside their reach box into `escaped` (escapedCount;
 * a non-finite position is not inside); whether there are none.
 */
function substepBoxes(s: SelfScratch, x: Float32Array, xp: Float32Array, np: number, start: boolean): boolean {
  const reach = s.reach, pb = s.particleBoxes, f = s.frame, j = f[FRAME_J];
  let out = 0;
  for (let p = 0; p < np; p++) {
    // after the particle pass, only those it moved can have left their boxes (the others were inside them, or were
    // given boxes around where they are, and have not moved)
    if (!start && s.movedAt[p] <= s.substepAt) continue;
    const jp = 3 * p, r = 6 * p;
    let inside = true;
    for (let c = 0; c < 3; c++) {
      pb[r + c] = Math.min(x[jp + c], xp[jp + c]); pb[r + 3 + c] = Math.max(x[jp + c], xp[jp + c]);
      // in the frame of the reach boxes
      const now = x[jp + c] - j * f[c], then = xp[jp + c] - (j - 1) * f[c];
      if (!(Math.min(now, then) >= reach[r + c] && Math.max(now, then) <= reach[r + 3 + c])) inside = false;
    }
    if (!inside) s.escaped[out++] = p;
    if (start) track(s, x, xp, p);
  }
  s.escapedCount = out;
  return out === 0;
}

/** Particle p's travel up to where it is now (SelfScratch.travel, seen) and its move over the substep so far. */
function track(s: SelfScratch, x: Float32Array, xp: Float32Array, p: number): void {
  const j = 3 * p, seen = s.seen;
  const dx = x[j] - seen[j], dy = x[j + 1] - seen[j + 1], dz = x[j + 2] - seen[j + 2];
  s.travel[p] += Math.sqrt(dx * dx + dy * dy + dz * dz);
  seen[j] = x[j]; seen[j + 1] = x[j + 1]; seen[j + 2] = x[j + 2];
  const mx = x[j] - xp[j], my = x[j + 1] - xp[j + 1], mz = x[j + 2] - xp[j + 2];
  s.move[p] = Math.sqrt(mx * mx + my * my + mz * mz);
}

/** The fewest substeps ahead a search looks (searchAhead). */
const AHEAD_LEAST = 2;

/**
 * How many substeps ahead a search (or an update) makes its reach boxes for, where `left` substeps of the frame are
 * left and the last whole search's candidates held `lasted` substeps (∞ before there was one): no more than they
 * held, at least AHEAD_LEAST. Where the lists hold a frame or more (a cloth at rest, or falling as one) that is the
 * frame's rest, as before; in a landing, searched every few substeps, the boxes look as far ahead as the last held —
 * smaller for the particles that move slowly (a fast one's is capped at REACH_SPAN of an edge anyway), so fewer pairs
 * are listed and passed over: fold at 64², frames 1–30 and 31–60, 105, 103 → 98, 96 ms a frame (docs/physics.md,
 * "Less of it").
 */
export function searchAhead(left: number, lasted: number): number {
  return Math.min(left, Math.max(AHEAD_LEAST, lasted));
}

/** How much of the mean rest edge length a reach box spans of predicted motion at most [-] (findCandidates). */
const REACH_SPAN = 1 / 2;

/**
 * What a search on `model` reads besides the state, for a kernel that searches itself: the mean rest edge length
 * [m] (a pair farther apart than it is tested as it is) and the most predicted motion a reach box spans [m].
 */
export function selfSearchLengths(model: ClothModel): { meanEdge: number; span: number } {
  const { meanEdge } = restMeasures(model);
  return { meanEdge, span: REACH_SPAN * meanEdge };
}

/**
 * Finds the candidate pairs for the substeps left in the frame: each particle's reach box (its box over this
 * substep, carried on over the `left` substeps of length h at its motion so far and gravity — but no farther than
 * REACH_SPAN of the mean rest edge length — with a margin of half that motion and at least h/4), the triangles' and
 * edges' from their corners', and the pairs whose boxes meet (box-tree.ts: a tree over the particles' boxes
 * against one over the triangles', and one over the edges' against itself; at 64² on fold a search took 20 ms at
 * rest and 39 ms in the fall, against 29 and 51 ms by the uniform grids before, the same pairs) less those farther
 * apart now than h and their reach radii (Trees.addPair: at 64² on fold at rest 17.6 k particle and 52.9 k edge
 * pairs listed instead of 27.0 k and 96.7 k). False when a box is not finite. (A fast cloth then finds them again
 * more often instead of listing every neighbour along a frame of its path: fold's fall at 64², frames 0–30,
 * searched 191 times instead of 168 and listed 95 k pairs instead of 143 k; frames 0–60 took 265 ms per frame
 * instead of 463. A third beat a half and a fifth then; since a search looks ahead no farther than the last lists
 * held, searchAhead, half an edge beats a third: fold at 64², frames 1–30 and 31–60, 96, 93 → 93, 88 ms a frame, and
 * a quarter, two thirds, three quarters and one edge no better.)
 */
function findCandidates(model: ClothModel, state: ClothState, params: SimParams, s: SelfScratch, hMax: number, h: number, left: number): boolean {
  const tri = model.triangles, nt = tri.length / 3, np = model.particleCount, edges = model.edges, ne = edges.length / 2;
  const x = state.positions, xp = state.previousPositions, g = params.gravity;
  const reach = s.reach, T = left * h;
  const span = REACH_SPAN * s.meanEdge;
  movingFrame(s.frame, x, xp, np);
  for (let p = 0; p < np; p++) reachBox(s, x, xp, g, p, left, T, span, hMax);
  const tr = s.triangleReach;
  for (let t = 0; t < nt; t++) unionOf(reach, tri, 3 * t, 3, tr, 6 * t, hMax);
  const er = s.edgeReach;
  for (let e = 0; e < ne; e++) unionOf(reach, edges, 2 * e, 2, er, 6 * e, 0.5 * (EDGE_SHARE * hMax));
  const trees = treesOf(model, s);
  if (!trees.particles.refit(reach) || !trees.triangles.refit(tr) || !trees.edges.refit(er)) { s.builtFor = NaN; return false; }
  countSelfSearch(model);
  s.builtFor = hMax;
  // distances are measured again from here
  s.travel.fill(0);
  s.seen.set(x);

  // particle against triangle, and edge against edge (each pair once, from its lower edge): the pairs whose reach
  // boxes meet and that can come within hMax of each other before they are found again (apart), then put in the
  // order they are resolved
  s.pairCount = 0;
  trees.particles.pairsWith(trees.triangles, reach, tr, trees.addPair);
  s.pairCount = sortPairs(s, s.pairs, s.pairCount, np);
  s.edgePairCount = 0;
  trees.edges.pairsWithin(er, trees.addEdgePair);
  const count = (s.edgePairCount = sortPairs(s, s.edgePairs, s.edgePairCount, ne));
  if (s.edgeMemo.length < 2 * count) s.edgeMemo = new Float64Array(s.edgePairs.length);
  s.edgeMemo.fill(-Infinity, 0, 2 * count);
  return true;
}

/**
 * Particle p's reach box and radius (findCandidates): its box over this substep carried on over the `left` substeps
 * (T [s] in all) at its motion so far and gravity, no farther than `span` [m], with a margin of half that motion and
 * at least hMax/4 [m].
 */
function reachBox(s: SelfScratch, x: Float32Array, xp: Float32Array, g: Float64Array, p: number, left: number, T: number, span: number, hMax: number): void {
  const reach = s.reach, jp = 3 * p, r = 6 * p, f = s.frame, j = f[FRAME_J];
  // where it is and was in the frame of the boxes
  const x0 = x[jp] - j * f[0], x1 = x[jp + 1] - j * f[1], x2 = x[jp + 2] - j * f[2];
  const q0 = xp[jp] - (j - 1) * f[0], q1 = xp[jp + 1] - (j - 1) * f[1], q2 = xp[jp + 2] - (j - 1) * f[2];
  const dx = (x0 - q0) * left + 0.5 * g[0] * T * T;
  const dy = (x1 - q1) * left + 0.5 * g[1] * T * T;
  const dz = (x2 - q2) * left + 0.5 * g[2] * T * T;
  const dl = Math.sqrt(dx * dx + dy * dy + dz * dz), k = dl > span ? span / dl : 1;
  const margin = Math.max(0.5 * dl * k, REACH_MARGIN * hMax);
  const e0 = reachAxis(reach, r, 0, q0, x0, dx * k, margin), e1 = reachAxis(reach, r, 1, q1, x1, dy * k, margin);
  const e2 = reachAxis(reach, r, 2, q2, x2, dz * k, margin);
  s.reachRadius[p] = Math.sqrt(e0 * e0 + e1 * e1 + e2 * e2);
}

/**
 * Axis c of the reach box at r: from min(x_prev, x, x + d) to max(…), each widened by the margin [m]; returns the
 * farther of its ends from x [m].
 */
function reachAxis(reach: Float64Array, r: number, c: number, q: number, x: number, d: number, margin: number): number {
  const lo = Math.min(q, x, x + d) - margin, hi = Math.max(q, x, x + d) + margin;
  reach[r + c] = lo; reach[r + 3 + c] = hi;
  return Math.max(x - lo, hi - x);
}

/** slot of SelfScratch.frame holding the substeps since the search */
const FRAME_J = 3;

/**
 * The frame a search makes its reach boxes in (into `frame`: the motion u per substep [m], and 0 substeps since):
 * the cloth's mean motion over this substep where its particles move less than SELF_FRAME_SHARE (half) as much
 * relative to it as they do at all (the sums of the lengths), else at rest. In a frame moving with a cloth that
 * falls or flies as one, its particles' reach boxes stay small, as at rest, and so do the lists of pairs; the
 * distances of two particles at one instant are the same in either frame, and a particle's path through a substep,
 * straight in the world, is straight in it too, so every pair that comes within reach of the other in a substep
 * still has reach boxes that meet.
 */
function movingFrame(frame: Float64Array, x: Float32Array, xp: Float32Array, np: number): void {
  let mx = 0, my = 0, mz = 0;
  for (let j = 0; j < 3 * np; j += 3) { mx += x[j] - xp[j]; my += x[j + 1] - xp[j + 1]; mz += x[j + 2] - xp[j + 2]; }
  mx /= np; my /= np; mz /= np;
  let still = 0, along = 0;
  for (let j = 0; j < 3 * np; j += 3) {
    const vx = x[j] - xp[j], vy = x[j + 1] - xp[j + 1], vz = x[j + 2] - xp[j + 2];
    still += Math.sqrt(vx * vx + vy * vy + vz * vz);
    along += Math.sqrt((vx - mx) * (vx - mx) + (vy - my) * (vy - my) + (vz - mz) * (vz - mz));
  }
  const moving = along < FRAME_SHARE * still;
  frame[0] = moving ? mx : 0; frame[1] = moving ? my : 0; frame[2] = moving ? mz : 0;
  frame[FRAME_J] = 0;
}

/** The most particles out of their reach boxes that updateCandidates takes (and the kernel's), as a share of the cloth's [-]. */
export const UPDATE_MOST = 1 / 200;

/**
 * Updates the candidates for the particles that left their reach boxes, when they are at most UPDATE_MOST of the
 * cloth (else false: findCandidates searches again whole). Those particles get new reach boxes, and their
 * triangles and edges new ones from their corners'; every pair of them is taken out of the lists and found again
 * against the trees (refitted), with the same tests as findCandidates. The other particles keep their boxes,
 * which still hold them. The apart test of the pairs found now measures every particle's reach radius from where
 * it is now (its box may have been made earlier, from elsewhere in it). The edge pairs' memo starts again, as after
 * a search. The pairs listed differ from a new search's, but a pair that is not listed cannot come within hMax, and
 * the lists are in the same order, so the cloth is the same: the WebAssembly kernel, which updates as this does
 * (self-search.as.ts selfUpdate: the same lists), steps layers and fold bit for bit as when it searches whole
 * (wasm/self-contact-wasm.test.ts). Once fold has landed, a search is mostly for a few particles
 * (scripts/self-search-escapes.mjs); what the updates save, and what they still cost (the refits and the lists'
 * passes, O(pairs)): docs/physics.md, "Its cost".
 */
function updateCandidates(model: ClothModel, state: ClothState, params: SimParams, s: SelfScratch, hMax: number, h: number, left: number): boolean {
  if (s.builtFor !== hMax) return false;
  const np = model.particleCount, tri = model.triangles, edges = model.edges;
  const x = state.positions, xp = state.previousPositions;
  const reach = s.reach;
  const { escaped, escapedCount: k, touchedTriangles, touchedEdges, escapedMark, triangleMark, edgeMark } = s;
  if (k > UPDATE_MOST * np) return false;
  const T = left * h, span = REACH_SPAN * s.meanEdge;
  let nt = 0, ne = 0;
  for (let i = 0; i < k; i++) {
    const p = escaped[i];
    reachBox(s, x, xp, params.gravity, p, left, T, span, hMax);
    escapedMark[p] = 1;
    for (let j = s.particleTriangles.start[p]; j < s.particleTriangles.start[p + 1]; j++) {
      const t = s.particleTriangles.list[j];
      if (!triangleMark[t]) { triangleMark[t] = 1; touchedTriangles[nt++] = t; }
    }
    for (let j = s.particleEdges.start[p]; j < s.particleEdges.start[p + 1]; j++) {
      const e = s.particleEdges.list[j];
      if (!edgeMark[e]) { edgeMark[e] = 1; touchedEdges[ne++] = e; }
    }
  }
  const tr = s.triangleReach, er = s.edgeReach;
  for (let i = 0; i < nt; i++) unionOf(reach, tri, 3 * touchedTriangles[i], 3, tr, 6 * touchedTriangles[i], hMax);
  for (let i = 0; i < ne; i++) unionOf(reach, edges, 2 * touchedEdges[i], 2, er, 6 * touchedEdges[i], 0.5 * (EDGE_SHARE * hMax));
  const trees = treesOf(model, s);
  const refitted = trees.particles.refit(reach) && trees.triangles.refit(tr) && trees.edges.refit(er);
  if (refitted) {
    const f = s.frame, since = f[FRAME_J];
    for (let p = 0; p < np; p++) {
      if (escapedMark[p]) continue;
      const r = 6 * p, j = 3 * p;
      let r2 = 0;
      for (let c = 0; c < 3; c++) {
        const at = x[j + c] - since * f[c], far = Math.max(at - reach[r + c], reach[r + 3 + c] - at);
        r2 += far * far;
      }
      s.reachRadius[p] = Math.sqrt(r2);
    }
    countSelfUpdate(model);
    s.travel.fill(0);
    s.seen.set(x);
    // the particle pairs of the particles and triangles moved out, and found again
    s.pairCount = keepUnmarked(s.pairs, s.pairCount, escapedMark, triangleMark);
    for (let i = 0; i < k; i++) trees.triangles.query(reach, 6 * escaped[i], tr, escaped[i], trees.addPair);
    for (let i = 0; i < nt; i++) trees.particles.query(tr, 6 * touchedTriangles[i], reach, touchedTriangles[i], trees.addStillPair);
    s.pairCount = sortPairs(s, s.pairs, s.pairCount, np);
    // the edge pairs of the edges moved out (each pair once, from its lower edge where both moved)
    s.edgePairCount = keepUnmarked(s.edgePairs, s.edgePairCount, edgeMark, edgeMark);
    for (let i = 0; i < ne; i++) trees.edges.query(er, 6 * touchedEdges[i], er, touchedEdges[i], trees.addMovedEdgePair);
    const count = (s.edgePairCount = sortPairs(s, s.edgePairs, s.edgePairCount, edges.length / 2));
    if (s.edgeMemo.length < 2 * count) s.edgeMemo = new Float64Array(s.edgePairs.length);
    s.edgeMemo.fill(-Infinity, 0, 2 * count);
  }
  for (let i = 0; i < k; i++) escapedMark[escaped[i]] = 0;
  for (let i = 0; i < nt; i++) triangleMark[touchedTriangles[i]] = 0;
  for (let i = 0; i < ne; i++) edgeMark[touchedEdges[i]] = 0;
  return refitted;
}

/** Keeps, in order, those of the first `count` pairs of `list` whose first is unmarked in `a` and second in `b`; returns how many. */
function keepUnmarked(list: Int32Array, count: number, a: Uint8Array, b: Uint8Array): number {
  let n = 0;
  for (let q = 0; q < count; q++) {
    const i = list[2 * q], j = list[2 * q + 1];
    if (a[i] || b[j]) continue;
    list[2 * n] = i; list[2 * n + 1] = j; n++;
  }
  return n;
}

/**
 * Puts the first `count` pairs of `list` (first entries below n) in the order they are resolved, (particle,
 * triangle) or (edge, edge) ascending, whatever order the trees gave them in, so that when and how the candidates
 * were found changes nothing: by their first entries (a counting sort), then each one's few by their second
 * (insertion). Returns count.
 */
function sortPairs(s: SelfScratch, list: Int32Array, count: number, n: number): number {
  if (s.bucket.length < n + 1) s.bucket = new Int32Array(n + 1);
  if (s.sorted.length < 2 * count) s.sorted = new Int32Array(list.length);
  const bucket = s.bucket, out = s.sorted;
  bucket.fill(0, 0, n + 1);
  for (let q = 0; q < count; q++) bucket[list[2 * q] + 1]++;
  for (let i = 0; i < n; i++) bucket[i + 1] += bucket[i];
  for (let q = 0; q < count; q++) {
    const at = bucket[list[2 * q]]++;
    out[2 * at] = list[2 * q]; out[2 * at + 1] = list[2 * q + 1];
  }
  // each bucket now ends where the next begins
  for (let i = 0, from = 0; i < n; i++) {
    const to = bucket[i];
    for (let a = from + 1; a < to; a++) {
      const v = out[2 * a + 1];
      let b = a - 1;
      for (; b >= from && out[2 * b + 1] > v; b--) out[2 * b + 3] = out[2 * b + 1];
      out[2 * b + 3] = v;
    }
    from = to;
  }
  // (copied by hand: a subarray to set from would be an object made at every sort)
  for (let i = 0; i < 2 * count; i++) list[i] = out[i];
  return count;
}

/** The trees over `model`'s particles, triangles and edges (box-tree.ts) and what their pairs are added by. */
interface Trees extends SelfContactTrees {
  /**
   * adds (particle, triangle) to the scratch's pairs unless the particle is a corner of the triangle, or the two are
   * apart: farther apart now than the distance the boxes were made for and their reach radii, tested where that
   * sum is under a mean rest edge (beyond, the reach is long: in the fall, where it would leave out nothing)
   */
  addPair: (p: number, t: number) => void;
  /** adds (edge, edge) to the scratch's edge pairs unless the two share a particle or are apart (as addPair) */
  addEdgePair: (e: number, f: number) => void;
  /** updateCandidates': addPair(p, t) for a particle whose box did not move (escapedMark) */
  addStillPair: (t: number, p: number) => void;
  /** updateCandidates': addEdgePair for the pair of e, an edge whose box moved, and f, once (from the lower where both did) */
  addMovedEdgePair: (e: number, f: number) => void;
}
const treesFor = new WeakMap<ClothModel, Trees>();

/** scratch for the vector between two edges' closest points when the candidates are found */
const apart = new Float64Array(3);

/** The bounding-box trees of a model's self-contact: over its particles, its triangles and its edges. */
export interface SelfContactTrees {
  readonly particles: BoxTree;
  readonly triangles: BoxTree;
  readonly edges: BoxTree;
}
const structureOf = new WeakMap<ClothModel, SelfContactTrees>();

/**
 * `model`'s trees, built once from its rest positions (each primitive by its centre) and refitted at each search:
 * the reference's, and the WebAssembly kernel's, which copies their structure into its memory.
 */
export function selfContactTrees(model: ClothModel): SelfContactTrees {
  let t = structureOf.get(model);
  if (t) return t;
  const x = model.restPositions, tri = model.triangles, edges = model.edges;
  const np = model.particleCount, nt = tri.length / 3, ne = edges.length / 2;
  const centre = (ids: Uint32Array, k: number, n: number): Float64Array => {
    const c = new Float64Array(3 * n);
    for (let i = 0; i < n; i++) for (let v = 0; v < k; v++) for (let d = 0; d < 3; d++) c[3 * i + d] += x[3 * ids[k * i + v] + d] / k;
    return c;
  };
  t = {
    particles: new BoxTree(Float64Array.from(x), np),
    triangles: new BoxTree(centre(tri, 3, nt), nt),
    edges: new BoxTree(centre(edges, 2, ne), ne),
  };
  structureOf.set(model, t);
  return t;
}

/** `model`'s trees and the callbacks that add their pairs to the scratch `s`. */
function treesOf(model: ClothModel, s: SelfScratch): Trees {
  const known = treesFor.get(model);
  if (known) return known;
  const tri = model.triangles, edges = model.edges;
  const addPair = (p: number, t: number): void => {
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    if (a === p || b === p || c === p) return;
    // apart: not within hMax of each other at any time while the candidates hold (every particle stays within
    // its reach radius of where it is now, and so every point of the triangle within its corners' largest)
    const R = s.reachRadius, near = s.builtFor + R[p] + Math.max(R[a], R[b], R[c]) + SKIP_MARGIN;
    if (near < s.meanEdge) {
      closestPoint(s.seen, 3 * p, 3 * a, 3 * b, 3 * c);
      if (nearest[0] > near) return;
    }
    const n = s.pairCount;
    if (2 * n + 2 > s.pairs.length) s.pairs = grown(s.pairs, 2 * n + 2);
    s.pairs[2 * n] = p; s.pairs[2 * n + 1] = t;
    s.pairCount = n + 1;
  };
  const addEdgePair = (e: number, f: number): void => {
    const a = edges[2 * e], b = edges[2 * e + 1], c = edges[2 * f], d = edges[2 * f + 1];
    if (c === a || c === b || d === a || d === b) return;
    // apart, as a particle and a triangle above, with the edges' contact distance at rest (h/2, resolveEdges): a pair
    // not listed stays farther apart than that while the lists hold; the margin for motion acts on the listed ones
    const R = s.reachRadius, near = EDGE_SHARE * s.builtFor + Math.max(R[a], R[b]) + Math.max(R[c], R[d]) + SKIP_MARGIN;
    if (near < s.meanEdge) {
      segmentClosest(s.seen, a, b, c, d, apart);
      if (nearest[0] > near) return;
    }
    const n = s.edgePairCount;
    if (2 * n + 2 > s.edgePairs.length) s.edgePairs = grown(s.edgePairs, 2 * n + 2);
    s.edgePairs[2 * n] = e; s.edgePairs[2 * n + 1] = f;
    s.edgePairCount = n + 1;
  };
  const t: Trees = {
    ...selfContactTrees(model),
    addPair,
    addEdgePair,
    addStillPair: (t, p) => { if (!s.escapedMark[p]) addPair(p, t); },
    addMovedEdgePair: (e, f) => { if (f !== e && !(s.edgeMark[f] && f < e)) addEdgePair(Math.min(e, f), Math.max(e, f)); },
  };
  treesFor.set(model, t);
  return t;
}

/** Box `out[o…o+5]` = the union of the reach boxes of the `k` particles ids[i…i+k−1], widened by `pad`. */
function unionOf(reach: Float64Array, ids: Uint32Array, i: number, k: number, out: Float64Array, o: number, pad: number): void {
  for (let c = 0; c < 3; c++) { out[o + c] = Infinity; out[o + 3 + c] = -Infinity; }
  for (let n = 0; n < k; n++) {
    const r = 6 * ids[i + n];
    for (let c = 0; c < 3; c++) {
      if (reach[r + c] < out[o + c]) out[o + c] = reach[r + c];
      if (reach[r + 3 + c] > out[o + 3 + c]) out[o + 3 + c] = reach[r + 3 + c];
    }
  }
  for (let c = 0; c < 3; c++) { out[o + c] -= pad; out[o + 3 + c] += pad; }
}

/** Whether box a[i…] meets box b[j…]. */
function overlap(a: Float64Array, i: number, b: Float64Array, j: number): boolean {
  return !(a[i] > b[j + 3] || a[i + 3] < b[j] || a[i + 1] > b[j + 4] || a[i + 4] < b[j + 1] || a[i + 2] > b[j + 5] || a[i + 5] < b[j + 2]);
}

/** A larger copy of a pair list (half again what is needed: it grows rarely, and only while candidates are found). */
function grown(list: Int32Array, need: number): Int32Array {
  const out = new Int32Array(Math.ceil(need * 1.5) + 64);
  out.set(list);
  return out;
}

/**
 * How far beyond h [m] a bound must say a pair is before it is skipped: the bounds are exact, the tests they stand
 * for are rounded (by far less). The generated table's constants, read once (an imported name is read through a
 * getter under vitest's module loader: colliders/shape.ts)
 */
const SKIP_MARGIN = SELF_SKIP_MARGIN, REACH_MARGIN = SELF_REACH_MARGIN, FRAME_SHARE = SELF_FRAME_SHARE, EDGE_SHARE = SELF_EDGE_SHARE;

/**
 * Triangle t's frame (SelfScratch.triFrame: the unit normals now and at the substep's start, the centroid now and
 * the radius about it), computed unless it is current; returns its offset in triFrame.
 */
function triangleFrame(s: SelfScratch, x: Float32Array, xp: Float32Array, t: number, ja: number, jb: number, jc: number): number {
  const o = 10 * t, at = s.triFrameAt[t], moved = s.movedAt;
  const thisSubstep = at >= s.substepAt;
  if (thisSubstep && moved[ja / 3] <= at && moved[jb / 3] <= at && moved[jc / 3] <= at) return o;
  const f = s.triFrame;
  unitNormal(x, ja, jb, jc, f, o);
  // the start of the substep stays where it was through the pass: its normal, once made in this substep, holds
  if (!thisSubstep) unitNormal(xp, ja, jb, jc, f, o + 3);
  const cx = (x[ja] + x[jb] + x[jc]) / 3, cy = (x[ja + 1] + x[jb + 1] + x[jc + 1]) / 3, cz = (x[ja + 2] + x[jb + 2] + x[jc + 2]) / 3;
  f[o + 6] = cx; f[o + 7] = cy; f[o + 8] = cz;
  const ax = x[ja] - cx, ay = x[ja + 1] - cy, az = x[ja + 2] - cz;
  const bx = x[jb] - cx, by = x[jb + 1] - cy, bz = x[jb + 2] - cz;
  const qx = x[jc] - cx, qy = x[jc + 1] - cy, qz = x[jc + 2] - cz;
  f[o + 9] = Math.sqrt(Math.max(ax * ax + ay * ay + az * az, bx * bx + by * by + bz * bz, qx * qx + qy * qy + qz * qz));
  s.triFrameAt[t] = s.clock;
  return o;
}

/** Marks particles as moved by a correction (their triangles' and edges' frames are computed again). */
function moved(s: SelfScratch, a: number, b: number, c: number, d: number): void {
  const m = s.movedAt, now = ++s.clock;
  m[a] = now; m[b] = now; m[c] = now; m[d] = now;
}

/**
 * Particle p against triangle t = (a, b, c): passed through, or too near (see the file's comment), kept h [m]
 * apart with kinetic and static friction mu, muS [-]. The plane sides come from the triangle's frame (the same
 * numbers planes computed pair by pair give); a particle that did not cross the plane and whose distance from the
 * centroid exceeds the triangle's radius by h is not near it, and costs nothing more. One that crossed it passed
 * through only if it is nearer the triangle now than h or δ, whichever is larger, δ its move over the substep and
 * the largest of the corners' summed (it was on the triangle at some instant of the substep, and since then neither
 * moved farther than that: a point of the triangle moves no farther than its farthest corner); farther, the side
 * changed because the triangle turned over (a sliver whose corner crossed its opposite edge), and the pair is left
 * as it is.
 */
function resolvePair(
  sc: SelfScratch, x: Float32Array, xp: Float32Array, w: Float32Array, p: number, t: number, a: number, b: number, c: number,
): void {
  const h = pairOf[PAIR_H], mu = pairOf[PAIR_MU], muS = pairOf[PAIR_MU_S];
  const jp = 3 * p, ja = 3 * a, jb = 3 * b, jc = 3 * c;
  const o = triangleFrame(sc, x, xp, t, ja, jb, jc), fr = sc.triFrame;
  // the side at the substep's start: the triangle's plane then
  const sPrev = fr[o + 3] * (xp[jp] - xp[ja]) + fr[o + 4] * (xp[jp + 1] - xp[ja + 1]) + fr[o + 5] * (xp[jp + 2] - xp[ja + 2]);
  // now: the distance along the plane's normal
  const s = fr[o] * (x[jp] - x[ja]) + fr[o + 1] * (x[jp + 1] - x[ja + 1]) + fr[o + 2] * (x[jp + 2] - x[ja + 2]);
  if (!Number.isFinite(s) || !Number.isFinite(sPrev)) return;
  // on its side and farther than h from the plane: farther from the triangle too
  if (Math.abs(s) >= h && Math.sign(s) === Math.sign(sPrev)) return;
  const crossed = sPrev !== 0 && Math.sign(s) !== Math.sign(sPrev);
  if (!crossed) {
    // on its side: the triangle lies within its radius of the centroid, so farther than radius + h is not near
    const ex = x[jp] - fr[o + 6], ey = x[jp + 1] - fr[o + 7], ez = x[jp + 2] - fr[o + 8], far = fr[o + 9] + h + SKIP_MARGIN;
    if (ex * ex + ey * ey + ez * ez >= far * far) return;
  }
  dir[0] = fr[o]; dir[1] = fr[o + 1]; dir[2] = fr[o + 2];
  let C: number; // constraint value along dir: negative when violated
  const inside = crossed && projectionInside(x, jp, ja, jb, jc);
  if (crossed && (inside || projectionInside(xp, jp, ja, jb, jc))) {
    // passed through, if near enough now to have (the distance: from the plane where it projects inside)
    const move = sc.move;
    let d = Math.abs(s);
    if (!inside) {
      closestPoint(x, jp, ja, jb, jc);
      d = nearest[0];
    }
    if (d >= Math.max(h, move[p] + Math.max(move[a], move[b], move[c])) + SKIP_MARGIN) return;
    // back to its side, h from the plane (dir is the plane's normal, sign as then)
    const side = Math.sign(sPrev);
    if (!inside) {
      // through the triangle as it was, beside it as it is: the weights of the projection now, clamped to it
      barycentric(x, jp, ja, jb, jc);
      const b0 = Math.max(bary[0], 0), b1 = Math.max(bary[1], 0), b2 = Math.max(bary[2], 0), sum = b0 + b1 + b2;
      bary[0] = b0 / sum; bary[1] = b1 / sum; bary[2] = b2 / sum;
    }
    dir[0] *= side; dir[1] *= side; dir[2] *= side;
    C = side * s - h;
  } else {
    // on its side: nearer than h to the triangle's closest point?
    closestPoint(x, jp, ja, jb, jc);
    const d = nearest[0];
    if (d >= h) return;
    if (d > 1e-12) {
      const cx = bary[0] * x[ja] + bary[1] * x[jb] + bary[2] * x[jc];
      const cy = bary[0] * x[ja + 1] + bary[1] * x[jb + 1] + bary[2] * x[jc + 1];
      const cz = bary[0] * x[ja + 2] + bary[1] * x[jb + 2] + bary[2] * x[jc + 2];
      dir[0] = (x[jp] - cx) / d; dir[1] = (x[jp + 1] - cy) / d; dir[2] = (x[jp + 2] - cz) / d;
    } else {
      // on the triangle: out to the side it came from
      const side = sPrev !== 0 ? Math.sign(sPrev) : 1;
      dir[0] *= side; dir[1] *= side; dir[2] *= side;
    }
    C = d - h;
  }
  const wp = w[p], wa = w[a], wb = w[b], wc = w[c];
  const denom = wp + bary[0] * bary[0] * wa + bary[1] * bary[1] * wb + bary[2] * bary[2] * wc;
  if (denom <= 0) return;
  const lambda = -C / denom; // > 0: p moves along dir, the triangle's point against it
  const depth = lambda * denom; // = −C, how far the pair is pushed apart
  // friction: the relative tangential motion over the substep
  let rx = x[jp] - xp[jp], ry = x[jp + 1] - xp[jp + 1], rz = x[jp + 2] - xp[jp + 2];
  for (let k = 0; k < 3; k++) {
    const q = 3 * (k === 0 ? a : k === 1 ? b : c);
    rx -= bary[k] * (x[q] - xp[q]); ry -= bary[k] * (x[q + 1] - xp[q + 1]); rz -= bary[k] * (x[q + 2] - xp[q + 2]);
  }
  const rn = rx * dir[0] + ry * dir[1] + rz * dir[2];
  const tx = rx - rn * dir[0], ty = ry - rn * dir[1], tz = rz - rn * dir[2];
  const tl = Math.sqrt(tx * tx + ty * ty + tz * tz);
  const f = tl < 1e-12 ? 0 : tl < muS * depth ? 1 : Math.min((mu * depth) / tl, 1);
  // the correction: normal λ·dir, and −f·t shared the same way (p takes its share, the triangle the rest)
  const kx = lambda * dir[0] - (f * tx) / denom, ky = lambda * dir[1] - (f * ty) / denom, kz = lambda * dir[2] - (f * tz) / denom;
  moved(sc, p, a, b, c);
  x[jp] += wp * kx; x[jp + 1] += wp * ky; x[jp + 2] += wp * kz;
  for (let k = 0; k < 3; k++) {
    const q = 3 * (k === 0 ? a : k === 1 ? b : c), m = (k === 0 ? wa : k === 1 ? wb : wc) * bary[k];
    x[q] -= m * kx; x[q + 1] -= m * ky; x[q + 2] -= m * kz;
  }
  track(sc, x, xp, p); track(sc, x, xp, a); track(sc, x, xp, b); track(sc, x, xp, c);
}

/**
 * The unit normal (b − a) × (c − a) of the triangle (ja, jb, jc) of array x into out[o…o+2]; NaN for a degenerate
 * triangle (then every plane distance from it is NaN).
 */
function unitNormal(x: Float32Array, ja: number, jb: number, jc: number, out: Float64Array, o: number): void {
  const ux = x[jb] - x[ja], uy = x[jb + 1] - x[ja + 1], uz = x[jb + 2] - x[ja + 2];
  const vx = x[jc] - x[ja], vy = x[jc + 1] - x[ja + 1], vz = x[jc + 2] - x[ja + 2];
  const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
  if (!(l > 1e-20)) { out[o] = out[o + 1] = out[o + 2] = NaN; return; }
  out[o] = nx / l; out[o + 1] = ny / l; out[o + 2] = nz / l;
}

/** The barycentric weights (into `bary`) of the projection of jp onto the triangle's plane, unclamped. */
function barycentric(x: Float32Array, jp: number, ja: number, jb: number, jc: number): void {
  const ux = x[jb] - x[ja], uy = x[jb + 1] - x[ja + 1], uz = x[jb + 2] - x[ja + 2];
  const vx = x[jc] - x[ja], vy = x[jc + 1] - x[ja + 1], vz = x[jc + 2] - x[ja + 2];
  const qx = x[jp] - x[ja], qy = x[jp + 1] - x[ja + 1], qz = x[jp + 2] - x[ja + 2];
  const uu = ux * ux + uy * uy + uz * uz, uv = ux * vx + uy * vy + uz * vz, vv = vx * vx + vy * vy + vz * vz;
  const qu = qx * ux + qy * uy + qz * uz, qv = qx * vx + qy * vy + qz * vz;
  const det = uu * vv - uv * uv;
  const b1 = det > 0 ? (vv * qu - uv * qv) / det : 0, b2 = det > 0 ? (uu * qv - uv * qu) / det : 0;
  bary[0] = 1 - b1 - b2; bary[1] = b1; bary[2] = b2;
}

/** Whether the projection of jp onto the triangle's plane lies inside it (weights left in `bary`). */
function projectionInside(x: Float32Array, jp: number, ja: number, jb: number, jc: number): boolean {
  barycentric(x, jp, ja, jb, jc);
  return bary[0] >= 0 && bary[1] >= 0 && bary[2] >= 0;
}

/** Distance from jp to the closest point of the triangle, into nearest[0]; its weights go into `bary` (Ericson 2005, §5.1.5). */
function closestPoint(x: Float32Array, jp: number, ja: number, jb: number, jc: number): void {
  const abx = x[jb] - x[ja], aby = x[jb + 1] - x[ja + 1], abz = x[jb + 2] - x[ja + 2];
  const acx = x[jc] - x[ja], acy = x[jc + 1] - x[ja + 1], acz = x[jc + 2] - x[ja + 2];
  const apx = x[jp] - x[ja], apy = x[jp + 1] - x[ja + 1], apz = x[jp + 2] - x[ja + 2];
  const d1 = abx * apx + aby * apy + abz * apz, d2 = acx * apx + acy * apy + acz * apz;
  let u: number, v: number; // weights of b and c
  if (d1 <= 0 && d2 <= 0) { u = 0; v = 0; } else {
    const bpx = x[jp] - x[jb], bpy = x[jp + 1] - x[jb + 1], bpz = x[jp + 2] - x[jb + 2];
    const d3 = abx * bpx + aby * bpy + abz * bpz, d4 = acx * bpx + acy * bpy + acz * bpz;
    const cpx = x[jp] - x[jc], cpy = x[jp + 1] - x[jc + 1], cpz = x[jp + 2] - x[jc + 2];
    const d5 = abx * cpx + aby * cpy + abz * cpz, d6 = acx * cpx + acy * cpy + acz * cpz;
    const vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) { u = 1; v = 0; }
    else if (d6 >= 0 && d5 <= d6) { u = 0; v = 1; }
    else if (vc <= 0 && d1 >= 0 && d3 <= 0) { u = d1 / (d1 - d3); v = 0; }
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) { u = 0; v = d2 / (d2 - d6); }
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) { v = (d4 - d3) / ((d4 - d3) + (d5 - d6)); u = 1 - v; }
    else { const den = 1 / (va + vb + vc); u = vb * den; v = vc * den; }
  }
  bary[0] = 1 - u - v; bary[1] = u; bary[2] = v;
  const cx = x[ja] + u * abx + v * acx, cy = x[ja + 1] + u * aby + v * acy, cz = x[ja + 2] + u * abz + v * acz;
  const ex = x[jp] - cx, ey = x[jp + 1] - cy, ez = x[jp + 2] - cz;
  nearest[0] = Math.sqrt(ex * ex + ey * ey + ez * ez);
}

/**
 * Edge against edge, after the particles against the triangles (the crossings those leave: two edges passing
 * through each other while every vertex stays outside the other's triangles). Each candidate pair of edges sharing
 * no particle whose boxes over the substep (each widened by h/2) meet: the closest points p (on a–b, at s) and q (on
 * c–d, at t), now and at the substep's start. **Passed through**: both pairs of closest points inside their edges
 * and the vector q→p now against its direction then — the edges are moved apart, by inverse mass and the weights
 * (1 − s, s, 1 − t, t), until p is on its side again at the pair's distance h_e along that direction. **Too near**:
 * apart to h_e along q→p. Friction as for the particles (Bridson, Fedkiw & Anderson 2002, §7.2's edge–edge
 * proximity, position-based). h_e is SELF_EDGE_SHARE (half) of h at rest and grows by δ, the sum of the two edges'
 * largest end moves over the substep, up to h: where layers lie on each other the particle pass already holds them
 * h apart, and the edge pass is there for what that pass cannot see (edges crossing with no vertex near), which needs
 * a margin for the motion, not the whole thickness (docs/physics.md, "Edge against edge").
 */
function collideEdges(model: ClothModel, state: ClothState, params: SimParams, s: SelfScratch, hMax: number): void {
  const edges = model.edges, ne = edges.length / 2;
  const x = state.positions, xp = state.previousPositions, w = state.invMass;
  // each box widened by h/2: two edges nearer than h have boxes that meet
  const boxes = s.edgeBoxes, pb = s.particleBoxes, r = 0.5 * hMax;
  for (let e = 0; e < ne; e++) {
    const b = 6 * e, i = 6 * edges[2 * e], j = 6 * edges[2 * e + 1];
    boxes[b] = Math.min(pb[i], pb[j]) - r;
    boxes[b + 1] = Math.min(pb[i + 1], pb[j + 1]) - r;
    boxes[b + 2] = Math.min(pb[i + 2], pb[j + 2]) - r;
    boxes[b + 3] = Math.max(pb[i + 3], pb[j + 3]) + r;
    boxes[b + 4] = Math.max(pb[i + 4], pb[j + 4]) + r;
    boxes[b + 5] = Math.max(pb[i + 5], pb[j + 5]) + r;
  }
  const owner = params.owner, { thickness, friction, staticFriction } = params.perCloth;
  const pairs = s.edgePairs;
  for (let q = 0; q < s.edgePairCount; q++) {
    const e = pairs[2 * q], f = pairs[2 * q + 1];
    if (!overlap(boxes, 6 * e, boxes, 6 * f)) continue;
    const a = edges[2 * e], b = edges[2 * e + 1], c = edges[2 * f], d = edges[2 * f + 1];
    const ca = owner[a], cc = owner[c];
    const k = pairOf;
    if (ca === cc) {
      k[PAIR_H] = Math.min(thickness[ca], hMax); k[PAIR_MU] = friction[ca]; k[PAIR_MU_S] = staticFriction[ca];
    } else {
      k[PAIR_H] = Math.min(0.5 * (thickness[ca] + thickness[cc]), hMax);
      k[PAIR_MU] = Math.sqrt(friction[ca] * friction[cc]); k[PAIR_MU_S] = Math.sqrt(staticFriction[ca] * staticFriction[cc]);
    }
    resolveEdges(s, x, xp, w, q, e, f, a, b, c, d);
  }
}

/** closest points of two segments: the parameters on each (segmentClosest) */
const st = new Float64Array(2);
/** the vector q→p between them now, and then */
const gap = new Float64Array(3);
const gap0 = new Float64Array(3);

/**
 * Closest points of segments a–b and c–d of array x (Ericson 2005, §5.1.9): their parameters into `st` (p = a +
 * s(b − a), q = c + t(d − c)), the vector p − q into `out`, its length into nearest[0].
 */
function segmentClosest(x: Float32Array, a: number, b: number, c: number, d: number, out: Float64Array): void {
  const ja = 3 * a, jb = 3 * b, jc = 3 * c, jd = 3 * d;
  const ux = x[jb] - x[ja], uy = x[jb + 1] - x[ja + 1], uz = x[jb + 2] - x[ja + 2];
  const vx = x[jd] - x[jc], vy = x[jd + 1] - x[jc + 1], vz = x[jd + 2] - x[jc + 2];
  const rx = x[ja] - x[jc], ry = x[ja + 1] - x[jc + 1], rz = x[ja + 2] - x[jc + 2];
  const A = ux * ux + uy * uy + uz * uz, E = vx * vx + vy * vy + vz * vz, F = vx * rx + vy * ry + vz * rz;
  let s = 0, t = 0;
  if (A <= 1e-24 && E <= 1e-24) { s = 0; t = 0; } else if (A <= 1e-24) { t = Math.min(Math.max(F / E, 0), 1); } else {
    const C = ux * rx + uy * ry + uz * rz;
    if (E <= 1e-24) { s = Math.min(Math.max(-C / A, 0), 1); } else {
      const B = ux * vx + uy * vy + uz * vz, den = A * E - B * B;
      s = den > 1e-24 ? Math.min(Math.max((B * F - C * E) / den, 0), 1) : 0;
      t = (B * s + F) / E;
      if (t < 0) { t = 0; s = Math.min(Math.max(-C / A, 0), 1); } else if (t > 1) { t = 1; s = Math.min(Math.max((B - C) / A, 0), 1); }
    }
  }
  st[0] = s; st[1] = t;
  out[0] = rx + s * ux - t * vx; out[1] = ry + s * uy - t * vy; out[2] = rz + s * uz - t * vz;
  nearest[0] = Math.sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
}

/**
 * Whether the closest point's parameter params[i] lies inside its edge (not at an end): read from the array, not
 * passed (a number passed to a call V8 does not inline is boxed: colliders/shape.ts).
 */
function inside(params: Float64Array, i: number): boolean {
  return params[i] > 1e-6 && params[i] < 1 - 1e-6;
}

/** resolveEdges' closest points' parameters now, kept while segmentClosest measures them at the substep's start */
const stNow = new Float64Array(2);

/**
 * Edge e = (a, b)'s frame (SelfScratch.edgeFrame: its midpoint now and half its vector), computed unless it is
 * current; returns its offset in edgeFrame.
 */
function edgeFrame(s: SelfScratch, x: Float32Array, e: number, a: number, b: number): number {
  const o = 6 * e, at = s.edgeFrameAt[e];
  if (at >= s.substepAt && s.movedAt[a] <= at && s.movedAt[b] <= at) return o;
  const f = s.edgeFrame, ja = 3 * a, jb = 3 * b;
  f[o] = 0.5 * (x[ja] + x[jb]); f[o + 1] = 0.5 * (x[ja + 1] + x[jb + 1]); f[o + 2] = 0.5 * (x[ja + 2] + x[jb + 2]);
  f[o + 3] = 0.5 * (x[jb] - x[ja]); f[o + 4] = 0.5 * (x[jb + 1] - x[ja + 1]); f[o + 5] = 0.5 * (x[jb + 2] - x[ja + 2]);
  s.edgeFrameAt[e] = s.clock;
  return o;
}

/**
 * Edges e = a–b and f = c–d, pair q of the list: passed through, or too near (see collideEdges), kept h_e [m] apart
 * (the pair's h, pairOf, made min(h, SELF_EDGE_SHARE·h + δ)) with friction mu, muS [-]. A pair at least h_e and δ
 * apart now, δ the sum of the edges' largest end moves over the substep, is neither too near nor passed through
 * (passing through needs the distance now to be at most δ: q→p then differs by at most δ from the vector between
 * the points of the same parameters now, whose dot product with q→p now is at least |q→p now|², the closest point
 * of a convex set). Three lower bounds on the distance now say
 * so before the closest points: the pair's last measured distance less what its particles travelled since (a
 * segment moves no farther than its ends); along the line through the midpoints each segment spans its extent
 * along that line (the separation of the two projections); and the closest points now, measured.
 */
function resolveEdges(
  sc: SelfScratch, x: Float32Array, xp: Float32Array, w: Float32Array,
  q: number, e: number, f: number, a: number, b: number, c: number, d: number,
): void {
  const move = sc.move, travel = sc.travel, memo = sc.edgeMemo;
  const motion = Math.max(move[a], move[b]) + Math.max(move[c], move[d]);
  const h = Math.min(pairOf[PAIR_H], EDGE_SHARE * pairOf[PAIR_H] + motion), mu = pairOf[PAIR_MU], muS = pairOf[PAIR_MU_S];
  const apart = Math.max(h, motion) + SKIP_MARGIN;
  // each edge's ends summed first (the kernel keeps them so, per edge)
  const travelled = (travel[a] + travel[b]) + (travel[c] + travel[d]);
  if (memo[2 * q] - (travelled - memo[2 * q + 1]) >= apart) return;
  memo[2 * q + 1] = travelled;
  const oe = edgeFrame(sc, x, e, a, b), of = edgeFrame(sc, x, f, c, d), fr = sc.edgeFrame;
  const mx = fr[oe] - fr[of], my = fr[oe + 1] - fr[of + 1], mz = fr[oe + 2] - fr[of + 2];
  const m2 = mx * mx + my * my + mz * mz, ml = Math.sqrt(m2);
  const extent = Math.abs(mx * fr[oe + 3] + my * fr[oe + 4] + mz * fr[oe + 5]) + Math.abs(mx * fr[of + 3] + my * fr[of + 4] + mz * fr[of + 5]);
  // |m| − the half extents along m̂, times |m| (strictly: coinciding midpoints prove nothing)
  if (m2 - extent > apart * ml) {
    memo[2 * q] = (m2 - extent) / ml;
    return;
  }
  segmentClosest(x, a, b, c, d, gap);
  const len = nearest[0];
  memo[2 * q] = len;
  if (len >= apart) return;
  const s = st[0], t = st[1];
  stNow[0] = s; stNow[1] = t;
  segmentClosest(xp, a, b, c, d, gap0);
  const len0 = nearest[0];
  const in0 = inside(st, 0) && inside(st, 1);
  if (!Number.isFinite(len) || !Number.isFinite(len0)) return;
  let C: number;
  if (in0 && inside(stNow, 0) && inside(stNow, 1) && len0 > 1e-12 && gap[0] * gap0[0] + gap[1] * gap0[1] + gap[2] * gap0[2] < 0) {
    // passed through: back to the side of then, h along that direction
    dir[0] = gap0[0] / len0; dir[1] = gap0[1] / len0; dir[2] = gap0[2] / len0;
    C = gap[0] * dir[0] + gap[1] * dir[1] + gap[2] * dir[2] - h;
  } else {
    if (len >= h || len < 1e-12) return;
    dir[0] = gap[0] / len; dir[1] = gap[1] / len; dir[2] = gap[2] / len;
    C = len - h;
  }
  const ka = 1 - s, kb = s, kc = 1 - t, kd = t;
  const wa = w[a], wb = w[b], wc = w[c], wd = w[d];
  const denom = ka * ka * wa + kb * kb * wb + kc * kc * wc + kd * kd * wd;
  if (!(denom > 0)) return;
  const lambda = -C / denom, depth = -C;
  // friction: the relative tangential motion of p against q over the substep
  const ja = 3 * a, jb = 3 * b, jc = 3 * c, jd = 3 * d;
  const rx = ka * (x[ja] - xp[ja]) + kb * (x[jb] - xp[jb]) - kc * (x[jc] - xp[jc]) - kd * (x[jd] - xp[jd]);
  const ry = ka * (x[ja + 1] - xp[ja + 1]) + kb * (x[jb + 1] - xp[jb + 1]) - kc * (x[jc + 1] - xp[jc + 1]) - kd * (x[jd + 1] - xp[jd + 1]);
  const rz = ka * (x[ja + 2] - xp[ja + 2]) + kb * (x[jb + 2] - xp[jb + 2]) - kc * (x[jc + 2] - xp[jc + 2]) - kd * (x[jd + 2] - xp[jd + 2]);
  const rn = rx * dir[0] + ry * dir[1] + rz * dir[2];
  const tx = rx - rn * dir[0], ty = ry - rn * dir[1], tz = rz - rn * dir[2];
  const tl = Math.sqrt(tx * tx + ty * ty + tz * tz);
  const fs = tl < 1e-12 ? 0 : tl < muS * depth ? 1 : Math.min((mu * depth) / tl, 1);
  const kx = lambda * dir[0] - (fs * tx) / denom, ky = lambda * dir[1] - (fs * ty) / denom, kz = lambda * dir[2] - (fs * tz) / denom;
  moved(sc, a, b, c, d);
  x[ja] += wa * ka * kx; x[ja + 1] += wa * ka * ky; x[ja + 2] += wa * ka * kz;
  x[jb] += wb * kb * kx; x[jb + 1] += wb * kb * ky; x[jb + 2] += wb * kb * kz;
  x[jc] -= wc * kc * kx; x[jc + 1] -= wc * kc * ky; x[jc + 2] -= wc * kc * kz;
  x[jd] -= wd * kd * kx; x[jd + 1] -= wd * kd * ky; x[jd + 2] -= wd * kd * kz;
  track(sc, x, xp, a); track(sc, x, xp, b); track(sc, x, xp, c); track(sc, x, xp, d);
}
