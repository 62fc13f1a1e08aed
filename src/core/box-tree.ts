/**
 * A bounding-box tree over a fixed set of primitives (a model's particles, triangles or edges), built once from
 * their rest positions and refitted to new boxes whenever the pairs are searched for: the broad phase of
 * self-contact (self-contact.ts). A cloth keeps its topology, so neighbours at rest stay neighbours and a refitted
 * tree stays tight (the bounding-volume hierarchies of cloth collision since Volino & Magnenat-Thalmann 1994 and
 * Bridson et al. 2002). The pairs it yields are exactly those whose boxes meet, each once, in no particular order.
 *
 * Nodes are stored depth first: node i's left child is i + 1, its right child `right[i]`; a leaf (right[i] < 0)
 * holds the primitives order[first[i] … first[i] + size[i]).
 */

/**
 * the most primitives in a leaf: with 8 (leaves of 5–8) fold's whole searches at 64² in its landing (frames 1–60)
 * took 7 % less than with 4 (scripts/self-contact-ab.mjs, 2026-12-07: 54.5 → 50.5 ms a frame), 12
 * and 16 no less than 8; at 128² the same as 4 (docs/performance.md, "Two builds in one process")
 */
const LEAF = 8;

export class BoxTree {
  /** the primitives, leaf by leaf */
  readonly order: Int32Array;
  readonly first: Int32Array;
  readonly size: Int32Array;
  readonly right: Int32Array;
  /** each node's box (min x, y, z, max x, y, z), of the last refit */
  readonly boxes: Float64Array;
  readonly nodeCount: number;
  /** a stack of node pairs for the traversals, grown when a traversal needs more */
  private stack: Int32Array = new Int32Array(256);

  /** Builds the tree over the primitives whose centres (3 numbers each, n of them) are `centres`: median splits along the longest side. */
  constructor(centres: Float64Array, n: number) {
    this.order = Int32Array.from({ length: n }, (_, i) => i);
    // a binary tree whose leaves each hold a primitive or more (one empty leaf when n is 0) has fewer than 2n nodes
    const most = 2 * Math.max(n, 1);
    this.first = new Int32Array(most);
    this.size = new Int32Array(most);
    this.right = new Int32Array(most);
    let count = 0;
    const split = (from: number, to: number): void => {
      const node = count++;
      this.first[node] = from;
      this.size[node] = to - from;
      if (to - from <= LEAF) { this.right[node] = -1; return; }
      const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = from; i < to; i++) {
        for (let c = 0; c < 3; c++) {
          const v = centres[3 * this.order[i] + c];
          if (v < lo[c]) lo[c] = v;
          if (v > hi[c]) hi[c] = v;
        }
      }
      const ax = hi[0] - lo[0] >= hi[1] - lo[1] && hi[0] - lo[0] >= hi[2] - lo[2] ? 0 : hi[1] - lo[1] >= hi[2] - lo[2] ? 1 : 2;
      const mid = (from + to) >> 1;
      select(this.order, from, to, mid, centres, ax);
      split(from, mid);
      this.right[node] = count;
      split(mid, to);
    };
    split(0, n);
    this.nodeCount = count;
    this.boxes = new Float64Array(6 * count);
  }

  /**
   * The nodes' boxes from the primitives' (`prims`, six numbers each); false (the tree then unusable until the next
   * refit) when a box is not finite.
   */
  refit(prims: Float64Array): boolean {
    const { boxes, first, size, right, order } = this;
    for (let node = this.nodeCount - 1; node >= 0; node--) {
      const o = 6 * node;
      if (right[node] < 0) {
        for (let c = 0; c < 3; c++) { boxes[o + c] = Infinity; boxes[o + 3 + c] = -Infinity; }
        for (let i = first[node], end = first[node] + size[node]; i < end; i++) {
          const p = 6 * order[i];
          for (let c = 0; c < 3; c++) {
            if (prims[p + c] < boxes[o + c]) boxes[o + c] = prims[p + c];
            if (prims[p + 3 + c] > boxes[o + 3 + c]) boxes[o + 3 + c] = prims[p + 3 + c];
          }
        }
      } else {
        const l = o + 6, r = 6 * right[node];
        for (let c = 0; c < 3; c++) {
          boxes[o + c] = Math.min(boxes[l + c], boxes[r + c]);
          boxes[o + 3 + c] = Math.max(boxes[l + 3 + c], boxes[r + 3 + c]);
        }
      }
    }
    // an infinite box reaches the root's; a NaN the leaves' comparisons skip, so it is looked for in the boxes
    for (let c = 0; c < 6; c++) if (!Number.isFinite(boxes[c])) return false;
    for (let i = 0; i < prims.length; i++) if (prims[i] !== prims[i]) return false;
    return true;
  }

  /**
   * Calls visit(i, j) for every primitive i of this tree and j of `other` whose boxes (`mine`, `theirs`, as
   * refitted) meet.
   */
  pairsWith(other: BoxTree, mine: Float64Array, theirs: Float64Array, visit: (i: number, j: number) => void): void {
    let stack: Int32Array = this.stack, top = 0;
    stack[top++] = 0; stack[top++] = 0;
    const A = this.boxes, B = other.boxes;
    while (top > 0) {
      const b = stack[--top], a = stack[--top];
      if (!meets(A, 6 * a, B, 6 * b)) continue;
      const leafA = this.right[a] < 0, leafB = other.right[b] < 0;
      if (leafA && leafB) {
        for (let i = this.first[a], ie = i + this.size[a]; i < ie; i++) {
          const p = this.order[i];
          for (let j = other.first[b], je = j + other.size[b]; j < je; j++) {
            const q = other.order[j];
            if (meets(mine, 6 * p, theirs, 6 * q)) visit(p, q);
          }
        }
        continue;
      }
      if (top + 4 > stack.length) stack = this.grow();
      if (leafB || (!leafA && this.size[a] >= other.size[b])) {
        stack[top++] = a + 1; stack[top++] = b;
        stack[top++] = this.right[a]; stack[top++] = b;
      } else {
        stack[top++] = a; stack[top++] = b + 1;
        stack[top++] = a; stack[top++] = other.right[b];
      }
    }
  }

  /** Calls visit(i, j), i < j, for every two primitives of this tree whose boxes (`prims`, as refitted) meet. */
  pairsWithin(prims: Float64Array, visit: (i: number, j: number) => void): void {
    let stack: Int32Array = this.stack, top = 0;
    stack[top++] = 0; stack[top++] = 0;
    const A = this.boxes, { first, size, right, order } = this;
    while (top > 0) {
      const b = stack[--top], a = stack[--top];
      if (top + 6 > stack.length) stack = this.grow();
      if (a === b) {
        if (right[a] < 0) {
          for (let i = first[a], end = i + size[a]; i < end; i++) {
            for (let j = i + 1; j < end; j++) {
              const p = order[i], q = order[j];
              if (meets(prims, 6 * p, prims, 6 * q)) visit(Math.min(p, q), Math.max(p, q));
            }
          }
        } else {
          const l = a + 1, r = right[a];
          stack[top++] = l; stack[top++] = l;
          stack[top++] = r; stack[top++] = r;
          stack[top++] = l; stack[top++] = r;
        }
        continue;
      }
      if (!meets(A, 6 * a, A, 6 * b)) continue;
      const leafA = right[a] < 0, leafB = right[b] < 0;
      if (leafA && leafB) {
        for (let i = first[a], ie = i + size[a]; i < ie; i++) {
          const p = order[i];
          for (let j = first[b], je = j + size[b]; j < je; j++) {
            const q = order[j];
            if (meets(prims, 6 * p, prims, 6 * q)) visit(Math.min(p, q), Math.max(p, q));
          }
        }
      } else if (leafB || (!leafA && size[a] >= size[b])) {
        stack[top++] = a + 1; stack[top++] = b;
        stack[top++] = right[a]; stack[top++] = b;
      } else {
        stack[top++] = a; stack[top++] = b + 1;
        stack[top++] = a; stack[top++] = right[b];
      }
    }
  }

  /**
   * Calls visit(id, j) for every primitive j of this tree whose box (`prims`, as refitted) meets box[o…o+5] (`id`:
   * the box's own, handed on, so that visit needs no closure of its own).
   */
  query(box: Float64Array, o: number, prims: Float64Array, id: number, visit: (id: number, j: number) => void): void {
    let stack: Int32Array = this.stack, top = 0;
    stack[top++] = 0;
    const A = this.boxes, { first, size, right, order } = this;
    while (top > 0) {
      const a = stack[--top];
      if (!meets(A, 6 * a, box, o)) continue;
      if (right[a] < 0) {
        for (let i = first[a], end = i + size[a]; i < end; i++) if (meets(prims, 6 * order[i], box, o)) visit(id, order[i]);
        continue;
      }
      if (top + 2 > stack.length) stack = this.grow();
      stack[top++] = a + 1; stack[top++] = right[a];
    }
  }

  private grow(): Int32Array {
    const s = new Int32Array(2 * this.stack.length);
    s.set(this.stack);
    return (this.stack = s);
  }
}

/**
 * Reorders ids[from … to) so that ids[mid] is the one whose centre's coordinate `ax` is mid − from'th smallest (ties
 * by id), none before it larger and none after it smaller (Hoare's selection).
 */
function select(ids: Int32Array, from: number, to: number, mid: number, centres: Float64Array, ax: number): void {
  const key = (i: number) => centres[3 * ids[i] + ax];
  const less = (i: number, v: number, id: number) => key(i) < v || (key(i) === v && ids[i] < id);
  let lo = from, hi = to - 1;
  while (hi > lo) {
    const pivot = (lo + hi) >> 1, v = key(pivot), id = ids[pivot];
    let i = lo, j = hi;
    while (i <= j) {
      while (less(i, v, id)) i++;
      while (ids[j] !== id && !less(j, v, id)) j--;
      if (i <= j) { const t = ids[i]; ids[i] = ids[j]; ids[j] = t; i++; j--; }
    }
    if (mid <= j) hi = j;
    else if (mid >= i) lo = i;
    else return;
  }
}

/** Whether box a[i…] meets box b[j…] (touching counts). */
function meets(a: Float64Array, i: number, b: Float64Array, j: number): boolean {
  return !(a[i] > b[j + 3] || a[i + 3] < b[j] || a[i + 1] > b[j + 4] || a[i + 4] < b[j + 1] || a[i + 2] > b[j + 5] || a[i + 5] < b[j + 2]);
}
