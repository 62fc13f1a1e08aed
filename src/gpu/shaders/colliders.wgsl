// Collider shapes (core/colliders/*.ts) in their own frames, placed and moved by their pose (colliders/pose.ts
// PosedCollider, one `Collider` record per collider and substep), and the friction rule shared by the contact
// kernels. Shapes in their own frame: a sphere at the origin; a floor or plane the half-space y < 0; a box
// axis-aligned at the origin; a capsule's axis from y = −half length to +half length; a cylinder's axis along y.

/** World point p in the collider's own frame: Rᵀ·(p − o). */
fn toLocal(c: Collider, p: vec3f) -> vec3f {
  let d = p - vec3f(c.pose0.w, c.pose1.w, c.pose2.w);
  return d.x * c.pose0.xyz + d.y * c.pose1.xyz + d.z * c.pose2.xyz;
}

/** A direction of the collider's own frame in the world: R·v. */
fn toWorldDirection(c: Collider, v: vec3f) -> vec3f {
  return vec3f(dot(c.pose0.xyz, v), dot(c.pose1.xyz, v), dot(c.pose2.xyz, v));
}

/** A point of the collider's own frame in the world: R·l + o. */
fn toWorld(c: Collider, l: vec3f) -> vec3f {
  return toWorldDirection(c, l) + vec3f(c.pose0.w, c.pose1.w, c.pose2.w);
}

/** How far the surface point now at world p moved over the substep [m] (PosedCollider.surfaceMotion). */
fn surfaceMotion(c: Collider, p: vec3f) -> vec3f {
  return vec3f(dot(c.motion0.xyz, p) + c.motion0.w, dot(c.motion1.xyz, p) + c.motion1.w, dot(c.motion2.xyz, p) + c.motion2.w);
}

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
 * Signed distance [m] of point q (the collider's own frame) from a shape of type `kind` with numbers `s`
 * (PosedCollider.shapeParams), negative inside; its outward normal (own frame) goes to *n.
 */
fn localDistance(kind: u32, s: vec4f, q: vec3f, n: ptr<function, vec3f>) -> f32 {
  switch kind {
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

/** Signed distance [m] of world point p from the collider's surface (negative inside); the world normal goes to *n. */
fn colliderDistance(c: Collider, p: vec3f, n: ptr<function, vec3f>) -> f32 {
  var nl: vec3f;
  let d = localDistance(c.kind, c.shape, toLocal(c, p), &nl);
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
