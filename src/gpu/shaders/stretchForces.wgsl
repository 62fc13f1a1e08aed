// The global stretch step, each pass 1 of 4, per spring s of the model (stretchCoefficients: k, L, β/h, w = k + β/h):
// the local step, the spring's direction at its rest length, as its part of the right-hand side of
//   A·Δx = Σ_s S_sᵀ·f_s,   f_s = k·(L·d/|d| − Δy) + (β/h)·((d − Δy) − (u·d/|d|²)·d),
// the step of the CPU (A·x = M/h²·y + Σ S_sᵀ·(k·d_s + (β/h)·q_s), pinned columns eliminated) for the correction
// Δx = x − y from the predicted positions y: d = x_a − x_b now, Δy = y_a − y_b, u = d − (x_prev,a − x_prev,b) its
// motion since the substep's start, of which the damping term removes the part along the spring. Relative positions
// only, and grouped so that float32 keeps what is small: d − Δy is this substep's motion.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let s = flatIndex(gid, nwg);
  if (s >= arrayLength(&springForce)) { return; }
  let c = stretchCoefficients[s];
  if (c.w == 0.0) {
    springForce[s] = vec4f(0.0);
    return;
  }
  let ab = springs[s];
  let d = positions[ab.x].xyz - positions[ab.y].xyz;
  let dy = globalY[ab.x].xyz - globalY[ab.y].xyz;
  let len = length(d);
  var toRest = -dy;
  var along = 0.0;
  if (len > 1e-12) {
    toRest = (c.y / len) * d - dy;
    let u = d - (previous[ab.x].xyz - previous[ab.y].xyz);
    along = dot(u, d) / (len * len);
  }
  springForce[s] = vec4f(c.x * toRest + c.z * ((d - dy) - along * d), 0.0);
}
