#!/usr/bin/env node
// A study, not a feature (issue 10; docs/materials.md §3.6, "Bending hysteresis"): does the bending hysteresis that
// KES-FB2 measures (2HB, the width of the moment–curvature loop: a bend must overcome HB = 2HB/2 of moment per unit
// width before it moves, the fabric's internal friction) account for what the `cusick` scene misses on source 16's
// fabrics, the four whose B, 2HB, weight and drape coefficient were measured together? Drape's bending is elastic
// only; this script adds the friction to the TypeScript reference's frame from outside, without changing the product.
//
// The model: internal friction in bending (Miguel et al. 2013, "Modeling and Estimation of Internal Friction in
// Cloth", ACM TOG 32(6): a Dahl model in parallel with the elastic bending) in its stick–slip limit, a stiff spring in
// series with a slider, per stencil of the cotangent Laplacian (Wardetzky et al. 2007; model.ts): s_v = C_v·n_v, the
// stencil's 3-vector C_v ≈ A_v·(κ1 + κ2)·n along the vertex normal n_v (the area-weighted mean of its triangles'),
// carries a slider position s_p and the force f = k_f·(s_v − s_p), |f| ≤ HB. The pair (s_v, f) does work f·ds_v =
// f·A_v·dκ, so a cap of HB dissipates HB per unit area and unit curvature at any mesh and in any direction (the
// first line printed: Σ|C_v| of the disc bent into cylinders at four angles to the lattice). k_f = ratio·B/A_v (the
// elastic stencil's stiffness times `--ratio`, 10: the slider's spring is ten times the bending's). Solved after the
// substep's global bending step as XPBD passes (Macklin et al. 2016) with λ accumulated over `--passes` passes and
// held to ±HB·h²; after each stencil's update the slider follows so that |k_f·(s_v − s_p)| ≤ HB. A disc starts flat:
// s_p = 0.
//
//   npx tsc -p tsconfig.build.json && node scripts/bending-hysteresis.mjs [--fabrics A,B,C,F] [--seeds 1]
//       [--resolution 48] [--passes 24] [--ratio 10] [--hysteresis 1 (a factor on each fabric's 2HB: 0 for none)]
//       [--substeps S --iterations I] [--damping D (material.damping [N·s/m], the scene's cotton's 0.1 unless given)]
// prints each specimen's drape coefficient and folds beside the measured ones. The reference runs every phase in
// TypeScript (the WebAssembly kernel cannot be handed a phase from outside); with `--hysteresis 0` it reads what
// scripts/cusick-measured.mjs reads on the kernel (C, seed 1: 0.475 both).
import { PHASE, runFrame, setScenePath, TsBackend, Simulation, bendingStencils } from '../dist/core/index.js';
import { REFERENCE } from '../dist/core/reference.js';
import { FABRICS, mean, specimenScene } from './cusick-common.mjs';
import { arg } from './solver-study-common.mjs';

/** source 16's folds (docs/materials.md §3.6) */
const MEASURED_FOLDS = { A: 2, B: 5, C: 5, F: 7 };

const chosen = arg('fabrics', 'A,B,C,F').split(',');
const seeds = arg('seeds', '1').split(',').map(Number);
const resolution = Number(arg('resolution', '48'));
const passes = Number(arg('passes', '24')), ratio = Number(arg('ratio', '10')), factor = Number(arg('hysteresis', '1'));
const substeps = arg('substeps', null), iterations = arg('iterations', null), damping = arg('damping', null);
for (const id of chosen) {
  const f = FABRICS.find((x) => x[0] === id);
  if (!f || f[8] === null) throw new Error(`--fabrics: '${id}' has no measured 2HB (${FABRICS.filter((x) => x[8] !== null).map((x) => x[0]).join(', ')} have)`);
}
if (!(Number.isInteger(passes) && passes >= 1 && ratio > 0 && factor >= 0)) throw new Error('--passes: an integer ≥ 1; --ratio > 0; --hysteresis ≥ 0');

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
        if (friction) for (let p = 0; p < passes; p++) friction.pass(state, frame.h, p === 0);
      },
    };
  }
  frame(model, params, dt) { runFrame(model, this.state, params, dt, this.phaseBackend); }
}

console.log(`the cusick scene at ${resolution} cells, ${substeps ?? 'the default'} substeps × ${iterations ?? 'the default'} passes${damping !== null ? `, material.damping ${damping}` : ''}; bending hysteresis ${factor} × 2HB, ${passes} friction passes a substep, slider spring ${ratio} × B; seeds ${seeds.join(', ')}`);
{
  const sim = new Simulation(specimenScene(FABRICS.find((x) => x[0] === chosen[0]), seeds[0], { resolution }), { kernel: 'ts' });
  console.log(`Σ|C_v| on a cylinder at 0°, 22.5°, 45°, 90° to the lattice, over the first: ${isotropy(sim.model)}`);
  sim.dispose();
}
console.log('| fabric | HB [mN] | HB/B [1/m] | specimens: drape coefficient, folds → mean | measured (folds) | Drape − measured |');
console.log('|---|---|---|---|---|---|');
const pairs = [];
for (const f of FABRICS.filter((x) => chosen.includes(x[0]))) {
  const [id, what, , , , [B], measured, , twoHB] = f;
  const HB = factor * twoHB / 2;
  const runs = seeds.map((seed) => {
    let scene = specimenScene(f, seed, { resolution, substeps, iterations });
    if (damping !== null) scene = setScenePath(scene, 'material.damping', Number(damping));
    const sim = new Simulation(scene, { kernel: 'ts' });
    if (sim.params.bending === 'springs' || sim.params.bendingSolve !== 'global') throw new Error('the cusick scene no longer solves bending stencils together, the phase the friction follows');
    sim.useBackend(new HysteresisBackend(sim.model, HB > 0 ? new BendingFriction(sim.model, HB, B) : null));
    sim.advance(Math.round(scene.duration * 60));
    const t = sim.report().test;
    sim.dispose();
    return t;
  });
  const dc = mean(runs.map((t) => t.drapeCoefficient));
  pairs.push([measured, dc]);
  console.log(`| ${id} (${what}) | ${(HB * 1e3).toFixed(3)} | ${(HB / B).toFixed(1)} | ${runs.map((t) => `${t.drapeCoefficient.toFixed(3)}, ${t.folds}`).join('; ')} → ${dc.toFixed(3)} | ${measured.toFixed(3)} (${MEASURED_FOLDS[id]}) | ${(dc - measured >= 0 ? '+' : '')}${(dc - measured).toFixed(3)} |`);
}
if (pairs.length > 1) {
  const n = pairs.length, mx = mean(pairs.map((p) => p[0])), my = mean(pairs.map((p) => p[1]));
  let sxx = 0, sxy = 0, sdd = 0;
  for (const [x, y] of pairs) { sxx += (x - mx) ** 2; sxy += (x - mx) * (y - my); sdd += (y - x) ** 2; }
  console.log(`\n${n} fabrics: Drape − measured ${(my - mx).toFixed(3)} on average, RMS ${Math.sqrt(sdd / n).toFixed(3)}; slope of Drape's on the measured ${(sxy / sxx).toFixed(2)}`);
}
