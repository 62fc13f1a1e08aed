// The self-contact grid (docs/gpu.md, "Self-contact"): a spatial hash of cubic cells, built anew for the triangles
// and again for the edges every substep (selfBoxes, selfCount, selfScan, selfScanTotals, selfScanAdd, selfScatter:
// a counting sort by bucket). The cell is the largest primitive box of the build, times 1.01, so a box meets at most
// 2 cells along each axis (8 in all) and every loop over cells is bounded; a primitive goes into each bucket of its
// cells once. A query visits the cells of its own box and takes a pair only in the cell of the lowest corner of the
// two boxes' overlap, which both boxes meet: each pair once, whatever the hash collisions.

/** f32 bits at and above which a box extent is not finite (+∞, NaN): nothing is kept apart that substep. */
const SELF_NOT_FINITE: u32 = 0x7f800000u;

/** 1 / the cell size [1/m] of a grid whose largest box extent has the f32 bits `bits` [m]. */
fn cellInverse(bits: u32) -> f32 {
  return 1.0 / (bitcast<f32>(bits) * 1.01);
}

/** The integer coordinates of the cell holding point p [m], cells of 1/inv [m]. */
fn cellOf(p: vec3f, inv: f32) -> vec3i {
  return vec3i(floor(p * inv));
}

/** The bucket of cell c: its coordinates hashed (Teschner et al. 2003), modulo globals.selfBuckets (a power of two). */
fn bucketOf(c: vec3i) -> u32 {
  let u = bitcast<vec3u>(c);
  return ((u.x * 73856093u) ^ (u.y * 19349663u) ^ (u.z * 83492791u)) & (globals.selfBuckets - 1u);
}

/**
 * The lowest cell of box [lo, hi] [m]; its cells along each axis (1 or 2: the cell is larger than any box of the
 * build, the clamp only bounds the loops) go to *span.
 */
fn boxCells(lo: vec3f, hi: vec3f, inv: f32, span: ptr<function, vec3i>) -> vec3i {
  let c0 = cellOf(lo, inv);
  *span = clamp(cellOf(hi, inv) - c0 + vec3i(1), vec3i(1), vec3i(2));
  return c0;
}

/** Cell s (0…7) of a box whose lowest cell is c0 and whose span is `span`, into *c; false where s is outside it. */
fn boxCell(c0: vec3i, span: vec3i, s: u32, c: ptr<function, vec3i>) -> bool {
  let o = vec3i(i32(s & 1u), i32((s >> 1u) & 1u), i32((s >> 2u) & 1u));
  *c = c0 + o;
  return all(o < span);
}

/** Whether cell s of the box (inside it) is the first of its cells in its bucket: a primitive goes into a bucket once. */
fn firstInBucket(c0: vec3i, span: vec3i, s: u32) -> bool {
  var c: vec3i;
  boxCell(c0, span, s, &c);
  let b = bucketOf(c);
  for (var r = 0u; r < s; r++) {
    var d: vec3i;
    if (boxCell(c0, span, r, &d) && bucketOf(d) == b) { return false; }
  }
  return true;
}

/** Whether point p lies in box [lo, hi] [m]. */
fn inBox(p: vec3f, lo: vec3f, hi: vec3f) -> bool {
  return all(p >= lo) && all(p <= hi);
}
