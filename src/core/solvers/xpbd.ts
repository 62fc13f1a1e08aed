/**
 * XPBD: extended position-based dynamics (Macklin, Müller & Chentanez 2016, "XPBD: Position-Based Simulation of
 * Compliant Constrained Dynamics") with small steps (Macklin et al. 2019, "Small Steps in Physics Simulation"):
 * n substeps of one constraint pass each, the Lagrange multiplier starting from zero every substep.
 *
 * Every spring is a distance constraint C = |x_a − x_b| − L with compliance α = 1/k [m/N] taken from the same
 * stiffness numbers as the mass-spring solver, so one fabric description drives both and stiffness does not
 * depend on the substep count. Damping uses the paper's constraint damping with β = material.damping [N·s/m]:
 *   α̃ = α/h²,  γ = α̃·β̃/h = α·β/h,
 *   Δλ = (−C − α̃·λ − γ·∇C·(x − x_prev)) / ((1 + γ)·(w_a + w_b) + α̃),   Δx_a = w_a·Δλ·∇C,  Δx_b = −w_b·Δλ·∇C.
 * Structural and shear springs are also capped at stretchFactor × rest inside the same projection (a hard limit
 * as in Provot 1995); then free particles are pulled back by their tethers to the nearest pin (tethers.ts) and one
 * stretch-limiting pass catches what later batches stretched again. One Gauss–Seidel pass per substep propagates
 * an impact only a few springs; these keep a fine cloth from overstretching meanwhile (docs/physics.md).
 * Its own phase is the distance constraints; the schedule (schedule.ts) strings it together with the shared ones.
 */
import { BEND, bendingStencils, type ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';

/**
 * One Gauss–Seidel pass over every distance constraint, batch by batch (colour order: springs of a batch share no
 * particle, which is what a parallel backend relies on; here it only fixes the order). With `accumulate`, λ is
 * read from state.lambdas (several iterations per substep); otherwise it starts from zero. The whole Δλ, damping
 * included, is added to λ (the paper's Eq. 26; not the hard stretch cap, which is no constraint force): with the
 * damping left out of λ, each further pass of a substep applied it again against a λ that did not hold it, and a
 * clamped cloth with the hinges blew up at 40 substeps × 16 passes (docs/physics.md, "Three specimens").
 */
export function solveDistanceConstraints(
  model: ClothModel, state: ClothState, params: SimParams, h: number, accumulate: boolean,
): void {
  const x = state.positions, xp = state.previousPositions, w = state.invMass, lambdas = state.lambdas;
  const springs = model.springs, rest = model.restLengths, compliance = params.compliance;
  const invH2 = 1 / (h * h);
  // each spring's damping and stretch limit are its cloth's (params.perCloth; one value for one cloth)
  const owner = params.owner, damping = params.springDamping, stretch = params.perCloth.stretchFactor;
  for (const batch of model.batches) {
    const bend = batch.kind === BEND;
    for (let s = batch.start; s < batch.end; s++) {
      const alpha = compliance[s];
      if (alpha === Infinity) continue;
      const pa = springs[2 * s], pb = springs[2 * s + 1];
      const betaOverH = damping[s] / h, cap = bend ? Infinity : stretch[owner[pa]];
      const wa = w[pa], wb = w[pb];
      const wsum = wa + wb;
      if (wsum === 0) continue;
      const a = 3 * pa, b = 3 * pb;
      const dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
      const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
      if (len < 1e-12) continue;
      const alphaT = alpha * invH2;
      const gamma = alpha * betaOverH;
      // one division: q = 1/(len·D) gives both 1/D = len·q and 1/len = D·q
      const D = (1 + gamma) * wsum + alphaT;
      const q = 1 / (len * D);
      const lambda = accumulate ? lambdas[s] : 0;
      let dl = (rest[s] - len - alphaT * lambda) * len * q;
      if (gamma > 0) {
        dl -= gamma * q * (
          (x[a] - xp[a] - x[b] + xp[b]) * dx +
          (x[a + 1] - xp[a + 1] - x[b + 1] + xp[b + 1]) * dy +
          (x[a + 2] - xp[a + 2] - x[b + 2] + xp[b + 2]) * dz);
      }
      lambdas[s] = lambda + dl;
      // hard stretch limit: the new length len + wsum·dl may not exceed cap × rest
      const over = len + wsum * dl - cap * rest[s];
      if (over > 0) dl -= over / wsum;
      const invLen = D * q;
      const nx = dx * invLen, ny = dy * invLen, nz = dz * invLen;
      const sa = wa * dl, sb = wb * dl;
      x[a] += sa * nx; x[a + 1] += sa * ny; x[a + 2] += sa * nz;
      x[b] -= sb * nx; x[b + 1] -= sb * ny; x[b + 2] -= sb * nz;
    }
  }
}

/**
 * One Gauss–Seidel pass over the bending stencils of the params' model (solver.bending 'hinges' or 'laplacian';
 * model.ts BendingStencils), batch by batch. Each stencil's C = Σ K_k x_k is linear in the positions, a 3-vector
 * with ∇_{x_k} C = K_k·I, and its energy ½·|C|²/α with compliance α = A/B (params.stencilCompliance) sums to the
 * plate's ½·B·κ² per unit area for a sheet bent to curvature κ without stretching: the isometric bending model of
 * Bergou et al. 2006 at the hinges (4 particles), the cotangent Laplacian (Wardetzky et al. 2007) at the interior
 * vertices (the vertex and its neighbours). So, with α̃ = α/h² (Macklin et al. 2016, the constraint's three
 * components at once, their system being diagonal):
 *   Δλ = (−C − α̃·λ) / (Σ w_k K_k² + α̃),   Δx_k = w_k·K_k·Δλ.
 * No damping term: bending is undamped (the stretch constraints' damping and the air carry the losses). With
 * `accumulate`, λ is read from state.bendingLambdas (several passes per substep); otherwise it starts from zero.
 */
export function solveBending(model: ClothModel, state: ClothState, params: SimParams, h: number, accumulate: boolean): void {
  const stencils = bendingStencils(model, params.bending);
  if (!stencils) return;
  const x = state.positions, w = state.invMass, lambdas = state.bendingLambdas;
  const { offsets, vertices, weights: K } = stencils, compliance = params.stencilCompliance;
  const invH2 = 1 / (h * h);
  for (const batch of stencils.batches) {
    for (let e = batch.start; e < batch.end; e++) {
      const alpha = compliance[e];
      if (alpha === Infinity) continue;
      const from = offsets[e], to = offsets[e + 1];
      let sum = 0, cx = 0, cy = 0, cz = 0;
      for (let k = from; k < to; k++) {
        const i = vertices[k], kk = K[k], at = 3 * i;
        sum += w[i] * kk * kk;
        cx += kk * x[at]; cy += kk * x[at + 1]; cz += kk * x[at + 2];
      }
      const alphaT = alpha * invH2;
      const denom = sum + alphaT;
      if (!(denom > 0)) continue;
      const inv = 1 / denom;
      const l = 3 * e;
      const lx = accumulate ? lambdas[l] : 0, ly = accumulate ? lambdas[l + 1] : 0, lz = accumulate ? lambdas[l + 2] : 0;
      const dx = (-cx - alphaT * lx) * inv, dy = (-cy - alphaT * ly) * inv, dz = (-cz - alphaT * lz) * inv;
      lambdas[l] = lx + dx; lambdas[l + 1] = ly + dy; lambdas[l + 2] = lz + dz;
      for (let k = from; k < to; k++) {
        const i = vertices[k], s = w[i] * K[k], at = 3 * i;
        x[at] += s * dx; x[at + 1] += s * dy; x[at + 2] += s * dz;
      }
    }
  }
}
