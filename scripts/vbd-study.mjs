#!/usr/bin/env node
// Issue 10 (converged stretch): Vertex Block Descent (Chen, Macklin, Yuksel, Kim & Nießner 2024, "Vertex Block Descent",
// ACM TOG 43(4)) as a candidate, measured on the hanging sheet and in free fall. A standalone prototype like
// gn-solver.mjs: it reads the ClothModel and SimParams the library builds (dist/) and steps its own float64 arrays;
// not integrated into the core.
//
// Per substep h: y = x + h·v + h²·g (pins held), then `passes` Gauss–Seidel passes over the free particles, each taking
// one Newton step on its own part of the implicit-Euler energy
//   G(x) = Σ_i (m_i/2h²)|x_i − y_i|² + Σ_springs ½k(|x_a − x_b| − L)² + Σ_stencils ½|Σ K_k x_k|²/α,
// H_i·Δx_i = f_i with H_i = (m_i/h²)I + Σ_springs [(k + β/h)n̂n̂ᵀ + k·max(0, 1 − L/l)(I − n̂n̂ᵀ)] + Σ_stencils (K_i²/α)I,
// the springs' damping β (material.damping) on the stretching rate only (as XPBD's), then v = (x − x_t)/h.
// Where the descent starts (the paper's §3.6) decides what one pass gives, so three starts are measured:
//   y         the prediction with gravity, x_t + h·v + h²·g;
//   inertia   without it, x_t + h·v: a cloth at rest is then a fixed point exactly at the static equilibrium;
//   adaptive  the paper's, x_t + h·v + h²·g·clamp(a_t·ĝ/|g|, 0, 1), a_t the particle's acceleration last substep;
//   pins      x_t + h·v + h²·g·s, one s for the cloth: the share of its weight its pins did not carry last substep
//             (1 − the pull of the springs on the pins along ĝ over m·|g|, clamped to [0, 1]).
// Then the same passes on the built-in cantilever scene (hinges) and on cotton held by one corner, swinging down,
// beside XPBD (the library). What was tried against their instability: --clamp F limits each particle's step to
// F × its shortest spring (0: no limit); --compressed abs gives a compressed spring the magnitude of its transverse
// stiffness instead of zero; --line-search yes halves a step until the particle's own energy does not rise;
// --safeguard yes starts a substep from x_t wherever G is lower there than at the start chosen.
//
//   npx tsc -p tsconfig.build.json && node scripts/vbd-study.mjs      (~5 min)
//   options: --fabrics rubber,cotton  --faces 16,32,64  --starts y,inertia,adaptive,pins  --settings 20x1
//            --budget 15 (seconds per hanging case)  --bending springs|hinges|laplacian  --clamp 0
//            --compressed clamp|abs  --line-search no|yes  --safeguard no|yes
//            --cantilever cotton,silk,leather,rubber,denim  --swing yes|no  --swing-bending hinges|springs|laplacian
import { FABRICS as NAMED, Simulation, builtinScene, measureTest, modelFor, resolveParams, scenePins, setScenePath, validateScene } from '../dist/core/index.js';
import { FABRICS, arg, hangingScene, hangingTheory, measureHanging } from './solver-study-common.mjs';

const fabrics = arg('fabrics', 'rubber,cotton').split(',');
const facesList = arg('faces', '16,32,64').split(',').map(Number);
const starts = arg('starts', 'y,inertia,adaptive,pins').split(',');
const settings = arg('settings', '20x1').split(',').map((s) => s.split('x').map(Number));
const budget = Number(arg('budget', '15')) * 1000;
const bending = arg('bending', 'springs');
const CLAMP = Number(arg('clamp', '0'));
const COMPRESSED = arg('compressed', 'clamp');
const LINE_SEARCH = arg('line-search', 'no') === 'yes';
const SAFEGUARD = arg('safeguard', 'no') === 'yes';

class VBD {
  constructor(scene, start) {
    const model = modelFor(scene), params = resolveParams(model, scene);
    this.model = model; this.params = params; this.start = start;
    const n = model.particleCount;
    this.n = n;
    this.pinned = new Uint8Array(n);
    for (const i of scenePins(model, scene)) this.pinned[i] = 1;
    this.x = Float64Array.from(model.restPositions);
    this.xt = new Float64Array(3 * n); this.y = new Float64Array(3 * n);
    this.v = new Float64Array(3 * n); this.vPrev = new Float64Array(3 * n);
    this.steps = 0;
    this.clothShare = 1;
    this.safeguarded = 0;
    this.mass = params.particleMass;
    // particle → springs with stiffness, particle → stencil entries
    const springs = model.springs, m = model.restLengths.length;
    const lists = Array.from({ length: n }, () => []);
    for (let s = 0; s < m; s++) if (params.stiffness[s] > 0) { lists[springs[2 * s]].push(s); lists[springs[2 * s + 1]].push(s); }
    this.springStart = new Int32Array(n + 1);
    for (let i = 0; i < n; i++) this.springStart[i + 1] = this.springStart[i] + lists[i].length;
    this.springOf = Int32Array.from(lists.flat());
    this.shortest = new Float64Array(n).fill(Infinity);
    for (let i = 0; i < n; i++) for (const s of lists[i]) this.shortest[i] = Math.min(this.shortest[i], model.restLengths[s]);
    this.st = params.bending === 'springs' ? null : model.stencils[params.bending];
    if (this.st) {
      const st = this.st, el = Array.from({ length: n }, () => []);
      for (let e = 0; e < st.offsets.length - 1; e++) {
        if (!(params.stencilCompliance[e] < Infinity)) continue;
        for (let q = st.offsets[e]; q < st.offsets[e + 1]; q++) el[st.vertices[q]].push([e, q]);
      }
      this.entryStart = new Int32Array(n + 1);
      for (let i = 0; i < n; i++) this.entryStart[i + 1] = this.entryStart[i] + el[i].length;
      this.entryStencil = Int32Array.from(el.flat().map((p) => p[0]));
      this.entryWeight = Float64Array.from(el.flat().map((p) => st.weights[p[1]]));
      this.c = new Float64Array(3 * (st.offsets.length - 1));
    }
  }

  step(dt, substeps, passes) {
    const h = dt / substeps;
    for (let s = 0; s < substeps; s++) this.substep(h, passes);
  }

  substep(h, passes) {
    const { n, x, xt, y, v, vPrev, pinned, params } = this;
    const [gx, gy, gz] = params.gravity, g2 = gx * gx + gy * gy + gz * gz, hh = h * h;
    for (let i = 0; i < n; i++) {
      const a = 3 * i;
      for (let d = 0; d < 3; d++) xt[a + d] = x[a + d];
      if (pinned[i]) { y[a] = x[a]; y[a + 1] = x[a + 1]; y[a + 2] = x[a + 2]; continue; }
      y[a] = x[a] + h * v[a] + hh * gx; y[a + 1] = x[a + 1] + h * v[a + 1] + hh * gy; y[a + 2] = x[a + 2] + h * v[a + 2] + hh * gz;
      let share = 1;
      if (this.start === 'inertia') share = 0;
      else if (this.start === 'pins') share = this.clothShare;
      else if (this.start === 'adaptive' && this.steps > 1) {
        const ax = (v[a] - vPrev[a]) / h, ay = (v[a + 1] - vPrev[a + 1]) / h, az = (v[a + 2] - vPrev[a + 2]) / h;
        share = Math.min(1, Math.max(0, (ax * gx + ay * gy + az * gz) / g2));
      }
      x[a] = y[a] - (1 - share) * hh * gx; x[a + 1] = y[a + 1] - (1 - share) * hh * gy; x[a + 2] = y[a + 2] - (1 - share) * hh * gz;
    }
    if (SAFEGUARD) {
      // start from x_t instead where that is lower in G: then the pass, which never raises G, ends no higher than
      // x_t, the bound implicit Euler's stability rests on
      const startG = this.energyG(x, h);
      if (this.energyG(xt, h) < startG) { x.set(xt); this.safeguarded++; }
    }
    for (let p = 0; p < passes; p++) this.pass(h);
    for (let j = 0; j < 3 * n; j++) { vPrev[j] = v[j]; v[j] = (x[j] - xt[j]) / h; }
    if (this.start === 'pins') {
      // the share of the cloth's weight its pins do not carry: what pulls the pins along g, over m·|g|
      const springs = this.model.springs, k = params.stiffness, rest = this.model.restLengths;
      let pull = 0, weight = 0;
      for (let i = 0; i < n; i++) if (!pinned[i]) weight += this.mass[i] * Math.sqrt(g2);
      for (let s = 0; s < rest.length; s++) {
        const a = springs[2 * s], b = springs[2 * s + 1];
        if (pinned[a] === pinned[b] || !(k[s] > 0)) continue;
        const p = pinned[a] ? a : b, o = pinned[a] ? b : a;
        const dx = x[3 * o] - x[3 * p], dy = x[3 * o + 1] - x[3 * p + 1], dz = x[3 * o + 2] - x[3 * p + 2], l = Math.hypot(dx, dy, dz);
        const f = k[s] * (l - rest[s]) / l; // force on the pin, toward the free particle
        pull += f * (dx * gx + dy * gy + dz * gz) / Math.sqrt(g2);
      }
      this.clothShare = Math.min(1, Math.max(0, 1 - pull / weight));
    }
    this.steps++;
  }

  pass(h) {
    const { n, x, xt, y, pinned, mass, model, params, st } = this;
    const springs = model.springs, rest = model.restLengths, k = params.stiffness, damping = params.springDamping;
    const invH = 1 / h, invH2 = invH * invH;
    if (st) {
      const c = this.c;
      for (let e = 0; e < st.offsets.length - 1; e++) {
        let cx = 0, cy = 0, cz = 0;
        for (let q = st.offsets[e]; q < st.offsets[e + 1]; q++) {
          const at = 3 * st.vertices[q], kk = st.weights[q];
          cx += kk * x[at]; cy += kk * x[at + 1]; cz += kk * x[at + 2];
        }
        c[3 * e] = cx; c[3 * e + 1] = cy; c[3 * e + 2] = cz;
      }
    }
    for (let i = 0; i < n; i++) {
      if (pinned[i]) continue;
      const a = 3 * i, xi = x[a], yi = x[a + 1], zi = x[a + 2], mh = mass[i] * invH2;
      let fx = -mh * (xi - y[a]), fy = -mh * (yi - y[a + 1]), fz = -mh * (zi - y[a + 2]);
      let h00 = mh, h01 = 0, h02 = 0, h11 = mh, h12 = 0, h22 = mh;
      for (let q = this.springStart[i]; q < this.springStart[i + 1]; q++) {
        const s = this.springOf[q], ks = k[s], o = springs[2 * s] === i ? springs[2 * s + 1] : springs[2 * s], b = 3 * o;
        const dx = xi - x[b], dy = yi - x[b + 1], dz = zi - x[b + 2], l = Math.sqrt(dx * dx + dy * dy + dz * dz);
        if (l < 1e-12) continue;
        const nx = dx / l, ny = dy / l, nz = dz / l, L = rest[s], bh = damping[s] * invH;
        const rate = nx * (xi - xt[a] - x[b] + xt[b]) + ny * (yi - xt[a + 1] - x[b + 1] + xt[b + 1]) + nz * (zi - xt[a + 2] - x[b + 2] + xt[b + 2]);
        const along = -ks * (l - L) - bh * rate;
        fx += along * nx; fy += along * ny; fz += along * nz;
        // the transverse stiffness k(1 − L/l): clamped at 0 when compressed (the paper's), or its magnitude (--compressed abs)
        const t = l > L ? ks * (1 - L / l) : COMPRESSED === 'abs' ? ks * (L / l - 1) : 0, nn = ks + bh - t;
        h00 += t + nn * nx * nx; h11 += t + nn * ny * ny; h22 += t + nn * nz * nz;
        h01 += nn * nx * ny; h02 += nn * nx * nz; h12 += nn * ny * nz;
      }
      if (st) {
        for (let q = this.entryStart[i]; q < this.entryStart[i + 1]; q++) {
          const e = this.entryStencil[q], kk = this.entryWeight[q], g = kk / params.stencilCompliance[e];
          fx -= g * this.c[3 * e]; fy -= g * this.c[3 * e + 1]; fz -= g * this.c[3 * e + 2];
          h00 += g * kk; h11 += g * kk; h22 += g * kk;
        }
      }
      const c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22, c02 = h01 * h12 - h02 * h11;
      const det = h00 * c00 + h01 * c01 + h02 * c02;
      if (!(det > 0)) continue;
      const c11 = h00 * h22 - h02 * h02, c12 = h01 * h02 - h00 * h12, c22 = h00 * h11 - h01 * h01;
      let ddx = (c00 * fx + c01 * fy + c02 * fz) / det, ddy = (c01 * fx + c11 * fy + c12 * fz) / det, ddz = (c02 * fx + c12 * fy + c22 * fz) / det;
      if (CLAMP > 0) {
        const len = Math.sqrt(ddx * ddx + ddy * ddy + ddz * ddz), most = CLAMP * this.shortest[i];
        if (len > most) { const r = most / len; ddx *= r; ddy *= r; ddz *= r; }
      }
      if (LINE_SEARCH) {
        // backtracking on the particle's own energy (inertia, springs, stencils): halve the step until it does not rise
        const e0 = this.localEnergy(i, 0, 0, 0, h);
        let tries = 0;
        while (this.localEnergy(i, ddx, ddy, ddz, h) > e0 && tries++ < 20) { ddx *= 0.5; ddy *= 0.5; ddz *= 0.5; }
      }
      if (st) {
        for (let q = this.entryStart[i]; q < this.entryStart[i + 1]; q++) {
          const e = this.entryStencil[q], kk = this.entryWeight[q];
          this.c[3 * e] += kk * ddx; this.c[3 * e + 1] += kk * ddy; this.c[3 * e + 2] += kk * ddz;
        }
      }
      x[a] = xi + ddx; x[a + 1] = yi + ddy; x[a + 2] = zi + ddz;
    }
  }

  /** The substep's whole energy G at positions p: inertia, springs, stencils. */
  energyG(p, h) {
    const { n, y, mass, model, params, st } = this;
    let e = 0;
    for (let i = 0; i < n; i++) e += 0.5 * mass[i] / (h * h) * ((p[3 * i] - y[3 * i]) ** 2 + (p[3 * i + 1] - y[3 * i + 1]) ** 2 + (p[3 * i + 2] - y[3 * i + 2]) ** 2);
    const springs = model.springs;
    for (let s = 0; s < model.restLengths.length; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      const l = Math.sqrt((p[a] - p[b]) ** 2 + (p[a + 1] - p[b + 1]) ** 2 + (p[a + 2] - p[b + 2]) ** 2);
      e += 0.5 * params.stiffness[s] * (l - model.restLengths[s]) ** 2;
    }
    if (st) {
      for (let en = 0; en < st.offsets.length - 1; en++) {
        if (!(params.stencilCompliance[en] < Infinity)) continue;
        let cx = 0, cy = 0, cz = 0;
        for (let q = st.offsets[en]; q < st.offsets[en + 1]; q++) {
          const at = 3 * st.vertices[q], kk = st.weights[q];
          cx += kk * p[at]; cy += kk * p[at + 1]; cz += kk * p[at + 2];
        }
        e += 0.5 * (cx * cx + cy * cy + cz * cz) / params.stencilCompliance[en];
      }
    }
    return e;
  }

  /** Particle i's own part of the substep's energy with it moved by (dx, dy, dz) (--line-search). */
  localEnergy(i, dx, dy, dz, h) {
    const { x, y, mass, model, params, st } = this, a = 3 * i;
    const px = x[a] + dx, py = x[a + 1] + dy, pz = x[a + 2] + dz;
    let e = 0.5 * mass[i] / (h * h) * ((px - y[a]) ** 2 + (py - y[a + 1]) ** 2 + (pz - y[a + 2]) ** 2);
    for (let q = this.springStart[i]; q < this.springStart[i + 1]; q++) {
      const s = this.springOf[q], o = model.springs[2 * s] === i ? model.springs[2 * s + 1] : model.springs[2 * s], b = 3 * o;
      const l = Math.sqrt((px - x[b]) ** 2 + (py - x[b + 1]) ** 2 + (pz - x[b + 2]) ** 2);
      e += 0.5 * params.stiffness[s] * (l - model.restLengths[s]) ** 2;
    }
    if (st) {
      for (let q = this.entryStart[i]; q < this.entryStart[i + 1]; q++) {
        const en = this.entryStencil[q], kk = this.entryWeight[q];
        e += 0.5 * ((this.c[3 * en] + kk * dx) ** 2 + (this.c[3 * en + 1] + kk * dy) ** 2 + (this.c[3 * en + 2] + kk * dz) ** 2) / params.stencilCompliance[en];
      }
    }
    return e;
  }

  kinetic() {
    let e = 0;
    for (let i = 0; i < this.n; i++) e += 0.5 * this.mass[i] * (this.v[3 * i] ** 2 + this.v[3 * i + 1] ** 2 + this.v[3 * i + 2] ** 2);
    return e;
  }
}

console.log(`Vertex block descent, bending ${bending}: hanging sheet (elongation ÷ ρ_A·g·L²/(2k), settled as in hanging-strain.mjs) and free fall`);
for (const fabric of fabrics) {
  const th = hangingTheory(fabric);
  console.log(`\n${fabric}: theory elongation ${(1000 * th.elongation).toFixed(3)} mm`);
  console.log('| faces | substeps × passes | start | frames | KE [J] | last-chunk drift | elongation ratio | ms/frame |');
  console.log('|---|---|---|---|---|---|---|---|');
  for (const faces of facesList) for (const [substeps, passes] of settings) for (const start of starts) {
    const scene = hangingScene(fabric, faces, substeps, passes, bending);
    const sim = new VBD(scene, start);
    const mgl = FABRICS[fabric].mass * 9.81;
    const t0 = performance.now();
    let prev = NaN, drift = NaN, ke = NaN, frames = 0, settled = false;
    while (performance.now() - t0 < budget) {
      for (let f = 0; f < 30; f++) sim.step(1 / 60, substeps, passes);
      frames += 30;
      const m = measureHanging(sim.x, faces);
      ke = sim.kinetic();
      drift = (m.elongation - prev) / m.elongation;
      prev = m.elongation;
      if (frames >= 300 && Math.abs(drift) < 0.001 && ke < 1e-6 * mgl) { settled = true; break; }
    }
    const ms = (performance.now() - t0) / frames;
    const m = measureHanging(sim.x, faces);
    console.log(`| ${faces}² | ${substeps} × ${passes} | ${start} | ${frames}${settled ? '' : ' (not settled)'} | ${ke.toExponential(1)} | ` +
      `${(100 * drift).toFixed(2)} % | ${(m.elongation / th.elongation).toFixed(2)} | ${ms.toFixed(1)} |`);
  }
}

// free fall: the same sheet hanging in the plane of gravity, unpinned, 0.5 s; drop of its top-left particle ÷ ½gt²
console.log('\nFree fall of the unpinned sheet, in the plane of gravity, 0.5 s at 32² (drop ÷ ½·g·t²):');
console.log('| fabric | substeps × passes | start | drop ratio |');
console.log('|---|---|---|---|');
for (const fabric of fabrics) for (const [substeps, passes] of settings) for (const start of starts) {
  const scene = validateScene({ ...hangingScene(fabric, 32, substeps, passes, bending), pins: [] });
  const sim = new VBD(scene, start);
  const y0 = sim.x[1];
  for (let f = 0; f < 30; f++) sim.step(1 / 60, substeps, passes);
  console.log(`| ${fabric} | ${substeps} × ${passes} | ${start} | ${((y0 - sim.x[1]) / (0.5 * 9.81 * 0.25)).toFixed(3)} |`);
}

// the built-in cantilever scene (hinges; at --settings, the scene's own being 20 × 1; this prototype has no air, the
// scene has still air)
console.log('\nThe cantilever scene, 32 faces, hinges, 6 s: chord → bending length ÷ c, and the chord over the sixth second');
console.log('| fabric | substeps × passes | start | chord at 6 s → c / c_theory | chord over the sixth second |');
console.log('|---|---|---|---|---|');
for (const fabric of arg('cantilever', 'cotton,silk,leather,rubber,denim').split(',').filter(Boolean)) for (const [substeps, passes] of settings) for (const start of starts) {
  const f = NAMED[fabric], c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
  const scene = setScenePath(builtinScene('cantilever'), 'material.fabric', fabric);
  const sim = new VBD(scene, start);
  const read = () => measureTest(sim.model, { positions: sim.x, pinned: sim.pinned }, scene);
  let lo = Infinity, hi = -Infinity;
  for (let fr = 0; fr < 360; fr++) {
    sim.step(1 / 60, substeps, passes);
    if (fr >= 300) { const a = read().chordAngle; lo = Math.min(lo, a); hi = Math.max(hi, a); }
  }
  const t = read();
  console.log(`| ${fabric} | ${substeps} × ${passes} | ${start} | ${t.chordAngle.toFixed(1)}° → ${(t.bendingLength / c).toFixed(3)} | ${lo.toFixed(1)}–${hi.toFixed(1)}° |`);
}

// a swing: cotton held by one corner, horizontal at the start, falls and swings through 90°; the height of its
// centroid against XPBD's (the library, Gauss–Seidel, 20 × 1, TypeScript) at 0.25 s steps
if (arg('swing', 'yes') === 'yes') {
  const scene = validateScene({
    cloth: { resolution: 32, width: 1, height: 1, position: [0, 1.5, 0] },
    material: { fabric: 'cotton' }, solver: { bending: arg('swing-bending', 'hinges'), selfContact: false }, colliders: [], pins: ['top-left'],
  });
  const centroidY = (x) => { let s = 0; for (let i = 1; i < x.length; i += 3) s += x[i]; return s / (x.length / 3); };
  const rows = [];
  const xpbd = new Simulation(scene, { kernel: 'ts' });
  const ref = [];
  for (let k = 0; k < 8; k++) { xpbd.advance(15); ref.push(centroidY(xpbd.state.positions)); }
  xpbd.dispose();
  rows.push(['XPBD', ref]);
  for (const [substeps, passes] of settings) for (const start of starts) {
    const sim = new VBD(scene, start), ys = [];
    for (let k = 0; k < 8; k++) { for (let f = 0; f < 15; f++) sim.step(1 / 60, substeps, passes); ys.push(centroidY(sim.x)); }
    rows.push([`${start}, ${substeps} × ${passes}`, ys]);
  }
  console.log('\nCotton held by one corner, 32², swinging down: the centroid\'s height [m] every 0.25 s');
  console.log('| solver / start | ' + ref.map((_, k) => `${(0.25 * (k + 1)).toFixed(2)} s`).join(' | ') + ' |');
  console.log('|---|' + ref.map(() => '---').join('|') + '|');
  for (const [name, ys] of rows) console.log(`| ${name} | ${ys.map((v) => v.toFixed(3)).join(' | ')} |`);
}
