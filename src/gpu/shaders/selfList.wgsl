// The self-contact candidates' list (selfFindPoints, selfFindEdges): pairs appended with an atomic count.

/**
 * Appends pair (i, j) to the candidates' list (selfPairs: [0] the pairs found, then the pairs), or only counts it
 * past the list's capacity (globals.selfPairCapacity).
 */
fn addPair(i: u32, j: u32) {
  let k = atomicAdd(&selfPairs[0], 1u);
  if (k >= globals.selfPairCapacity) { return; }
  atomicStore(&selfPairs[1u + 2u * k], i);
  atomicStore(&selfPairs[2u + 2u * k], j);
}
