// Triangle contact of a mesh collider (core/colliders/mesh.ts triangleDeepest, step for step, in f32; what every
// shape's shares is in triangleContact.wgsl): over a cloth triangle the distance to a mesh is smallest at a vertex
// (which particle contact keeps out) or where a sharp edge of the mesh comes nearest the triangle, so the deepest
// point is the triangle's point nearest the sharp edges within reach, found by a walk of the mesh's BVH (meshNodes,
// a stack of MESH_STACK entries, each node at most once) with the triangle's box; a sharp edge of a closed piece
// through the triangle, or that point inside a closed piece: the golden-section search; an open shell's sharp edge
// through it: the side the triangle's vertices are on.

/** How a mesh's triangleDeepest ends besides ANSWERED, EVALUATE and SEARCH: evaluated, then searched if inside; an open shell through it. */
const EVALUATE_MESH: u32 = 3u;
const SIDES: u32 = 4u;

/** Squared gap [m²] between node k's box and the box lo–hi (zero where they overlap). */
fn meshBoxGap2(k: u32, lo: vec3f, hi: vec3f) -> f32 {
  let g = max(max(meshNodes[k].lo - hi, lo - meshNodes[k].hi), vec3f(0.0));
  return dot(g, g);
}

/**
 * A mesh's sharp edges against the triangle (mesh.ts triangleDeepest, its walk): the triangle's point nearest the
 * sharp edges within `within` (its weights to *bary: EVALUATE_MESH), found by a walk of the mesh's BVH with the
 * triangle's box, each triangle owning its sharp edges once; ANSWERED with `within` in *out when none is that near;
 * where a sharp edge passes through the triangle, SEARCH (an edge of a closed piece) or SIDES (of an open shell; the
 * crossing's weights to *bary). Only a mesh with a sharp edge gets here (else it needs no triangle contact: its
 * minCurvatureRadius is Infinity), and always with a bound (the contact thickness).
 */
fn meshSharpEdges(col: Collider, a: vec3f, b: vec3f, c: vec3f, within: f32, out: ptr<function, Deepest>, bary: ptr<function, vec3f>) -> u32 {
  *out = Deepest(within, vec3f(1.0, 0.0, 0.0), vec3f(0.0, 1.0, 0.0));
  let lo = min(a, min(b, c));
  let hi = max(a, max(b, c));
  // the triangle's unit normal and plane offset: an edge wholly farther than the best from its plane is skipped
  var tn = cross(b - a, c - a);
  let tl = length(tn);
  if (tl > 0.0) { tn /= tl; }
  let toff = dot(tn, a);
  let root = col.meshRoot;
  var best2 = max(within, 0.0) * max(within, 0.0);
  var found = false;
  var crossing = -1;
  if (meshBoxGap2(root, lo, hi) > best2) { return ANSWERED; }
  var stack: array<u32, MESH_STACK>;
  var top = 0u;
  var n = root;
  // each node is visited at most once
  let nodes = arrayLength(&meshNodes);
  for (var visit = 0u; visit < nodes; visit++) {
    let count = meshNodes[n].count;
    let first = meshNodes[n].first;
    if (count > 0u) {
      for (var t = first; t < first + count; t++) {
        let f = meshTriangles[t].flags;
        if (f < MESH_SHARP_EDGE) { continue; }
        var v = array<vec3f, 3>(meshTriangles[t].a, meshTriangles[t].b, meshTriangles[t].c);
        for (var e = 0u; e < 3u; e++) {
          if ((f & (MESH_SHARP_EDGE << e)) == 0u) { continue; }
          let p = v[e];
          let q = v[(e + 1u) % 3u];
          // the edge's box against the triangle's
          let g = max(max(min(p, q) - hi, lo - max(p, q)), vec3f(0.0));
          if (dot(g, g) > best2) { continue; }
          if (tl > 0.0) {
            let hp = dot(tn, p) - toff;
            let hq = dot(tn, q) - toff;
            let above = min(hp, hq);
            let below = max(hp, hq);
            if ((hp > 0.0 && hq > 0.0 && above * above > best2) || (hp < 0.0 && hq < 0.0 && below * below > best2)) { continue; }
          }
          let st = segmentTriangleClosest(p, q, a, b, c);
          if (st.w <= CROSSING_SQUARED) {
            crossing = i32(t);
            *bary = st.xyz;
            break;
          }
          if (st.w < best2) {
            best2 = st.w;
            found = true;
            *bary = st.xyz;
          }
        }
        if (crossing >= 0) { break; }
      }
      if (crossing >= 0) { break; }
    } else {
      let l = first;
      let r = first + 1u;
      let dl = meshBoxGap2(l, lo, hi);
      let dr = meshBoxGap2(r, lo, hi);
      if (dl < dr) {
        if (dr <= best2) { stack[top] = r; top++; }
        if (dl <= best2) { n = l; continue; }
      } else {
        if (dl <= best2) { stack[top] = l; top++; }
        if (dr <= best2) { n = r; continue; }
      }
    }
    var next = -1;
    while (top > 0u) {
      top--;
      if (meshBoxGap2(stack[top], lo, hi) <= best2) {
        next = i32(stack[top]);
        break;
      }
    }
    if (next < 0) { break; }
    n = u32(next);
  }
  if (crossing >= 0) { return select(SIDES, SEARCH, (meshTriangles[crossing].flags & MESH_SIGNED) != 0u); }
  return select(ANSWERED, EVALUATE_MESH, found);
}

/**
 * The deepest point of triangle (a, b, c) (the mesh's own frame) for mesh collider `col` (mesh.ts triangleDeepest):
 * its point nearest the sharp edges within `within` (else `within`), searched where that point is inside a closed
 * piece or a closed piece's sharp edge passes through the triangle; an open shell's sharp edge through it: that point,
 * at distance 0, towards the side its vertices are on (the sum of their normals; the triangle's own normal where they
 * are on both sides).
 */
fn triangleDeepest(col: Collider, a: vec3f, b: vec3f, c: vec3f, within: f32) -> Deepest {
  var out: Deepest;
  var bary = vec3f(1.0, 0.0, 0.0);
  var end = meshSharpEdges(col, a, b, c, within, &out, &bary);
  if (end == SIDES) {
    var v = array<vec3f, 3>(a, b, c);
    var sum = vec3f(0.0);
    for (var k = 0u; k < 3u; k++) {
      var n: vec3f;
      localDistance(col, v[k], FAR, &n);
      sum += n;
    }
    var l = length(sum);
    if (l < 1e-9) {
      sum = cross(b - a, c - a);
      l = select(length(sum), 1.0, length(sum) == 0.0);
    }
    return Deepest(0.0, bary, sum / l);
  }
  // at most twice: the nearest point to the sharp edges evaluated, and searched where it is inside a closed piece
  for (var round = 0u; round < 2u && end != ANSWERED; round++) {
    if (end == SEARCH) {
      bary = goldenDeepest(col, a, b, c);
      end = EVALUATE;
    }
    var n: vec3f;
    let d = localDistance(col, bary.x * a + bary.y * b + bary.z * c, FAR, &n);
    out = Deepest(d, bary, n);
    end = select(ANSWERED, SEARCH, end == EVALUATE_MESH && d < 0.0);
  }
  return out;
}
