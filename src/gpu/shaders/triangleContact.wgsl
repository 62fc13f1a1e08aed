// Triangle contact, what every shape's shares (ColliderShape.triangleDeepest; docs/physics.md "Contact"): closest
// points of segments and triangles, and the nested golden-section search of convex.ts over the triangle, on
// `localDistance` in the shape's own frame (shapes.wgsl or meshCollider.wgsl: a kernel includes one). Each family's
// `triangleDeepest`: shapeTriangles.wgsl (sphere, box, capsule, cylinder), meshTriangles.wgsl (a mesh). In f32, by
// the TypeScript reference's method step for step; thresholds for degenerate cases are the GPU's own, chosen for f32
// (docs/gpu.md, "Triangle contact"). Every function is written with one call site of each costly callee (the
// golden-section search as one loop of evaluations, one final evaluation of the deepest point): shader compilers
// inline every call, and SwiftShader takes minutes over a kernel that inlines the shape's distance a hundred times.

/** segments shorter than this squared [m²] are points */
const TINY_SQUARED: f32 = 1e-30;
/** a·e − b² below this share of a·e: parallel segments (f32 leaves ~1e-7 of a·e of it) */
const PARALLEL: f32 = 1e-6;
/** a segment this close (squared) [m²] to the triangle crosses it */
const CROSSING_SQUARED: f32 = 1e-24;
/** (√5 − 1)/2 */
const GOLDEN: f32 = 0.6180339887;

/** The deepest point of a triangle: signed distance [m], barycentric weights, outward normal (the shape's own frame). */
struct Deepest {
  d: f32,
  bary: vec3f,
  n: vec3f,
}

/** Closest points of segments p1–q1 and p2–q2 (Ericson §5.1.9; convex.ts): (s, t, squared distance). */
fn segmentSegmentClosest(p1: vec3f, q1: vec3f, p2: vec3f, q2: vec3f) -> vec3f {
  let d1 = q1 - p1;
  let d2 = q2 - p2;
  let r = p1 - p2;
  let a = dot(d1, d1);
  let e = dot(d2, d2);
  let f = dot(d2, r);
  var s = 0.0;
  var t = 0.0;
  if (a <= TINY_SQUARED && e <= TINY_SQUARED) {
    // two points
  } else if (a <= TINY_SQUARED) {
    t = clamp(f / e, 0.0, 1.0);
  } else {
    let c = dot(d1, r);
    if (e <= TINY_SQUARED) {
      s = clamp(-c / a, 0.0, 1.0);
    } else {
      let b = dot(d1, d2);
      let denom = a * e - b * b;
      if (denom > PARALLEL * a * e) { s = clamp((b * f - c * e) / denom, 0.0, 1.0); }
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  let d = p1 + s * d1 - (p2 + t * d2);
  return vec3f(s, t, dot(d, d));
}

/**
 * Closest points of segment p–q and triangle (a, b, c) (convex.ts segmentTriangleClosest): the triangle point's
 * barycentric weights in xyz, the squared distance in w (0 where the segment crosses the triangle).
 */
fn segmentTriangleClosest(p: vec3f, q: vec3f, a: vec3f, b: vec3f, c: vec3f) -> vec4f {
  let ab = b - a;
  let ac = c - a;
  let nrm = cross(ab, ac);
  let nn = dot(nrm, nrm);
  if (nn > 0.0) {
    let d0 = dot(nrm, p - a);
    let d1 = dot(nrm, q - a);
    if (((d0 <= 0.0 && d1 >= 0.0) || (d0 >= 0.0 && d1 <= 0.0)) && d0 != d1) {
      let t = d0 / (d0 - d1);
      let i = p + t * (q - p) - a;
      let w = dot(nrm, cross(ab, i)) / nn;
      let v = dot(nrm, cross(i, ac)) / nn;
      if (v >= 0.0 && w >= 0.0 && v + w <= 1.0) { return vec4f(1.0 - v - w, v, w, 0.0); }
    }
  }
  var best = vec4f(0.0, 0.0, 0.0, FAR);
  // end points against the triangle
  for (var k = 0u; k < 2u; k++) {
    let e = select(p, q, k == 1u);
    let bary = closestPointOnTriangle(e, a, b, c);
    let d = bary.x * a + bary.y * b + bary.z * c - e;
    let d2 = dot(d, d);
    if (d2 < best.w) { best = vec4f(bary, d2); }
  }
  // the segment against each edge
  var v = array<vec3f, 3>(a, b, c);
  for (var k = 0u; k < 3u; k++) {
    let st = segmentSegmentClosest(p, q, v[k], v[(k + 1u) % 3u]);
    if (st.z < best.w) {
      var bary = vec3f(0.0);
      bary[k] = 1.0 - st.y;
      bary[(k + 1u) % 3u] = st.y;
      best = vec4f(bary, st.z);
    }
  }
  return best;
}

/**
 * min over v ∈ [0, 1 − u] of f(u, v) = sd(a + u·ub + v·vb) by golden section, then the ends of the range, in
 * convex.ts' order of evaluations; the best point so far (d, u, v) is kept in *best.
 */
fn goldenInner(col: Collider, a: vec3f, ub: vec3f, vb: vec3f, u: f32, best: ptr<function, vec3f>) -> f32 {
  var lo = 0.0;
  var hi = 1.0 - u;
  var x1 = hi - GOLDEN * (hi - lo);
  var x2 = lo + GOLDEN * (hi - lo);
  var f1 = 0.0;
  var f2 = 0.0;
  var ends = FAR;
  // evaluations: x1, x2, one new point per iteration, then v = 0 and v = 1 − u
  for (var k = 0u; k < GOLDEN_ITERATIONS + 4u; k++) {
    var v = x1;
    var first = k == 0u;
    if (k == 1u) {
      v = x2;
    } else if (k >= 2u && k < GOLDEN_ITERATIONS + 2u) {
      first = f1 <= f2;
      if (first) {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); v = x1;
      } else {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); v = x2;
      }
    } else if (k >= GOLDEN_ITERATIONS + 2u) {
      v = select(1.0 - u, 0.0, k == GOLDEN_ITERATIONS + 2u);
    }
    var n: vec3f;
    let f = localDistance(col, a + u * ub + v * vb, FAR, &n);
    if (f < (*best).x) { *best = vec3f(f, u, v); }
    if (k >= GOLDEN_ITERATIONS + 2u) { ends = min(ends, f); } else if (first) { f1 = f; } else { f2 = f; }
  }
  return min(min(f1, f2), ends);
}

/**
 * The convex signed distance minimised over the triangle by nested golden-section searches (convex.ts
 * goldenDeepest): the barycentric weights of the best point evaluated.
 */
fn goldenDeepest(col: Collider, a: vec3f, b: vec3f, c: vec3f) -> vec3f {
  let ub = b - a;
  let vb = c - a;
  var best = vec3f(FAR, 0.0, 0.0);
  var lo = 0.0;
  var hi = 1.0;
  var x1 = hi - GOLDEN * (hi - lo);
  var x2 = lo + GOLDEN * (hi - lo);
  var f1 = 0.0;
  var f2 = 0.0;
  // searches at: x1, x2, one new u per iteration, then u = 0 and u = 1
  for (var k = 0u; k < GOLDEN_ITERATIONS + 4u; k++) {
    var u = x1;
    var first = k == 0u;
    if (k == 1u) {
      u = x2;
    } else if (k >= 2u && k < GOLDEN_ITERATIONS + 2u) {
      first = f1 <= f2;
      if (first) {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - GOLDEN * (hi - lo); u = x1;
      } else {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + GOLDEN * (hi - lo); u = x2;
      }
    } else if (k >= GOLDEN_ITERATIONS + 2u) {
      u = select(1.0, 0.0, k == GOLDEN_ITERATIONS + 2u);
    }
    let f = goldenInner(col, a, ub, vb, u, &best);
    if (k < GOLDEN_ITERATIONS + 2u) { if (first) { f1 = f; } else { f2 = f; } }
  }
  return vec3f(1.0 - best.y - best.z, best.y, best.z);
}

/** How a triangleDeepest ends: the answer as it stands, the shape's distance at `bary`, or the golden-section search. */
const ANSWERED: u32 = 0u;
const EVALUATE: u32 = 1u;
const SEARCH: u32 = 2u;
