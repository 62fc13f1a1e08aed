// A collider's pose (colliders/pose.ts PosedCollider: world = R·local + o at the end of the substep, one `Collider`
// record per collider and substep) and the motion of its surface over the substep: what the contact kernels and the
// carry kernel share.

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
