// What both self-contact pair passes share (selfPoints, selfEdges): a pair's correction of a particle summed into its
// fixed-point total for the pass (selfApply moves it by the mean), and the friction rule.

/**
 * Adds share[j]·k [m], a pair's correction of particle ids[j], to that particle's sum of the pass (each component
 * clamped to ±SELF_CLAMP m, then SELF_FIXED per metre) and counts the pair, for the pair's four particles (a share
 * of 0: a particle the pair does not move, not counted). One loop, one call site per kernel: the atomics are
 * emitted once (SwiftShader's compiled kernel slows with every copy).
 */
fn addCorrections(ids: array<u32, 4>, share: vec4f, k: vec3f) {
  for (var j = 0u; j < 4u; j++) {
    if (share[j] == 0.0) { continue; }
    let i = ids[j];
    let q = vec3i(round(clamp(share[j] * k, vec3f(-SELF_CLAMP), vec3f(SELF_CLAMP)) * SELF_FIXED));
    atomicAdd(&selfDelta[4u * i], q.x);
    atomicAdd(&selfDelta[4u * i + 1u], q.y);
    atomicAdd(&selfDelta[4u * i + 2u], q.z);
    atomicAdd(&selfDelta[4u * i + 3u], 1);
  }
}

/**
 * Position-based Coulomb friction between two layers (self-contact.ts): the share of their relative tangential
 * motion over the substep, `tangential` [m], to remove for a pair pushed apart by `depth` [m]: all of it within the
 * static cone, else μ_k·depth of it. The cloth's own coefficients (the GPU takes only cloths that agree in them, so
 * the CPU's geometric mean between two cloths is the same number).
 */
fn selfFriction(tangential: f32, depth: f32) -> f32 {
  if (tangential < 1e-12) { return 0.0; }
  if (tangential < globals.staticFriction * depth) { return 1.0; }
  return min(globals.friction * depth / tangential, 1.0);
}
