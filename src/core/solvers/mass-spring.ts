/**
 * The seed's solver: a mass-spring cloth integrated with position Verlet, Hooke springs with damping along each
 * spring, then position-based stretch limiting (Provot 1995, "Deformation constraints in a mass-spring model to
 * describe rigid cloth behavior"): a structural or shear spring longer than stretchFactor × rest is projected back,
 * the correction split by inverse mass, solver.iterations passes; before that, free particles are pulled back by
 * their tethers to the nearest pin (tethers.ts). Explicit, so stiffness and damping are limited, spring by spring,
 * to what the substep can carry at their particles (params.ts limitPerSpring, which reports it). Its own phase is the
 * spring forces; the schedule (schedule.ts) strings it together with the shared ones.
 */
import type { ClothModel } from '../model.js';
import type { SimParams } from '../params.js';
import type { ClothState } from '../state.js';

/**
 * Spring forces [N] added to state.forces: F_a = −(k·(|d| − L) + c·(v_a − v_b)·d̂)·d̂, F_b = −F_a with d = x_a − x_b,
 * velocities v = (x − x_prev)/h of the last substep; k and c per spring (params.stiffness, params.springDamping:
 * what the stability limit left of the material's values).
 */
export function accumulateSpringForces(model: ClothModel, state: ClothState, params: SimParams, h: number): void {
  const x = state.positions, xp = state.previousPositions, f = state.forces;
  const springs = model.springs, rest = model.restLengths, k = params.stiffness, c = params.springDamping;
  const m = rest.length;
  for (let s = 0; s < m; s++) {
    const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
    const dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
    const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
    if (len < 1e-12) continue;
    const inv = 1 / len;
    const nx = dx * inv, ny = dy * inv, nz = dz * inv;
    const rv = (x[a] - xp[a] - x[b] + xp[b]) * nx + (x[a + 1] - xp[a + 1] - x[b + 1] + xp[b + 1]) * ny + (x[a + 2] - xp[a + 2] - x[b + 2] + xp[b + 2]) * nz;
    const mag = -(k[s] * (len - rest[s]) + (c[s] / h) * rv);
    const fx = mag * nx, fy = mag * ny, fz = mag * nz;
    f[a] += fx; f[a + 1] += fy; f[a + 2] += fz;
    f[b] -= fx; f[b + 1] -= fy; f[b + 2] -= fz;
  }
}
