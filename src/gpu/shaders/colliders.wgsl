// Collider shapes (colliders/*.ts) and the friction rule shared by the two contact kernels.

/** Signed distance of p from the collider's surface [m] (negative inside); the outward normal goes to *n. */
fn shapeDistance(c: Collider, p: vec3f, n: ptr<function, vec3f>) -> f32 {
  if (c.kind == COLLIDER_SPHERE) {
    let d = p - c.data.xyz;
    let l = length(d);
    if (l > 1e-12) { *n = d / l; } else { *n = vec3f(0.0, 1.0, 0.0); }
    return l - c.data.w;
  }
  // COLLIDER_FLOOR
  *n = vec3f(0.0, 1.0, 0.0);
  return p.y - c.data.x;
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

/** Barycentric weights of the point of triangle (a, b, c) closest to p (Ericson 2005, §5.1.5). */
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
    let v = d1 / (d1 - d3);
    return vec3f(1.0 - v, v, 0.0);
  }
  let cp = p - c;
  let d5 = dot(ab, cp);
  let d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) { return vec3f(0.0, 0.0, 1.0); }
  let vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    let w = d2 / (d2 - d6);
    return vec3f(1.0 - w, 0.0, w);
  }
  let va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    let w = (d4 - d3) / (d4 - d3 + (d5 - d6));
    return vec3f(0.0, 1.0 - w, w);
  }
  let denom = 1.0 / (va + vb + vc);
  let v = vb * denom;
  let w = vc * denom;
  return vec3f(1.0 - v - w, v, w);
}
