/**
 * The WebAssembly kernel's self-contact (the `selfContact` phase; self-contact.ts is the reference): the host's
 * part. The kernel finds the candidate pairs ahead itself (self-search.as.ts: the reference's search on the
 * reference's trees, whose structure is copied into its memory once, the same pairs in the same order) into two
 * pair windows; every substep it computes the particles' boxes over the substep and checks them against the reach
 * boxes, and runs the particle–triangle and edge–edge passes over the pairs (self-contact.as.ts), with the
 * reference's operations in its order: the same cloth bit for bit. Search and passes run on the calling thread
 * (Gauss–Seidel, in the pairs' order) between two substep() calls of the other phases. The windows have a fixed
 * size in the kernel's memory (its size is fixed when the kernel is made); a search that finds more pairs than a
 * window holds is made again in TypeScript (findSelfCandidates), which keeps them here and copies them in window
 * by window every substep, in order, which only costs the copies. Several cloths: each particle's cloth and each
 * cloth's thickness and friction are in the kernel's memory, so cloths that differ in them run here too. Where a
 * few particles left their reach boxes (at most UPDATE_MOST of the cloth), the kernel updates its own search's
 * candidates for them (selfUpdate: the reference's updateCandidates, the same pairs) instead of searching whole.
 */
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import {
  UPDATE_MOST, countSelfSearch, countSelfUpdate, findSelfCandidates, rowsOf, searchAhead, selfContactDistance,
  selfContactTrees, selfSearchLengths, type SelfCandidates,
} from '../self-contact.js';
import type { BoxTree } from '../box-tree.js';
import type { ClothState } from '../state.js';

/** What the kernel exports for self-contact (self-contact.as.ts). */
export interface SelfContactExports {
  configureSelf(...layout: number[]): void;
  selfBoxes(start: boolean): number;
  selfFrame(ux: number, uy: number, uz: number): void;
  selfFound(edgePairs: number): void;
  selfTriangleBoxes(hMax: number, pairs: number): void;
  selfParticles(count: number, hMax: number): void;
  selfEdgeBoxes(hMax: number, pairs: number): void;
  selfEdges(count: number, hMax: number, memo: boolean): void;
  selfStaleEdges(): number;
  selfEdgeRecords(): number;
  configureSearch(...layout: number[]): void;
  selfSearch(hMax: number, left: number, h: number, gx: number, gy: number, gz: number, span: number, edge: number, window: number, edgeWindow: number): number;
  selfUpdate(count: number, hMax: number, left: number, h: number, gx: number, gy: number, gz: number, span: number, window: number, edgeWindow: number): number;
  foundPairs(): number;
  foundEdgePairs(): number;
}

/**
 * Pairs a window holds by default [pairs]: per particle, particle–triangle and edge–edge, and at least. The most a
 * search found in fold's landing: 23 and 69 per particle at 64², 29.8 and 85.9 at 128² (where the contact distance
 * is a larger share of an edge, as at every finer size: half the smallest rest altitude).
 */
const WINDOW_PER_PARTICLE = 32;
const EDGE_WINDOW_PER_PARTICLE = 96;
const WINDOW_MIN = 1 << 14;
/** node pairs the kernel's tree traversals can hold (a traversal's stack grows by at most two a level: ~60 at 256²) */
const STACK_PAIRS = 1024;
/**
 * Pairs an update may find per particle it takes (selfUpdate's scratch; one that finds more searches whole): the
 * particles' and the triangles' pairs, or the edges' (an escaped particle's up to 12 edges, each with the pairs of
 * an edge: about 64 at fold's 64² landing).
 */
const FRESH_PER_UPDATED = 1024;
/** one tree's descriptor in the kernel (self-search.as.ts Tree): order, first, size, right, boxes, node count, parent, leaf */
const TREE_FIELDS = 8;

/** Where self-contact's arrays lie in the kernel's memory (byte offsets) and how many pairs each window holds. */
export interface SelfContactLayout {
  tris: number; edges: number; owner: number; cloth: number; reach: number; pbox: number; tbox: number; ebox: number;
  tframe: number; eframe: number; tframeAt: number; eframeAt: number; movedAt: number; pairs: number; edgePairs: number;
  /** the pass each triangle's box and each edge's record was made for */
  tboxAt: number; eboxAt: number;
  travel: number; seen: number; move: number; edgeMemo: number; window: number; edgeWindow: number;
  /** each particle's edges, as rows (self-contact.ts rowsOf): where each particle's start, and the list */
  edgeStart: number; edgeList: number;
  /** the search's: the three trees' descriptors and arrays, the reach radii and boxes, its scratch */
  trees: number; tree: { order: number; first: number; size: number; right: number; boxes: number; parent: number; leaf: number }[];
  radius: number; treach: number; ereach: number; bucket: number; stack: number; tradius: number; eradius: number;
  radiusAt: number;
  /** each particle's triangles, as rows (self-contact.ts rowsOf): where each particle's start, and the list */
  triStart: number; triList: number;
  /** the update's: the particles out of their boxes, marks, the triangles and edges it does, its fresh pairs (freshCap) */
  escaped: number; marks: number; touched: number; fresh: number; freshCap: number;
}

/**
 * Lays self-contact's arrays out for `model` with `take(bytes)` (the kernel's allocator: returns the byte offset);
 * `window` [pairs] sets both windows' size (tests: a small one, to run the window-by-window path).
 */
export function layoutSelfContact(model: ClothModel, take: (bytes: number) => number, window?: number): SelfContactLayout {
  const n = model.particleCount, nt = model.triangles.length / 3, ne = model.edges.length / 2;
  const w = window ?? Math.max(WINDOW_MIN, WINDOW_PER_PARTICLE * n), we = window ?? Math.max(WINDOW_MIN, EDGE_WINDOW_PER_PARTICLE * n);
  const { particles, triangles, edges } = selfContactTrees(model);
  const tree = [particles, triangles, edges].map((t: BoxTree) => ({
    order: take(4 * t.order.length), first: take(4 * t.nodeCount), size: take(4 * t.nodeCount), right: take(4 * t.nodeCount), boxes: take(48 * t.nodeCount),
    parent: take(4 * t.nodeCount), leaf: take(4 * t.order.length),
  }));
  const freshCap = Math.max(1 << 12, FRESH_PER_UPDATED * Math.ceil(UPDATE_MOST * n));
  return {
    trees: take(4 * TREE_FIELDS * 3), tree, radius: take(8 * n), treach: take(48 * nt), ereach: take(48 * ne), tradius: take(8 * nt), eradius: take(8 * ne),
    radiusAt: take(4 * n), triStart: take(4 * (n + 1)), triList: take(12 * nt),
    bucket: take(4 * (Math.max(n, ne) + 1)), stack: take(8 * STACK_PAIRS),
    escaped: take(4 * n), marks: take(n + nt + ne), touched: take(4 * (nt + ne)), fresh: take(16 * freshCap), freshCap,
    tris: take(12 * nt), edges: take(8 * ne), owner: take(n), cloth: take(24 * (model.clothStarts.length - 1)),
    // the edges' records a cache line each, on a cache line's boundary (take gives 16-byte ones)
    reach: take(48 * n), pbox: take(48 * n), tbox: take(48 * nt), ebox: Math.ceil(take(64 * ne + 48) / 64) * 64,
    tframe: take(80 * nt), eframe: take(48 * ne), tframeAt: take(4 * nt), eframeAt: take(4 * ne), movedAt: take(4 * n),
    tboxAt: take(4 * nt), eboxAt: take(4 * ne),
    pairs: take(8 * w), edgePairs: take(8 * we), travel: take(8 * n), seen: take(12 * n), move: take(8 * n), edgeMemo: take(16 * we),
    window: w, edgeWindow: we, edgeStart: take(4 * (n + 1)), edgeList: take(8 * ne),
  };
}

/** Candidate pairs as a search left them: (particle, triangle) and (edge, edge), and whether the kernel or TypeScript found them. */
export interface ListedPairs {
  readonly pairs: Int32Array;
  readonly edgePairs: Int32Array;
  readonly foundBy: 'kernel' | 'typescript';
}

/** A pair list kept on the host while it is larger than its window, and the window it is copied into. */
class PairList {
  /** the window in the kernel's memory: pairs of i32 */
  readonly pairWindow: Int32Array;
  /** the list when it is larger than the window, else unused (grows rarely) */
  private overflow = new Int32Array(0);
  /** pairs in the list; whether they are all in the window */
  count = 0;
  resident = true;

  constructor(memory: ArrayBufferLike, at: number, pairs: number) {
    this.pairWindow = new Int32Array(memory, at, 2 * pairs);
  }

  /** A copy of the list's pairs. */
  copy(): Int32Array {
    return (this.resident ? this.pairWindow : this.overflow).slice(0, 2 * this.count);
  }

  /** The kernel's search wrote `count` pairs into the window (they are all there). */
  found(count: number): void {
    this.count = count;
    this.resident = true;
  }

  /** Takes the first `count` pairs of `list` (after a search): into the window when they fit, else kept here. */
  take(list: Int32Array, count: number): void {
    this.count = count;
    this.resident = 2 * count <= this.pairWindow.length;
    if (this.resident) {
      this.pairWindow.set(list.subarray(0, 2 * count));
      return;
    }
    if (this.overflow.length < 2 * count) this.overflow = new Int32Array(Math.ceil(3 * count));
    this.overflow.set(list.subarray(0, 2 * count));
  }

  /**
   * Runs `pass(count, hMax, resident)` over every pair in order: the window at once (resident: the window keeps its
   * pairs from substep to substep), or one window after another.
   */
  run(pass: (count: number, hMax: number, resident: boolean) => void, hMax: number): void {
    if (this.resident) {
      pass(this.count, hMax, true);
      return;
    }
    const cap = this.pairWindow.length / 2;
    for (let q = 0; q < this.count; q += cap) {
      const k = Math.min(cap, this.count - q);
      this.pairWindow.set(this.overflow.subarray(2 * q, 2 * (q + k)));
      pass(k, hMax, false);
    }
  }
}

/** One kernel's self-contact: its arrays in the kernel's memory and the candidates it holds. */
export class KernelSelfContact {
  private readonly exports: SelfContactExports;
  private readonly reach: Float64Array;
  private readonly owner: Uint8Array;
  private readonly cloth: Float64Array;
  private readonly pairs: PairList;
  private readonly edgePairs: PairList;
  /** the distance h [m] the candidates in the kernel were found for (NaN: none) */
  private builtFor = NaN;
  /** substeps since the last whole search (this one included), and how many the one before it held (∞: none yet): searchAhead */
  private since = Infinity;
  private lasted = Infinity;
  /** who found the candidates last */
  private foundBy: ListedPairs['foundBy'] | null = null;
  private paramsSeen: SimParams | undefined;
  /** the search's lengths [m] (selfSearchLengths) and the windows' sizes [pairs] */
  private readonly lengths: { meanEdge: number; span: number };
  private readonly windows: [number, number];
  private readonly particles: (count: number, hMax: number) => void;
  private readonly edges: (count: number, hMax: number, resident: boolean) => void;

  /** Self-contact for `model` in the kernel whose memory is `memory`, laid out by layoutSelfContact. */
  constructor(model: ClothModel, memory: ArrayBufferLike, layout: SelfContactLayout, exports: SelfContactExports) {
    const n = model.particleCount, nt = model.triangles.length / 3, ne = model.edges.length / 2;
    new Uint32Array(memory, layout.tris, 3 * nt).set(model.triangles);
    new Uint32Array(memory, layout.edges, 2 * ne).set(model.edges);
    this.reach = new Float64Array(memory, layout.reach, 6 * n);
    this.owner = new Uint8Array(memory, layout.owner, n);
    this.cloth = new Float64Array(memory, layout.cloth, 3 * (model.clothStarts.length - 1));
    this.pairs = new PairList(memory, layout.pairs, layout.window);
    this.edgePairs = new PairList(memory, layout.edgePairs, layout.edgeWindow);
    this.exports = exports;
    const l = layout;
    exports.configureSelf(l.tris, l.edges, l.owner, l.cloth, l.reach, l.pbox, l.tbox, l.ebox, l.tframe, l.eframe,
      l.tframeAt, l.eframeAt, l.movedAt, l.pairs, l.edgePairs, l.travel, l.seen, l.move, l.edgeMemo, l.escaped, l.edgeStart,
      l.edgeList, nt, ne, l.tboxAt, l.eboxAt);
    // each particle's edges and triangles (the edge pass's records, the update's primitives)
    const rows = rowsOf(model.edges, 2, n), triRows = rowsOf(model.triangles, 3, n);
    new Int32Array(memory, l.edgeStart, n + 1).set(rows.start);
    new Int32Array(memory, l.edgeList, 2 * ne).set(rows.list);
    new Int32Array(memory, l.triStart, n + 1).set(triRows.start);
    new Int32Array(memory, l.triList, 3 * nt).set(triRows.list);
    // the trees' structure (the reference's, built once), and where each tree lies
    const trees = selfContactTrees(model), descriptors = new Int32Array(memory, l.trees, TREE_FIELDS * 3);
    [trees.particles, trees.triangles, trees.edges].forEach((t, k) => {
      const at = l.tree[k], nodes = t.nodeCount;
      new Int32Array(memory, at.order, t.order.length).set(t.order);
      new Int32Array(memory, at.first, nodes).set(t.first.subarray(0, nodes));
      new Int32Array(memory, at.size, nodes).set(t.size.subarray(0, nodes));
      new Int32Array(memory, at.right, nodes).set(t.right.subarray(0, nodes));
      descriptors.set([at.order, at.first, at.size, at.right, at.boxes, nodes, at.parent, at.leaf], TREE_FIELDS * k);
    });
    // after configureSelf: the search reads the particles' edge rows it set
    exports.configureSearch(l.trees, l.radius, l.treach, l.ereach, l.bucket, l.stack, STACK_PAIRS, nt, ne, l.marks, l.touched, l.fresh, l.freshCap, l.tradius, l.eradius, l.radiusAt,
      l.triStart, l.triList);
    this.lengths = selfSearchLengths(model);
    this.windows = [l.window, l.edgeWindow];
    this.particles = (count, hMax) => exports.selfParticles(count, hMax);
    // the edge pairs' measured distances hold while the window keeps its pairs
    this.edges = (count, hMax, resident) => exports.selfEdges(count, hMax, resident);
  }

  /**
   * One substep of self-contact on the kernel's state, as collideSelf: substep length h [s], `left` substeps of the
   * frame left (this one included).
   */
  run(model: ClothModel, state: ClothState, params: SimParams, h: number, left: number): void {
    if (model.triangles.length / 3 < 2) return;
    const hMax = selfContactDistance(model, params);
    if (!(hMax > 0)) return;
    if (params !== this.paramsSeen) {
      // each particle's cloth, each cloth's thickness and friction
      this.owner.set(params.owner);
      const { thickness, friction, staticFriction } = params.perCloth;
      for (let c = 0; c < thickness.length; c++) {
        this.cloth[3 * c] = thickness[c]; this.cloth[3 * c + 1] = friction[c]; this.cloth[3 * c + 2] = staticFriction[c];
      }
      this.paramsSeen = params;
    }
    const ex = this.exports;
    this.since++;
    const ahead = searchAhead(left, this.lasted);
    // the candidates hold while every particle's box over this substep is inside its reach box
    const out = ex.selfBoxes(true);
    if (!(this.builtFor === hMax && out === 0) && !this.update(model, params, out, hMax, h, ahead) && !this.find(model, state, params, hMax, h, ahead)) return;
    ex.selfTriangleBoxes(hMax, this.pairs.count);
    this.pairs.run(this.particles, hMax);
    // the particle pass may have pushed a particle out of its reach box
    const pushed = ex.selfBoxes(false);
    if (pushed !== 0 && !this.update(model, params, pushed, hMax, h, ahead) && !this.find(model, state, params, hMax, h, ahead)) return;
    ex.selfEdgeBoxes(hMax, this.edgePairs.count);
    this.edgePairs.run(this.edges, hMax);
  }

  /**
   * Updates the kernel's own candidates for the `out` particles out of their reach boxes where they are few, as
   * the reference's updateCandidates; false where it does not (too many, none found yet or found in TypeScript, an
   * unstable cloth, or pairs beyond the windows: a whole search follows).
   */
  private update(model: ClothModel, params: SimParams, out: number, hMax: number, h: number, left: number): boolean {
    if (this.builtFor !== hMax || this.foundBy !== 'kernel' || out > UPDATE_MOST * model.particleCount) return false;
    const g = params.gravity, ex = this.exports;
    if (ex.selfUpdate(out, hMax, left, h, g[0], g[1], g[2], this.lengths.span, this.windows[0], this.windows[1]) !== 1) return false;
    countSelfUpdate(model);
    this.pairs.found(ex.foundPairs());
    this.edgePairs.found(ex.foundEdgePairs());
    return true;
  }

  /**
   * Finds the candidates: in the kernel, or where they do not fit its windows in TypeScript (findSelfCandidates),
   * copied into the kernel; false for an unstable cloth.
   */
  private find(model: ClothModel, state: ClothState, params: SimParams, hMax: number, h: number, left: number): boolean {
    const g = params.gravity, ex = this.exports;
    const found = ex.selfSearch(hMax, left, h, g[0], g[1], g[2], this.lengths.span, this.lengths.meanEdge, this.windows[0], this.windows[1]);
    if (found === 0) {
      this.builtFor = NaN;
      this.foundBy = null;
      return false;
    }
    if (found === 1) {
      countSelfSearch(model);
      const edgePairs = ex.foundEdgePairs();
      this.pairs.found(ex.foundPairs());
      this.edgePairs.found(edgePairs);
      ex.selfFound(edgePairs);
      this.searched();
      this.builtFor = hMax;
      this.foundBy = 'kernel';
      return true;
    }
    const c: SelfCandidates | null = findSelfCandidates(model, state, params, h, left);
    if (!c) {
      this.builtFor = NaN;
      this.foundBy = null;
      return false;
    }
    this.reach.set(c.reach);
    ex.selfFrame(c.frame[0], c.frame[1], c.frame[2]);
    this.pairs.take(c.pairs, c.pairCount);
    this.edgePairs.take(c.edgePairs, c.edgePairCount);
    this.exports.selfFound(this.edgePairs.resident ? c.edgePairCount : 0);
    this.searched();
    this.builtFor = hMax;
    this.foundBy = 'typescript';
    return true;
  }

  /** A whole search was made: the lists before it held `since` substeps (searchAhead). */
  private searched(): void {
    this.lasted = this.since;
    this.since = 0;
  }

  /**
   * How many of the last edge pass's records are not current (tests: none between two substeps), and how many it
   * made (the pairs' edges: the rest are made when a pass reads them).
   */
  edgeRecords(): { stale: number; made: number } {
    return { stale: this.exports.selfStaleEdges(), made: this.exports.selfEdgeRecords() };
  }

  /** The candidates as the last search left them (tests), or null before the first. */
  listed(): ListedPairs | null {
    return this.foundBy && { pairs: this.pairs.copy(), edgePairs: this.edgePairs.copy(), foundBy: this.foundBy };
  }
}
