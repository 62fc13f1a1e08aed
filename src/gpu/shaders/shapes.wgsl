// The analytic collider shapes (core/colliders/*.ts) in their own frames: a sphere at the origin; a floor or plane
// the half-space y < 0; a box axis-aligned at the origin; a capsule's axis from y = −half length to +half length; a
// cylinder's axis along y. The contact kernels of analytic colliders include this; those of mesh colliders include
// meshCollider.wgsl instead, which defines `localDistance` for a mesh.

/** Box of half extents h (box.ts signedDistance): outside, the distance to its nearest point; inside, the nearest face. */
fn boxDistance(h: vec3f, q: vec3f, n: ptr<function, vec3f>) -> f32 {
  let e = abs(q) - h;
  if (e.x > 0.0 || e.y > 0.0 || e.z > 0.0) {
    let o = max(e, vec3f(0.0));
    let d = length(o);
    *n = sign(q) * o / d;
    return d;
  }
  if (e.x >= e.y && e.x >= e.z) { *n = vec3f(select(1.0, -1.0, q.x < 0.0), 0.0, 0.0); return e.x; }
  if (e.y >= e.z) { *n = vec3f(0.0, select(1.0, -1.0, q.y < 0.0), 0.0); return e.y; }
  *n = vec3f(0.0, 0.0, select(1.0, -1.0, q.z < 0.0));
  return e.z;
}

/**
 * Signed distance [m] of point q (the collider's own frame) from collider c's shape (its type c.kind, its numbers
 * c.shape: PosedCollider.shapeParams), negative inside; its outward normal (own frame) goes to *n. Exact wherever
 * the point is: `within` (the mesh collider's bound, meshCollider.wgsl, which has the same signature) asks nothing
 * of an analytic shape.
 */
fn localDistance(c: Collider, q: vec3f, within: f32, n: ptr<function, vec3f>) -> f32 {
  let s = c.shape;
  switch c.kind {
    case COLLIDER_SPHERE: {
      let l = length(q);
      if (l > 1e-12) { *n = q / l; } else { *n = vec3f(0.0, 1.0, 0.0); }
      return l - s.x;
    }
    case COLLIDER_BOX: {
      return boxDistance(s.xyz, q, n);
    }
    case COLLIDER_CAPSULE: {
      // from the axis' nearest point; on the axis, sideways (capsule.ts: the axis × the world axis least aligned)
      let d = vec3f(q.x, q.y - clamp(q.y, -s.x, s.x), q.z);
      let l = length(d);
      if (l > 1e-12) { *n = d / l; } else if (s.x > 0.0) { *n = vec3f(0.0, 0.0, -1.0); } else { *n = vec3f(0.0, 1.0, 0.0); }
      return l - s.y;
    }
    case COLLIDER_CYLINDER: {
      // cylinder.ts signedDistance with its axis along y
      let rho = length(q.xz);
      var h = vec3f(0.0, 0.0, -1.0);
      if (rho > 1e-12) { h = vec3f(q.x / rho, 0.0, q.z / rho); }
      let sy = select(1.0, -1.0, q.y < 0.0);
      let er = rho - s.x;
      let ey = abs(q.y) - s.y;
      if (er > 0.0 || ey > 0.0) {
        let o = max(vec2f(er, ey), vec2f(0.0));
        let d = length(o);
        *n = (o.x * h + vec3f(0.0, o.y * sy, 0.0)) / d;
        return d;
      }
      if (er >= ey) { *n = h; return er; }
      *n = vec3f(0.0, sy, 0.0);
      return ey;
    }
    default: {
      // COLLIDER_FLOOR, COLLIDER_PLANE: the half-space y < 0
      *n = vec3f(0.0, 1.0, 0.0);
      return q.y;
    }
  }
}

