// Self-contact, the edges' candidates (selfGrid.wgsl): each edge against the later edges of the edge grid's cells of
// its box over the substep, listed in selfPairs for selfEdges where the CPU's tests could act on them: the two boxes
// over the substep (each widened by h/2) meet (collideEdges' test), the edges share no particle, and either their
// boxes now, widened by h/2, meet (they may be too near) or they were not on either side of each other along one axis
// both at the substep's start and now (they may have passed through; as in selfFindPoints, boxes apart along an axis
// at both ends of the substep stay apart all of it). One thread per edge; a pair past the list's capacity is
// counted, not kept.

/** The box of segment a–b [m]: lowest corner into *lo, highest into *hi. */
fn segmentBox(a: vec3f, b: vec3f, lo: ptr<function, vec3f>, hi: ptr<function, vec3f>) {
  *lo = min(a, b);
  *hi = max(a, b);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let e = flatIndex(gid, nwg);
  if (e >= globals.edgeCount) { return; }
  let bits = selfStarts[0];
  if (bits >= SELF_NOT_FINITE) { return; }
  let inv = cellInverse(bits);
  let r = vec3f(globals.selfDistance);
  let lo = selfBoxes[2u * e].xyz;
  let hi = selfBoxes[2u * e + 1u].xyz;
  let ab = edges[e];
  var lo1: vec3f;
  var hi1: vec3f;
  var lo0: vec3f;
  var hi0: vec3f;
  segmentBox(positions[ab.x].xyz, positions[ab.y].xyz, &lo1, &hi1);
  segmentBox(previous[ab.x].xyz, previous[ab.y].xyz, &lo0, &hi0);
  var span: vec3i;
  let c0 = boxCells(lo, hi, inv, &span);
  for (var s = 0u; s < 8u; s++) {
    var cell: vec3i;
    if (!boxCell(c0, span, s, &cell)) { continue; }
    let bucket = bucketOf(cell);
    let end = selfStarts[2u + bucket];
    for (var i = selfStarts[1u + bucket]; i < end; i++) {
      let f = selfEntries[i];
      if (f <= e) { continue; }
      let flo = selfBoxes[2u * f].xyz;
      let fhi = selfBoxes[2u * f + 1u].xyz;
      if (any(lo > fhi) || any(flo > hi)) { continue; }
      // each pair once: in the cell of the lowest corner of the two boxes' overlap
      if (any(cellOf(max(lo, flo), inv) != cell)) { continue; }
      let cd = edges[f];
      if (cd.x == ab.x || cd.x == ab.y || cd.y == ab.x || cd.y == ab.y) { continue; }
      var glo1: vec3f;
      var ghi1: vec3f;
      var glo0: vec3f;
      var ghi0: vec3f;
      segmentBox(positions[cd.x].xyz, positions[cd.y].xyz, &glo1, &ghi1);
      segmentBox(previous[cd.x].xyz, previous[cd.y].xyz, &glo0, &ghi0);
      // r = h: the two boxes, each widened by h/2, meet
      let near = all(lo1 <= ghi1 + r) && all(glo1 <= hi1 + r);
      let apart = any((hi1 < glo1) & (hi0 < glo0)) || any((ghi1 < lo1) & (ghi0 < lo0));
      if (!near && apart) { continue; }
      addPair(e, f);
    }
  }
}
