// Triangle contact of the analytic shapes (triangleContact.wgsl has what every shape's shares): the deepest point of a
// triangle in the shape's own frame, by the TypeScript reference's method step for step (core/colliders/sphere.ts,
// capsule.ts, box.ts, cylinder.ts, convex.ts), in f32:
//   sphere    the triangle's point closest to the centre (exact)
//   capsule   the closest points of its axis segment and the triangle (exact)
//   box       the vertex certificate; else, outside, the closest features (a vertex, or the triangle's point
//             nearest one of the 12 edges: exact); a triangle crossing the box: the golden-section search
//   cylinder  the vertex certificate; else the triangle's point closest to the axis where it lies against the
//             curved side (exact); else the golden-section search

/** the certificate's allowance for rounding [m] (convex.ts vertexDeepest) */
const CERTIFICATE_SLACK: f32 = 1e-7;

/**
 * The vertex certificate (convex.ts vertexDeepest): if a vertex's tangent plane has the whole triangle on or above
 * it, that vertex is the deepest point (*done = true); if the tangent planes show the whole triangle at least
 * `within` away, that bound (*done = true). Else *done = false and the deepest vertex with its normal.
 */
fn vertexDeepest(col: Collider, a: vec3f, b: vec3f, c: vec3f, within: f32, done: ptr<function, bool>) -> Deepest {
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
    let d = localDistance(col, v[k], FAR, &n);
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

/** Whether segment p–q meets the box of half extents h (box.ts segmentHitsIn, slabs). */
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
      out = vertexDeepest(col, a, b, c, select(FAR, within, kind == COLLIDER_BOX), &done);
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
    bary = goldenDeepest(col, a, b, c);
    end = EVALUATE;
  }
  if (end == EVALUATE) {
    var n: vec3f;
    let d = localDistance(col, bary.x * a + bary.y * b + bary.z * c, FAR, &n);
    out = Deepest(d, bary, n);
  }
  return out;
}
