// Self-contact, the particles' candidates (selfGrid.wgsl): each particle p (a pinned or grabbed one too: moved, it
// pushes the cloth it meets) against the triangles of the
// triangle grid's cells of its box over the substep, listed in selfPairs for selfPoints where the CPU's tests could
// act on them: the triangle's box over the substep (widened by h) holds p now or at the substep's start (collideSelf's
// test), the triangle does not have p as a corner, and either p is within h of the triangle's box now (it may be too
// near) or p was not on one side of the triangle's boxes along one axis both at the substep's start and now (it may
// have passed through: a point on one side of a moving triangle's box at both ends of the substep, under straight
// motion, is on that side all the substep, since the box's extent along the axis is convex in time). One thread per
// particle; a pair past the list's capacity (globals.selfPairCapacity) is counted, not kept.

/** Whether point x (now) and q (then) [m] lie on one side of boxes [lo1, hi1] (now) and [lo0, hi0] (then) along one axis. */
fn sameSide(x: vec3f, q: vec3f, lo1: vec3f, hi1: vec3f, lo0: vec3f, hi0: vec3f) -> bool {
  return any((x < lo1) & (q < lo0)) || any((x > hi1) & (q > hi0));
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let p = flatIndex(gid, nwg);
  if (p >= globals.particleCount) { return; }
  let bits = selfStarts[0];
  if (bits >= SELF_NOT_FINITE) { return; }
  let inv = cellInverse(bits);
  let h = vec3f(globals.selfDistance);
  let x = positions[p].xyz;
  let q = previous[p].xyz;
  let lo = min(x, q);
  var span: vec3i;
  let c0 = boxCells(lo, max(x, q), inv, &span);
  for (var s = 0u; s < 8u; s++) {
    var cell: vec3i;
    if (!boxCell(c0, span, s, &cell)) { continue; }
    let bucket = bucketOf(cell);
    let end = selfStarts[2u + bucket];
    for (var e = selfStarts[1u + bucket]; e < end; e++) {
      let t = selfEntries[e];
      let tlo = selfBoxes[2u * t].xyz;
      let thi = selfBoxes[2u * t + 1u].xyz;
      if (!(inBox(x, tlo, thi) || inBox(q, tlo, thi))) { continue; }
      // each pair once: in the cell of the lowest corner of the two boxes' overlap
      if (any(cellOf(max(lo, tlo), inv) != cell)) { continue; }
      let a = triangles[3u * t];
      let b = triangles[3u * t + 1u];
      let c = triangles[3u * t + 2u];
      if (a == p || b == p || c == p) { continue; }
      let xa = positions[a].xyz;
      let xb = positions[b].xyz;
      let xc = positions[c].xyz;
      let qa = previous[a].xyz;
      let qb = previous[b].xyz;
      let qc = previous[c].xyz;
      let lo1 = min(xa, min(xb, xc));
      let hi1 = max(xa, max(xb, xc));
      if (!inBox(x, lo1 - h, hi1 + h) && sameSide(x, q, lo1, hi1, min(qa, min(qb, qc)), max(qa, max(qb, qc)))) { continue; }
      addPair(p, t);
    }
  }
}
