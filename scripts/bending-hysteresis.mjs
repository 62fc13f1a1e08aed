#!/usr/bin/env node
// A study, not a feature (issue 10; docs/materials.md §3.6, "Bending hysteresis"): does the bending hysteresis that
// KES-FB2 measures (2HB, the width of the moment–curvature loop: a bend must overcome HB = 2HB/2 of moment per unit
// width before it moves, the fabric's internal friction) account for what the `cusick` scene misses on source 16's
// fabrics, the four whose B, 2HB, weight and drape coefficient were measured together? Drape's bending is elastic
// only; this script adds the friction to the TypeScript reference's frame from outside, without changing the product.
//
// The model: internal friction in bending (Miguel et al. 2013, "Modeling and Estimation of Internal Friction in
// Cloth", ACM TOG 32(6): a Dahl model in parallel with the elastic bending) in its stick–slip limit, a stiff spring in
// series with a slider, per stencil of the cotangent Laplacian (Wardetzky et al. 2007; model.ts): s_v = ±|C_v| (the
// stencil's 3-vector C_v ≈ A_v·(κ1 + κ2)·n, signed by its part along the vertex normal n_v, the area-weighted mean
// of its triangles'; `--direction normal`: C_v·n_v) carries a slider position s_p and the force f = k_f·(s_v − s_p), |f| ≤ HB. The pair (s_v, f) does work f·ds_v =
// f·A_v·dκ, so a cap of HB dissipates HB per unit area and unit curvature at any mesh and in any direction (the
// first line printed: Σ|C_v| of the disc bent into cylinders at four angles to the lattice). k_f = ratio·B/A_v (the
// elastic stencil's stiffness times `--ratio`, 10: the slider's spring is ten times the bending's). It runs after each
// substep's global bending step, solved one of two ways (`--solve`):
// - cg (the default): the backward-Euler step of the springs and their sliders together, a convex problem (the
//   slider's energy Huber's function), by semi-smooth Newton with conjugate gradients, so that no spring pulls harder
//   than HB within the step either (BendingFriction.solve; `--newton N`, the most Newton iterations a substep, 30).
//   Until 2026-12-08 it solved the springs stuck and moved the sliders after, which let a spring pull up to 50 times
//   HB within the step where the pedestal's contact moves the skirt (its rim, at 40 × 16);
// - passes: `--passes` XPBD passes (Macklin et al. 2016), λ accumulated and held to ±HB·h², each slider following
//   after its stencil's update (the first try: stiff, overlapping springs in Gauss–Seidel passes, whose
//   convergence was not shown; docs/materials.md §3.6, "Bending hysteresis").
// A disc starts flat: s_p = 0.
//
//   npx tsc -p tsconfig.build.json && node scripts/bending-hysteresis.mjs [--fabrics A,B,C,F] [--seeds 1]
//       [--resolution 48] [--solve cg|passes] [--passes 24] [--ratio 10] [--hysteresis 1 (a factor on each fabric's
//       2HB: 0 for none)]
//       [--substeps S --iterations I] [--damping D (material.damping [N·s/m], the scene's cotton's 0.1 unless given)]
//       [--lower T (the skirt laid on a support that is then lowered: a 40 cm square plate 1 cm thick whose top is the
//       pedestal's, moved 30 cm down at constant speed over T [s], the scene then run T + 6 s; without it the skirt
//       falls free from flat, as in the scene)]
//       [--direction laplacian|normal (what each slider acts along in the cg step: C_v's own direction signed by its
//       normal part, s_v = ±|C_v|, which a turn of the normal alone leaves as it is, the default since 2026-12-08;
//       or the vertex normal, s_v = C_v·n_v, the first choice, under which a skirt solved closely crept down
//       for as long as it ran: docs/materials.md §3.6)]
//       [--history S (each specimen's drape coefficient and folds every S seconds as it falls and settles)]
//       [--cantilever R (instead: the `cantilever` scene at cloth.resolution R with each fabric's ρ_A and B, its
//       bending length with and without the friction)]
// prints each specimen's drape coefficient and folds beside the measured ones. The reference runs every phase in
// TypeScript (the WebAssembly kernel cannot be handed a phase from outside); with `--hysteresis 0` it reads what
// scripts/cusick-measured.mjs reads on the kernel (C, seed 1: 0.475 both).
import { builtinScene, PHASE, runFrame, setScenePath, TsBackend, Simulation, bendingStencils } from '../dist/core/index.js';
import { REFERENCE } from '../dist/core/reference.js';
import { FABRICS, mean, specimenScene } from './cusick-common.mjs';
import { arg } from './solver-study-common.mjs';

const chosen = arg('fabrics', 'A,B,C,F').split(',');
const seeds = arg('seeds', '1').split(',').map(Number);
const resolution = Number(arg('resolution', '48'));
const newtonMost = Number(arg('newton', '30'));
const along = arg('direction', 'laplacian');
if (along !== 'normal' && along !== 'laplacian') throw new Error(`--direction: normal or laplacian, got '${along}'`);
const passes = Number(arg('passes', '24')), ratio = Number(arg('ratio', '10')), factor = Number(arg('hysteresis', '1'));
const substeps = arg('substeps', null), iterations = arg('iterations', null), damping = arg('damping', null);
const lower = arg('lower', null);
const history = arg('history', null);
const method = arg('solve', 'cg');
const cantilever = arg('cantilever', null);
if (method !== 'cg' && method !== 'passes') throw new Error(`--solve: cg or passes, got '${method}'`);
for (const id of chosen) {
  const f = FABRICS.find((x) => x[0] === id);
  if (!f || f[8] === null) throw new Error(`--fabrics: '${id}' has no measured 2HB (${FABRICS.filter((x) => x[8] !== null).map((x) => x[0]).join(', ')} have)`);
}
if (!(Number.isInteger(passes) && passes >= 1 && ratio > 0 && factor >= 0 && (history === null || Number(history) > 0) && Number.isInteger(newtonMost) && newtonMost >= 1)) throw new Error('--passes, --newton: integers ≥ 1; --ratio > 0; --hysteresis ≥ 0; --history > 0');

/** The friction's memory for one model: sliders, λ of the substep, vertex normals (made once, before the frames). */
class BendingFriction {
  constructor(model, HB, B) {
    this.model = model;
    this.stencils = bendingStencils(model, 'laplacian');
    this.HB = HB;
    this.B = B;
    const m = this.stencils.areas.length;
    this.slider = new Float64Array(m);
    this.lambda = new Float64Array(m);
    this.normals = new Float64Array(3 * model.particleCount);
    // the implicit step's vectors (3 per particle) and per-stencil values
    const N3 = 3 * model.particleCount;
    this.cg = {
      d: new Float64Array(N3), r: new Float64Array(N3), z: new Float64Array(N3), p: new Float64Array(N3), q: new Float64Array(N3), diag: new Float64Array(N3),
      grad: new Float64Array(N3), step: new Float64Array(N3), trial: new Float64Array(N3),
      s0: new Float64Array(m), kf: new Float64Array(m), ka: new Float64Array(m), u: new Float64Array(m), nv: new Float64Array(3 * m), t: new Float64Array(m),
    };
    // the most CG iterations of one Newton iteration, Newton iterations, and CG iterations of one step, over the run
    this.iterations = 0;
    this.newton = 0;
    this.cgPerStep = 0;
  }

  /** vertex normals: the sum of each vertex's triangles' (area-weighted) normals */
  updateNormals(x) {
    const n = this.normals, tri = this.model.triangles;
    n.fill(0);
    for (let t = 0; t < tri.length; t += 3) {
      const a = 3 * tri[t], b = 3 * tri[t + 1], c = 3 * tri[t + 2];
      const ux = x[b] - x[a], uy = x[b + 1] - x[a + 1], uz = x[b + 2] - x[a + 2];
      const vx = x[c] - x[a], vy = x[c + 1] - x[a + 1], vz = x[c + 2] - x[a + 2];
      const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      n[a] += nx; n[a + 1] += ny; n[a + 2] += nz;
      n[b] += nx; n[b + 1] += ny; n[b + 2] += nz;
      n[c] += nx; n[c + 1] += ny; n[c + 2] += nz;
    }
  }

  /**
   * The friction's step solved implicitly: with each slider's direction at x* (the positions the elastic step left,
   * `direction`) held, s_v(x* + d) = s_v(x*) + g_v·d is linear in the step d (g_v: K_k times that direction at
   * particle k), and the backward-Euler step of
   * the springs in series with their sliders is the convex problem
   *   min_d ½·|M^½·d|²/h² + Σ_v φ_v(s_v(x* + d) − s_p),
   * φ_v(u) = ½·k_f·u² for |u| ≤ r = HB/k_f and HB·|u| − ½·HB·r beyond (the slider gives: Huber's function, whose
   * minimiser with the slider then moved to within r is the return mapping done inside the step, so no spring ever
   * pulls harder than HB). Solved by semi-smooth Newton: each iteration a linear solve with the sticking stencils'
   * stiffness (conjugate gradients, Jacobi-preconditioned, to a relative residual of 10⁻⁸), then a backtracking line
   * search on the objective, until the gradient is 10⁻⁸ of the first one's (at most `newtonMost` iterations).
   * Pinned particles held. Then each slider follows to within r of its spring's end.
   */
  solve(state, h) {
    const x = state.positions, w = state.invMass, { offsets, vertices, weights: K, areas } = this.stencils;
    const m = areas.length, N3 = x.length, n = this.normals, sp = this.slider;
    const { d, r, z, p, q, diag, s0, kf, nv, ka, u, grad, step, trial } = this.cg, h2 = h * h, HB = this.HB;
    this.updateNormals(x);
    for (let e = 0; e < m; e++) {
      const from = offsets[e], to = offsets[e + 1], v = 3 * vertices[from];
      const len = Math.hypot(n[v], n[v + 1], n[v + 2]);
      kf[e] = len > 0 ? ratio * this.B / areas[e] : 0;
      this.direction(x, e, len, nv);
      const nx = nv[3 * e], ny = nv[3 * e + 1], nz = nv[3 * e + 2];
      let sv = 0;
      for (let k = from; k < to; k++) { const at = 3 * vertices[k]; sv += K[k] * (x[at] * nx + x[at + 1] * ny + x[at + 2] * nz); }
      s0[e] = sv;
    }
    // u_e = s_v(x* + d) − s_p, the objective, and (with `withGrad`) its gradient, for the step `y`
    const gd = (y, e) => {
      let g = 0;
      const nx = nv[3 * e], ny = nv[3 * e + 1], nz = nv[3 * e + 2];
      for (let k = offsets[e]; k < offsets[e + 1]; k++) { const i = vertices[k], at = 3 * i; if (w[i] > 0) g += K[k] * (y[at] * nx + y[at + 1] * ny + y[at + 2] * nz); }
      return g;
    };
    const objective = (y, withGrad) => {
      let phi = 0;
      for (let i = 0; i < N3; i += 3) {
        const mi = w[i / 3] > 0 ? 1 / (w[i / 3] * h2) : 0;
        phi += 0.5 * mi * (y[i] * y[i] + y[i + 1] * y[i + 1] + y[i + 2] * y[i + 2]);
        if (withGrad) { grad[i] = mi * y[i]; grad[i + 1] = mi * y[i + 1]; grad[i + 2] = mi * y[i + 2]; }
      }
      for (let e = 0; e < m; e++) {
        if (kf[e] === 0) continue;
        const ue = s0[e] + gd(y, e) - sp[e], reach = HB / kf[e];
        phi += Math.abs(ue) <= reach ? 0.5 * kf[e] * ue * ue : HB * Math.abs(ue) - 0.5 * HB * reach;
        if (withGrad) {
          u[e] = ue;
          const f = Math.abs(ue) <= reach ? kf[e] * ue : Math.sign(ue) * HB;
          const nx = nv[3 * e], ny = nv[3 * e + 1], nz = nv[3 * e + 2];
          for (let k = offsets[e]; k < offsets[e + 1]; k++) { const i = vertices[k], at = 3 * i; if (w[i] > 0) { const c = f * K[k]; grad[at] += c * nx; grad[at + 1] += c * ny; grad[at + 2] += c * nz; } }
        }
      }
      if (withGrad) for (let i = 0; i < N3; i += 3) if (!(w[i / 3] > 0)) grad[i] = grad[i + 1] = grad[i + 2] = 0;
      return phi;
    };
    d.fill(0);
    let phi = objective(d, true), g0 = 0, newton = 0, cgTotal = 0;
    for (let i = 0; i < N3; i++) g0 += grad[i] * grad[i];
    for (; newton < newtonMost && g0 > 0; newton++) {
      let gg = 0;
      for (let i = 0; i < N3; i++) gg += grad[i] * grad[i];
      if (gg <= 1e-16 * g0) break;
      // the sticking stencils' stiffness; the Newton system H·step = −grad
      for (let i = 0; i < N3; i += 3) diag[i] = diag[i + 1] = diag[i + 2] = w[i / 3] > 0 ? 1 / (w[i / 3] * h2) : 1;
      for (let e = 0; e < m; e++) {
        ka[e] = kf[e] > 0 && Math.abs(u[e]) <= HB / kf[e] ? kf[e] : 0;
        if (ka[e] === 0) continue;
        const nx = nv[3 * e], ny = nv[3 * e + 1], nz = nv[3 * e + 2];
        for (let k = offsets[e]; k < offsets[e + 1]; k++) { const i = vertices[k], at = 3 * i; if (w[i] > 0) { const c = ka[e] * K[k] * K[k]; diag[at] += c * nx * nx; diag[at + 1] += c * ny * ny; diag[at + 2] += c * nz * nz; } }
      }
      let rz = 0, bb = 0;
      for (let i = 0; i < N3; i++) { step[i] = 0; r[i] = -grad[i]; z[i] = r[i] / diag[i]; p[i] = z[i]; rz += r[i] * z[i]; bb += r[i] * r[i]; }
      let it = 0;
      for (; it < 2000; it++) {
        this.apply(p, q, w, h2);
        let pq = 0;
        for (let i = 0; i < N3; i++) pq += p[i] * q[i];
        const a = rz / pq;
        let rr = 0;
        for (let i = 0; i < N3; i++) { step[i] += a * p[i]; r[i] -= a * q[i]; rr += r[i] * r[i]; }
        if (rr <= 1e-16 * bb) break;
        let rz2 = 0;
        for (let i = 0; i < N3; i++) { z[i] = r[i] / diag[i]; rz2 += r[i] * z[i]; }
        const beta = rz2 / rz;
        rz = rz2;
        for (let i = 0; i < N3; i++) p[i] = z[i] + beta * p[i];
      }
      cgTotal += it;
      this.iterations = Math.max(this.iterations, it);
      // backtracking (Armijo) on the convex objective
      let slope = 0;
      for (let i = 0; i < N3; i++) slope += grad[i] * step[i];
      let a = 1, next = phi;
      for (let tries = 0; tries < 40; tries++, a *= 0.5) {
        for (let i = 0; i < N3; i++) trial[i] = d[i] + a * step[i];
        next = objective(trial, false);
        if (next <= phi + 1e-4 * a * slope) break;
      }
      if (!(next < phi)) break; // no descent left: at the minimum to rounding
      d.set(trial);
      phi = objective(d, true);
    }
    this.newton = Math.max(this.newton, newton);
    this.cgPerStep = Math.max(this.cgPerStep, cgTotal);
    for (let i = 0; i < N3; i++) if (w[(i / 3) | 0] > 0) x[i] += d[i];
    // each slider to within r of its spring's end (u at the final d, from the last gradient's evaluation)
    for (let e = 0; e < m; e++) {
      if (kf[e] === 0) continue;
      const ue = s0[e] + gd(d, e) - sp[e], reach = HB / kf[e];
      if (ue > reach) sp[e] += ue - reach; else if (ue < -reach) sp[e] += ue + reach;
    }
  }

  /**
   * The direction stencil e's slider acts along at positions x, into out[3e…3e+2] (`len`: the length of the vertex
   * normal's sum, 0 for none): the unit vertex normal (`--direction normal`), or C_v's own direction with the sign
   * of its normal part (`--direction laplacian`: s_v = ±|C_v|, which a turn of the normal alone does not change), the
   * normal where C_v is 0.
   */
  direction(x, e, len, out) {
    const { offsets, vertices, weights: K } = this.stencils, n = this.normals, v = 3 * vertices[offsets[e]];
    let dx = len > 0 ? n[v] / len : 0, dy = len > 0 ? n[v + 1] / len : 0, dz = len > 0 ? n[v + 2] / len : 0;
    if (along === 'laplacian') {
      let cx = 0, cy = 0, cz = 0;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) { const at = 3 * vertices[k]; cx += K[k] * x[at]; cy += K[k] * x[at + 1]; cz += K[k] * x[at + 2]; }
      const c = Math.hypot(cx, cy, cz), sign = cx * dx + cy * dy + cz * dz < 0 ? -1 : 1;
      if (c > 0) { dx = sign * cx / c; dy = sign * cy / c; dz = sign * cz / c; }
    }
    out[3 * e] = dx; out[3 * e + 1] = dy; out[3 * e + 2] = dz;
  }

  /** A·y into out: M/h²·y + Σ_v k_a·g_v·(g_vᵀ·y), k_a the sticking stencils' k_f (0 where the slider gives), pinned rows the identity (set by solve) */
  apply(y, out, w, h2) {
    const { offsets, vertices, weights: K, areas } = this.stencils, { ka: kf, nv, t } = this.cg, m = areas.length, N3 = y.length;
    for (let i = 0; i < N3; i += 3) { const mi = w[i / 3] > 0 ? 1 / (w[i / 3] * h2) : 1; out[i] = mi * y[i]; out[i + 1] = mi * y[i + 1]; out[i + 2] = mi * y[i + 2]; }
    for (let e = 0; e < m; e++) {
      if (kf[e] === 0) continue;
      const from = offsets[e], to = offsets[e + 1], nx = nv[3 * e], ny = nv[3 * e + 1], nz = nv[3 * e + 2];
      let g = 0;
      for (let k = from; k < to; k++) { const i = vertices[k], at = 3 * i; if (w[i] > 0) g += K[k] * (y[at] * nx + y[at + 1] * ny + y[at + 2] * nz); }
      t[e] = kf[e] * g;
      for (let k = from; k < to; k++) { const i = vertices[k], at = 3 * i; if (w[i] > 0) { const c = t[e] * K[k]; out[at] += c * nx; out[at + 1] += c * ny; out[at + 2] += c * nz; } }
    }
  }

  /** the largest |k_f·(s_v − s_p)| / HB over the stencils now: at most 1 where the friction is resolved */
  worstForce(x) {
    const { offsets, vertices, weights: K, areas } = this.stencils, n = this.normals;
    this.updateNormals(x);
    let worst = 0;
    const dir = this.cg.nv;
    for (let e = 0; e < areas.length; e++) {
      const v = 3 * vertices[offsets[e]], len = Math.hypot(n[v], n[v + 1], n[v + 2]);
      if (!(len > 0)) continue;
      this.direction(x, e, len, dir);
      let sv = 0;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) { const at = 3 * vertices[k]; sv += K[k] * (x[at] * dir[3 * e] + x[at + 1] * dir[3 * e + 1] + x[at + 2] * dir[3 * e + 2]); }
      worst = Math.max(worst, Math.abs(ratio * this.B / areas[e] * (sv - this.slider[e])) / this.HB);
    }
    return worst;
  }

  /** one pass over the stencils, batch by batch; `first`: the substep's first pass (λ from zero) */
  pass(state, h, first) {
    const x = state.positions, w = state.invMass, { offsets, vertices, weights: K, areas, batches } = this.stencils;
    const n = this.normals, sp = this.slider, lam = this.lambda, h2 = h * h, cap = this.HB * h2;
    if (first) lam.fill(0);
    this.updateNormals(x);
    for (const batch of batches) {
      for (let e = batch.start; e < batch.end; e++) {
        const from = offsets[e], to = offsets[e + 1], v = 3 * vertices[from];
        let nx = n[v], ny = n[v + 1], nz = n[v + 2];
        const len = Math.hypot(nx, ny, nz);
        if (!(len > 0)) continue;
        nx /= len; ny /= len; nz /= len;
        let s = 0, sum = 0;
        for (let k = from; k < to; k++) {
          const i = vertices[k], at = 3 * i;
          s += K[k] * (x[at] * nx + x[at + 1] * ny + x[at + 2] * nz);
          sum += w[i] * K[k] * K[k];
        }
        const kf = ratio * this.B / areas[e], alphaT = 1 / (kf * h2), l0 = lam[e];
        let dl = (sp[e] - s - alphaT * l0) / (sum + alphaT);
        if (l0 + dl > cap) dl = cap - l0; else if (l0 + dl < -cap) dl = -cap - l0;
        lam[e] = l0 + dl;
        for (let k = from; k < to; k++) {
          const i = vertices[k], d = w[i] * K[k] * dl, at = 3 * i;
          x[at] += d * nx; x[at + 1] += d * ny; x[at + 2] += d * nz;
        }
        // the slider follows where the spring would pull harder than HB
        const moved = s + sum * dl, reach = this.HB / kf;
        if (moved - sp[e] > reach) sp[e] = moved - reach; else if (moved - sp[e] < -reach) sp[e] = moved + reach;
      }
    }
  }
}

/**
 * The friction's isotropy: Σ_v |C_v| over the Laplacian's stencils for the rest mesh bent, without stretching, into
 * a cylinder of radius 10 cm whose axis lies at 0°, 22.5°, 45° and 90° to the lattice, each over the first.
 */
function isotropy(model) {
  const { offsets, vertices, weights: K } = bendingStencils(model, 'laplacian'), p = model.restPositions, R = 0.1;
  const x = new Float64Array(p.length);
  const sums = [0, Math.PI / 8, Math.PI / 4, Math.PI / 2].map((angle) => {
    const c = Math.cos(angle), sn = Math.sin(angle);
    for (let i = 0; i < p.length; i += 3) {
      const u = c * p[i] + sn * p[i + 2], v = -sn * p[i] + c * p[i + 2], bu = R * Math.sin(u / R);
      x[i] = c * bu - sn * v; x[i + 1] = R * (1 - Math.cos(u / R)); x[i + 2] = sn * bu + c * v;
    }
    let sum = 0;
    for (let e = 0; e + 1 < offsets.length; e++) {
      let cx = 0, cy = 0, cz = 0;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) { const at = 3 * vertices[k]; cx += K[k] * x[at]; cy += K[k] * x[at + 1]; cz += K[k] * x[at + 2]; }
      sum += Math.hypot(cx, cy, cz);
    }
    return sum;
  });
  return sums.map((v) => (v / sums[0]).toFixed(5)).join(', ');
}

/** The TypeScript reference's frame, its global bending step followed by the friction's passes. */
class HysteresisBackend extends TsBackend {
  constructor(model, friction) {
    super(model);
    this.phaseBackend = {
      phases: { name: 'bending hysteresis (study)', where: 'in this script', sharesMemory: true, solvers: ['xpbd'], phases: 1 << PHASE.globalBending },
      run: (_mask, m, state, params, frame) => {
        REFERENCE[PHASE.globalBending](m, state, params, frame);
        if (friction && method === 'cg') friction.solve(state, frame.h);
        else if (friction) for (let p = 0; p < passes; p++) friction.pass(state, frame.h, p === 0);
        // how well the step resolved the friction, right after it, in each frame's last substep
        if (friction && frame.sub === frame.substeps - 1) friction.lastWorst = friction.worstForce(state.positions);
      },
    };
  }
  frame(model, params, dt) { runFrame(model, this.state, params, dt, this.phaseBackend); }
}

console.log(`the cusick scene at ${resolution} cells, ${substeps ?? 'the default'} substeps × ${iterations ?? 'the default'} passes${damping !== null ? `, material.damping ${damping}` : ''}${lower !== null ? `, laid on a support lowered over ${lower} s` : ''}; bending hysteresis ${factor} × 2HB, ${method === 'cg' ? 'solved by conjugate gradients' : `${passes} friction passes a substep`}, slider spring ${ratio} × B; seeds ${seeds.join(', ')}`);
if (cantilever !== null) {
  // the Peirce cantilever (ASTM D1388) as the scene runs it, the strip pushed over the edge: with the friction a bend
  // must overcome HB before it moves, so the strip should read a longer bending length than c = (B/(ρ_A·g))^(1/3)
  console.log(`the cantilever scene at ${cantilever} faces, ${method === 'cg' ? 'the friction solved by conjugate gradients' : `${passes} friction passes a substep`}`);
  console.log('| fabric | HB/B [1/m] | c [cm] | bending length without friction [cm] | with [cm] | most CG iterations a substep |');
  console.log('|---|---|---|---|---|---|');
  for (const f of FABRICS.filter((x) => chosen.includes(x[0]))) {
    const [id, what, rho, , , [B], , , twoHB] = f;
    const HB = factor * twoHB / 2;
    const read = (withFriction) => {
      let scene = builtinScene('cantilever');
      scene = setScenePath(scene, 'material.arealDensity', rho);
      scene = setScenePath(scene, 'material.bendingRigidity', B);
      scene = setScenePath(scene, 'cloth.resolution', Number(cantilever));
      const sim = new Simulation(scene, { kernel: 'ts' });
      const friction = withFriction ? new BendingFriction(sim.model, HB, B) : null;
      sim.useBackend(new HysteresisBackend(sim.model, friction));
      sim.advance(Math.round(scene.duration * 60));
      const length = sim.report().test.bendingLength;
      sim.dispose();
      return [length, friction ? friction.iterations : 0];
    };
    const [without] = read(false), [withF, its] = read(true);
    console.log(`| ${id} (${what}) | ${(HB / B).toFixed(1)} | ${(Math.cbrt(B / (rho * 9.81)) * 100).toFixed(2)} | ${(without * 100).toFixed(2)} | ${(withF * 100).toFixed(2)} | ${method === 'cg' ? its : '–'} |`);
  }
  process.exit(0);
}
{
  const sim = new Simulation(specimenScene(FABRICS.find((x) => x[0] === chosen[0]), seeds[0], { resolution }), { kernel: 'ts' });
  console.log(`Σ|C_v| on a cylinder at 0°, 22.5°, 45°, 90° to the lattice, over the first: ${isotropy(sim.model)}`);
  sim.dispose();
}
console.log('| fabric | HB [mN] | HB/B [1/m] | specimens: drape coefficient, folds → mean | measured (folds) | Drape − measured |');
console.log('|---|---|---|---|---|---|');
const pairs = [];
let cgMost = 0, newtonSeen = 0, cgStepMost = 0;
const worst = [];
for (const f of FABRICS.filter((x) => chosen.includes(x[0]))) {
  const [id, what, , , , [B], measured, , twoHB, measuredFolds] = f;
  const HB = factor * twoHB / 2;
  const runs = seeds.map((seed) => {
    let scene = specimenScene(f, seed, { resolution, substeps, iterations });
    if (damping !== null) scene = setScenePath(scene, 'material.damping', Number(damping));
    if (lower !== null) {
      const T = Number(lower), pedestalTop = 0.5;
      const support = {
        type: 'box', center: [0, pedestalTop - 0.005, 0], halfExtents: [0.2, 0.005, 0.2],
        motion: { keyframes: [{ time: 0, translation: [0, 0, 0] }, { time: T, translation: [0, -0.3, 0] }] },
      };
      scene = setScenePath(scene, 'colliders', [...scene.colliders, support]);
      scene = setScenePath(scene, 'duration', T + 6);
    }
    const sim = new Simulation(scene, { kernel: 'ts' });
    if (sim.params.bending === 'springs' || sim.params.bendingSolve !== 'global') throw new Error('the cusick scene no longer solves bending stencils together, the phase the friction follows');
    const friction = HB > 0 ? new BendingFriction(sim.model, HB, B) : null;
    sim.useBackend(new HysteresisBackend(sim.model, friction));
    const frames = Math.round(scene.duration * 60);
    if (history !== null) {
      // the reading as the skirt falls and settles: when its folds form, and whether they change
      const every = Math.max(1, Math.round(Number(history) * 60)), trace = [];
      for (let done = 0; done < frames;) {
        const step = Math.min(every, frames - done);
        sim.advance(step);
        done += step;
        const r = sim.report().test;
        trace.push(`${(done / 60).toFixed(1)} s ${r.drapeCoefficient.toFixed(3)}, ${r.folds}`);
      }
      console.log(`${id} seed ${seed}, ${friction ? 'with' : 'without'} the friction: ${trace.join('; ')}`);
    } else sim.advance(frames);
    const t = sim.report().test;
    if (friction) { cgMost = Math.max(cgMost, friction.iterations ?? 0); newtonSeen = Math.max(newtonSeen, friction.newton); cgStepMost = Math.max(cgStepMost, friction.cgPerStep); worst.push(`${id} seed ${seed}: ${friction.lastWorst.toFixed(2)}`); }
    sim.dispose();
    return t;
  });
  const dc = mean(runs.map((t) => t.drapeCoefficient));
  pairs.push([measured, dc]);
  console.log(`| ${id} (${what}) | ${(HB * 1e3).toFixed(3)} | ${(HB / B).toFixed(1)} | ${runs.map((t) => `${t.drapeCoefficient.toFixed(3)}, ${t.folds}`).join('; ')} → ${dc.toFixed(3)} | ${measured.toFixed(3)} (${measuredFolds}) | ${(dc - measured >= 0 ? '+' : '')}${(dc - measured).toFixed(3)} |`);
}
if (pairs.length > 1) {
  const n = pairs.length, mx = mean(pairs.map((p) => p[0])), my = mean(pairs.map((p) => p[1]));
  let sxx = 0, sxy = 0, sdd = 0;
  for (const [x, y] of pairs) { sxx += (x - mx) ** 2; sxy += (x - mx) * (y - my); sdd += (y - x) ** 2; }
  console.log(`\n${n} fabrics: Drape − measured ${(my - mx).toFixed(3)} on average, RMS ${Math.sqrt(sdd / n).toFixed(3)}; slope of Drape's on the measured ${(sxy / sxx).toFixed(2)}`);
}
if (worst.length) console.log(`the sliders' springs right after the friction's step in the last substep, the largest |k_f·(s_v − s_p)| / HB (at most 1 where it resolved the friction): ${worst.join('; ')}`);
if (method === 'cg' && cgMost > 0) console.log(`the friction's step took at most ${newtonSeen} Newton iterations a substep (${newtonMost} allowed), ${cgMost} conjugate-gradient iterations in one of them and ${cgStepMost} in one substep`);
