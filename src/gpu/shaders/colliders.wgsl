// What every contact kernel shares, whatever its shapes: a collider's signed distance in the world (through its pose,
// pose.wgsl, and `localDistance` in its own frame: the analytic shapes' in shapes.wgsl, a mesh's in meshCollider.wgsl;
// a kernel includes one of the two), the closest point of a triangle, and the friction rule.

/** A very large distance [m]: as `within`, no bound asked for. */
const FAR: f32 = 1e30;

/** Barycentric weights of the point of triangle (a, b, c) closest to p (Ericson 2005, §5.1.5; sphere.ts). */
fn closestPointOnTriangle(p: vec3f, a: vec3f, b: vec3f, c: vec3f) -> vec3f {
  let ab = b - a;
  let ac = c - a;
  let ap = p - a;
  let d1 = dot(ab, ap);
  let d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) { return vec3f(1.0, 0.0, 0.0); }
  let bp = p - b;
  let d3 = dot(ab, bp);
  let d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) { return vec3f(0.0, 1.0, 0.0); }
  let vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    // (a zero-length edge gives 0/0: its end a, as sphere.ts)
    let v = select(0.0, d1 / (d1 - d3), d1 - d3 > 0.0);
    return vec3f(1.0 - v, v, 0.0);
  }
  let cp = p - c;
  let d5 = dot(ab, cp);
  let d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) { return vec3f(0.0, 0.0, 1.0); }
  let vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    let w = select(0.0, d2 / (d2 - d6), d2 - d6 > 0.0);
    return vec3f(1.0 - w, 0.0, w);
  }
  let va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    let e = d4 - d3 + (d5 - d6);
    let w = select(0.0, (d4 - d3) / e, e > 0.0);
    return vec3f(0.0, 1.0 - w, w);
  }
  let sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // a degenerate triangle that rounding brought here: its nearest vertex (sphere.ts)
    let da = dot(ap, ap);
    let db = dot(bp, bp);
    let dc = dot(cp, cp);
    if (da <= db && da <= dc) { return vec3f(1.0, 0.0, 0.0); }
    if (db <= dc) { return vec3f(0.0, 1.0, 0.0); }
    return vec3f(0.0, 0.0, 1.0);
  }
  let v = vb / sum;
  let w = vc / sum;
  return vec3f(1.0 - v - w, v, w);
}

/**
 * Signed distance [m] of world point p from the collider's surface (negative inside); the world normal goes to *n.
 * A mesh may answer `within` for a point with nothing that near (and then leaves *n alone).
 */
fn colliderDistance(c: Collider, p: vec3f, within: f32, n: ptr<function, vec3f>) -> f32 {
  var nl: vec3f;
  let d = localDistance(c, toLocal(c, p), within, &nl);
  *n = toWorldDirection(c, nl);
  return d;
}

/**
 * Position-based Coulomb friction (phases.ts frictionScale): the share of the tangential displacement of a
 * contact over the substep to remove.
 */
fn frictionScale(tangential: f32, depth: f32) -> f32 {
  if (tangential < 1e-12) { return 0.0; }
  if (tangential < globals.staticFriction * depth) { return 1.0; }
  return min(globals.friction * depth / tangential, 1.0);
}

// the push-out depth that bounds friction (phases.ts frictionScale, its pressed depth): an overlap of `overlap` [m] of which the point
// moved `movedIn` into the surface this substep, the rest undone at most `recover` a substep
fn pressedDepth(overlap: f32, movedIn: f32, recover: f32) -> f32 {
  let over = overlap - movedIn;
  if (over <= 0.0) { return overlap; }
  return movedIn + max(0.0, min(over, 2.0 * recover - over));
}
