// The global stretch step, each pass 4 of 4, per particle: x ← y + Δx for the free particles (y: the pass's start,
// stretchStart; the residuals kept, as the CPU keeps them). The grabbed particle g stays where the grab put it:
// with z = A⁻¹·e_g (grabColumn: the stretch factor's), Δx − z·Δx_g/z_g is the exact solution with Δx_g = 0.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u, @builtin(num_workgroups) nwg: vec3u) {
  let i = flatIndex(gid, nwg);
  if (i >= globals.particleCount || pinned[i] != 0u) { return; }
  let rowOf = factorIndex[FACTOR_ROW_OF];
  let row = factorIndex[rowOf + i];
  var d = globalX[row].xyz;
  let g = globals.grabbed;
  if (g >= 0 && pinned[u32(g)] == 0u) {
    if (u32(g) == i) { return; }
    let rg = factorIndex[rowOf + u32(g)];
    d -= (grabColumn[row] / grabColumn[rg]) * globalX[rg].xyz;
  }
  positions[i] = vec4f(globalY[i].xyz + d, 0.0);
}
