// solveBending (solvers/xpbd.ts) for the bending stencils of one colour batch [batch.start, batch.end): the hinges
// of Bergou et al. 2006 (4 particles) or the vertices of the cotangent Laplacian (the vertex and its neighbours),
// stored CSR (model.ts BendingStencils). Stencils of a batch share no particle, so each thread owns its particles
// for the dispatch. C = Σ K_k x_k is a 3-vector, linear in the positions (∇_{x_k} C = K_k·I), so its three
// components are solved at once, their system being diagonal:
//   α̃ = α/h²,  Δλ = (−C − α̃·λ) / (Σ w_k K_k² + α̃),  Δx_k = w_k·K_k·Δλ,
// λ ← λ + Δλ (λ starts from 0 unless PASS_READ_LAMBDA). No damping term: bending is undamped, as on the CPU.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let e = batch.start + flatIndex(gid, nwg);
  if (e >= batch.end) { return; }
  let alpha = stencilCompliance[e];
  if (alpha < 0.0) { return; } // no rigidity or no stencil: no constraint
  let k0 = stencilOffsets[e];
  let k1 = stencilOffsets[e + 1u];
  var sum = 0.0;
  var c = vec3f(0.0);
  for (var k = k0; k < k1; k++) {
    let i = stencilVertices[k];
    let kk = stencilWeights[k];
    sum += invMass[i] * kk * kk;
    c += kk * positions[i].xyz;
  }
  let alphaT = alpha * sub.invH2;
  let denom = sum + alphaT;
  if (!(denom > 0.0)) { return; } // every particle pinned and no compliance
  let at = 3u * e;
  var lambda = vec3f(0.0);
  if ((batch.flags & PASS_READ_LAMBDA) != 0u) {
    lambda = vec3f(stencilLambdas[at], stencilLambdas[at + 1u], stencilLambdas[at + 2u]);
  }
  let dl = (-c - alphaT * lambda) / denom;
  let next = lambda + dl;
  stencilLambdas[at] = next.x;
  stencilLambdas[at + 1u] = next.y;
  stencilLambdas[at + 2u] = next.z;
  for (var k = k0; k < k1; k++) {
    let i = stencilVertices[k];
    // Δx_k = (w_k·K_k)·Δλ
    positions[i] = vec4f(positions[i].xyz + (invMass[i] * stencilWeights[k]) * dl, 0.0);
  }
}
