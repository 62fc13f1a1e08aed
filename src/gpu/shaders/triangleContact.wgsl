// Triangle contact: the deepest point of a triangle with respect to a collider's shape (ColliderShape.triangleDeepest),
// in the shape's own frame, by the TypeScript reference's method step for step (core/colliders/sphere.ts, capsule.ts,
// box.ts, cylinder.ts, convex.ts; docs/physics.md "Contact"), in f32:
//   sphere    the triangle's point closest to the centre (exact)
//   capsule   the closest points of its axis segment and the triangle (exact)
//   box       the vertex certificate; else, outside, the closest features (a vertex, or the triangle's point
//             nearest one of the 12 edges: exact); a triangle crossing the box: the golden-section search
//   cylinder  the vertex certificate; else the triangle's point closest to the axis where it lies against the
//             curved side (exact); else the golden-section search
// Thresholds for degenerate cases are the GPU's own, chosen for f32 (docs/gpu.md, "Triangle contact"). Every
// function is written with one call site of each costly callee (the golden-section search as one loop of
// evaluations, one final evaluation of the deepest point): shader compilers inline every call, and SwiftShader
// takes minutes over a kernel that inlines the shape's distance a hundred times.

/** A very large distance [m] (no bound asked for). */
const FAR: f32 = 1e30;
/** segments shorter than this squared [m²] are points */
const TINY_SQUARED: f32 = 1e-30;
/** a·e − b² below this share of a·e: parallel segments (f32 leaves ~1e-7 of a·e of it) */
const PARALLEL: f32 = 1e-6;
/** the certificate's allowance for rounding [m] (convex.ts vertexDeepest) */
const CERTIFICATE_SLACK: f32 = 1e-7;
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
 * The vertex certificate (convex.ts vertexDeepest): if a vertex's tangent plane has the whole triangle on or above
 * it, that vertex is the deepest point (*done = true); if the tangent planes show the whole triangle at least
 * `within` away, that bound (*done = true). Else *done = false and the deepest vertex with its normal.
 */
fn vertexDeepest(kind: u32, s: vec4f, a: vec3f, b: vec3f, c: vec3f, within: f32, done: ptr<function, bool>) -> Deepest {
  var v = array<vec3f, 3>(a, b, c);
  var best = FAR;
  var bestK = 0u;
  var bestN = vec3f(0.0);
  var certified = false;
  var certK = 0u;
  var certD = FAR;
  var certN = vec3f(0.0);
  var bound = -FAR;
  for (var k = 0u; k < 3u; k++) {
    var n: vec3f;
    let d = localDistance(kind, s, v[k], &n);
    // the other vertices' height above this vertex's tangent plane
    let lowest = min(dot(n, a - v[k]), min(dot(n, b - v[k]), dot(n, c - v[k])));
    bound = max(bound, d + min(lowest, 0.0));
    if (lowest >= -CERTIFICATE_SLACK && d < certD) {
      certified = true;
      certK = k;
      certD = d;
      certN = n;
    }
    if (!certified && d < best) {
      best = d;
      bestK = k;
      bestN = n;
    }
  }
  var unit = array<vec3f, 3>(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 1.0, 0.0), vec3f(0.0, 0.0, 1.0));
  if (certified) {
    *done = true;
    return Deepest(certD, unit[certK], certN);
  }
  *done = bound >= within;
  return Deepest(select(best, bound, *done), unit[bestK], bestN);
}

/**
 * min over v ∈ [0, 1 − u] of f(u, v) = sd(a + u·ub + v·vb) by golden section, then the ends of the range, in
 * convex.ts' order of evaluations; the best point so far (d, u, v) is kept in *best.
 */
fn goldenInner(kind: u32, s: vec4f, a: vec3f, ub: vec3f, vb: vec3f, u: f32, best: ptr<function, vec3f>) -> f32 {
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
    let f = localDistance(kind, s, a + u * ub + v * vb, &n);
    if (f < (*best).x) { *best = vec3f(f, u, v); }
    if (k >= GOLDEN_ITERATIONS + 2u) { ends = min(ends, f); } else if (first) { f1 = f; } else { f2 = f; }
  }
  return min(min(f1, f2), ends);
}

/**
 * The convex signed distance minimised over the triangle by nested golden-section searches (convex.ts
 * goldenDeepest): the barycentric weights of the best point evaluated.
 */
fn goldenDeepest(kind: u32, s: vec4f, a: vec3f, b: vec3f, c: vec3f) -> vec3f {
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
    let f = goldenInner(kind, s, a, ub, vb, u, &best);
    if (k < GOLDEN_ITERATIONS + 2u) { if (first) { f1 = f; } else { f2 = f; } }
  }
  return vec3f(1.0 - best.y - best.z, best.y, best.z);
}

/**
 * Where an axis (direction u) crosses the triangle (convex.ts axisCrossingNormal): the triangle's normal with its
 * component along the axis removed, the triangle's own normal if that leaves nothing.
 */
fn axisCrossingNormal(a: vec3f, b: vec3f, c: vec3f, u: vec3f) -> vec3f {
  var n = cross(b - a, c - a);
  let uu = dot(u, u);
  if (uu > 0.0) {
    let side = n - (dot(n, u) / uu) * u;
    if (dot(side, side) > 1e-6 * dot(n, n)) { n = side; }
  }
  let l = length(n);
  return n / select(l, 1.0, l == 0.0);
}

/** Whether segment p–q meets the box of half extents h (box.ts segmentHits, slabs). */
fn segmentHitsBox(h: vec3f, p: vec3f, q: vec3f) -> bool {
  let e = q - p;
  var lo = 0.0;
  var hi = 1.0;
  for (var i = 0u; i < 3u; i++) {
    if (abs(e[i]) < 1e-30) {
      if (abs(p[i]) > h[i]) { return false; }
      continue;
    }
    let ta = (-h[i] - p[i]) / e[i];
    let tb = (h[i] - p[i]) / e[i];
    lo = max(lo, min(ta, tb));
    hi = min(hi, max(ta, tb));
    if (lo > hi) { return false; }
  }
  return true;
}

/** How triangleDeepest ends: the answer as it stands, the shape's distance at `bary`, or the golden-section search. */
const ANSWERED: u32 = 0u;
const EVALUATE: u32 = 1u;
const SEARCH: u32 = 2u;

/**
 * A box's closest features (box.ts triangleDeepest after the certificate), for a triangle whose deepest vertex
 * `dv` is outside the box: SEARCH where the triangle crosses the box, else *bary the triangle's point nearest the
 * box (EVALUATE), or ANSWERED when that is the vertex itself (*out, its distance and normal).
 */
fn boxFeatures(h: vec3f, a: vec3f, b: vec3f, c: vec3f, dv: vec3f, out: ptr<function, Deepest>, bary: ptr<function, vec3f>) -> u32 {
  var nv: vec3f;
  let vertex = boxDistance(h, dv.x * a + dv.y * b + dv.z * c, &nv);
  *out = Deepest(vertex, dv, nv);
  // crossing the box: a vertex in it, an edge of the triangle through it (or, below, an edge of the box through it)
  if (vertex <= 0.0) { return SEARCH; }
  var v = array<vec3f, 3>(a, b, c);
  for (var k = 0u; k < 3u; k++) {
    if (segmentHitsBox(h, v[k], v[(k + 1u) % 3u])) { return SEARCH; }
  }
  var best = vertex;
  var found = false;
  let g = (a + b + c) / 3.0;
  let reach = sqrt(max(dot(a - g, a - g), max(dot(b - g, b - g), dot(c - g, c - g))));
  // the 12 edges, in box.ts' order: from each corner k along each axis its bits lack
  for (var k = 0u; k < 8u; k++) {
    let e0 = select(-h, h, vec3<bool>((k & 1u) != 0u, (k & 2u) != 0u, (k & 4u) != 0u));
    for (var axis = 0u; axis < 3u; axis++) {
      if ((k & (1u << axis)) != 0u) { continue; }
      var e1 = e0;
      e1[axis] = h[axis];
      // an edge farther from the triangle's centre than its reach plus the best so far cannot be nearer
      let u = e1 - e0;
      let t = clamp(dot(g - e0, u) / dot(u, u), 0.0, 1.0);
      if (length(e0 + t * u - g) - reach >= best) { continue; }
      let st = segmentTriangleClosest(e0, e1, a, b, c);
      if (st.w <= CROSSING_SQUARED) { return SEARCH; }
      if (st.w < best * best) {
        best = sqrt(st.w);
        found = true;
        *bary = st.xyz;
      }
    }
  }
  return select(ANSWERED, EVALUATE, found);
}

/**
 * The deepest point of triangle (a, b, c) (the collider's own frame) for collider `col` (sphere.ts, capsule.ts,
 * box.ts, cylinder.ts triangleDeepest). A box may answer with any value ≥ `within` when the whole triangle is at
 * least that far away. Only shapes with triangle contact get here (not a floor or a plane).
 */
fn triangleDeepest(col: Collider, a: vec3f, b: vec3f, c: vec3f, within: f32) -> Deepest {
  let kind = col.kind;
  let s = col.shape;
  var out = Deepest(FAR, vec3f(1.0, 0.0, 0.0), vec3f(0.0, 1.0, 0.0));
  var bary = vec3f(1.0, 0.0, 0.0);
  var end = EVALUATE;
  if (kind == COLLIDER_SPHERE) {
    // the triangle's point closest to the centre
    bary = closestPointOnTriangle(vec3f(0.0), a, b, c);
  } else {
    var done = kind == COLLIDER_CAPSULE;
    if (!done) {
      // box, cylinder: the vertex certificate (a cylinder asks no bound)
      out = vertexDeepest(kind, s, a, b, c, select(FAR, within, kind == COLLIDER_BOX), &done);
      end = ANSWERED;
    }
    if (kind == COLLIDER_BOX && !done) {
      end = boxFeatures(s.xyz, a, b, c, out.bary, &out, &bary);
    } else if (kind == COLLIDER_CAPSULE || !done) {
      // capsule: the closest points of its axis segment and the triangle; cylinder: of its axis line (a segment
      // reaching past every vertex's projection), the answer where that point lies against the curved side
      let capsule = kind == COLLIDER_CAPSULE;
      let half = select(s.y + 1.0 + max(length(a), max(length(b), length(c))), s.x, capsule);
      let st = segmentTriangleClosest(vec3f(0.0, -half, 0.0), vec3f(0.0, half, 0.0), a, b, c);
      bary = st.xyz;
      let q = st.x * a + st.y * b + st.z * c;
      let side = abs(q.y) - s.y <= 0.0 && sqrt(st.w) - s.x >= abs(q.y) - s.y;
      if (!capsule && !side) {
        end = SEARCH;
      } else if (st.w > CROSSING_SQUARED) {
        end = EVALUATE;
      } else {
        // the axis crosses the triangle: pushed off sideways, along the triangle's normal made perpendicular to it
        out = Deepest(-select(s.x, s.y, capsule), bary, axisCrossingNormal(a, b, c, vec3f(0.0, select(1.0, s.x, capsule), 0.0)));
        end = ANSWERED;
      }
    }
  }
  if (end == SEARCH) {
    bary = goldenDeepest(kind, s, a, b, c);
    end = EVALUATE;
  }
  if (end == EVALUATE) {
    var n: vec3f;
    let d = localDistance(kind, s, bary.x * a + bary.y * b + bary.z * c, &n);
    out = Deepest(d, bary, n);
  }
  return out;
}
