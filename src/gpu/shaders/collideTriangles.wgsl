// collide (phases.ts), triangle part, for collider globals.colliders[batch.flags] and the triangles of one colour,
// triOrder[batch.start .. batch.end): triangles of a colour share no vertex, so each thread owns its three
// particles for the dispatch (Gauss–Seidel over colours, as the constraint solve; no float atomics). The deepest
// point of the triangle is pushed out to the contact thickness, with friction; the correction is shared by
// barycentric weight and inverse mass so that Σ bary_i·Δx_i is the wanted displacement.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let k = batch.start + flatIndex(gid, nwg);
  if (k >= batch.end) { return; }
  let shape = globals.colliders[batch.flags];
  let t = triOrder[k];
  let a = triangles[3u * t];
  let b = triangles[3u * t + 1u];
  let c = triangles[3u * t + 2u];
  let xa = positions[a].xyz;
  let xb = positions[b].xyz;
  let xc = positions[c].xyz;
  var n: vec3f;
  // every point of a triangle stretched at most 2× lies within `reach` of vertex a
  if (shapeDistance(shape, xa, &n) > globals.reach) { return; }
  // only spheres get here (a half-space's deepest point is a vertex)
  let bary = closestPointOnTriangle(shape.data.xyz, xa, xb, xc);
  let q = bary.x * xa + bary.y * xb + bary.z * xc;
  let d = shapeDistance(shape, q, &n);
  let th = globals.thickness;
  if (d >= th) { return; }
  let wa = invMass[a] * bary.x;
  let wb = invMass[b] * bary.y;
  let wc = invMass[c] * bary.z;
  let denom = wa * bary.x + wb * bary.y + wc * bary.z;
  if (denom == 0.0) { return; }
  let depth = th - d;
  let m = bary.x * (xa - previous[a].xyz) + bary.y * (xb - previous[b].xyz) + bary.z * (xc - previous[c].xyz);
  let tang = m - dot(m, n) * n;
  let fs = frictionScale(length(tang), depth);
  let dx = (depth * n - fs * tang) / denom;
  positions[a] = vec4f(xa + wa * dx, 0.0);
  positions[b] = vec4f(xb + wb * dx, 0.0);
  positions[c] = vec4f(xc + wc * dx, 0.0);
}
