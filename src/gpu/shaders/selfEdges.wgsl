// collideSelf's edge pass (self-contact.ts collideEdges, resolveEdges), Jacobi, after the particle pass, over the
// edge pairs selfFindEdges listed (selfPairs; how many in selfArgs[3]), one pair per thread (an indirect dispatch).
// The closest points p (on a–b, at s) and q (on c–d, at t), now and at the substep's start: passed through (both
// pairs inside their edges, q→p now against its direction then): apart along that direction until p is on its side,
// h_e from q; else, nearer than h_e: apart to h_e along q→p. h_e is SELF_EDGE_SHARE of the self-contact distance h,
// more by the two edges' largest end moves over the substep (summed), up to h (self-contact.ts resolveEdges). Shared
// by inverse mass and the weights (1 − s, s, 1 − t, t), with friction; every correction from the positions at the
// pass's start, summed per particle (selfCorrect.wgsl) for selfApply.

/**
 * Closest points of segments a–b and c–d [m] (Ericson 2005, §5.1.9; self-contact.ts segmentClosest): their
 * parameters into *st (p = a + s(b − a), q = c + t(d − c)); returns p − q.
 */
fn segmentClosest(a: vec3f, b: vec3f, c: vec3f, d: vec3f, st: ptr<function, vec2f>) -> vec3f {
  let u = b - a;
  let v = d - c;
  let r = a - c;
  let A = dot(u, u);
  let E = dot(v, v);
  let F = dot(v, r);
  var s = 0.0;
  var t = 0.0;
  if (A <= 1e-24 && E <= 1e-24) {
    s = 0.0;
  } else if (A <= 1e-24) {
    t = clamp(F / E, 0.0, 1.0);
  } else {
    let C = dot(u, r);
    if (E <= 1e-24) {
      s = clamp(-C / A, 0.0, 1.0);
    } else {
      let B = dot(u, v);
      let den = A * E - B * B;
      s = select(0.0, clamp((B * F - C * E) / den, 0.0, 1.0), den > 1e-24);
      t = (B * s + F) / E;
      if (t < 0.0) { t = 0.0; s = clamp(-C / A, 0.0, 1.0); }
      else if (t > 1.0) { t = 1.0; s = clamp((B - C) / A, 0.0, 1.0); }
    }
  }
  *st = vec2f(s, t);
  return r + s * u - t * v;
}

/** Whether a closest point's parameter lies inside its edge (not at an end). */
fn insideEdge(v: f32) -> bool {
  return v > 1e-6 && v < 1.0 - 1e-6;
}

/** Edges a–b and c–d: the pair's corrections summed, if it needs any. */
fn resolveEdges(a: u32, b: u32, c: u32, d: u32) {
  let xa = positions[a].xyz;
  let xb = positions[b].xyz;
  let xc = positions[c].xyz;
  let xd = positions[d].xyz;
  let qa = previous[a].xyz;
  let qb = previous[b].xyz;
  let qc = previous[c].xyz;
  let qd = previous[d].xyz;
  let motion = max(length(xa - qa), length(xb - qb)) + max(length(xc - qc), length(xd - qd));
  let h = min(globals.selfDistance, SELF_EDGE_SHARE * globals.selfDistance + motion);
  var st0: vec2f;
  let gap0 = segmentClosest(qa, qb, qc, qd, &st0);
  let len0 = length(gap0);
  var st: vec2f;
  let gap = segmentClosest(xa, xb, xc, xd, &st);
  let len = length(gap);
  if (!(len < 1e30) || !(len0 < 1e30)) { return; } // not finite
  // at least h_e and δ apart now: neither too near nor passed through (passing through needs the distance now to be
  // at most δ; self-contact.ts resolveEdges)
  if (len >= max(h, motion)) { return; }
  var dir: vec3f;
  var C: f32; // the constraint along dir [m]: negative when violated
  if (insideEdge(st0.x) && insideEdge(st0.y) && insideEdge(st.x) && insideEdge(st.y) && len0 > 1e-12 && dot(gap, gap0) < 0.0) {
    // passed through: back to the side of then, h along that direction
    dir = gap0 / len0;
    C = dot(gap, dir) - h;
  } else {
    if (len >= h || len < 1e-12) { return; }
    dir = gap / len;
    C = len - h;
  }
  let k = vec4f(1.0 - st.x, st.x, 1.0 - st.y, st.y);
  let w = vec4f(invMass[a], invMass[b], invMass[c], invMass[d]);
  let denom = dot(k * k, w);
  if (!(denom > 0.0)) { return; }
  let lambda = -C / denom;
  // friction: the relative tangential motion of p against q over the substep
  let r = k.x * (xa - qa) + k.y * (xb - qb) - k.z * (xc - qc) - k.w * (xd - qd);
  let t = r - dot(r, dir) * dir;
  let f = selfFriction(length(t), -C);
  let m = lambda * dir - (f / denom) * t;
  addCorrections(array<u32, 4>(a, b, c, d), w * k * vec4f(1.0, 1.0, -1.0, -1.0), m);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let k = flatIndex(gid, nwg);
  if (k >= selfArgs[3]) { return; }
  let ab = edges[selfPairs[1u + 2u * k]];
  let cd = edges[selfPairs[2u + 2u * k]];
  resolveEdges(ab.x, ab.y, cd.x, cd.y);
}
