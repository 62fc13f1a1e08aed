// updateVelocities (phases.ts), once per frame after the last substep: v = (x − x_prev)/h for every particle, the
// positions' residuals included. One thread per particle; bound with the last substep's record (sub.invH).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  let d = (positions[i].xyz - previous[i].xyz) + (residuals[i].xyz - previousResiduals[i].xyz);
  velocities[i] = vec4f(d * sub.invH, 0.0);
}
