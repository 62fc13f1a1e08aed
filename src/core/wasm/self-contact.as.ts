// Self-contact's narrow phase (the selfContact phase; self-contact.ts is the reference and says what it does): each
// substep, every particle's box over the substep and the check that it is still inside its reach box, then the
// particle–triangle pass and the edge–edge pass over the candidate pairs found ahead (by selfSearch, self-search.as.ts,
// or where its windows overflow by the host's findCandidates in TypeScript, copied here). The same operations in the same order as the reference, f64 on the f32 positions, so
// the same cloth bit for bit. One thread, a Gauss–Seidel pass in the pairs' order: the host calls these on thread 0
// between two substep() calls (the helpers wait for the next dispatch).
import { N, W, X, XP } from './arrays.as';
import { SELF_EDGE_SHARE, SELF_SKIP_MARGIN as SKIP_MARGIN } from './layout.generated.as';

// The arrays (byte offsets, laid out by the host: self-contact-wasm.ts) and counts, set by configureSelf().
/** the triangles' particles, u32 × 3 per triangle */
export let TRIS: usize = 0;
/** the edges' particles, u32 × 2 per edge */
export let EDGES: usize = 0;
/** the cloth of each particle, u8 */
let OWNER: usize = 0;
/** per cloth: thickness [m], kinetic and static friction [-], f64 × 3 */
let CLOTH: usize = 0;
/** each particle's reach box (selfSearch's, or the host's copied after a search in TypeScript), f64 × 6: min x, y, z, max x, y, z [m] */
export let REACH: usize = 0;
/** each particle's box over the substep, f64 × 6 [m] */
let PBOX: usize = 0;
/**
 * each triangle's box over the substep widened by h, f64 × 6 [m], made when the particle pass first reads it
 * (triangleBox), and the particle pass it was made for (i32: boxEpoch)
 */
let TBOX: usize = 0;
let TBOX_AT: usize = 0;
/**
 * each edge's record for the edge pass, 64 bytes (a cache line): its box over the substep widened by h/2, f64 × 6
 * [m]; its ends' travel summed [m] and their larger move over the substep [m], f64 each (made when the edge pass
 * first reads it, edgeRecord, and kept so through the pass: edgesOf), and the edge pass it was made for (i32: boxEpoch)
 */
let EBOX: usize = 0;
let EBOX_AT: usize = 0;
/** the edges of each particle, as rows: where each particle's start (i32 × (particles + 1)) in the list (i32) */
export let PEDGE_START: usize = 0;
export let PEDGE_LIST: usize = 0;
/**
 * each triangle's frame, f64 × 10: the unit normal now and at the substep's start, the centroid now [m], the
 * largest distance of a corner from it [m]; each edge's, f64 × 6: its midpoint now [m], half its vector b − a now [m]
 */
let TFRAME: usize = 0;
let EFRAME: usize = 0;
/** the clock when each triangle's and each edge's frame was computed, and when each particle last moved, i32 */
let TFRAME_AT: usize = 0;
let EFRAME_AT: usize = 0;
let MOVED_AT: usize = 0;
/** the candidate pairs: (particle, triangle) and (edge, edge), i32 × 2 each */
export let PAIRS: usize = 0;
export let EDGE_PAIRS: usize = 0;
/**
 * how far each particle can have moved since the candidates were found [m], f64 (the sum of its moves between the
 * times self-contact looked at it: each phase's start, each correction), and where it was the last time, f32 × 3
 */
let TRAVEL: usize = 0;
let SEEN: usize = 0;
/** each particle's move over the substep so far, |x − x_prev| [m], f64 */
let MOVE: usize = 0;
/**
 * per edge pair of EDGE_PAIRS: a lower bound on its distance [m] once measured (−∞ before) and its four particles'
 * travel then [m], f64 × 2
 */
export let EDGE_MEMO: usize = 0;
/** the particles out of their reach boxes at the last selfBoxes, i32 (the first selfBoxes returned) */
export let ESCAPED: usize = 0;
/** triangles and edges */
let NT: i32 = 0;
let NE: i32 = 0;

/**
 * counts substeps and corrections: a frame is current while it was computed in this substep (at or after
 * substepAt) and none of its particles moved after it. Reset (every frame made stale) before it could overflow.
 */
let clock: i32 = 0;
let substepAt: i32 = 0;
/**
 * counts the passes (two a substep): a triangle's box or an edge's record is this pass's where the pass made them all
 * (allMade) or its stamp (TBOX_AT, EBOX_AT) is boxEpoch; and the distance h [m] the pass widens them by. A pass with
 * fewer pairs than LAZY_SHARE of its primitives makes only those its pairs read, as they read them (a cloth at rest, its
 * layers apart: the pass costs its pairs, not the cloth); one with more makes them all first, in order, which costs
 * less than reading them scattered. Either way from the same numbers (the particles' boxes do not change during a
 * pass), so the same boxes.
 */
let boxEpoch: i32 = 0;
let boxH: f64 = 0;
let allMade = false;
/** pairs per primitive below which a pass makes only the boxes its pairs read */
const LAZY_SHARE: f64 = 0.5;

/**
 * The frame the reach boxes are made in (self-contact.ts movingFrame): its motion per substep [m] and the substeps
 * since the last search (a point x at the end of this substep is at x − J·U in it, at its start x − (J − 1)·U).
 */
export let FRAME_UX: f64 = 0;
export let FRAME_UY: f64 = 0;
export let FRAME_UZ: f64 = 0;
export let FRAME_J: f64 = 0;

/** Sets the frame of reach boxes found in TypeScript (self-contact-wasm.ts), 0 substeps since. */
export function selfFrame(ux: f64, uy: f64, uz: f64): void {
  FRAME_UX = ux; FRAME_UY = uy; FRAME_UZ = uz; FRAME_J = 0;
}

/** Component k of the frame's motion per substep [m]. */
@inline export function frameU(k: usize): f64 { return k == 0 ? FRAME_UX : k == 1 ? FRAME_UY : FRAME_UZ; }

/** Sets the arrays' byte offsets and the counts (the host's layout). */
export function configureSelf(
  tris: usize, edges: usize, owner: usize, cloth: usize, reach: usize, pbox: usize, tbox: usize, ebox: usize,
  tframe: usize, eframe: usize, tframeAt: usize, eframeAt: usize, movedAt: usize, pairs: usize, edgePairs: usize,
  travel: usize, seen: usize, move: usize, edgeMemo: usize, escaped: usize, edgeStart: usize, edgeList: usize,
  triangles: i32, edgeCount: i32, tboxAt: usize, eboxAt: usize,
): void {
  TRIS = tris; EDGES = edges; OWNER = owner; CLOTH = cloth; REACH = reach; PBOX = pbox; TBOX = tbox; EBOX = ebox;
  TBOX_AT = tboxAt; EBOX_AT = eboxAt;
  TFRAME = tframe; EFRAME = eframe; TFRAME_AT = tframeAt; EFRAME_AT = eframeAt; MOVED_AT = movedAt;
  PAIRS = pairs; EDGE_PAIRS = edgePairs; TRAVEL = travel; SEEN = seen; MOVE = move; EDGE_MEMO = edgeMemo;
  ESCAPED = escaped; PEDGE_START = edgeStart; PEDGE_LIST = edgeList;
  NT = triangles; NE = edgeCount;
  resetClock();
}

/** Every frame stale, the clock back at 0. */
function resetClock(): void {
  for (let t = 0; t < NT; t++) store<i32>(TFRAME_AT + (<usize>t << 2), -1);
  for (let e = 0; e < NE; e++) store<i32>(EFRAME_AT + (<usize>e << 2), -1);
  for (let p = 0; p < N; p++) store<i32>(MOVED_AT + (<usize>p << 2), 0);
  clock = 0;
  resetBoxes();
}

/** Every triangle's box and edge's record stale, the passes' count back at 0. */
function resetBoxes(): void {
  memory.fill(TBOX_AT, 0xff, <usize>NT << 2);
  memory.fill(EBOX_AT, 0xff, <usize>NE << 2);
  boxEpoch = 0;
}

/**
 * A new pass over `pairs` pairs of `primitives` triangles or edges: every box stale, to be made widened by `h` [m];
 * whether the pass makes them all first (allMade).
 */
function nextPass(h: f64, pairs: i32, primitives: i32): bool {
  if (boxEpoch > 1 << 30) resetBoxes();
  boxEpoch++;
  boxH = h;
  allMade = <f64>pairs >= LAZY_SHARE * <f64>primitives;
  return allMade;
}

/** Coordinate k (0, 1, 2) of particle byte offset j of the positions now / at the substep's start [m]. */
@inline function xn(j: usize, k: usize): f64 { return <f64>load<f32>(X + j + (k << 2)); }
@inline function xs(j: usize, k: usize): f64 { return <f64>load<f32>(XP + j + (k << 2)); }
/** Adds d [m] to coordinate k of particle byte offset j now (rounded to f32, as the reference's `x[j] += d`). */
@inline function addX(j: usize, k: usize, d: f64): void {
  const at = X + j + (k << 2);
  store<f32>(at, <f32>(<f64>load<f32>(at) + d));
}
/** Math.sign as the reference reads it (its sign of ±0 is 0 for these comparisons). */
@inline function sign(v: f64): f64 { return v > 0 ? 1 : v < 0 ? -1 : 0; }
/** Field k of an f64 array at byte offset `base`. */
@inline function f64At(base: usize, k: usize): f64 { return load<f64>(base + (k << 3)); }

/**
 * Each particle's box over the substep (x_prev to x) into PBOX, and (`start`: the phase's start, a new substep in the
 * reach boxes' frame) its travel and move (track); the particles whose box, in the frame of the reach boxes, does not
 * lie inside their reach box (a non-finite position's does not) into ESCAPED, and how many they are (0: the
 * candidates hold): self-contact.ts substepBoxes().
 */
export function selfBoxes(start: bool): i32 {
  if (start) FRAME_J += 1;
  const J = FRAME_J;
  // the frame's offsets at the substep's end and start (J·U, (J − 1)·U): x and y as two lanes, z alone; each
  // particle's the same way below, the same IEEE operations as coordinate by coordinate
  const u = f64x2.replace_lane(f64x2.splat(FRAME_UX), 1, FRAME_UY);
  const nowU = f64x2.mul(f64x2.splat(J), u), thenU = f64x2.mul(f64x2.splat(J - 1), u);
  const nowUZ = J * FRAME_UZ, thenUZ = (J - 1) * FRAME_UZ;
  let out = 0;
  for (let p = 0; p < N; p++) {
    // after the particle pass, only those it moved can have left their boxes (the others were inside them, or were
    // given boxes around where they are, and have not moved)
    if (!start && load<i32>(MOVED_AT + (<usize>p << 2)) <= substepAt) continue;
    const j = <usize>p * 12, box = PBOX + <usize>p * 48, reach = REACH + <usize>p * 48;
    const a = f64x2.promote_low_f32x4(v128.load64_zero(X + j)), b = f64x2.promote_low_f32x4(v128.load64_zero(XP + j));
    const az = xn(j, 2), bz = xs(j, 2);
    v128.store(box, f64x2.min(a, b)); store<f64>(box, min(az, bz), 16);
    v128.store(box, f64x2.max(a, b), 24); store<f64>(box, max(az, bz), 40);
    const now = f64x2.sub(a, nowU), then = f64x2.sub(b, thenU), nowZ = az - nowUZ, thenZ = bz - thenUZ;
    // !(min ≥ reach min && max ≤ reach max) on any axis: out (a NaN compares false, so it is out)
    const inXY = v128.and(f64x2.ge(f64x2.min(now, then), v128.load(reach)), f64x2.le(f64x2.max(now, then), v128.load(reach, 24)));
    if (!(i64x2.all_true(inXY) & (min(nowZ, thenZ) >= f64At(reach, 2)) & (max(nowZ, thenZ) <= f64At(reach, 5)))) {
      store<i32>(ESCAPED + (<usize>(out++) << 2), p);
    }
    if (start) track(p);
  }
  return out;
}

/** Particle p's travel up to where it is now (TRAVEL, SEEN) and its move over the substep so far (MOVE). */
function track(p: u32): void {
  const j = <usize>p * 12, seen = SEEN + j;
  // x and y as two lanes: (dx² + dy²) + dz² for the travel and the move, as the scalar sums, both roots at once
  const x = f64x2.promote_low_f32x4(v128.load64_zero(X + j)), xz = xn(j, 2);
  const d = f64x2.sub(x, f64x2.promote_low_f32x4(v128.load64_zero(seen))), dz = xz - <f64>load<f32>(seen, 8);
  const m = f64x2.sub(x, f64x2.promote_low_f32x4(v128.load64_zero(XP + j))), mz = xz - xs(j, 2);
  const d2 = f64x2.mul(d, d), m2 = f64x2.mul(m, m);
  const xx = v128.shuffle<f64>(d2, m2, 0, 2), yy = v128.shuffle<f64>(d2, m2, 1, 3);
  const roots = f64x2.sqrt(f64x2.add(f64x2.add(xx, yy), f64x2.replace_lane(f64x2.splat(dz * dz), 1, mz * mz)));
  const t = TRAVEL + (<usize>p << 3);
  store<f64>(t, load<f64>(t) + f64x2.extract_lane(roots, 0));
  store<i64>(seen, load<i64>(X + j)); store<f32>(seen, load<f32>(X + j, 8), 8);
  store<f64>(MOVE + (<usize>p << 3), f64x2.extract_lane(roots, 1));
}

/**
 * After a search: distances are measured again from here (every particle's travel 0 from where it is, the first
 * `edgePairs` pairs' memo unknown).
 */
export function selfFound(edgePairs: i32): void {
  for (let p = 0; p < N; p++) {
    const j = <usize>p * 12;
    store<f64>(TRAVEL + (<usize>p << 3), 0);
    store<f32>(SEEN + j, load<f32>(X + j)); store<f32>(SEEN + j, load<f32>(X + j, 4), 4); store<f32>(SEEN + j, load<f32>(X + j, 8), 8);
  }
  for (let q = 0; q < edgePairs; q++) {
    store<f64>(EDGE_MEMO + (<usize>q << 4), -Infinity);
    store<f64>(EDGE_MEMO + (<usize>q << 4), -Infinity, 8);
  }
}

/**
 * A new particle pass over `pairs` pairs, the start of collideSelf's: the triangles' boxes over the substep (their
 * corners' PBOX), widened by hMax [m], made now or as the pass reads them (triangleBox), and a new substep for the
 * frames.
 */
export function selfTriangleBoxes(hMax: f64, pairs: i32): void {
  if (nextPass(hMax, pairs, NT)) for (let t = 0; t < NT; t++) makeTriangleBox(t);
  if (clock > 1 << 30) resetClock();
  substepAt = ++clock;
}

/** Triangle t's box over the substep widened by the pass's h (TBOX), made unless it is this pass's; its byte offset. */
@inline function triangleBox(t: i32): usize {
  const at = TBOX_AT + (<usize>t << 2);
  if (allMade || load<i32>(at) == boxEpoch) return TBOX + <usize>t * 48;
  store<i32>(at, boxEpoch);
  return makeTriangleBox(t);
}

/** Makes triangle t's box over the substep widened by the pass's h (TBOX); its byte offset. */
@inline function makeTriangleBox(t: i32): usize {
  const b = TBOX + <usize>t * 48, tr = TRIS + <usize>t * 12, r = boxH;
  const lo = f64x2.splat(-r), hi = f64x2.splat(r), mixed = f64x2.replace_lane(hi, 0, -r), low = i64x2(-1, 0);
  const i = PBOX + <usize>load<u32>(tr) * 48, j = PBOX + <usize>load<u32>(tr, 4) * 48, k = PBOX + <usize>load<u32>(tr, 8) * 48;
  // lanes (min x, min y), (min z, max x), (max y, max z): pmin/pmax, one instruction each (no NaN reaches here:
  // a non-finite position fails the reach check first; ±0 give the same box once widened)
  const i1 = v128.load(i, 16), j1 = v128.load(j, 16), k1 = v128.load(k, 16);
  v128.store(b, f64x2.add(f64x2.pmin(f64x2.pmin(v128.load(i), v128.load(j)), v128.load(k)), lo));
  v128.store(b, f64x2.add(v128.bitselect(f64x2.pmin(f64x2.pmin(i1, j1), k1), f64x2.pmax(f64x2.pmax(i1, j1), k1), low), mixed), 16);
  v128.store(b, f64x2.add(f64x2.pmax(f64x2.pmax(v128.load(i, 32), v128.load(j, 32)), v128.load(k, 32)), hi), 32);
  return b;
}

/**
 * A new edge pass over `pairs` pairs, the start of collideEdges: the edges' records (EBOX), their boxes over the
 * substep (their ends' PBOX) widened by hMax/2 [m] and their ends' travel and move, made now or as the pass reads
 * them (edgeRecord).
 */
export function selfEdgeBoxes(hMax: f64, pairs: i32): void {
  if (nextPass(0.5 * hMax, pairs, NE)) for (let e = 0; e < NE; e++) makeEdgeRecord(e);
}

/** Whether edge e's record is this pass's (then edgesOf keeps it current). */
@inline function recordMade(e: i32): bool { return allMade || load<i32>(EBOX_AT + (<usize>e << 2)) == boxEpoch; }

/** Edge e's record (EBOX), made unless it is this pass's; its byte offset. */
@inline function edgeRecord(e: i32): usize {
  if (recordMade(e)) return EBOX + (<usize>e << 6);
  store<i32>(EBOX_AT + (<usize>e << 2), boxEpoch);
  return makeEdgeRecord(e);
}

/** Makes edge e's record (EBOX): its box widened by the pass's h, its ends' travel and move; its byte offset. */
@inline function makeEdgeRecord(e: i32): usize {
  const b = EBOX + (<usize>e << 6), ed = EDGES + <usize>e * 8, r = boxH;
  edgeEnds(e);
  const lo = f64x2.splat(-r), hi = f64x2.splat(r), mixed = f64x2.replace_lane(hi, 0, -r), low = i64x2(-1, 0);
  const i = PBOX + <usize>load<u32>(ed) * 48, j = PBOX + <usize>load<u32>(ed, 4) * 48;
  // as triangleBox
  const i1 = v128.load(i, 16), j1 = v128.load(j, 16);
  v128.store(b, f64x2.add(f64x2.pmin(v128.load(i), v128.load(j)), lo));
  v128.store(b, f64x2.add(v128.bitselect(f64x2.pmin(i1, j1), f64x2.pmax(i1, j1), low), mixed), 16);
  v128.store(b, f64x2.add(f64x2.pmax(v128.load(i, 32), v128.load(j, 32)), hi), 32);
  return b;
}

/** Edge e's ends' travel summed [m] (what its record holds, EBOX). */
@inline function edgeTravel(e: i32): f64 {
  const ed = EDGES + <usize>e * 8;
  return perParticle(TRAVEL, load<u32>(ed)) + perParticle(TRAVEL, load<u32>(ed, 4));
}

/** The larger of edge e's ends' moves over the substep [m] (what its record holds, EBOX). */
@inline function edgeMove(e: i32): f64 {
  const ed = EDGES + <usize>e * 8;
  return max(perParticle(MOVE, load<u32>(ed)), perParticle(MOVE, load<u32>(ed, 4)));
}

/** Edge e's record's travel and move (EBOX), as they are now. */
@inline function edgeEnds(e: i32): void {
  const b = EBOX + (<usize>e << 6);
  store<f64>(b, edgeTravel(e), 48);
  store<f64>(b, edgeMove(e), 56);
}

/**
 * How many of the last edge pass's records (EBOX) do not hold their ends' travel and move as they are now, or their
 * box as their ends' boxes (PBOX) make it (tests: none, after a pass).
 */
export function selfStaleEdges(): i32 {
  let stale = 0;
  for (let e = 0; e < NE; e++) {
    if (!recordMade(e)) continue;
    const b = EBOX + (<usize>e << 6), ed = EDGES + <usize>e * 8;
    const i = PBOX + <usize>load<u32>(ed) * 48, j = PBOX + <usize>load<u32>(ed, 4) * 48;
    let box = true;
    for (let k: usize = 0; k < 3; k++) {
      box = box && f64At(b, k) == min(f64At(i, k), f64At(j, k)) - boxH && f64At(b, k + 3) == max(f64At(i, k + 3), f64At(j, k + 3)) + boxH;
    }
    if (!box || load<f64>(b, 48) != edgeTravel(e) || load<f64>(b, 56) != edgeMove(e)) stale++;
  }
  return stale;
}

/** How many edges' records the last edge pass made (tests: the check above reads these). */
export function selfEdgeRecords(): i32 {
  let made = 0;
  for (let e = 0; e < NE; e++) if (recordMade(e)) made++;
  return made;
}

/** The records of the edges of particle p made in this pass, after it moved (edgeEnds; the others are made when read). */
function edgesOf(p: u32): void {
  for (let i = load<i32>(PEDGE_START + (<usize>p << 2)), end = load<i32>(PEDGE_START + ((<usize>p + 1) << 2)); i < end; i++) {
    const e = load<i32>(PEDGE_LIST + (<usize>i << 2));
    if (recordMade(e)) edgeEnds(e);
  }
}

/**
 * Whether the point of f32 positions `base` at byte offset j lies in the box at byte offset b: the comparisons of
 * !(x < min x || x > max x || …), x and y two lanes at a time, without branches.
 */
@inline function pointInBox(b: usize, base: usize, j: usize): bool {
  const xy = f64x2.promote_low_f32x4(v128.load64_zero(base + j)), z = <f64>load<f32>(base + j, 8);
  const out = v128.or(f64x2.lt(xy, v128.load(b)), f64x2.gt(xy, v128.load(b, 24)));
  return !v128.any_true(out) & !(z < f64At(b, 2)) & !(z > f64At(b, 5));
}

/** Whether the boxes at byte offsets a and b meet. */
@inline export function overlap(a: usize, b: usize): bool {
  // the same comparisons as !(a.min > b.max || b.min > a.max) axis by axis, x and y two lanes at a time, without
  // branches (a traversal's tests are as often true as not)
  const apart = v128.or(f64x2.gt(v128.load(a), v128.load(b, 24)), f64x2.gt(v128.load(b), v128.load(a, 24)));
  return !v128.any_true(apart) & !(f64At(a, 2) > f64At(b, 5)) & !(f64At(b, 2) > f64At(a, 5));
}

/** Cloth c's thickness [m], kinetic and static friction [-]. */
@inline function clothValue(c: i32, k: usize): f64 { return f64At(CLOTH + <usize>c * 24, k); }

/**
 * Particle–triangle pairs [0, count) of PAIRS, in order, as collideSelf's particle pass: a particle whose
 * position now or then lies in the triangle's box, with its pair's distance (at most hMax [m]) and friction.
 */
export function selfParticles(count: i32, hMax: f64): void {
  for (let q = 0; q < count; q++) {
    const pr = PAIRS + (<usize>q << 3);
    const p = load<i32>(pr), t = load<i32>(pr, 4);
    const jp = <usize>p * 12, bb = triangleBox(t);
    if (!(pointInBox(bb, X, jp) | pointInBox(bb, XP, jp))) continue;
    const tr = TRIS + <usize>t * 12;
    const a = load<u32>(tr), b = load<u32>(tr, 4), c = load<u32>(tr, 8);
    const cp = <i32>load<u8>(OWNER + <usize>p), ct = <i32>load<u8>(OWNER + <usize>a);
    if (cp == ct) {
      resolvePair(min(clothValue(cp, 0), hMax), clothValue(cp, 1), clothValue(cp, 2), p, t, a, b, c);
    } else {
      const hp = min(0.5 * (clothValue(cp, 0) + clothValue(ct, 0)), hMax);
      resolvePair(hp, Math.sqrt(clothValue(cp, 1) * clothValue(ct, 1)), Math.sqrt(clothValue(cp, 2) * clothValue(ct, 2)), p, t, a, b, c);
    }
  }
}

/** Marks particles as moved by a correction (their triangles' and edges' frames are computed again). */
function moved(a: u32, b: u32, c: u32, d: u32): void {
  const now = ++clock;
  store<i32>(MOVED_AT + (<usize>a << 2), now);
  store<i32>(MOVED_AT + (<usize>b << 2), now);
  store<i32>(MOVED_AT + (<usize>c << 2), now);
  store<i32>(MOVED_AT + (<usize>d << 2), now);
}

/** Whether particle p has not moved since clock value `at`. */
@inline function stillSince(p: u32, at: i32): bool { return load<i32>(MOVED_AT + (<usize>p << 2)) <= at; }

/** The unit normal of triangle (ja, jb, jc) (byte offsets) of positions `base` into the f64s at `out`; NaN if degenerate. */
function unitNormal(base: usize, ja: usize, jb: usize, jc: usize, out: usize): void {
  const ax = <f64>load<f32>(base + ja), ay = <f64>load<f32>(base + ja, 4), az = <f64>load<f32>(base + ja, 8);
  const ux = <f64>load<f32>(base + jb) - ax, uy = <f64>load<f32>(base + jb, 4) - ay, uz = <f64>load<f32>(base + jb, 8) - az;
  const vx = <f64>load<f32>(base + jc) - ax, vy = <f64>load<f32>(base + jc, 4) - ay, vz = <f64>load<f32>(base + jc, 8) - az;
  const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
  if (!(l > 1e-20)) {
    store<f64>(out, NaN); store<f64>(out, NaN, 8); store<f64>(out, NaN, 16);
    return;
  }
  store<f64>(out, nx / l); store<f64>(out, ny / l, 8); store<f64>(out, nz / l, 16);
}

/** Triangle t's frame (TFRAME), computed unless it is current; returns its byte offset. */
function triangleFrame(t: i32, a: u32, b: u32, c: u32): usize {
  const o = TFRAME + <usize>t * 80, atP = TFRAME_AT + (<usize>t << 2), at = load<i32>(atP);
  const thisSubstep = at >= substepAt;
  if (thisSubstep && stillSince(a, at) && stillSince(b, at) && stillSince(c, at)) return o;
  const ja = <usize>a * 12, jb = <usize>b * 12, jc = <usize>c * 12;
  unitNormal(X, ja, jb, jc, o);
  // as the reference: the normal at the substep's start, once made in this substep, holds
  if (!thisSubstep) unitNormal(XP, ja, jb, jc, o + 24);
  const cx = (xn(ja, 0) + xn(jb, 0) + xn(jc, 0)) / 3, cy = (xn(ja, 1) + xn(jb, 1) + xn(jc, 1)) / 3, cz = (xn(ja, 2) + xn(jb, 2) + xn(jc, 2)) / 3;
  store<f64>(o, cx, 48); store<f64>(o, cy, 56); store<f64>(o, cz, 64);
  const ax = xn(ja, 0) - cx, ay = xn(ja, 1) - cy, az = xn(ja, 2) - cz;
  const bx = xn(jb, 0) - cx, by = xn(jb, 1) - cy, bz = xn(jb, 2) - cz;
  const qx = xn(jc, 0) - cx, qy = xn(jc, 1) - cy, qz = xn(jc, 2) - cz;
  store<f64>(o, Math.sqrt(max(max(ax * ax + ay * ay + az * az, bx * bx + by * by + bz * bz), qx * qx + qy * qy + qz * qz)), 72);
  store<i32>(atP, clock);
  return o;
}

// barycentric weights of the last projection or closest point, and the correction's direction
let B0: f64 = 0, B1: f64 = 0, B2: f64 = 0;
let DX: f64 = 0, DY: f64 = 0, DZ: f64 = 0;

/** The weights (B0, B1, B2) of the projection of jp onto the plane of (ja, jb, jc) of positions `base`, unclamped. */
function barycentric(base: usize, jp: usize, ja: usize, jb: usize, jc: usize): void {
  const ax = <f64>load<f32>(base + ja), ay = <f64>load<f32>(base + ja, 4), az = <f64>load<f32>(base + ja, 8);
  const ux = <f64>load<f32>(base + jb) - ax, uy = <f64>load<f32>(base + jb, 4) - ay, uz = <f64>load<f32>(base + jb, 8) - az;
  const vx = <f64>load<f32>(base + jc) - ax, vy = <f64>load<f32>(base + jc, 4) - ay, vz = <f64>load<f32>(base + jc, 8) - az;
  const qx = <f64>load<f32>(base + jp) - ax, qy = <f64>load<f32>(base + jp, 4) - ay, qz = <f64>load<f32>(base + jp, 8) - az;
  const uu = ux * ux + uy * uy + uz * uz, uv = ux * vx + uy * vy + uz * vz, vv = vx * vx + vy * vy + vz * vz;
  const qu = qx * ux + qy * uy + qz * uz, qv = qx * vx + qy * vy + qz * vz;
  const det = uu * vv - uv * uv;
  const b1 = det > 0 ? (vv * qu - uv * qv) / det : 0, b2 = det > 0 ? (uu * qv - uv * qu) / det : 0;
  B0 = 1 - b1 - b2; B1 = b1; B2 = b2;
}

/** Whether the projection of jp onto the triangle's plane lies inside it (weights left in B0…B2). */
function projectionInside(base: usize, jp: usize, ja: usize, jb: usize, jc: usize): bool {
  barycentric(base, jp, ja, jb, jc);
  return B0 >= 0 && B1 >= 0 && B2 >= 0;
}

/** Distance [m] from jp to the closest point of triangle (ja, jb, jc) now, its weights into B0…B2 (Ericson 2005, §5.1.5). */
export function closestPoint(jp: usize, ja: usize, jb: usize, jc: usize): f64 {
  const abx = xn(jb, 0) - xn(ja, 0), aby = xn(jb, 1) - xn(ja, 1), abz = xn(jb, 2) - xn(ja, 2);
  const acx = xn(jc, 0) - xn(ja, 0), acy = xn(jc, 1) - xn(ja, 1), acz = xn(jc, 2) - xn(ja, 2);
  const apx = xn(jp, 0) - xn(ja, 0), apy = xn(jp, 1) - xn(ja, 1), apz = xn(jp, 2) - xn(ja, 2);
  const d1 = abx * apx + aby * apy + abz * apz, d2 = acx * apx + acy * apy + acz * apz;
  let u: f64, v: f64; // weights of b and c
  if (d1 <= 0 && d2 <= 0) { u = 0; v = 0; } else {
    const bpx = xn(jp, 0) - xn(jb, 0), bpy = xn(jp, 1) - xn(jb, 1), bpz = xn(jp, 2) - xn(jb, 2);
    const d3 = abx * bpx + aby * bpy + abz * bpz, d4 = acx * bpx + acy * bpy + acz * bpz;
    const cpx = xn(jp, 0) - xn(jc, 0), cpy = xn(jp, 1) - xn(jc, 1), cpz = xn(jp, 2) - xn(jc, 2);
    const d5 = abx * cpx + aby * cpy + abz * cpz, d6 = acx * cpx + acy * cpy + acz * cpz;
    const vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) { u = 1; v = 0; }
    else if (d6 >= 0 && d5 <= d6) { u = 0; v = 1; }
    else if (vc <= 0 && d1 >= 0 && d3 <= 0) { u = d1 / (d1 - d3); v = 0; }
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) { u = 0; v = d2 / (d2 - d6); }
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) { v = (d4 - d3) / ((d4 - d3) + (d5 - d6)); u = 1 - v; }
    else { const den = 1 / (va + vb + vc); u = vb * den; v = vc * den; }
  }
  B0 = 1 - u - v; B1 = u; B2 = v;
  const cx = xn(ja, 0) + u * abx + v * acx, cy = xn(ja, 1) + u * aby + v * acy, cz = xn(ja, 2) + u * abz + v * acz;
  const ex = xn(jp, 0) - cx, ey = xn(jp, 1) - cy, ez = xn(jp, 2) - cz;
  return Math.sqrt(ex * ex + ey * ey + ez * ez);
}

/** Position-based Coulomb friction scale for tangential motion tl [m] against a push depth [m], as the reference's. */
@inline function frictionScale(tl: f64, depth: f64, mu: f64, muS: f64): f64 {
  return tl < 1e-12 ? 0 : tl < muS * depth ? 1 : min((mu * depth) / tl, 1);
}

/**
 * Particle p against triangle t = (a, b, c): passed through (if near enough now to have), or too near, kept h [m]
 * apart with kinetic and static friction mu, muS [-] (self-contact.ts resolvePair, operation for operation).
 */
function resolvePair(h: f64, mu: f64, muS: f64, p: i32, t: i32, a: u32, b: u32, c: u32): void {
  const jp = <usize>p * 12, ja = <usize>a * 12, jb = <usize>b * 12, jc = <usize>c * 12;
  const o = triangleFrame(t, a, b, c);
  // the side at the substep's start, and now
  const sPrev = f64At(o, 3) * (xs(jp, 0) - xs(ja, 0)) + f64At(o, 4) * (xs(jp, 1) - xs(ja, 1)) + f64At(o, 5) * (xs(jp, 2) - xs(ja, 2));
  const s = f64At(o, 0) * (xn(jp, 0) - xn(ja, 0)) + f64At(o, 1) * (xn(jp, 1) - xn(ja, 1)) + f64At(o, 2) * (xn(jp, 2) - xn(ja, 2));
  if (!isFinite<f64>(s) || !isFinite<f64>(sPrev)) return;
  if (Math.abs(s) >= h && sign(s) == sign(sPrev)) return;
  const crossed = sPrev != 0 && sign(s) != sign(sPrev);
  if (!crossed) {
    const ex = xn(jp, 0) - f64At(o, 6), ey = xn(jp, 1) - f64At(o, 7), ez = xn(jp, 2) - f64At(o, 8), far = f64At(o, 9) + h + SKIP_MARGIN;
    if (ex * ex + ey * ey + ez * ez >= far * far) return;
  }
  DX = f64At(o, 0); DY = f64At(o, 1); DZ = f64At(o, 2);
  let C: f64; // constraint value along the direction: negative when violated
  const inside = crossed && projectionInside(X, jp, ja, jb, jc);
  if (crossed && (inside || projectionInside(XP, jp, ja, jb, jc))) {
    // passed through, if near enough now to have: nearer than h or its move and the triangle's largest corner move
    const d = inside ? Math.abs(s) : closestPoint(jp, ja, jb, jc);
    const motion = perParticle(MOVE, p) + max(max(perParticle(MOVE, a), perParticle(MOVE, b)), perParticle(MOVE, c));
    if (d >= max(h, motion) + SKIP_MARGIN) return;
    // back to its side, h from the plane
    const side = sign(sPrev);
    if (!inside) {
      barycentric(X, jp, ja, jb, jc);
      const b0 = max(B0, 0), b1 = max(B1, 0), b2 = max(B2, 0), sum = b0 + b1 + b2;
      B0 = b0 / sum; B1 = b1 / sum; B2 = b2 / sum;
    }
    DX *= side; DY *= side; DZ *= side;
    C = side * s - h;
  } else {
    // on its side: nearer than h to the triangle's closest point?
    const d = closestPoint(jp, ja, jb, jc);
    if (d >= h) return;
    if (d > 1e-12) {
      const cx = B0 * xn(ja, 0) + B1 * xn(jb, 0) + B2 * xn(jc, 0);
      const cy = B0 * xn(ja, 1) + B1 * xn(jb, 1) + B2 * xn(jc, 1);
      const cz = B0 * xn(ja, 2) + B1 * xn(jb, 2) + B2 * xn(jc, 2);
      DX = (xn(jp, 0) - cx) / d; DY = (xn(jp, 1) - cy) / d; DZ = (xn(jp, 2) - cz) / d;
    } else {
      const side: f64 = sPrev != 0 ? sign(sPrev) : 1;
      DX *= side; DY *= side; DZ *= side;
    }
    C = d - h;
  }
  const wp = <f64>load<f32>(W + (<usize>p << 2)), wa = <f64>load<f32>(W + (<usize>a << 2));
  const wb = <f64>load<f32>(W + (<usize>b << 2)), wc = <f64>load<f32>(W + (<usize>c << 2));
  const denom = wp + B0 * B0 * wa + B1 * B1 * wb + B2 * B2 * wc;
  if (denom <= 0) return;
  const lambda = -C / denom;
  const depth = lambda * denom;
  // friction: the relative tangential motion over the substep
  let rx = xn(jp, 0) - xs(jp, 0), ry = xn(jp, 1) - xs(jp, 1), rz = xn(jp, 2) - xs(jp, 2);
  rx -= B0 * (xn(ja, 0) - xs(ja, 0)); ry -= B0 * (xn(ja, 1) - xs(ja, 1)); rz -= B0 * (xn(ja, 2) - xs(ja, 2));
  rx -= B1 * (xn(jb, 0) - xs(jb, 0)); ry -= B1 * (xn(jb, 1) - xs(jb, 1)); rz -= B1 * (xn(jb, 2) - xs(jb, 2));
  rx -= B2 * (xn(jc, 0) - xs(jc, 0)); ry -= B2 * (xn(jc, 1) - xs(jc, 1)); rz -= B2 * (xn(jc, 2) - xs(jc, 2));
  const rn = rx * DX + ry * DY + rz * DZ;
  const tx = rx - rn * DX, ty = ry - rn * DY, tz = rz - rn * DZ;
  const f = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), depth, mu, muS);
  const kx = lambda * DX - (f * tx) / denom, ky = lambda * DY - (f * ty) / denom, kz = lambda * DZ - (f * tz) / denom;
  moved(<u32>p, a, b, c);
  addX(jp, 0, wp * kx); addX(jp, 1, wp * ky); addX(jp, 2, wp * kz);
  const ma = wa * B0, mb = wb * B1, mc = wc * B2;
  addX(ja, 0, -(ma * kx)); addX(ja, 1, -(ma * ky)); addX(ja, 2, -(ma * kz));
  addX(jb, 0, -(mb * kx)); addX(jb, 1, -(mb * ky)); addX(jb, 2, -(mb * kz));
  addX(jc, 0, -(mc * kx)); addX(jc, 1, -(mc * ky)); addX(jc, 2, -(mc * kz));
  track(<u32>p); track(a); track(b); track(c);
}

/**
 * Edge–edge pairs [0, count) of EDGE_PAIRS, in order, as collideEdges: a pair whose edges' boxes meet, with its
 * pair's distance (at most hMax [m]) and friction; `memo`: the pairs' EDGE_MEMO holds for them (not when the host
 * copies the list in window by window).
 */
export function selfEdges(count: i32, hMax: f64, memo: bool): void {
  for (let q = 0; q < count; q++) {
    const pr = EDGE_PAIRS + (<usize>q << 3);
    const e = load<i32>(pr), f = load<i32>(pr, 4);
    const be = edgeRecord(e), bf = edgeRecord(f);
    if (!overlap(be, bf)) continue;
    // resolveEdges' first skip from the two records alone, with hMax for the pair's h (its h_e at least the pair's):
    // a pair it skips, that skips too (the same numbers)
    if (memo) {
      const m = EDGE_MEMO + (<usize>q << 4), motion = load<f64>(be, 56) + load<f64>(bf, 56);
      const apart = max(min(hMax, SELF_EDGE_SHARE * hMax + motion), motion) + SKIP_MARGIN;
      if (load<f64>(m) - ((load<f64>(be, 48) + load<f64>(bf, 48)) - load<f64>(m, 8)) >= apart) continue;
    }
    const ea = EDGES + <usize>e * 8, fa = EDGES + <usize>f * 8;
    const a = load<u32>(ea), b = load<u32>(ea, 4), c = load<u32>(fa), d = load<u32>(fa, 4);
    const ca = <i32>load<u8>(OWNER + <usize>a), cc = <i32>load<u8>(OWNER + <usize>c);
    const m = memo ? EDGE_MEMO + (<usize>q << 4) : 0;
    if (ca == cc) {
      resolveEdges(min(clothValue(ca, 0), hMax), clothValue(ca, 1), clothValue(ca, 2), m, e, f, a, b, c, d);
    } else {
      const h = min(0.5 * (clothValue(ca, 0) + clothValue(cc, 0)), hMax);
      resolveEdges(h, Math.sqrt(clothValue(ca, 1) * clothValue(cc, 1)), Math.sqrt(clothValue(ca, 2) * clothValue(cc, 2)), m, e, f, a, b, c, d);
    }
  }
}

/** Edge e = (a, b)'s frame (EFRAME), computed unless it is current; returns its byte offset. */
function edgeFrame(e: i32, a: u32, b: u32): usize {
  const o = EFRAME + <usize>e * 48, atP = EFRAME_AT + (<usize>e << 2), at = load<i32>(atP);
  if (at >= substepAt && stillSince(a, at) && stillSince(b, at)) return o;
  const ja = <usize>a * 12, jb = <usize>b * 12;
  store<f64>(o, 0.5 * (xn(ja, 0) + xn(jb, 0))); store<f64>(o, 0.5 * (xn(ja, 1) + xn(jb, 1)), 8); store<f64>(o, 0.5 * (xn(ja, 2) + xn(jb, 2)), 16);
  store<f64>(o, 0.5 * (xn(jb, 0) - xn(ja, 0)), 24); store<f64>(o, 0.5 * (xn(jb, 1) - xn(ja, 1)), 32); store<f64>(o, 0.5 * (xn(jb, 2) - xn(ja, 2)), 40);
  store<i32>(atP, clock);
  return o;
}

// the closest points' parameters (segmentClosest) and the vector q→p between them, now and then
let S: f64 = 0, T: f64 = 0;
let GX: f64 = 0, GY: f64 = 0, GZ: f64 = 0;

/**
 * Closest points of segments a–b and c–d (byte offsets) of positions `base` (Ericson 2005, §5.1.9): their
 * parameters into S, T, the vector p − q into GX, GY, GZ; returns its length [m].
 */
export function segmentClosest(base: usize, ja: usize, jb: usize, jc: usize, jd: usize): f64 {
  const ax = <f64>load<f32>(base + ja), ay = <f64>load<f32>(base + ja, 4), az = <f64>load<f32>(base + ja, 8);
  const cx = <f64>load<f32>(base + jc), cy = <f64>load<f32>(base + jc, 4), cz = <f64>load<f32>(base + jc, 8);
  const ux = <f64>load<f32>(base + jb) - ax, uy = <f64>load<f32>(base + jb, 4) - ay, uz = <f64>load<f32>(base + jb, 8) - az;
  const vx = <f64>load<f32>(base + jd) - cx, vy = <f64>load<f32>(base + jd, 4) - cy, vz = <f64>load<f32>(base + jd, 8) - cz;
  const rx = ax - cx, ry = ay - cy, rz = az - cz;
  const A = ux * ux + uy * uy + uz * uz, E = vx * vx + vy * vy + vz * vz, F = vx * rx + vy * ry + vz * rz;
  let s: f64 = 0, t: f64 = 0;
  if (A <= 1e-24 && E <= 1e-24) { s = 0; t = 0; } else if (A <= 1e-24) { t = min(max(F / E, 0), 1); } else {
    const C = ux * rx + uy * ry + uz * rz;
    if (E <= 1e-24) { s = min(max(-C / A, 0), 1); } else {
      const B = ux * vx + uy * vy + uz * vz, den = A * E - B * B;
      s = den > 1e-24 ? min(max((B * F - C * E) / den, 0), 1) : 0;
      t = (B * s + F) / E;
      if (t < 0) { t = 0; s = min(max(-C / A, 0), 1); } else if (t > 1) { t = 1; s = min(max((B - C) / A, 0), 1); }
    }
  }
  S = s; T = t;
  GX = rx + s * ux - t * vx; GY = ry + s * uy - t * vy; GZ = rz + s * uz - t * vz;
  return Math.sqrt(GX * GX + GY * GY + GZ * GZ);
}

/** Whether a closest point's parameter lies inside its edge (not at an end). */
@inline function inside(v: f64): bool { return v > 1e-6 && v < 1 - 1e-6; }

/** Particle p's value in an f64 array at byte offset `base`. */
@inline function perParticle(base: usize, p: u32): f64 { return load<f64>(base + (<usize>p << 3)); }

/**
 * Edges e = a–b and f = c–d: passed through, or too near, kept h_e = min(hPair, SELF_EDGE_SHARE·hPair + δ) [m]
 * apart (δ the two edges' largest end moves over the substep, summed) with friction mu, muS [-] (self-contact.ts
 * resolveEdges, operation for operation, with its three skips); `memo`: the byte offset of the pair's EDGE_MEMO
 * entry, or 0 for none.
 */
function resolveEdges(hPair: f64, mu: f64, muS: f64, memo: usize, e: i32, f: i32, a: u32, b: u32, c: u32, d: u32): void {
  const be = EBOX + (<usize>e << 6), bf = EBOX + (<usize>f << 6);
  const motion = load<f64>(be, 56) + load<f64>(bf, 56);
  const h = min(hPair, SELF_EDGE_SHARE * hPair + motion);
  const apart = max(h, motion) + SKIP_MARGIN;
  const travelled = load<f64>(be, 48) + load<f64>(bf, 48);
  if (memo != 0) {
    if (load<f64>(memo) - (travelled - load<f64>(memo, 8)) >= apart) return;
    store<f64>(memo, travelled, 8);
  }
  const fe = edgeFrame(e, a, b), ff = edgeFrame(f, c, d);
  const mx = f64At(fe, 0) - f64At(ff, 0), my = f64At(fe, 1) - f64At(ff, 1), mz = f64At(fe, 2) - f64At(ff, 2);
  const m2 = mx * mx + my * my + mz * mz, ml = Math.sqrt(m2);
  const extent = Math.abs(mx * f64At(fe, 3) + my * f64At(fe, 4) + mz * f64At(fe, 5)) + Math.abs(mx * f64At(ff, 3) + my * f64At(ff, 4) + mz * f64At(ff, 5));
  if (m2 - extent > apart * ml) {
    if (memo != 0) store<f64>(memo, (m2 - extent) / ml);
    return;
  }
  const ja = <usize>a * 12, jb = <usize>b * 12, jc = <usize>c * 12, jd = <usize>d * 12;
  const len = segmentClosest(X, ja, jb, jc, jd);
  if (memo != 0) store<f64>(memo, len);
  if (len >= apart) return;
  const s = S, t = T, gx = GX, gy = GY, gz = GZ;
  const len0 = segmentClosest(XP, ja, jb, jc, jd);
  const in0 = inside(S) && inside(T);
  if (!isFinite<f64>(len) || !isFinite<f64>(len0)) return;
  let C: f64, dx: f64, dy: f64, dz: f64;
  if (in0 && inside(s) && inside(t) && len0 > 1e-12 && gx * GX + gy * GY + gz * GZ < 0) {
    // passed through: back to the side of then, h along that direction
    dx = GX / len0; dy = GY / len0; dz = GZ / len0;
    C = gx * dx + gy * dy + gz * dz - h;
  } else {
    if (len >= h || len < 1e-12) return;
    dx = gx / len; dy = gy / len; dz = gz / len;
    C = len - h;
  }
  const ka = 1 - s, kb = s, kc = 1 - t, kd = t;
  const wa = <f64>load<f32>(W + (<usize>a << 2)), wb = <f64>load<f32>(W + (<usize>b << 2));
  const wc = <f64>load<f32>(W + (<usize>c << 2)), wd = <f64>load<f32>(W + (<usize>d << 2));
  const denom = ka * ka * wa + kb * kb * wb + kc * kc * wc + kd * kd * wd;
  if (!(denom > 0)) return;
  const lambda = -C / denom, depth = -C;
  // friction: the relative tangential motion of p against q over the substep
  const rx = ka * (xn(ja, 0) - xs(ja, 0)) + kb * (xn(jb, 0) - xs(jb, 0)) - kc * (xn(jc, 0) - xs(jc, 0)) - kd * (xn(jd, 0) - xs(jd, 0));
  const ry = ka * (xn(ja, 1) - xs(ja, 1)) + kb * (xn(jb, 1) - xs(jb, 1)) - kc * (xn(jc, 1) - xs(jc, 1)) - kd * (xn(jd, 1) - xs(jd, 1));
  const rz = ka * (xn(ja, 2) - xs(ja, 2)) + kb * (xn(jb, 2) - xs(jb, 2)) - kc * (xn(jc, 2) - xs(jc, 2)) - kd * (xn(jd, 2) - xs(jd, 2));
  const rn = rx * dx + ry * dy + rz * dz;
  const tx = rx - rn * dx, ty = ry - rn * dy, tz = rz - rn * dz;
  const fs = frictionScale(Math.sqrt(tx * tx + ty * ty + tz * tz), depth, mu, muS);
  const kx = lambda * dx - (fs * tx) / denom, ky = lambda * dy - (fs * ty) / denom, kz = lambda * dz - (fs * tz) / denom;
  moved(a, b, c, d);
  addX(ja, 0, wa * ka * kx); addX(ja, 1, wa * ka * ky); addX(ja, 2, wa * ka * kz);
  addX(jb, 0, wb * kb * kx); addX(jb, 1, wb * kb * ky); addX(jb, 2, wb * kb * kz);
  addX(jc, 0, -(wc * kc * kx)); addX(jc, 1, -(wc * kc * ky)); addX(jc, 2, -(wc * kc * kz));
  addX(jd, 0, -(wd * kd * kx)); addX(jd, 1, -(wd * kd * ky)); addX(jd, 2, -(wd * kd * kz));
  track(a); track(b); track(c); track(d);
  edgesOf(a); edgesOf(b); edgesOf(c); edgesOf(d);
}
