// updateVelocities (phases.ts), once per frame after the last substep: v = (x − x_prev)/h for every particle.
// One thread per particle; bound with the last substep's record (sub.invH).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  velocities[i] = vec4f((positions[i].xyz - previous[i].xyz) * sub.invH, 0.0);
}
