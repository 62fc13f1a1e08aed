// Self-contact: the indirect dispatch of the pair pass that follows (selfPoints or selfEdges) from the pairs the
// candidates kernel listed: selfArgs = its workgroups (x, spilling into y past MAX_WORKGROUPS_X, as the encoder's
// dispatches do; z = 1) and the pairs to resolve (at most the list's capacity); the most found by any pass since the
// last readback in selfArgs[4] (past the capacity: pairs left unresolved, which the readback reports); the list's
// count zeroed for the next one. One thread.

@compute @workgroup_size(WG)
fn main(@builtin(global_invocation_id) gid: vec3u) {
  if (gid.x != 0u) { return; }
  let found = atomicLoad(&selfPairs[0]);
  let n = min(found, globals.selfPairCapacity);
  atomicStore(&selfPairs[0], 0u);
  selfArgs[4] = max(selfArgs[4], found);
  let groups = (n + WG - 1u) / WG;
  let x = min(groups, MAX_WORKGROUPS_X);
  selfArgs[0] = x;
  selfArgs[1] = select(1u, (groups + x - 1u) / x, x > 0u);
  selfArgs[2] = 1u;
  selfArgs[3] = n;
}
