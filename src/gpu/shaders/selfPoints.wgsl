// collideSelf's particle pass (self-contact.ts resolvePair), Jacobi, over the particle–triangle pairs selfFindPoints
// listed (selfPairs; how many in selfArgs[3]), one pair per thread (an indirect dispatch: selfPairArgs). Each pair is
// the CPU's:
// - passed through (side memory): p on one side of the triangle's plane at the substep's start, on the other now,
//   its projection inside the triangle (now or then), and nearer it now than h or p's move and the triangle's
//   largest corner move summed (farther, it cannot have passed through in this substep): back to its side, h from
//   the plane;
// - too near: on its side but nearer than h to the triangle's closest point: apart to h;
// the correction shared by inverse mass and barycentric weight, with friction on the relative tangential motion.
// Every correction is computed from the positions at the pass's start and summed per particle (selfCorrect.wgsl);
// selfApply then moves each particle by the mean of its own.

/** The unit normal of triangle (a, b, c) [m] into *n; false for a degenerate triangle. */
fn planeNormal(a: vec3f, b: vec3f, c: vec3f, n: ptr<function, vec3f>) -> bool {
  let m = cross(b - a, c - a);
  let l = length(m);
  if (!(l > 1e-20)) { return false; }
  *n = m / l;
  return true;
}

/** The barycentric weights of the projection of q onto the plane of (a, b, c), unclamped (self-contact.ts barycentric). */
fn planeWeights(q: vec3f, a: vec3f, b: vec3f, c: vec3f) -> vec3f {
  let u = b - a;
  let v = c - a;
  let r = q - a;
  let uu = dot(u, u);
  let uv = dot(u, v);
  let vv = dot(v, v);
  let ru = dot(r, u);
  let rv = dot(r, v);
  let det = uu * vv - uv * uv;
  let b1 = select(0.0, (vv * ru - uv * rv) / det, det > 0.0);
  let b2 = select(0.0, (uu * rv - uv * ru) / det, det > 0.0);
  return vec3f(1.0 - b1 - b2, b1, b2);
}

/** The barycentric weights of the point of (a, b, c) closest to q (Ericson 2005, §5.1.5; self-contact.ts closestPoint). */
fn closestWeights(q: vec3f, a: vec3f, b: vec3f, c: vec3f) -> vec3f {
  let ab = b - a;
  let ac = c - a;
  let ap = q - a;
  let d1 = dot(ab, ap);
  let d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) { return vec3f(1.0, 0.0, 0.0); }
  let bp = q - b;
  let d3 = dot(ab, bp);
  let d4 = dot(ac, bp);
  let cp = q - c;
  let d5 = dot(ab, cp);
  let d6 = dot(ac, cp);
  let vc = d1 * d4 - d3 * d2;
  let vb = d5 * d2 - d1 * d6;
  let va = d3 * d6 - d5 * d4;
  var u: f32;
  var v: f32;
  if (d3 >= 0.0 && d4 <= d3) { u = 1.0; v = 0.0; }
  else if (d6 >= 0.0 && d5 <= d6) { u = 0.0; v = 1.0; }
  else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) { u = d1 / (d1 - d3); v = 0.0; }
  else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) { u = 0.0; v = d2 / (d2 - d6); }
  else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) { v = (d4 - d3) / ((d4 - d3) + (d5 - d6)); u = 1.0 - v; }
  else { let den = 1.0 / (va + vb + vc); u = vb * den; v = vc * den; }
  return vec3f(1.0 - u - v, u, v);
}

/** Particle p (inverse mass wp) against triangle (a, b, c): the pair's corrections summed, if it needs any. */
fn resolvePair(p: u32, wp: f32, a: u32, b: u32, c: u32) {
  let h = globals.selfDistance;
  let x = positions[p].xyz;
  let xa = positions[a].xyz;
  let xb = positions[b].xyz;
  let xc = positions[c].xyz;
  let q = previous[p].xyz;
  let qa = previous[a].xyz;
  let qb = previous[b].xyz;
  let qc = previous[c].xyz;
  // the side at the substep's start (the triangle's plane then), and now (the plane now, and the distance along it)
  var n0: vec3f;
  var n: vec3f;
  if (!planeNormal(qa, qb, qc, &n0) || !planeNormal(xa, xb, xc, &n)) { return; }
  let sPrev = dot(n0, q - qa);
  let s = dot(n, x - xa);
  // on its side and farther than h from the plane: farther from the triangle too
  if (abs(s) >= h && sign(s) == sign(sPrev)) { return; }
  var bary = planeWeights(x, xa, xb, xc);
  let inside = all(bary >= vec3f(0.0));
  var dir: vec3f;
  var C: f32; // the constraint along dir [m]: negative when violated
  if (sPrev != 0.0 && sign(s) != sign(sPrev) && (inside || all(planeWeights(q, qa, qb, qc) >= vec3f(0.0)))) {
    // passed through, if near enough now to have: nearer than h or its move and the triangle's largest corner move
    // summed (the distance from the plane where it projects inside, else from the closest point)
    let motion = length(x - q) + max(max(length(xa - qa), length(xb - qb)), length(xc - qc));
    var d = abs(s);
    if (!inside) {
      let k = closestWeights(x, xa, xb, xc);
      d = length(x - (k.x * xa + k.y * xb + k.z * xc));
    }
    if (d >= max(h, motion)) { return; }
    // back to its side, h from the plane (through the triangle as it was, beside it as it is: the weights of the
    // projection now, clamped to it)
    if (!inside) {
      let k = max(bary, vec3f(0.0));
      bary = k / (k.x + k.y + k.z);
    }
    let side = sign(sPrev);
    dir = side * n;
    C = side * s - h;
  } else {
    // on its side: nearer than h to the triangle's closest point?
    bary = closestWeights(x, xa, xb, xc);
    let gap = x - (bary.x * xa + bary.y * xb + bary.z * xc);
    let d = length(gap);
    if (d >= h) { return; }
    if (d > 1e-12) {
      dir = gap / d;
    } else {
      // on the triangle: out to the side it came from
      dir = select(1.0, sign(sPrev), sPrev != 0.0) * n;
    }
    C = d - h;
  }
  let wa = invMass[a];
  let wb = invMass[b];
  let wc = invMass[c];
  let denom = wp + bary.x * bary.x * wa + bary.y * bary.y * wb + bary.z * bary.z * wc;
  if (denom <= 0.0) { return; }
  let lambda = -C / denom; // > 0: p moves along dir, the triangle's point against it
  // friction: the relative tangential motion over the substep
  let r = (x - q) - (bary.x * (xa - qa) + bary.y * (xb - qb) + bary.z * (xc - qc));
  let t = r - dot(r, dir) * dir;
  let f = selfFriction(length(t), -C);
  let k = lambda * dir - (f / denom) * t;
  addCorrections(array<u32, 4>(p, a, b, c), vec4f(wp, -wa * bary.x, -wb * bary.y, -wc * bary.z), k);
}

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let k = flatIndex(gid, nwg);
  if (k >= selfArgs[3]) { return; }
  let p = selfPairs[1u + 2u * k];
  let t = selfPairs[2u + 2u * k];
  // p may be pinned or grabbed (inverse mass 0): then the triangle alone moves
  resolvePair(p, invMass[p], triangles[3u * t], triangles[3u * t + 1u], triangles[3u * t + 2u]);
}
