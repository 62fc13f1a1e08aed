// limitStretch (phases.ts), run by XPBD after the tethers: a structural or shear spring of the batch
// [batch.start, batch.end) longer than stretchFactor × rest is projected back to that length, the correction
// shared by inverse mass. One dispatch per colour batch, like the constraint solve (bend batches are skipped).

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let s = batch.start + flatIndex(gid, nwg);
  if (s >= batch.end) { return; }
  let ab = springs[s];
  let wa = invMass[ab.x];
  let wb = invMass[ab.y];
  let wsum = wa + wb;
  if (wsum == 0.0) { return; }
  let xa = positions[ab.x].xyz;
  let xb = positions[ab.y].xyz;
  let d = xa - xb;
  let len2 = dot(d, d);
  let m = globals.stretchFactor * springData[s].x;
  if (len2 <= m * m) { return; }
  let len = sqrt(len2);
  let scale = (len - m) / (len * wsum);
  positions[ab.x] = vec4f(xa - (wa * scale) * d, 0.0);
  positions[ab.y] = vec4f(xb + (wb * scale) * d, 0.0);
}
