// accumulateWind (phases.ts), per triangle: the force of the air moving at `sub.wind` relative to the triangle's
// mean velocity over the last substep, F = ½ρ·|v|·(v·n)·area·n, one third of it for each vertex (windK = ¼ρ/3 because |N| = 2·area).
// Being an explicit drag it is capped at m̄·|v·n|/(2h) per vertex share (m̄ = 1/Σw over the triangle's free
// inverse masses), as on the CPU. Written per triangle; `integrate` gathers it per particle over the incident
// triangles (no float atomics).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let t = flatIndex(gid, nwg);
  if (t >= globals.triangleCount) { return; }
  let a = triangles[3u * t];
  let b = triangles[3u * t + 1u];
  let c = triangles[3u * t + 2u];
  let xa = positions[a].xyz;
  let n = cross(positions[b].xyz - xa, positions[c].xyz - xa); // |n| = 2·area
  let nl = length(n);
  if (nl < 1e-20) {
    triForces[t] = vec4f(0.0);
    return;
  }
  // the triangle's velocity over the last substep, Σ(x − x_prev)/(3h)
  let moved = (xa - previous[a].xyz) + (positions[b].xyz - previous[b].xyz) + (positions[c].xyz - previous[c].xyz);
  let r = sub.wind - moved * (sub.invH / 3.0);
  let rn = dot(r, n);
  let vn = rn / nl; // relative air speed along the unit normal
  let cap = abs(vn) * (0.5 * sub.invH) / (baseInvMass[a] + baseInvMass[b] + baseInvMass[c]);
  let fmag = clamp(globals.windK * length(r) * rn, -cap, cap);
  triForces[t] = vec4f((fmag / nl) * n, 0.0);
}
