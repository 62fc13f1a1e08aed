// A mesh collider's signed distance in its own frame (core/colliders/mesh.ts MeshCollider.signedDistance, step for
// step, in f32): the nearest triangle by a walk of its BVH (colliders/bvh.ts TriangleBvh.closest: nearer child
// first, a node no nearer than the best so far skipped, a triangle whose plane is already farther skipped), then the
// sign by the angle-weighted pseudo-normal of the feature the closest point lies on in a closed piece (Bærentzen &
// Aanæs 2005), or, in an open piece, the unsigned distance with the normal towards the point's side. Its tables:
// meshNodes (the hierarchy, from Collider.meshRoot) and meshTriangles (gpu/meshes.ts). Walks use a stack of
// MESH_STACK entries (a hierarchy deeper than that is refused) and visit each node at most once.

/** Squared distance [m²] from point p to node k's box (0 inside it; TriangleBvh.boxDistance2). */
fn meshBoxDistance2(k: u32, p: vec3f) -> f32 {
  let g = max(max(meshNodes[k].lo - p, p - meshNodes[k].hi), vec3f(0.0));
  return dot(g, g);
}

/** The nearest triangle of a mesh: its index in meshTriangles (−1: none nearer than asked) and its closest point's weights. */
struct MeshHit {
  t: i32,
  bary: vec3f,
}

/**
 * The triangle of the mesh under node `root` nearest point p among those nearer than √max2 [m] (TriangleBvh.closest,
 * in its order: ties go to the triangle met first).
 */
fn meshClosest(root: u32, p: vec3f, max2: f32) -> MeshHit {
  var hit = MeshHit(-1, vec3f(1.0, 0.0, 0.0));
  var best2 = max2;
  if (meshBoxDistance2(root, p) >= best2) { return hit; }
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
        let a = meshTriangles[t].a;
        // the triangle's plane no nearer than the best: neither is the triangle
        let h = dot(meshTriangles[t].normal, p - a);
        if (h * h >= best2) { continue; }
        let b = meshTriangles[t].b;
        let c = meshTriangles[t].c;
        let w = closestPointOnTriangle(p, a, b, c);
        let d = w.x * a + w.y * b + w.z * c - p;
        let d2 = dot(d, d);
        if (d2 < best2) {
          best2 = d2;
          hit = MeshHit(i32(t), w);
        }
      }
    } else {
      let l = first;
      let r = first + 1u;
      let dl = meshBoxDistance2(l, p);
      let dr = meshBoxDistance2(r, p);
      if (dl < dr) {
        if (dr < best2) { stack[top] = r; top++; }
        if (dl < best2) { n = l; continue; }
      } else {
        if (dl < best2) { stack[top] = l; top++; }
        if (dr < best2) { n = r; continue; }
      }
    }
    // next: the top of the stack that is still nearer than the best
    var next = -1;
    while (top > 0u) {
      top--;
      if (meshBoxDistance2(stack[top], p) < best2) {
        next = i32(stack[top]);
        break;
      }
    }
    if (next < 0) { break; }
    n = u32(next);
  }
  return hit;
}

/**
 * Signed distance [m] of point q (the mesh's own frame) from mesh collider c, its normal to *n (MeshCollider
 * signedDistance, without its coarse grid: that only spares queries, it never changes an answer); the signature of
 * the analytic shapes' localDistance (shapes.wgsl), which the kernels of mesh colliders have instead. With `within`
 * below FAR: the query bounded by it; a point with no triangle that near answers `within` (writing no normal), unless
 * it may be inside a closed piece (in the mesh's box), which takes the unbounded query for its sign.
 */
fn localDistance(c: Collider, q: vec3f, within: f32, n: ptr<function, vec3f>) -> f32 {
  var max2 = select(FAR, within * within, within > 0.0 && within < FAR);
  var hit = MeshHit(-1, vec3f(1.0, 0.0, 0.0));
  for (var query = 0u; query < 2u; query++) {
    hit = meshClosest(c.meshRoot, q, max2);
    if (hit.t >= 0 || max2 >= FAR || c.meshClosed == 0u || meshBoxDistance2(c.meshRoot, q) > 0.0) { break; }
    max2 = FAR;
  }
  if (hit.t < 0) { return within; }
  // the distance and normal from the closest point (MeshCollider.distanceTo)
  let t = u32(hit.t);
  let u = hit.bary;
  let tri = meshTriangles[t];
  let v = q - (u.x * tri.a + u.y * tri.b + u.z * tri.c);
  let d = length(v);
  var nn = tri.normal;
  if ((tri.flags & MESH_SIGNED) == 0u) {
    // an open shell: unsigned, away from the surface
    if (d > 1e-12) { *n = v / d; } else { *n = nn; }
    return d;
  }
  // the pseudo-normal of the feature the closest point lies on (closestPointOnTriangle gives exact 0 and 1)
  if (u.x == 1.0) {
    nn = tri.normalA;
  } else if (u.y == 1.0) {
    nn = tri.normalB;
  } else if (u.z == 1.0) {
    nn = tri.normalC;
  } else if (u.x == 0.0 || u.y == 0.0 || u.z == 0.0) {
    // edge e runs corner e → e + 1: the one whose weight is not zero on either end
    let o = select(select(tri.across0, tri.across2, u.y == 0.0), tri.across1, u.x == 0.0);
    if (o >= 0) { nn += meshTriangles[o].normal; }
  }
  let sg = select(1.0, -1.0, dot(v, nn) < 0.0);
  if (d > 1e-12) {
    *n = (sg * v) / d;
  } else {
    let l = length(nn);
    *n = nn / select(l, 1.0, l == 0.0);
  }
  return sg * d;
}
