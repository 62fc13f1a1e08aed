// solveBending (solvers/xpbd.ts) for the hinges of one colour batch [batch.start, batch.end): hinges of a batch
// share no particle, so each thread owns its four particles for the dispatch. The isometric bending model (Bergou
// et al. 2006): C = Σ K_i x_i is a 3-vector, linear in the positions (∇_{x_i} C = K_i·I), so its three components
// are solved at once, their system being diagonal:
//   α̃ = α/h²,  Δλ = (−C − α̃·λ) / (Σ w_i K_i² + α̃),  Δx_i = w_i·K_i·Δλ,
// λ ← λ + Δλ (λ starts from 0 unless PASS_READ_LAMBDA). No damping term: bending is undamped, as on the CPU.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let e = batch.start + flatIndex(gid, nwg);
  if (e >= batch.end) { return; }
  let alpha = hingeCompliance[e];
  if (alpha < 0.0) { return; } // no rigidity or no stencil: no constraint
  let ids = hinges[e];
  let k = hingeWeights[e];
  let w = vec4f(invMass[ids.x], invMass[ids.y], invMass[ids.z], invMass[ids.w]);
  let alphaT = alpha * sub.invH2;
  let denom = dot(w * k, k) + alphaT;
  if (!(denom > 0.0)) { return; } // every particle pinned and no compliance
  let x0 = positions[ids.x].xyz;
  let x1 = positions[ids.y].xyz;
  let x2 = positions[ids.z].xyz;
  let x3 = positions[ids.w].xyz;
  let c = k.x * x0 + k.y * x1 + k.z * x2 + k.w * x3;
  let at = 3u * e;
  var lambda = vec3f(0.0);
  if ((batch.flags & PASS_READ_LAMBDA) != 0u) {
    lambda = vec3f(hingeLambdas[at], hingeLambdas[at + 1u], hingeLambdas[at + 2u]);
  }
  let dl = (-c - alphaT * lambda) / denom;
  let next = lambda + dl;
  hingeLambdas[at] = next.x;
  hingeLambdas[at + 1u] = next.y;
  hingeLambdas[at + 2u] = next.z;
  let step = w * k; // Δx_i = (w_i·K_i)·Δλ
  positions[ids.x] = vec4f(x0 + step.x * dl, 0.0);
  positions[ids.y] = vec4f(x1 + step.y * dl, 0.0);
  positions[ids.z] = vec4f(x2 + step.z * dl, 0.0);
  positions[ids.w] = vec4f(x3 + step.w * dl, 0.0);
}
