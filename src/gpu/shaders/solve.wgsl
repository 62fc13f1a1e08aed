// solveDistanceConstraints (solvers/xpbd.ts) for the springs of one colour batch [batch.start, batch.end):
// springs of a batch share no particle, so each thread owns its two particles for the dispatch.
//   α̃ = α/h², γ = α·β/h, D = 1/((1 + γ)·(w_a + w_b) + α̃),
//   Δλ = (−C − α̃·λ − γ·∇C·(x − x_prev))·D,
// λ ← λ + Δλ (damping included, as in the paper; λ starts from 0 unless PASS_READ_LAMBDA),
// then the hard stretch cap (structural and shear batches): the new length may not exceed cap × rest.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let s = batch.start + flatIndex(gid, nwg);
  if (s >= batch.end) { return; }
  let data = springData[s];
  let rest = data.x;
  let alpha = data.y;
  if (alpha < 0.0) { return; } // no stiffness: no constraint
  let ab = springs[s];
  let wa = invMass[ab.x];
  let wb = invMass[ab.y];
  let wsum = wa + wb;
  if (wsum == 0.0) { return; }
  let xa = positions[ab.x].xyz;
  let xb = positions[ab.y].xyz;
  let d = xa - xb;
  let len = length(d);
  if (len < 1e-12) { return; }
  let n = d / len;
  let alphaT = alpha * sub.invH2;
  let gamma = alpha * sub.betaOverH;
  var lambda = 0.0;
  if ((batch.flags & PASS_READ_LAMBDA) != 0u) { lambda = lambdas[s]; }
  let denom = 1.0 / ((1.0 + gamma) * wsum + alphaT);
  var dl = (rest - len - alphaT * lambda) * denom;
  if (gamma > 0.0) {
    dl -= gamma * denom * dot((xa - previous[ab.x].xyz) - (xb - previous[ab.y].xyz), n);
  }
  lambdas[s] = lambda + dl;
  if ((batch.flags & PASS_CAP) != 0u) {
    let over = len + wsum * dl - batch.cap * rest;
    if (over > 0.0) { dl -= over / wsum; }
  }
  positions[ab.x] = vec4f(xa + (wa * dl) * n, 0.0);
  positions[ab.y] = vec4f(xb - (wb * dl) * n, 0.0);
}
