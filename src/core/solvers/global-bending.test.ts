/**
 * The global bending step (solver.bendingSolve 'global', solvers/global-bending.ts), on both CPU kernels (the
 * WebAssembly kernel runs the reference's assembly with its own triangular solves, wasm/factored-wasm.ts).
 */
import { describe, expect, it } from 'vitest';
import { BEND_SPRING_PER_RIGIDITY, FABRICS } from '../fabrics.js';
import { bendingStencils } from '../model.js';
import { WasmBackend } from '../backend.js';
import { runFrame } from '../frame.js';
import { FRAME_DT } from '../params.js';
import { PhaseLog } from '../schedule.js';
import { setScenePath, validateScene } from '../scene.js';
import { builtinScene } from '../scenes.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { grab, release, setPinned } from '../state.js';
import { heldHingeShare, solveGlobalBending } from './global-bending.js';

describe.each<CpuKernel>(['ts', 'wasm'])('solver.bendingSolve "global" (xpbd), %s kernel', (kernel) => {
  /** the cantilever scene's bending length ÷ (B/(ρ_A·g))^⅓ with the hinges solved together, read at its duration */
  const cantilever = (fabric: string, faces: number): number => {
    let scene = setScenePath(builtinScene('cantilever'), 'material.fabric', fabric);
    scene = setScenePath(scene, 'solver.bending', 'hinges');
    scene = setScenePath(scene, 'solver.bendingSolve', 'global');
    scene = setScenePath(scene, 'cloth.resolution', faces);
    const sim = new Simulation(scene, { kernel });
    sim.advance(Math.round(scene.duration / FRAME_DT));
    const test = sim.report().test;
    sim.dispose();
    expect(test?.type).toBe('cantilever');
    const f = FABRICS[fabric as keyof typeof FABRICS];
    return (test as { bendingLength: number }).bendingLength / Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
  };

  // measured at 32 faces, damped and at rest when read: leather 1.00, cotton 0.99 (0.96 and 0.92 before the held
  // hinges, below, were made stiffer); one Gauss–Seidel pass a substep gives 0.19 and 0.65. The issue asks for 10 %.
  // Cotton on one kernel: the two read the same to three digits, and each run is 360 frames of the strip.
  it.each(kernel === 'wasm' ? ['leather', 'cotton'] : ['leather'])('the cantilever (ASTM D1388) at the scene\'s own settings: %s\'s bending length within 3 % of (B/(ρ_A·g))^⅓', (fabric) => {
    expect(Math.abs(cantilever(fabric, 32) - 1)).toBeLessThan(0.03);
  });

  it('the cantilever at 16 faces: leather within 3 % of its bending length (the hinges beside the clamp bend on their free side only; counted whole, 0.92)', () => {
    // measured 0.99; 1.00 at 32 faces
    expect(Math.abs(cantilever('leather', 16) - 1)).toBeLessThan(0.03);
  });

  it('the flaps of a cloth over a box come to rest: kinetic energy below 10⁻⁷ J at 12 s (16 faces; measured 2.3–2.5·10⁻⁸; without the stencils\' damping 0.7–1.3·10⁻⁶)', () => {
    // docs/physics.md "Bending solved together", "Why it is not the default": the 0.8 m cotton cloth dropped on a
    // 0.5 m box, its flaps hanging 15 cm over each side
    const sim = new Simulation(validateScene({
      cloth: { resolution: 16, width: 0.8, height: 0.8, position: [0, 0.55, 0] },
      colliders: [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.25, 0.2, 0.25], rotation: [0, 0, 0] }, { type: 'floor', height: 0 }],
      solver: { bending: 'hinges', bendingSolve: 'global' },
    }), { kernel });
    sim.advance(720);
    expect(sim.report().energy.kinetic).toBeLessThan(1e-7);
    sim.dispose();
  });

  it('a hinge with one free corner rings down with the damping ratio of its damping time, ζ = τ·ω/2 (stiffness-proportional damping)', () => {
    // one 10 cm quad of cotton, weightless, its hinge's edge and one wing pinned: the free corner's motion along the
    // normal is one mass on the hinge's linear stencil, m·z'' = −k·z − τ·k·z' (the springs act at second order only)
    const ring = (damping: number): { omega: number; zeta: number } => {
      const sim = new Simulation(validateScene({
        cloth: { resolution: 1, width: 0.1, height: 0.1, position: [0, 0, 0] }, colliders: [], gravity: [0, 0, 0],
        material: { fabric: 'cotton', damping }, solver: { bending: 'hinges', bendingSolve: 'global' },
      }), { kernel });
      const { offsets, vertices } = bendingStencils(sim.model, 'hinges')!;
      expect(offsets.length).toBe(2);
      const [a, b, c, free] = vertices;
      for (const p of [a, b, c]) setPinned(sim.state, p, true);
      const x = sim.state.positions, at = (i: number, k: number) => x[3 * i + k];
      const u = [0, 1, 2].map((k) => at(b, k) - at(a, k)), v = [0, 1, 2].map((k) => at(c, k) - at(a, k));
      const nrm = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
      const len = Math.hypot(nrm[0], nrm[1], nrm[2]);
      const rest = [0, 1, 2].map((k) => at(free, k));
      for (let k = 0; k < 3; k++) x[3 * free + k] = Math.fround(rest[k] + (5e-4 * nrm[k]) / len);
      const z: number[] = [];
      for (let f = 0; f < 480; f++) {
        sim.advance(1);
        z.push([0, 1, 2].reduce((sum, k) => sum + ((at(free, k) + sim.state.residuals[3 * free + k] - rest[k]) * nrm[k]) / len, 0));
      }
      // the maxima, each refined by the parabola through it and its neighbours: [time in frames, height]
      const peaks: [number, number][] = [];
      for (let f = 1; f + 1 < z.length; f++) {
        if (!(z[f] > z[f - 1] && z[f] >= z[f + 1])) continue;
        const d = (z[f - 1] - z[f + 1]) / (2 * (z[f - 1] - 2 * z[f] + z[f + 1]));
        peaks.push([f + d, z[f] - 0.25 * (z[f - 1] - z[f + 1]) * d]);
      }
      expect(peaks.length).toBeGreaterThanOrEqual(3);
      const period = ((peaks[2][0] - peaks[0][0]) / 2) * FRAME_DT;
      const decrement = Math.log(peaks[0][1] / peaks[2][1]) / 2;
      const zeta = decrement / Math.hypot(2 * Math.PI, decrement);
      return { omega: (2 * Math.PI) / period / Math.sqrt(1 - zeta * zeta), zeta };
    };
    const still = ring(0);
    // undamped it rings on but for backward Euler's own damping, ζ = ω·h/2 (0.0019 here; measured within 1 %)
    const h = FRAME_DT / 20;
    expect(still.omega).toBeGreaterThan(2);
    expect(Math.abs(still.zeta - (still.omega * h) / 2)).toBeLessThan(0.05 * (still.omega * h) / 2);
    // the damping for ζ = 0.1: τ = 0.2/ω, β = τ·k_b; it adds τ·ω/2 to that (measured within 0.5 %)
    const tau = 0.2 / still.omega;
    const damped = ring(tau * BEND_SPRING_PER_RIGIDITY * FABRICS.cotton.bendingRigidity);
    expect(Math.abs(damped.zeta - still.zeta - (tau * damped.omega) / 2)).toBeLessThan(0.03 * (tau * damped.omega) / 2);
  });

  it.each(['hinges', 'laplacian'] as const)('one step is the backward-Euler step of the %s\' energy and damping: M(x − x*)/h² + Σ K·(C(x) + τ/h·(C(x) − C(x_prev)))/α = 0 at every free particle, with pinned and grabbed ones held, and again after a pin is set (refactored)', (bending) => {
    const sim = new Simulation(validateScene({
      // a 5 cm sheet in 2 substeps, so that its stencils are stiff against its particles' inertia; at the origin, where
      // float32 positions round to 2e-9 m (at 1 m, their 6e-8 m is 2e-4 of the Laplacian's forces here)
      cloth: { resolution: 8, width: 0.05, height: 0.05, position: [0, 0, 0] }, colliders: [], pins: ['top-left', 'top-right'], gravity: [0, 0, 0],
      material: { fabric: 'leather' }, solver: { bending, bendingSolve: 'global', substeps: 2 },
    }), { kernel });
    const { model, state, params } = sim;
    const n = model.particleCount, x = state.positions, r = state.residuals;
    const h = FRAME_DT / params.substeps;
    const stencils = bendingStencils(model, bending)!;
    // leather's damping time, β/k_b = 0.5/(94 372 × 10⁻³) s = 5.3 ms, is 0.64 of a substep here: its pull is of the
    // order of the stiffness
    const tau = 0.5 / (BEND_SPRING_PER_RIGIDITY * 1e-3);
    expect(params.stencilDamping[0]).toBeCloseTo(tau, 9);
    /** the bending forces at positions p, and the damping's for the motion from the substep's start (x_prev) to p */
    const force = (p: Float64Array) => {
      const f = new Float64Array(3 * n), xp = state.previousPositions, rp = state.previousResiduals;
      for (let e = 0; e + 1 < stencils.offsets.length; e++) {
        const alpha = params.stencilCompliance[e], C = [0, 0, 0], Cp = [0, 0, 0];
        for (let k = stencils.offsets[e]; k < stencils.offsets[e + 1]; k++) {
          for (let c = 0; c < 3; c++) {
            const j = 3 * stencils.vertices[k] + c;
            C[c] += stencils.weights[k] * p[j];
            Cp[c] += stencils.weights[k] * (xp[j] + rp[j]);
          }
        }
        for (let k = stencils.offsets[e]; k < stencils.offsets[e + 1]; k++) {
          for (let c = 0; c < 3; c++) f[3 * stencils.vertices[k] + c] -= (stencils.weights[k] * (C[c] + (tau / h) * (C[c] - Cp[c]))) / alpha;
        }
      }
      return f;
    };
    /** bends the sheet, solves one step and returns max |M(x − x*)/h² − f(x)| over the free particles ÷ the forces at x* */
    const step = (g: number) => {
      // a smooth fold and a ripple, so that every stencil pulls
      for (let i = 0; i < n; i++) x[3 * i + 2] = Math.fround(0.002 * Math.sin(60 * x[3 * i]) + 0.0005 * Math.cos(140 * x[3 * i + 1]));
      // and another shape at the substep's start, which the damping pulls towards
      for (let i = 0; i < n; i++) state.previousPositions[3 * i + 2] = Math.fround(0.0015 * Math.cos(90 * x[3 * i]));
      if (g >= 0) {
        x[3 * g + 2] += 0.002;
        grab(state, g, [x[3 * g], x[3 * g + 1], x[3 * g + 2]]);
      }
      const before = Float64Array.from(x, (v, j) => v + r[j]);
      const f0 = force(before);
      solveGlobalBending(model, state, params, h);
      const after = Float64Array.from(x, (v, j) => v + r[j]);
      const f1 = force(after);
      let residual = 0, scale = 0, moved = 0;
      for (let i = 0; i < n; i++) {
        if (state.pinned[i] || i === g) {
          for (let c = 0; c < 3; c++) expect(after[3 * i + c]).toBe(before[3 * i + c]);
          continue;
        }
        for (let c = 0; c < 3; c++) {
          const j = 3 * i + c;
          residual = Math.max(residual, Math.abs((params.particleMass[i] * (after[j] - before[j])) / (h * h) - f1[j]));
          scale = Math.max(scale, Math.abs(f0[j]));
          moved = Math.max(moved, Math.abs(after[j] - before[j]));
        }
      }
      expect(moved).toBeGreaterThan(2e-4);
      return residual / scale;
    };
    expect([...state.pinned].filter((p) => p).length).toBe(2);
    // the grab: without the hold along z = A⁻¹·e_g the residual at its neighbours is of the order of the forces
    expect(step(40)).toBeLessThan(1e-4);
    release(state);
    // a pin set after the factor: a stale factor leaves the new pin's row free, and its neighbours' residual large
    setPinned(state, 30, true);
    expect(step(-1)).toBeLessThan(1e-4);
  });

  it('a frame runs globalBending, not the bending sweep, after the springs and before the tethers (on the WebAssembly kernel, with its solves)', () => {
    const sim = new Simulation(validateScene({ cloth: { resolution: 8 }, solver: { bending: 'hinges', bendingSolve: 'global' } }), { kernel });
    const log = new PhaseLog();
    if (kernel === 'wasm') (sim.backend as WasmBackend).kernel.frame(sim.model, sim.state, sim.params, FRAME_DT, log);
    else runFrame(sim.model, sim.state, sim.params, FRAME_DT, undefined, log);
    const names = log.names();
    expect(names.some((name) => name.startsWith('bending'))).toBe(false);
    expect(names.filter((name) => /^(distance|globalBending|tethers)\b/.test(name)).slice(0, 3))
      .toEqual(kernel === 'wasm' ? ['distance', 'globalBending', 'tethers'] : ['distance (reference)', 'globalBending (reference)', 'tethers (reference)']);
  });
});

describe('held hinges', () => {
  it('the energy report counts a hinge beside a held triangle as the global step solves it: on its free side, twice the energy of the whole hinge on a square', () => {
    // one 10 cm quad, its hinge's edge and one wing pinned (that triangle held), the free corner lifted 1 mm
    const bent = (bendingSolve: 'global' | 'gauss-seidel'): number => {
      const sim = new Simulation(validateScene({
        cloth: { resolution: 1, width: 0.1, height: 0.1, position: [0, 0, 0] }, colliders: [], gravity: [0, 0, 0],
        solver: { bending: 'hinges', bendingSolve },
      }));
      const { offsets, vertices } = bendingStencils(sim.model, 'hinges')!;
      expect(offsets.length).toBe(2);
      for (const p of [vertices[0], vertices[1], vertices[2]]) setPinned(sim.state, p, true);
      sim.state.positions[3 * vertices[3] + 1] += 1e-3;
      expect(heldHingeShare(sim.model.restPositions, vertices, 0, sim.state.pinned)).toBeCloseTo(0.5, 6);
      const e = sim.report().energy.bending;
      sim.dispose();
      return e;
    };
    const whole = bent('gauss-seidel');
    expect(whole).toBeGreaterThan(0);
    expect(bent('global') / whole).toBeCloseTo(2, 5);
  });
});
