// collide (phases.ts), triangle part, for collider batch.flags (its record at sub.colliderBase: where it is at the
// end of this substep) and the triangles of one colour, [batch.start, batch.end) (core sorts triangles by colour):
// they share no vertex, so each thread owns its three particles for the dispatch (Gauss–Seidel over colours, as the
// constraint solve; no float atomics). The deepest point of the triangle (`triangleDeepest`, in the collider's own
// frame) is pushed out to the contact thickness as a particle is (collideParticles), with friction on its motion
// relative to the surface; the correction is shared by barycentric weight and inverse mass so that Σ bary_i·Δx_i is
// the wanted displacement. Two kernels: collideTriangles for an analytic shape (shapes.wgsl, shapeTriangles.wgsl),
// collideMeshTriangles for a mesh collider (meshCollider.wgsl, meshTriangles.wgsl).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let t = batch.start + flatIndex(gid, nwg);
  if (t >= batch.end) { return; }
  let shape = colliders[sub.colliderBase + batch.flags];
  let a = triangles[3u * t];
  let b = triangles[3u * t + 1u];
  let c = triangles[3u * t + 2u];
  let xa = positions[a].xyz;
  let xb = positions[b].xyz;
  let xc = positions[c].xyz;
  var n: vec3f;
  // every point of a triangle stretched at most 2× lies within `reach` of vertex a
  if (colliderDistance(shape, xa, globals.reach, &n) >= globals.reach) { return; }
  let th = globals.thickness;
  let deep = triangleDeepest(shape, toLocal(shape, xa), toLocal(shape, xb), toLocal(shape, xc), th);
  if (deep.d >= th) { return; }
  let d = deep.d;
  let bary = deep.bary;
  n = toWorldDirection(shape, deep.n);
  let wa = invMass[a] * bary.x;
  let wb = invMass[b] * bary.y;
  let wc = invMass[c] * bary.z;
  let denom = wa * bary.x + wb * bary.y + wc * bary.z;
  // (not > 0: nothing free to move, or weights too degenerate to have any; NaN included)
  if (!(denom > 0.0)) { return; }
  // no corner moves more than TRIANGLE_SPREAD_MOST × the point's correction (phases.ts collideTriangles: a point
  // beside a pinned or grabbed corner would throw a free one across the cloth)
  let spread = max(max(wa, wb), wc) / denom;
  let scale = select(1.0, TRIANGLE_SPREAD_MOST / spread, spread > TRIANGLE_SPREAD_MOST);
  // motion of the contact point over the substep so far, relative to the surface, treated as a particle's
  // (collideParticles), the recovery shared among the triangles of a particle
  let pa = previous[a].xyz;
  let pb = previous[b].xyz;
  let pc = previous[c].xyz;
  var m = bary.x * (xa - pa) + bary.y * (xb - pb) + bary.z * (xc - pc);
  if (shape.moving != 0u) { m -= surfaceMotion(shape, bary.x * xa + bary.y * xb + bary.z * xc); }
  let mn = dot(m, n);
  let movedIn = max(-mn, 0.0);
  let depth = min(th - d, movedIn + sub.recoverTriangle);
  let tang = m - mn * n;
  let fs = frictionScale(length(tang), pressedDepth(th - d, movedIn, sub.recoverTriangle));
  let dx = ((depth * n - fs * tang) / denom) * scale;
  positions[a] = vec4f(xa + wa * dx, 0.0);
  positions[b] = vec4f(xb + wb * dx, 0.0);
  positions[c] = vec4f(xc + wc * dx, 0.0);
  // the outward motion the push-out made is not velocity: x_prev moves likewise
  let made = min(mn + depth, depth);
  if (made > 0.0) {
    let dp = ((made / denom) * scale) * n;
    previous[a] = vec4f(pa + wa * dp, 0.0);
    previous[b] = vec4f(pb + wb * dp, 0.0);
    previous[c] = vec4f(pc + wc * dp, 0.0);
  }
}
