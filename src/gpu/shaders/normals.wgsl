// Vertex normals for rendering: the area-weighted sum of the incident triangles' normals (triangles are
// counter-clockwise seen from the +normal side), normalised. A gather over the CSR adjacency, no atomics.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount) { return; }
  var sum = vec3f(0.0);
  let hi = adjacency[i + 1u];
  for (var k = adjacency[i]; k < hi; k++) {
    let t = adjacency[k];
    let xa = positions[triangles[3u * t]].xyz;
    sum += cross(positions[triangles[3u * t + 1u]].xyz - xa, positions[triangles[3u * t + 2u]].xyz - xa);
  }
  let l = length(sum);
  var n = vec3f(0.0, 1.0, 0.0);
  if (l > 1e-20) { n = sum / l; }
  normals[i] = vec4f(n, 0.0);
}
