// Self-contact's candidate search in the kernel (the reference is self-contact.ts findCandidates, which says what
// it finds and why): the frame the boxes are made in (movingFrame), each particle's reach box and radius, the
// triangles' and edges' reach boxes, the three
// bounding-box trees refitted to them (box-tree.ts refit; their structure is the host's, built once from the rest
// positions and copied here), the (particle, triangle) pairs of one tree against another and the (edge, edge) pairs
// of one tree with itself (BoxTree.pairsWith, pairsWithin), less those that cannot come within h before the next
// search (the reference's Trees.addPair, addEdgePair), sorted into the order they are resolved (sortPairs) and
// written into the pair windows that the passes read (self-contact.as.ts). The same operations on the same numbers
// as the reference, so the same pairs. One thread: the host calls it on thread 0 between two substep() calls.
// selfUpdate is the reference's updateCandidates: where a few particles left their reach boxes, their boxes, their
// triangles' and edges' and the trees' nodes above them are made again, and only their pairs are found again and
// merged into the lists (the reference's pairs, in its order).
import { N, X, XP } from './arrays.as';
import { SELF_EDGE_SHARE, SELF_FRAME_SHARE, SELF_REACH_MARGIN, SELF_SKIP_MARGIN as SKIP_MARGIN } from './layout.generated.as';
import {
  EDGE_MEMO, EDGE_PAIRS, EDGES, ESCAPED, FRAME_J, PAIRS, PEDGE_LIST, PEDGE_START, REACH, TRIS, closestPoint, frameU, overlap,
  segmentClosest, selfFrame,
} from './self-contact.as';

/** A tree's arrays (byte offsets) and node count, as the host writes them (self-contact-wasm.ts, TREE_FIELDS). */
@unmanaged class Tree {
  /** the primitives, leaf by leaf, i32 */
  order: usize;
  /** per node: its first primitive in `order`, how many it holds, its right child (−1: a leaf), i32 */
  first: usize;
  size: usize;
  right: usize;
  /** per node: its box, f64 × 6 (min x, y, z, max x, y, z) */
  boxes: usize;
  nodes: i32;
  /** per node its parent (−1: the root), per primitive its leaf, i32 (made by configureSearch) */
  parent: usize;
  leaf: usize;
}

/** the trees over the particles, the triangles and the edges */
let PARTICLE_TREE: Tree = changetype<Tree>(0);
let TRIANGLE_TREE: Tree = changetype<Tree>(0);
let EDGE_TREE: Tree = changetype<Tree>(0);
/** each particle's reach radius [m], f64, and the search or update it was measured for (i32: radiusNow) */
let RADIUS: usize = 0;
let RADIUS_AT: usize = 0;
let epoch: i32 = 0;
/**
 * each particle's triangles, as rows (self-contact.ts rowsOf): where each particle's start (i32 × (particles + 1)),
 * the list (i32); its edges' rows are the edge pass's (self-contact.as.ts PEDGE_START, PEDGE_LIST)
 */
let PTRI_START: usize = 0;
let PTRI_LIST: usize = 0;
/**
 * each triangle's and each edge's largest reach radius of its corners [m], f64 (radiiOf: what a search's pair filters
 * read); whether they are those of the radii now (a search made them; an update, which changes every radius and finds
 * few pairs, reads the corners' own)
 */
let TRADIUS: usize = 0;
let ERADIUS: usize = 0;
let radiiMade = false;
/** each triangle's and each edge's reach box (its corners' reach boxes widened by h and, an edge's, by SELF_EDGE_SHARE·h/2), f64 × 6 */
let TREACH: usize = 0;
let EREACH: usize = 0;
/**
 * where the trees put the pairs they find, before they are sorted, and how many it holds: for the particle pairs the
 * edge pairs' window, for the edge pairs the edge pairs' memo (16 bytes a pair, reset after each search), both
 * written over before they are read again
 */
let RAW: usize = 0;
let RAW_CAP: i32 = 0;
/** the counting sort's counts, i32 × (max(particles, edges) + 1) */
let BUCKET: usize = 0;
/** the traversals' stack of node pairs, i32 × 2 × STACK_CAP */
let STACK: usize = 0;
let STACK_CAP: i32 = 0;
/** triangles, edges */
let NT: i32 = 0;
let NE: i32 = 0;
/** selfUpdate's marks (u8 per particle, triangle and edge), its triangles and edges to do (i32), and where it finds pairs */
let PMARK: usize = 0;
let TMARK: usize = 0;
let EMARK: usize = 0;
let TOUCHED_T: usize = 0;
let TOUCHED_E: usize = 0;
/** the pairs selfUpdate finds, unsorted then sorted, i32 × 2 × FRESH_CAP each */
let FRESH: usize = 0;
let FRESH_SORTED: usize = 0;
let FRESH_CAP: i32 = 0;

/** what the last search found: pairs and edge pairs (in PAIRS and EDGE_PAIRS) */
let pairCount: i32 = 0;
let edgePairCount: i32 = 0;
/** the search's distance h and mean rest edge [m] (the pair filters read them) */
let hFor: f64 = 0;
let meanEdge: f64 = 0;

/**
 * Sets the arrays' byte offsets (the host's layout): the trees' descriptors (Tree, 32 bytes each) and the scratch;
 * makes each tree's parents and leaves.
 */
export function configureSearch(
  trees: usize, radius: usize, treach: usize, ereach: usize, bucket: usize, stack: usize, stackCap: i32, triangles: i32, edgeCount: i32,
  marks: usize, touched: usize, fresh: usize, freshCap: i32, tradius: usize, eradius: usize, radiusAt: usize,
  triStart: usize, triList: usize,
): void {
  PARTICLE_TREE = changetype<Tree>(trees);
  TRIANGLE_TREE = changetype<Tree>(trees + offsetof<Tree>());
  EDGE_TREE = changetype<Tree>(trees + 2 * offsetof<Tree>());
  RADIUS = radius; TREACH = treach; EREACH = ereach; BUCKET = bucket; TRADIUS = tradius; ERADIUS = eradius;
  RADIUS_AT = radiusAt; memory.fill(radiusAt, 0xff, <usize>N << 2);
  PTRI_START = triStart; PTRI_LIST = triList;
  STACK = stack; STACK_CAP = stackCap; NT = triangles; NE = edgeCount;
  PMARK = marks; TMARK = marks + <usize>N; EMARK = TMARK + <usize>triangles;
  memory.fill(marks, 0, <usize>N + <usize>triangles + <usize>edgeCount);
  TOUCHED_T = touched; TOUCHED_E = touched + (<usize>triangles << 2);
  FRESH = fresh; FRESH_SORTED = fresh + (<usize>freshCap << 3); FRESH_CAP = freshCap;
  links(PARTICLE_TREE); links(TRIANGLE_TREE); links(EDGE_TREE);
}

/**
 * Adds particle p's primitives (rows `start`, `list`) not yet marked in `mark` (u8) to `touched` (i32, `n` there
 * before), marking them; returns how many are there after.
 */
function touch(p: i32, start: usize, list: usize, mark: usize, touched: usize, n: i32): i32 {
  for (let k = i32At(start, p), end = i32At(start, p + 1); k < end; k++) {
    const q = i32At(list, k);
    if (load<u8>(mark + <usize>q) != 0) continue;
    store<u8>(mark + <usize>q, 1);
    store<i32>(touched + (<usize>(n++) << 2), q);
  }
  return n;
}

/** Tree t's parents and leaves (nodes depth first: node i's left child is i + 1, its right child right[i]). */
function links(t: Tree): void {
  store<i32>(t.parent, -1);
  for (let node = 0; node < t.nodes; node++) {
    const right = i32At(t.right, node);
    if (right >= 0) {
      store<i32>(t.parent + ((<usize>node + 1) << 2), node);
      store<i32>(t.parent + (<usize>right << 2), node);
      continue;
    }
    for (let i = i32At(t.first, node), end = i + i32At(t.size, node); i < end; i++) store<i32>(t.leaf + (<usize>i32At(t.order, i) << 2), node);
  }
}

/** pairs the last search found (selfSearch returned 1) */
export function foundPairs(): i32 { return pairCount; }
export function foundEdgePairs(): i32 { return edgePairCount; }

@inline function i32At(base: usize, k: i32): i32 { return load<i32>(base + (<usize>k << 2)); }
@inline function radius(p: u32): f64 { return load<f64>(RADIUS + (<usize>p << 3)); }

/**
 * Particle p's reach radius for an update: its own (made by reachOf for this search or update), or else the others
 * keep their boxes, which still hold them, and theirs is measured from where they are now in the boxes' frame, once.
 */
function radiusNow(p: u32): f64 {
  const at = RADIUS_AT + (<usize>p << 2);
  if (load<i32>(at) == epoch) return radius(p);
  const j = <usize>p * 12, r = REACH + <usize>p * 48, J = FRAME_J;
  let r2: f64 = 0;
  for (let c: usize = 0; c < 3; c++) {
    const x = <f64>load<f32>(X + j + (c << 2)) - J * frameU(c);
    const far = max(x - load<f64>(r + (c << 3)), load<f64>(r + 24 + (c << 3)) - x);
    r2 += far * far;
  }
  const v = Math.sqrt(r2);
  store<f64>(RADIUS + (<usize>p << 3), v);
  store<i32>(at, epoch);
  return v;
}

/**
 * Finds the candidate pairs for the substeps left in the frame (`left` of length h [s]; distance hMax [m], gravity
 * (gx, gy, gz) [m/s²], `span` and `edge` from selfSearchLengths) into the pair windows of `window` and `edgeWindow`
 * pairs. Returns 1 when found, 0 when a box is not finite (an unstable cloth: the reference's false), −1 when the
 * pairs do not fit the windows or the stack (the host then searches in TypeScript and copies them in window by window).
 */
export function selfSearch(
  hMax: f64, left: f64, h: f64, gx: f64, gy: f64, gz: f64, span: f64, edge: f64, window: i32, edgeWindow: i32,
): i32 {
  const T = left * h;
  movingFrame();
  epoch++;
  for (let p = 0; p < N; p++) reachOf(p, left, T, gx, gy, gz, span, hMax);
  for (let t = 0; t < NT; t++) unionOf(REACH, TRIS + <usize>t * 12, 0, 3, TREACH + <usize>t * 48, hMax);
  const half = 0.5 * (SELF_EDGE_SHARE * hMax);
  for (let e = 0; e < NE; e++) unionOf(REACH, EDGES + <usize>e * 8, 0, 2, EREACH + <usize>e * 48, half);
  if (!refit(PARTICLE_TREE, REACH, N) || !refit(TRIANGLE_TREE, TREACH, NT) || !refit(EDGE_TREE, EREACH, NE)) return 0;
  radiiOf();
  hFor = hMax;
  meanEdge = edge;

  // the particle pairs' scratch is the edge window, so no more than it holds (the host makes it the larger)
  RAW = EDGE_PAIRS; RAW_CAP = min(window, edgeWindow);
  const found = pairsWith(PARTICLE_TREE, TRIANGLE_TREE, REACH, TREACH);
  if (found < 0) return -1;
  // the edge memo, free until the edge pairs are found, holds the pass by triangle
  radixInto(found, NT, N, EDGE_MEMO, PAIRS);
  pairCount = found;
  RAW = EDGE_MEMO; RAW_CAP = edgeWindow;
  const foundEdges = pairsWithin(EDGE_TREE, EREACH);
  if (foundEdges < 0) return -1;
  // the memo's second half (16 bytes a pair: RAW takes the first 8 of each) holds the pass by second edge
  radixInto(foundEdges, NE, NE, EDGE_MEMO + (<usize>edgeWindow << 3), EDGE_PAIRS);
  edgePairCount = foundEdges;
  return 1;
}

/**
 * The reference's updateCandidates, for the `count` particles in ESCAPED (out of their reach boxes; the host has
 * checked that they are few and that this kernel's own search found the lists): their reach boxes made again, their
 * triangles' and edges' (from each particle's rows), the trees' nodes above them, every other particle's reach radius
 * from where it is now (when a pair filter reads it: radiusNow); their
 * pairs taken out of the lists, found again against the trees with the search's tests, sorted and merged in, so that
 * the lists are the reference's in its order. Unlike the reference it keeps the particles' travel and the edge pairs'
 * measured distances (carried with their pairs; the new pairs' unknown), which still bound them. Returns 1 when
 * updated, 0 when a box is not finite (as selfSearch), −1 when the pairs do not fit the windows, the fresh pairs'
 * scratch or the stack (the host then searches whole).
 */
export function selfUpdate(
  count: i32, hMax: f64, left: f64, h: f64, gx: f64, gy: f64, gz: f64, span: f64, window: i32, edgeWindow: i32,
): i32 {
  const T = left * h;
  // the others' radii are measured again, from where they are now, when a pair filter reads them (radiusNow)
  epoch++;
  for (let i = 0; i < count; i++) {
    const p = i32At(ESCAPED, i);
    reachOf(p, left, T, gx, gy, gz, span, hMax);
    store<u8>(PMARK + <usize>p, 1);
  }
  // their triangles and edges, each once (any order: the pairs are sorted after), then their reach boxes
  let nt = 0, ne = 0;
  for (let i = 0; i < count; i++) {
    const p = i32At(ESCAPED, i);
    nt = touch(p, PTRI_START, PTRI_LIST, TMARK, TOUCHED_T, nt);
    ne = touch(p, PEDGE_START, PEDGE_LIST, EMARK, TOUCHED_E, ne);
  }
  for (let i = 0; i < nt; i++) {
    const t = i32At(TOUCHED_T, i);
    unionOf(REACH, TRIS + <usize>t * 12, 0, 3, TREACH + <usize>t * 48, hMax);
  }
  const half = 0.5 * (SELF_EDGE_SHARE * hMax);
  for (let i = 0; i < ne; i++) {
    const e = i32At(TOUCHED_E, i);
    unionOf(REACH, EDGES + <usize>e * 8, 0, 2, EREACH + <usize>e * 48, half);
  }
  let result = 1;
  if (!refitAbove(PARTICLE_TREE, REACH, ESCAPED, count) || !refitAbove(TRIANGLE_TREE, TREACH, TOUCHED_T, nt) || !refitAbove(EDGE_TREE, EREACH, TOUCHED_E, ne)) {
    result = 0;
  } else {
    radiiMade = false;
    result = updatePairs(count, nt, window) && updateEdgePairs(ne, edgeWindow) ? 1 : -1;
  }
  for (let i = 0; i < count; i++) store<u8>(PMARK + <usize>i32At(ESCAPED, i), 0);
  for (let i = 0; i < nt; i++) store<u8>(TMARK + <usize>i32At(TOUCHED_T, i), 0);
  for (let i = 0; i < ne; i++) store<u8>(EMARK + <usize>i32At(TOUCHED_E, i), 0);
  return result;
}

/**
 * selfUpdate's particle pairs: those of the marked particles and triangles out, those of the `count` escaped
 * particles against every triangle and of the `nt` touched triangles against every other particle in; false when
 * they do not fit.
 */
function updatePairs(count: i32, nt: i32, window: i32): bool {
  const kept = keepUnmarked(PAIRS, pairCount, PMARK, TMARK, 0);
  RAW = FRESH; RAW_CAP = FRESH_CAP;
  let n = 0;
  for (let i = 0; i < count && n >= 0; i++) {
    const p = i32At(ESCAPED, i);
    n = query(TRIANGLE_TREE, REACH + <usize>p * 48, TREACH, p, QUERY_TRIANGLES, n);
  }
  for (let i = 0; i < nt && n >= 0; i++) {
    const t = i32At(TOUCHED_T, i);
    n = query(PARTICLE_TREE, TREACH + <usize>t * 48, REACH, t, QUERY_PARTICLES, n);
  }
  if (n < 0 || kept + n > window) return false;
  sortInto(n, N, FRESH_SORTED);
  mergeInto(PAIRS, kept, n, 0);
  pairCount = kept + n;
  return true;
}

/** selfUpdate's edge pairs: those of the `ne` touched edges out, and found again against every edge; false when they do not fit. */
function updateEdgePairs(ne: i32, edgeWindow: i32): bool {
  const kept = keepUnmarked(EDGE_PAIRS, edgePairCount, EMARK, EMARK, EDGE_MEMO);
  RAW = FRESH; RAW_CAP = FRESH_CAP;
  let n = 0;
  for (let i = 0; i < ne && n >= 0; i++) {
    const e = i32At(TOUCHED_E, i);
    n = query(EDGE_TREE, EREACH + <usize>e * 48, EREACH, e, QUERY_EDGES, n);
  }
  if (n < 0 || kept + n > edgeWindow) return false;
  sortInto(n, NE, FRESH_SORTED);
  mergeInto(EDGE_PAIRS, kept, n, EDGE_MEMO);
  edgePairCount = kept + n;
  return true;
}

/**
 * Keeps, in order, those of the first `count` pairs of `list` whose first entry is unmarked in `a` and second in
 * `b` (u8 marks), with their memo (16 bytes a pair at `memo`, 0: none); returns how many.
 */
function keepUnmarked(list: usize, count: i32, a: usize, b: usize, memo: usize): i32 {
  let n = 0;
  for (let q = 0; q < count; q++) {
    const at = list + (<usize>q << 3);
    if ((load<u8>(a + <usize>load<i32>(at)) | load<u8>(b + <usize>load<i32>(at, 4))) != 0) continue;
    if (n != q) {
      store<i64>(list + (<usize>n << 3), load<i64>(at));
      if (memo != 0) v128.store(memo + (<usize>n << 4), v128.load(memo + (<usize>q << 4)));
    }
    n++;
  }
  return n;
}

/**
 * Merges the `fresh` sorted pairs of FRESH_SORTED into the `kept` sorted pairs at the front of `list`, from the back
 * (in place: the list has room after them), ascending by first then second entry; a fresh pair's memo (`memo` ≠ 0)
 * is unknown, a kept one's moves with it.
 */
function mergeInto(list: usize, kept: i32, fresh: i32, memo: usize): void {
  let i = kept - 1, j = fresh - 1;
  for (let k = kept + fresh - 1; j >= 0; k--) {
    const f = FRESH_SORTED + (<usize>j << 3);
    const ff = load<i32>(f), fs = load<i32>(f, 4);
    let takeKept = false;
    if (i >= 0) {
      const kf = load<i32>(list + (<usize>i << 3)), ks = load<i32>(list + (<usize>i << 3), 4);
      takeKept = kf > ff || (kf == ff && ks > fs);
    }
    if (takeKept) {
      store<i64>(list + (<usize>k << 3), load<i64>(list + (<usize>i << 3)));
      if (memo != 0) v128.store(memo + (<usize>k << 4), v128.load(memo + (<usize>i << 4)));
      i--;
    } else {
      store<i64>(list + (<usize>k << 3), load<i64>(f));
      if (memo != 0) { store<f64>(memo + (<usize>k << 4), -Infinity); store<f64>(memo + (<usize>k << 4), 0, 8); }
      j--;
    }
  }
}

/** what a query adds (query's `kind`): (id, triangle), (particle, id) for an unmarked particle, (id, edge) once */
const QUERY_TRIANGLES = 0;
const QUERY_PARTICLES = 1;
const QUERY_EDGES = 2;

/**
 * Every primitive j of tree A whose box (`prims`) meets the box at `box` (primitive `id`'s), added to RAW as the
 * `n`th pair on through addPair or addEdgePair as `kind` says (the reference's BoxTree.query with Trees.addPair,
 * addStillPair, addMovedEdgePair); returns the pairs in RAW after, −1 when RAW or the stack is full.
 */
function query(A: Tree, box: usize, prims: usize, id: i32, kind: i32, n: i32): i32 {
  let top = 0;
  store<i32>(STACK, 0); top = 1;
  while (top > 0) {
    const a = i32At(STACK, --top);
    if (!overlap(A.boxes + <usize>a * 48, box)) continue;
    const right = i32At(A.right, a);
    if (right < 0) {
      for (let i = i32At(A.first, a), end = i + i32At(A.size, a); i < end; i++) {
        const j = i32At(A.order, i);
        if (!overlap(prims + <usize>j * 48, box)) continue;
        if (kind == QUERY_TRIANGLES) n = addPair(id, j, n);
        else if (kind == QUERY_PARTICLES) {
          if (load<u8>(PMARK + <usize>j) == 0) n = addPair(j, id, n);
        } else if (j != id && !(load<u8>(EMARK + <usize>j) != 0 && j < id)) n = addEdgePair(min(id, j), max(id, j), n);
        if (n < 0) return -1;
      }
      continue;
    }
    if (top + 2 > 2 * STACK_CAP) return -1;
    store<i32>(STACK + (<usize>top << 2), a + 1); store<i32>(STACK + ((<usize>top + 1) << 2), right);
    top += 2;
  }
  return n;
}

/** The frame a search makes its reach boxes in (the reference's movingFrame), 0 substeps since: selfFrame. */
function movingFrame(): void {
  let mx: f64 = 0, my: f64 = 0, mz: f64 = 0;
  for (let p = 0; p < N; p++) {
    const j = <usize>p * 12;
    mx += <f64>load<f32>(X + j) - <f64>load<f32>(XP + j);
    my += <f64>load<f32>(X + j, 4) - <f64>load<f32>(XP + j, 4);
    mz += <f64>load<f32>(X + j, 8) - <f64>load<f32>(XP + j, 8);
  }
  mx /= <f64>N; my /= <f64>N; mz /= <f64>N;
  let still: f64 = 0, along: f64 = 0;
  for (let p = 0; p < N; p++) {
    const j = <usize>p * 12;
    const vx = <f64>load<f32>(X + j) - <f64>load<f32>(XP + j), vy = <f64>load<f32>(X + j, 4) - <f64>load<f32>(XP + j, 4);
    const vz = <f64>load<f32>(X + j, 8) - <f64>load<f32>(XP + j, 8);
    still += Math.sqrt(vx * vx + vy * vy + vz * vz);
    along += Math.sqrt((vx - mx) * (vx - mx) + (vy - my) * (vy - my) + (vz - mz) * (vz - mz));
  }
  const moving = along < SELF_FRAME_SHARE * still;
  selfFrame(moving ? mx : 0, moving ? my : 0, moving ? mz : 0);
}

/**
 * Particle p's reach box and radius (the reference's reachBox): its box over this substep carried on over the `left`
 * substeps (T [s] in all) at its motion so far and gravity (gx, gy, gz) [m/s²], no farther than `span` [m], with a
 * margin of half that motion and at least hMax/4 [m]; its radius the farthest corner from where it is.
 */
@inline function reachOf(p: i32, left: f64, T: f64, gx: f64, gy: f64, gz: f64, span: f64, hMax: f64): void {
  const j = <usize>p * 12, r = REACH + <usize>p * 48;
  // where it is and was in the frame of the boxes
  const J = FRAME_J, J1 = J - 1;
  const x0 = <f64>load<f32>(X + j) - J * frameU(0), x1 = <f64>load<f32>(X + j, 4) - J * frameU(1), x2 = <f64>load<f32>(X + j, 8) - J * frameU(2);
  const q0 = <f64>load<f32>(XP + j) - J1 * frameU(0), q1 = <f64>load<f32>(XP + j, 4) - J1 * frameU(1), q2 = <f64>load<f32>(XP + j, 8) - J1 * frameU(2);
  const dx = (x0 - q0) * left + 0.5 * gx * T * T;
  const dy = (x1 - q1) * left + 0.5 * gy * T * T;
  const dz = (x2 - q2) * left + 0.5 * gz * T * T;
  const dl = Math.sqrt(dx * dx + dy * dy + dz * dz), k = dl > span ? span / dl : 1;
  const margin = max(0.5 * dl * k, SELF_REACH_MARGIN * hMax);
  // per axis: the box over x_prev, x and x + the predicted motion, widened by the margin; the farthest corner
  const e0 = reachAxis(r, 0, q0, x0, dx * k, margin), e1 = reachAxis(r, 1, q1, x1, dy * k, margin), e2 = reachAxis(r, 2, q2, x2, dz * k, margin);
  let r2: f64 = 0;
  r2 += e0 * e0; r2 += e1 * e1; r2 += e2 * e2;
  store<f64>(RADIUS + (<usize>p << 3), Math.sqrt(r2));
  store<i32>(RADIUS_AT + (<usize>p << 2), epoch);
}

/**
 * Axis k of a reach box at byte offset r: from min(x_prev, x, x + d) to max(…), each widened by the margin [m]
 * (the reference's order: the box, then the margin); returns the farthest of its ends from x [m].
 */
@inline function reachAxis(r: usize, k: usize, q: f64, x: f64, d: f64, margin: f64): f64 {
  const to = x + d;
  const lo = min(min(q, x), to) - margin, hi = max(max(q, x), to) + margin;
  store<f64>(r + (k << 3), lo);
  store<f64>(r + 24 + (k << 3), hi);
  return max(x - lo, hi - x);
}

/**
 * Box `out` = the union of the boxes (f64 × 6 each, from `base`) whose indices (32-bit) are `ids[from..to)`, widened
 * by `pad` [m].
 */
function unionOf(base: usize, ids: usize, from: i32, to: i32, out: usize, pad: f64): void {
  let l0 = Infinity, l1 = Infinity, l2 = Infinity, h0 = -Infinity, h1 = -Infinity, h2 = -Infinity;
  for (let n = from; n < to; n++) {
    const r = base + <usize>load<u32>(ids + (<usize>n << 2)) * 48;
    const a0 = load<f64>(r), a1 = load<f64>(r, 8), a2 = load<f64>(r, 16);
    const b0 = load<f64>(r, 24), b1 = load<f64>(r, 32), b2 = load<f64>(r, 40);
    if (a0 < l0) l0 = a0;
    if (a1 < l1) l1 = a1;
    if (a2 < l2) l2 = a2;
    if (b0 > h0) h0 = b0;
    if (b1 > h1) h1 = b1;
    if (b2 > h2) h2 = b2;
  }
  store<f64>(out, l0 - pad); store<f64>(out, l1 - pad, 8); store<f64>(out, l2 - pad, 16);
  store<f64>(out, h0 + pad, 24); store<f64>(out, h1 + pad, 32); store<f64>(out, h2 + pad, 40);
}

/** The tree's nodes' boxes from its `count` primitives' (`prims`, f64 × 6 each); false when a box is not finite. */
function refit(t: Tree, prims: usize, count: i32): bool {
  for (let node = t.nodes - 1; node >= 0; node--) refitNode(t, node, prims);
  // an infinite box reaches the root's; a NaN the leaves' comparisons skip, so it is looked for in the boxes
  for (let c = 0; c < 6; c++) if (!isFinite<f64>(load<f64>(t.boxes + (<usize>c << 3)))) return false;
  for (let i = 0, n = 6 * count; i < n; i++) {
    const v = load<f64>(prims + (<usize>i << 3));
    if (v != v) return false;
  }
  return true;
}

/** Node `node`'s box: its primitives' (a leaf) or its children's. */
@inline function refitNode(t: Tree, node: i32, prims: usize): void {
  const o = t.boxes + <usize>node * 48, right = i32At(t.right, node);
  if (right < 0) {
    const first = i32At(t.first, node);
    unionOf(prims, t.order, first, first + i32At(t.size, node), o, 0);
  } else {
    const l = o + 48, r = t.boxes + <usize>right * 48;
    v128.store(o, f64x2.min(v128.load(l), v128.load(r)));
    store<f64>(o, min(load<f64>(l, 16), load<f64>(r, 16)), 16);
    store<f64>(o, max(load<f64>(l, 24), load<f64>(r, 24)), 24);
    v128.store(o, f64x2.max(v128.load(l, 32), v128.load(r, 32)), 32);
  }
}

/**
 * The boxes of the nodes above the `count` primitives `ids` (i32) of the tree, after theirs (`prims`) changed: the
 * same boxes as a whole refit, the others being as they were; false when a box is not finite (as refit).
 */
function refitAbove(t: Tree, prims: usize, ids: usize, count: i32): bool {
  for (let i = 0; i < count; i++) {
    const id = i32At(ids, i);
    for (let c = 0; c < 6; c++) {
      const v = load<f64>(prims + <usize>id * 48 + (<usize>c << 3));
      if (v != v) return false;
    }
    for (let node = i32At(t.leaf, id); node >= 0; node = i32At(t.parent, node)) refitNode(t, node, prims);
  }
  for (let c = 0; c < 6; c++) if (!isFinite<f64>(load<f64>(t.boxes + (<usize>c << 3)))) return false;
  return true;
}

/** Each triangle's and edge's largest reach radius of its corners (TRADIUS, ERADIUS), from the particles' (RADIUS). */
function radiiOf(): void {
  for (let t = 0; t < NT; t++) {
    const tr = TRIS + <usize>t * 12;
    store<f64>(TRADIUS + (<usize>t << 3), max(max(radius(load<u32>(tr)), radius(load<u32>(tr, 4))), radius(load<u32>(tr, 8))));
  }
  for (let e = 0; e < NE; e++) {
    const ed = EDGES + <usize>e * 8;
    store<f64>(ERADIUS + (<usize>e << 3), max(radius(load<u32>(ed)), radius(load<u32>(ed, 4))));
  }
  radiiMade = true;
}

/**
 * Adds (particle p, triangle t) to RAW as the `n`th pair unless p is a corner of t or the two are apart (the
 * reference's Trees.addPair); returns the pairs in RAW after it, −1 when RAW is full.
 */
@inline function addPair(p: i32, t: i32, n: i32): i32 {
  const tr = TRIS + <usize>t * 12;
  const a = load<u32>(tr), b = load<u32>(tr, 4), c = load<u32>(tr, 8);
  if (a == <u32>p || b == <u32>p || c == <u32>p) return n;
  const rp = radiiMade ? radius(<u32>p) : radiusNow(<u32>p);
  const near = hFor + rp + (radiiMade ? load<f64>(TRADIUS + (<usize>t << 3)) : max(max(radiusNow(a), radiusNow(b)), radiusNow(c))) + SKIP_MARGIN;
  if (near < meanEdge && closestPoint(<usize>p * 12, <usize>a * 12, <usize>b * 12, <usize>c * 12) > near) return n;
  if (n >= RAW_CAP) return -1;
  const at = RAW + (<usize>n << 3);
  store<i32>(at, p); store<i32>(at, t, 4);
  return n + 1;
}

/** Adds (edge e, edge f), e < f, as addPair does (the reference's Trees.addEdgePair). */
@inline function addEdgePair(e: i32, f: i32, n: i32): i32 {
  const ea = EDGES + <usize>e * 8, fa = EDGES + <usize>f * 8;
  const a = load<u32>(ea), b = load<u32>(ea, 4), c = load<u32>(fa), d = load<u32>(fa, 4);
  if (c == a || c == b || d == a || d == b) return n;
  const near = SELF_EDGE_SHARE * hFor + (radiiMade ? load<f64>(ERADIUS + (<usize>e << 3)) + load<f64>(ERADIUS + (<usize>f << 3)) : max(radiusNow(a), radiusNow(b)) + max(radiusNow(c), radiusNow(d))) + SKIP_MARGIN;
  if (near < meanEdge && segmentClosest(X, <usize>a * 12, <usize>b * 12, <usize>c * 12, <usize>d * 12) > near) return n;
  if (n >= RAW_CAP) return -1;
  const at = RAW + (<usize>n << 3);
  store<i32>(at, e); store<i32>(at, f, 4);
  return n + 1;
}

@inline function push(top: i32, a: i32, b: i32): void {
  const at = STACK + (<usize>top << 2);
  store<i32>(at, a); store<i32>(at, b, 4);
}

/**
 * Every primitive p of tree A and q of tree B whose boxes (`mine`, `theirs`) meet, through addPair into RAW;
 * returns how many were added, −1 when RAW or the stack is full.
 */
function pairsWith(A: Tree, B: Tree, mine: usize, theirs: usize): i32 {
  let top = 0, n = 0;
  push(top, 0, 0); top += 2;
  while (top > 0) {
    top -= 2;
    const a = i32At(STACK, top), b = i32At(STACK, top + 1);
    if (!overlap(A.boxes + <usize>a * 48, B.boxes + <usize>b * 48)) continue;
    const ra = i32At(A.right, a), rb = i32At(B.right, b);
    if (ra < 0 && rb < 0) {
      const bBox = B.boxes + <usize>b * 48;
      for (let i = i32At(A.first, a), ie = i + i32At(A.size, a); i < ie; i++) {
        const p = i32At(A.order, i);
        // b's box holds each of its primitives' boxes: a primitive that misses it meets none of them
        if (!overlap(mine + <usize>p * 48, bBox)) continue;
        for (let j = i32At(B.first, b), je = j + i32At(B.size, b); j < je; j++) {
          const q = i32At(B.order, j);
          if (overlap(mine + <usize>p * 48, theirs + <usize>q * 48)) {
            n = addPair(p, q, n);
            if (n < 0) return -1;
          }
        }
      }
      continue;
    }
    if (top + 4 > 2 * STACK_CAP) return -1;
    if (rb < 0 || (ra >= 0 && i32At(A.size, a) >= i32At(B.size, b))) {
      push(top, a + 1, b); push(top + 2, ra, b);
    } else {
      push(top, a, b + 1); push(top + 2, a, rb);
    }
    top += 4;
  }
  return n;
}

/** Every two primitives p < q of tree A whose boxes (`prims`) meet, through addEdgePair into RAW (as pairsWith). */
function pairsWithin(A: Tree, prims: usize): i32 {
  let top = 0, n = 0;
  push(top, 0, 0); top += 2;
  while (top > 0) {
    top -= 2;
    const a = i32At(STACK, top), b = i32At(STACK, top + 1);
    if (top + 6 > 2 * STACK_CAP) return -1;
    const ra = i32At(A.right, a);
    if (a == b) {
      if (ra < 0) {
        for (let i = i32At(A.first, a), end = i + i32At(A.size, a); i < end; i++) {
          for (let j = i + 1; j < end; j++) {
            const p = i32At(A.order, i), q = i32At(A.order, j);
            if (overlap(prims + <usize>p * 48, prims + <usize>q * 48)) {
              n = addEdgePair(min(p, q), max(p, q), n);
              if (n < 0) return -1;
            }
          }
        }
      } else {
        const l = a + 1;
        push(top, l, l); push(top + 2, ra, ra); push(top + 4, l, ra);
        top += 6;
      }
      continue;
    }
    if (!overlap(A.boxes + <usize>a * 48, A.boxes + <usize>b * 48)) continue;
    const rb = i32At(A.right, b);
    if (ra < 0 && rb < 0) {
      const bBox = A.boxes + <usize>b * 48;
      for (let i = i32At(A.first, a), ie = i + i32At(A.size, a); i < ie; i++) {
        const p = i32At(A.order, i);
        if (!overlap(prims + <usize>p * 48, bBox)) continue;
        for (let j = i32At(A.first, b), je = j + i32At(A.size, b); j < je; j++) {
          const q = i32At(A.order, j);
          if (overlap(prims + <usize>p * 48, prims + <usize>q * 48)) {
            n = addEdgePair(min(p, q), max(p, q), n);
            if (n < 0) return -1;
          }
        }
      }
    } else if (rb < 0 || (ra >= 0 && i32At(A.size, a) >= i32At(A.size, b))) {
      push(top, a + 1, b); push(top + 2, ra, b);
      top += 4;
    } else {
      push(top, a, b + 1); push(top + 2, a, rb);
      top += 4;
    }
  }
  return n;
}

/**
 * The first `count` pairs of RAW (first entries below n, second below m) into `out` in the order they are resolved,
 * ascending by first then second entry (the reference's sortPairs, which sorts by the first and then by insertion;
 * no pair is listed twice, so the order is the same): a counting sort by the second entry into `temp` (8 bytes a
 * pair), then a stable one by the first. A search's lists, where a particle or an edge has dozens of pairs, for which
 * insertion costs as much as the rest of the sort.
 */
function radixInto(count: i32, m: i32, n: i32, temp: usize, out: usize): void {
  countingSort(RAW, count, m, 4, temp);
  countingSort(temp, count, n, 0, out);
}

/** The `count` pairs at `from` into `to` by the entry at byte `key` (0: first, 4: second; below `range`), stably. */
function countingSort(from: usize, count: i32, range: i32, key: usize, to: usize): void {
  memory.fill(BUCKET, 0, (<usize>range + 1) << 2);
  for (let q = 0; q < count; q++) {
    const at = BUCKET + ((<usize>load<i32>(from + (<usize>q << 3) + key) + 1) << 2);
    store<i32>(at, load<i32>(at) + 1);
  }
  for (let i = 0; i < range; i++) {
    const at = BUCKET + ((<usize>i + 1) << 2);
    store<i32>(at, load<i32>(at) + i32At(BUCKET, i));
  }
  for (let q = 0; q < count; q++) {
    const src = from + (<usize>q << 3), at = BUCKET + (<usize>load<i32>(src + key) << 2), k = load<i32>(at);
    store<i32>(at, k + 1);
    store<i64>(to + (<usize>k << 3), load<i64>(src));
  }
}

/**
 * The first `count` pairs of RAW (first entries below n) into `out` as radixInto does, for an update's few pairs:
 * a counting sort by the first entry, then insertion by the second (the reference's sortPairs).
 */
function sortInto(count: i32, n: i32, out: usize): void {
  countingSort(RAW, count, n, 0, out);
  // each bucket now ends where the next begins
  for (let i = 0, from = 0; i < n; i++) {
    const to = i32At(BUCKET, i);
    for (let a = from + 1; a < to; a++) {
      const v = load<i32>(out + (<usize>a << 3), 4);
      let b = a - 1;
      for (; b >= from && load<i32>(out + (<usize>b << 3), 4) > v; b--) store<i32>(out + (<usize>(b + 1) << 3), load<i32>(out + (<usize>b << 3), 4), 4);
      store<i32>(out + (<usize>(b + 1) << 3), v, 4);
    }
    from = to;
  }
}
