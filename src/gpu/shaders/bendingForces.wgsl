// The global bending step (core solvers/global-bending.ts solveGlobalBending), 1 of 4, per stencil e: its part of
// the right-hand side of (M/h² + Σ (1 + τ/h)·K·Kᵀ/α)·Δx = −Σ K·d_e, the step written for the correction Δx = x − x*
// from the positions x* the stretch solve left, with
//   d_e = (1 + τ/h)/α·C(x*) − (τ/h)/α·C(x_prev),   C(x) = Σ K_k x_k,
// x_prev the positions at the substep's start (the damping's pull). C is summed relative to the stencil's first
// particle (K sums to zero: a stencil does not see a translation), so that float32 keeps the curvature of a cloth far
// from the origin; what the residuals add lies below float32's resolution of a position.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let e = flatIndex(gid, nwg);
  if (e >= arrayLength(&stencilForce)) { return; }
  let k0 = stencilOffsets[e];
  let k1 = stencilOffsets[e + 1u];
  let coefficients = bendingCoefficients[e];
  var c = vec3f(0.0);
  var cp = vec3f(0.0);
  if (k1 > k0) {
    let first = stencilVertices[k0];
    let o = positions[first].xyz;
    let op = previous[first].xyz;
    for (var k = k0; k < k1; k++) {
      let i = stencilVertices[k];
      let w = stencilWeights[k];
      c += w * (positions[i].xyz - o);
      cp += w * (previous[i].xyz - op);
    }
  }
  stencilForce[e] = vec4f(coefficients.x * c - coefficients.y * cp, 0.0);
}
