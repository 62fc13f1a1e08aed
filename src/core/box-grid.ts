/**
 * A uniform grid over axis-aligned boxes, hashed into a table (Teschner et al. 2003, "Optimized Spatial Hashing for
 * Collision Detection of Deformable Objects"): the broad phase of the cloth's self-intersection count
 * (intersections.ts) and of the HUD's self-contact count (contacts.ts). Boxes are six numbers each (min x, y, z, max x, y, z);
 * the cell is a multiple of their mean largest side, at least a given size; each box is listed in every cell it
 * covers (a counting sort into compressed rows). Its arrays grow when a build needs more and are reused after.
 */
const HASH_X = 73856093, HASH_Y = 19349663, HASH_Z = 83492791;

export class BoxGrid {
  /** the cell's side [m] and its inverse, of the last build */
  cell = 1;
  inv = 1;
  /** the table: the boxes of slot h are items[start[h] … start[h + 1]) */
  start = new Int32Array(1);
  items = new Int32Array(0);
  private fill = new Int32Array(0);
  private mask = 0;

  /**
   * Buckets boxes 0 … n − 1 of `boxes`, with cells of `factor` × the mean largest side, at least `minCell`. False
   * (nothing built) when a box is not finite.
   */
  build(boxes: Float64Array, n: number, factor: number, minCell: number): boolean {
    let mean = 0;
    for (let t = 0; t < n; t++) {
      const b = 6 * t;
      mean += Math.max(boxes[b + 3] - boxes[b], boxes[b + 4] - boxes[b + 1], boxes[b + 5] - boxes[b + 2]);
    }
    if (!Number.isFinite(mean)) return false;
    this.cell = Math.max((factor * mean) / Math.max(n, 1), minCell);
    const inv = (this.inv = 1 / this.cell);
    let entries = 0;
    for (let t = 0; t < n; t++) {
      const b = 6 * t;
      entries += (Math.floor(boxes[b + 3] * inv) - Math.floor(boxes[b] * inv) + 1) *
        (Math.floor(boxes[b + 4] * inv) - Math.floor(boxes[b + 1] * inv) + 1) *
        (Math.floor(boxes[b + 5] * inv) - Math.floor(boxes[b + 2] * inv) + 1);
    }
    let size = 1;
    while (size < 2 * entries) size *= 2;
    if (this.start.length < size + 1) { this.start = new Int32Array(size + 1); this.fill = new Int32Array(size); }
    if (this.items.length < entries) this.items = new Int32Array(Math.ceil(entries * 1.5));
    this.mask = size - 1;
    const { start, fill, items } = this;
    start.fill(0, 0, size + 1);
    for (let pass = 0; pass < 2; pass++) {
      for (let t = 0; t < n; t++) {
        const b = 6 * t;
        const x0 = Math.floor(boxes[b] * inv), x1 = Math.floor(boxes[b + 3] * inv);
        const y0 = Math.floor(boxes[b + 1] * inv), y1 = Math.floor(boxes[b + 4] * inv);
        const z0 = Math.floor(boxes[b + 2] * inv), z1 = Math.floor(boxes[b + 5] * inv);
        for (let i = x0; i <= x1; i++) for (let j = y0; j <= y1; j++) for (let k = z0; k <= z1; k++) {
          const h = this.slot(i, j, k);
          if (pass === 0) start[h + 1]++;
          else items[fill[h]++] = t;
        }
      }
      if (pass === 0) {
        for (let h = 0; h < size; h++) start[h + 1] += start[h];
        for (let h = 0; h < size; h++) fill[h] = start[h];
      }
    }
    return true;
  }

  /** The table slot of cell (i, j, k) (cell coordinates: Math.floor(coordinate · inv)). */
  slot(i: number, j: number, k: number): number {
    return (Math.imul(i, HASH_X) ^ Math.imul(j, HASH_Y) ^ Math.imul(k, HASH_Z)) & this.mask;
  }
}

/**
 * Each triangle's box (of `triangles`, vertex indices three per triangle, at positions `x`) into `boxes`, six numbers
 * each, widened by `pad` [m]; false when a position is NaN (the boxes are then partly written).
 */
export function triangleBoxes(triangles: Uint32Array, x: ArrayLike<number>, boxes: Float64Array, pad: number): boolean {
  const n = triangles.length / 3;
  for (let t = 0; t < n; t++) {
    const b = 6 * t;
    boxes[b] = boxes[b + 1] = boxes[b + 2] = Infinity;
    boxes[b + 3] = boxes[b + 4] = boxes[b + 5] = -Infinity;
    for (let k = 0; k < 3; k++) {
      const j = 3 * triangles[3 * t + k];
      for (let c = 0; c < 3; c++) {
        const v = x[j + c];
        if (!(v >= -Infinity)) return false;
        if (v < boxes[b + c]) boxes[b + c] = v;
        if (v > boxes[b + 3 + c]) boxes[b + 3 + c] = v;
      }
    }
    for (let c = 0; c < 3; c++) { boxes[b + c] -= pad; boxes[b + 3 + c] += pad; }
  }
  return true;
}
