/**
 * A bounding-volume hierarchy over a triangle mesh, in flat typed arrays only (no object per node), so that the
 * WebAssembly kernel and a WGSL shader can later walk the very same buffers:
 *
 * - `bounds` (Float32Array, 6 per node): min x y z, max x y z of the node's triangles. Taken from the float32
 *   vertex coordinates themselves, so a box contains its triangles exactly.
 * - `nodes` (Uint32Array, 2 per node): [first, count]. count > 0: a leaf of the triangles first … first + count − 1
 *   (triangles are stored in leaf order); count = 0: an inner node whose children are nodes `first` and `first + 1`.
 *   Node 0 is the root.
 * - `triangles` (Uint32Array, 3 per triangle) in leaf order, and `order`: the input index of each.
 *
 * Built top-down by the surface area heuristic over BVH_BINS bins of triangle centroids per axis (Wald 2007, "On
 * fast construction of SAH-based bounding volume hierarchies"), at most BVH_MAX_LEAF triangles per leaf; a range whose
 * centroids all coincide is cut in half by index. Queries use a stack sized from the tree's depth and allocate
 * nothing.
 */
import { closestPointIn } from './sphere.js';

/** Centroid bins per axis of the SAH build. */
export const BVH_BINS = 16;
/** Most triangles in a leaf. A range of at most this many becomes a leaf when the SAH finds no cheaper split. */
export const BVH_MAX_LEAF = 4;

const scratchBary = new Float64Array(3);

export class TriangleBvh {
  /** node boxes: min x y z, max x y z per node */
  readonly bounds: Float32Array;
  /** per node [first, count]: a leaf's triangles, or (count 0) an inner node's first child */
  readonly nodes: Uint32Array;
  /** node count */
  readonly nodeCount: number;
  /** vertex positions, xyz interleaved (shared with the caller, not copied) */
  readonly positions: Float32Array;
  /** triangles in leaf order */
  readonly triangles: Uint32Array;
  /** input index of each triangle in leaf order */
  readonly order: Uint32Array;
  /** longest root-to-leaf path (root alone: 1) */
  readonly depth: number;
  /** traversal stack (a node pushes at most one sibling per level) */
  readonly stack: Uint32Array;
  /** squared distance of the last `closest` hit */
  d2 = Infinity;
  /**
   * Unit normals of the triangles in leaf order (xyz), when the owner has them: `closest` then skips a triangle
   * whose plane is already farther than the best (a dot product before the closest-point test).
   */
  normals: Float32Array | null = null;

  constructor(positions: Float32Array, triangles: Uint32Array) {
    const m = triangles.length / 3;
    if (m < 1) throw new RangeError('TriangleBvh: no triangles');
    this.positions = positions;
    // per-triangle box and centroid
    const box = new Float32Array(6 * m), cen = new Float32Array(3 * m);
    for (let t = 0; t < m; t++) {
      const a = 3 * triangles[3 * t], b = 3 * triangles[3 * t + 1], c = 3 * triangles[3 * t + 2];
      for (let k = 0; k < 3; k++) {
        const pa = positions[a + k], pb = positions[b + k], pc = positions[c + k];
        const lo = Math.min(pa, pb, pc), hi = Math.max(pa, pb, pc);
        box[6 * t + k] = lo; box[6 * t + 3 + k] = hi;
        cen[3 * t + k] = 0.5 * (lo + hi);
      }
    }
    const idx = new Uint32Array(m);
    for (let t = 0; t < m; t++) idx[t] = t;
    const maxNodes = 2 * m - 1;
    const bounds = new Float32Array(6 * maxNodes), nodes = new Uint32Array(2 * maxNodes);
    // work list: node, start, end, depth
    const work = new Uint32Array(4 * Math.max(64, 2 * Math.ceil(Math.log2(m + 1)) + 64));
    let workLen = 0, nodeCount = 1, depth = 1;
    let workCap = work.length;
    let list = work;
    const push = (node: number, s: number, e: number, d: number) => {
      if (workLen + 4 > workCap) {
        const bigger = new Uint32Array(2 * workCap);
        bigger.set(list);
        list = bigger; workCap = bigger.length;
      }
      list[workLen++] = node; list[workLen++] = s; list[workLen++] = e; list[workLen++] = d;
    };
    push(0, 0, m, 1);
    const binCount = new Uint32Array(3 * BVH_BINS);
    const binBox = new Float64Array(6 * 3 * BVH_BINS);
    const rightArea = new Float64Array(BVH_BINS);
    const rightCount = new Uint32Array(BVH_BINS);
    const area = (x0: number, y0: number, z0: number, x1: number, y1: number, z1: number) => {
      const dx = x1 - x0, dy = y1 - y0, dz = z1 - z0;
      return dx * dy + dy * dz + dz * dx;
    };
    while (workLen > 0) {
      const d = list[--workLen], e = list[--workLen], s = list[--workLen], node = list[--workLen];
      if (d > depth) depth = d;
      // node box and centroid box
      let bx0 = Infinity, by0 = Infinity, bz0 = Infinity, bx1 = -Infinity, by1 = -Infinity, bz1 = -Infinity;
      let cx0 = Infinity, cy0 = Infinity, cz0 = Infinity, cx1 = -Infinity, cy1 = -Infinity, cz1 = -Infinity;
      for (let i = s; i < e; i++) {
        const t = idx[i], o = 6 * t;
        if (box[o] < bx0) bx0 = box[o]; if (box[o + 1] < by0) by0 = box[o + 1]; if (box[o + 2] < bz0) bz0 = box[o + 2];
        if (box[o + 3] > bx1) bx1 = box[o + 3]; if (box[o + 4] > by1) by1 = box[o + 4]; if (box[o + 5] > bz1) bz1 = box[o + 5];
        const x = cen[3 * t], y = cen[3 * t + 1], z = cen[3 * t + 2];
        if (x < cx0) cx0 = x; if (y < cy0) cy0 = y; if (z < cz0) cz0 = z;
        if (x > cx1) cx1 = x; if (y > cy1) cy1 = y; if (z > cz1) cz1 = z;
      }
      const nb = 6 * node;
      bounds[nb] = bx0; bounds[nb + 1] = by0; bounds[nb + 2] = bz0; bounds[nb + 3] = bx1; bounds[nb + 4] = by1; bounds[nb + 5] = bz1;
      const count = e - s;
      const leaf = () => { nodes[2 * node] = s; nodes[2 * node + 1] = count; };
      if (count <= 1) { leaf(); continue; }
      // binned SAH: cost of a split = A_left·N_left + A_right·N_right (relative to the node's area)
      const cmin = [cx0, cy0, cz0], cext = [cx1 - cx0, cy1 - cy0, cz1 - cz0];
      let bestCost = Infinity, bestAxis = -1, bestBin = 0;
      binCount.fill(0);
      for (let ax = 0; ax < 3; ax++) {
        if (!(cext[ax] > 0)) continue;
        const o6 = 6 * BVH_BINS * ax;
        for (let b = 0; b < BVH_BINS; b++) {
          binBox[o6 + 6 * b] = Infinity; binBox[o6 + 6 * b + 1] = Infinity; binBox[o6 + 6 * b + 2] = Infinity;
          binBox[o6 + 6 * b + 3] = -Infinity; binBox[o6 + 6 * b + 4] = -Infinity; binBox[o6 + 6 * b + 5] = -Infinity;
        }
      }
      for (let i = s; i < e; i++) {
        const t = idx[i], o = 6 * t;
        for (let ax = 0; ax < 3; ax++) {
          if (!(cext[ax] > 0)) continue;
          let b = Math.floor(((cen[3 * t + ax] - cmin[ax]) / cext[ax]) * BVH_BINS);
          if (b >= BVH_BINS) b = BVH_BINS - 1;
          binCount[BVH_BINS * ax + b]++;
          const q = 6 * (BVH_BINS * ax + b);
          for (let k = 0; k < 3; k++) {
            if (box[o + k] < binBox[q + k]) binBox[q + k] = box[o + k];
            if (box[o + 3 + k] > binBox[q + 3 + k]) binBox[q + 3 + k] = box[o + 3 + k];
          }
        }
      }
      for (let ax = 0; ax < 3; ax++) {
        if (!(cext[ax] > 0)) continue;
        // sweep from the right: area and count of bins b … BINS−1
        let x0 = Infinity, y0 = Infinity, z0 = Infinity, x1 = -Infinity, y1 = -Infinity, z1 = -Infinity, n = 0;
        for (let b = BVH_BINS - 1; b > 0; b--) {
          const q = 6 * (BVH_BINS * ax + b), c = binCount[BVH_BINS * ax + b];
          if (c > 0) {
            x0 = Math.min(x0, binBox[q]); y0 = Math.min(y0, binBox[q + 1]); z0 = Math.min(z0, binBox[q + 2]);
            x1 = Math.max(x1, binBox[q + 3]); y1 = Math.max(y1, binBox[q + 4]); z1 = Math.max(z1, binBox[q + 5]);
          }
          n += c;
          rightCount[b] = n; rightArea[b] = n > 0 ? area(x0, y0, z0, x1, y1, z1) : 0;
        }
        x0 = Infinity; y0 = Infinity; z0 = Infinity; x1 = -Infinity; y1 = -Infinity; z1 = -Infinity; n = 0;
        for (let b = 0; b < BVH_BINS - 1; b++) {
          const q = 6 * (BVH_BINS * ax + b), c = binCount[BVH_BINS * ax + b];
          if (c > 0) {
            x0 = Math.min(x0, binBox[q]); y0 = Math.min(y0, binBox[q + 1]); z0 = Math.min(z0, binBox[q + 2]);
            x1 = Math.max(x1, binBox[q + 3]); y1 = Math.max(y1, binBox[q + 4]); z1 = Math.max(z1, binBox[q + 5]);
          }
          n += c;
          if (n === 0 || rightCount[b + 1] === 0) continue;
          const cost = area(x0, y0, z0, x1, y1, z1) * n + rightArea[b + 1] * rightCount[b + 1];
          if (cost < bestCost) { bestCost = cost; bestAxis = ax; bestBin = b; }
        }
      }
      const nodeArea = area(bx0, by0, bz0, bx1, by1, bz1);
      // a leaf costs its triangles; a split one traversal step (≈ one triangle test) plus its children's
      if (count <= BVH_MAX_LEAF && (bestAxis < 0 || nodeArea <= 0 || bestCost / nodeArea + 1 >= count)) { leaf(); continue; }
      let mid: number;
      if (bestAxis < 0) {
        // every centroid at one point: halve by index
        mid = s + (count >> 1);
      } else {
        // partition: bins ≤ bestBin go left
        const ax = bestAxis, lo = cmin[ax], ext = cext[ax];
        let i = s, j = e - 1;
        while (i <= j) {
          let b = Math.floor(((cen[3 * idx[i] + ax] - lo) / ext) * BVH_BINS);
          if (b >= BVH_BINS) b = BVH_BINS - 1;
          if (b <= bestBin) i++;
          else { const t = idx[i]; idx[i] = idx[j]; idx[j] = t; j--; }
        }
        mid = i;
        if (mid === s || mid === e) mid = s + (count >> 1);
      }
      const left = nodeCount;
      nodeCount += 2;
      nodes[2 * node] = left; nodes[2 * node + 1] = 0;
      push(left + 1, mid, e, d + 1);
      push(left, s, mid, d + 1);
    }
    this.nodeCount = nodeCount;
    this.bounds = bounds.slice(0, 6 * nodeCount);
    this.nodes = nodes.slice(0, 2 * nodeCount);
    this.order = idx;
    this.triangles = new Uint32Array(3 * m);
    for (let i = 0; i < m; i++) {
      const t = idx[i];
      this.triangles[3 * i] = triangles[3 * t]; this.triangles[3 * i + 1] = triangles[3 * t + 1]; this.triangles[3 * i + 2] = triangles[3 * t + 2];
    }
    this.depth = depth;
    this.stack = new Uint32Array(depth + 2);
  }

  /**
   * Squared distance from the point in this.query to node `n`'s box (0 inside it), into query[4]: through the
   * array, as closest's numbers (none boxed: colliders/shape.ts).
   */
  private boxDistance2(n: number): void {
    const b = this.bounds, o = 6 * n, q = this.query, px = q[0], py = q[1], pz = q[2];
    const dx = px < b[o] ? b[o] - px : px > b[o + 3] ? px - b[o + 3] : 0;
    const dy = py < b[o + 1] ? b[o + 1] - py : py > b[o + 4] ? py - b[o + 4] : 0;
    const dz = pz < b[o + 2] ? b[o + 2] - pz : pz > b[o + 5] ? pz - b[o + 5] : 0;
    q[4] = dx * dx + dy * dy + dz * dz;
  }

  /**
   * The triangle (leaf-order index) nearest point p among those nearer than √max2, with the barycentric weights of
   * its closest point written to `bary` and the squared distance to `this.d2`; −1 (writing nothing) when none is.
   * Ties go to the triangle met first. Nearer child first; a node no nearer than the best so far is skipped.
   */
  closest(px: number, py: number, pz: number, max2: number, bary: Float64Array): number {
    const q = this.query;
    q[0] = px; q[1] = py; q[2] = pz; q[3] = max2;
    return this.closestIn(bary);
  }

  /**
   * closestIn's point p [m] and bound max2 [m²] (slots 0–3; slot 4 is boxDistance2's answer): a caller in a step
   * writes them here and calls closestIn, so that no number passes through a call (colliders/shape.ts)
   */
  readonly query = new Float64Array(5);
  /** closestPointIn's point and triangle */
  private readonly triangleArgs = new Float64Array(12);

  /** closest on the point and bound in this.query. */
  closestIn(bary: Float64Array): number {
    const q = this.query, px = q[0], py = q[1], pz = q[2], max2 = q[3];
    const nodes = this.nodes, tri = this.triangles, p = this.positions, stack = this.stack, nrm = this.normals;
    let best2 = max2, best = -1, top = 0;
    let n = 0;
    this.boxDistance2(0);
    if (q[4] >= best2) return -1;
    const tv = this.triangleArgs;
    tv[0] = px; tv[1] = py; tv[2] = pz;
    for (;;) {
      const count = nodes[2 * n + 1];
      if (count > 0) {
        const first = nodes[2 * n];
        for (let t = first; t < first + count; t++) {
          const a = 3 * tri[3 * t], b = 3 * tri[3 * t + 1], c = 3 * tri[3 * t + 2];
          if (nrm) {
            const h = nrm[3 * t] * (px - p[a]) + nrm[3 * t + 1] * (py - p[a + 1]) + nrm[3 * t + 2] * (pz - p[a + 2]);
            if (h * h >= best2) continue;
          }
          tv[3] = p[a]; tv[4] = p[a + 1]; tv[5] = p[a + 2]; tv[6] = p[b]; tv[7] = p[b + 1]; tv[8] = p[b + 2];
          tv[9] = p[c]; tv[10] = p[c + 1]; tv[11] = p[c + 2];
          closestPointIn(tv, scratchBary);
          const u = scratchBary[0], v = scratchBary[1], w = scratchBary[2];
          const dx = u * p[a] + v * p[b] + w * p[c] - px;
          const dy = u * p[a + 1] + v * p[b + 1] + w * p[c + 1] - py;
          const dz = u * p[a + 2] + v * p[b + 2] + w * p[c + 2] - pz;
          const d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < best2) { best2 = d2; best = t; bary[0] = u; bary[1] = v; bary[2] = w; }
        }
      } else {
        const l = nodes[2 * n], r = l + 1;
        this.boxDistance2(l);
        const dl = q[4];
        this.boxDistance2(r);
        const dr = q[4];
        if (dl < dr) {
          if (dr < best2) stack[top++] = r;
          if (dl < best2) { n = l; continue; }
        } else {
          if (dl < best2) stack[top++] = l;
          if (dr < best2) { n = r; continue; }
        }
      }
      // next: the top of the stack that is still nearer than the best
      let next = -1;
      while (top > 0) {
        const k = stack[--top];
        this.boxDistance2(k);
        if (q[4] < best2) { next = k; break; }
      }
      if (next < 0) break;
      n = next;
    }
    this.d2 = best2;
    return best;
  }
}
