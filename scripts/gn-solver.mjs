// A Gauss–Newton prototype on XPBD's constraints (issue 10's converged solver, a candidate) over Drape's own model and
// parameters, for scripts/pd-study.mjs (--part gn). Standalone like pd-solver.mjs: it reads a ClothModel and SimParams
// built by the library (dist/) and steps its own float64 arrays. Not integrated into the core.
//
// Per substep h it solves implicit Euler with the springs as compliant constraints (Macklin et al. 2016's XPBD, its
// Newton step taken whole instead of one Gauss–Seidel sweep; Goldenthal et al. 2007's fast projection with compliance):
//   A·x = M/h²·x̃ + Jᵀ·f + (pinned terms),   C(x) + α·f = 0,   A = M/h² + Σ_stencils (B/A_e)·K_eK_eᵀ,
// f the springs' forces [N] (f = −k·C), J the springs' directions, α = 1/k. A holds the inertia and the bending
// stencils, which are quadratic: it is one scalar matrix for the three coordinates, ordered once (RCM) and factored
// once (envelope Cholesky, pd-solver.mjs). Each Gauss–Newton iteration takes the directions where the cloth is now —
// so a spring turns freely and only its length is stiff, which a constant matrix of the springs (Projective Dynamics)
// cannot give — and solves the Schur complement (J·A⁻¹·Jᵀ + α)·δf = −C − α·f − J·(x̂ − x), x̂ = A⁻¹(M/h²·x̃ + Jᵀf +
// pins), by conjugate gradients preconditioned by its diagonal; then x = x̂ + A⁻¹Jᵀδf. The forces start each substep
// from the last (a static load is not rebuilt from nothing every substep, as XPBD's λ is). No damping: implicit Euler's.
import { EnvelopeCholesky as Envelope, reverseCuthillMcKee } from '../dist/core/solvers/sparse.js';
import { EnvelopeCholesky, rcm } from './pd-solver.mjs';

export class GNSolver {
  /**
   * model, params: the library's; pinned: Uint8Array (1 = fixed); opts: { substeps, iterations (Gauss–Newton
   * iterations per substep), tol (the conjugate gradients' relative residual), maxCg, precondition ('diagonal';
   * 'rest': J₀·D⁻¹·J₀ᵀ + α factored once; 'woodbury': the Schur complement at rest, exactly; 'warped': the same
   * with H₀ turned particle by particle; 'primal': Gauss–Newton on the positions, preconditioned by the turned H₀),
   * refresh (with
   * 'woodbury': refactor it at the cloth's directions after a substep of more than this many iterations) }.
   * Gravity and pins only: no colliders, no air.
   */
  constructor(model, params, pinned, opts) {
    this.model = model;
    this.params = params;
    this.opts = { substeps: 20, iterations: 1, tol: 1e-3, maxCg: 500, precondition: 'diagonal', refresh: Infinity, ...opts };
    const n = model.particleCount;
    this.n = n;
    this.pinned = pinned;
    this.x = Float64Array.from(model.restPositions);
    this.v = new Float64Array(3 * n);
    this.mass = Float64Array.from(params.particleMass);
    const sp = [], al = [], rl = [];
    for (let s = 0; s < model.restLengths.length; s++) {
      const alpha = params.compliance[s], a = model.springs[2 * s], b = model.springs[2 * s + 1];
      if (!(alpha < Infinity) || (pinned[a] && pinned[b])) continue;
      sp.push(a, b); al.push(alpha); rl.push(model.restLengths[s]);
    }
    this.springs = Int32Array.from(sp); this.alpha = Float64Array.from(al); this.rest = Float64Array.from(rl);
    const m = this.alpha.length;
    // the bending stencils of params.bending (none for the skip-one springs, which are springs above)
    const st = params.bending === 'springs' ? null : model.stencils[params.bending];
    const adj = Array.from({ length: n }, () => new Set());
    this.stencils = [];
    if (st) {
      for (let e = 0; e < st.areas.length; e++) {
        const a = params.stencilCompliance[e];
        if (!(a < Infinity)) continue;
        const idx = Array.from(st.vertices.subarray(st.offsets[e], st.offsets[e + 1]));
        if (idx.every((i) => pinned[i])) continue;
        this.stencils.push({ idx, K: Array.from(st.weights.subarray(st.offsets[e], st.offsets[e + 1])), w: 1 / a });
        for (const i of idx) for (const j of idx) if (i !== j && !pinned[i] && !pinned[j]) adj[i].add(j);
      }
    }
    const free = [];
    for (let i = 0; i < n; i++) if (!pinned[i]) free.push(i);
    const local = new Int32Array(n).fill(-1);
    free.forEach((i, k) => { local[i] = k; });
    const order = rcm(free.map((i) => [...adj[i]].map((j) => local[j])));
    this.nf = free.length;
    this.row = new Int32Array(n).fill(-1);
    for (let r = 0; r < this.nf; r++) this.row[free[order[r]]] = r;
    this.h = 1 / 60 / this.opts.substeps;
    const inertia = 1 / (this.h * this.h);
    const first = new Int32Array(this.nf);
    for (let i = 0; i < n; i++) {
      if (pinned[i]) continue;
      let f = this.row[i];
      for (const j of adj[i]) f = Math.min(f, this.row[j]);
      first[this.row[i]] = f;
    }
    this.chol = new EnvelopeCholesky(this.nf, first);
    // A's diagonal (by particle), for the preconditioner
    this.Adiag = new Float64Array(n).fill(Infinity);
    for (let i = 0; i < n; i++) if (!pinned[i]) { this.chol.add(this.row[i], this.row[i], this.mass[i] * inertia); this.Adiag[i] = this.mass[i] * inertia; }
    for (const { idx, K, w } of this.stencils) {
      for (let p = 0; p < idx.length; p++) {
        const i = idx[p];
        if (pinned[i]) continue;
        this.Adiag[i] += w * K[p] * K[p];
        for (let q = 0; q <= p; q++) {
          const j = idx[q];
          if (!pinned[j]) this.chol.add(this.row[i], this.row[j], w * K[p] * K[q]);
        }
      }
    }
    this.chol.factor();
    this.f = new Float64Array(m);
    this.nrm = new Float64Array(3 * m);
    this.xt = new Float64Array(3 * n); this.xOld = new Float64Array(3 * n); this.c0 = new Float64Array(3 * n);
    this.xh = new Float64Array(3 * n); this.w3 = new Float64Array(3 * n); this.D = new Float64Array(3 * n); this.b = new Float64Array(3 * this.nf);
    this.rhs = new Float64Array(m); this.r = new Float64Array(m); this.z = new Float64Array(m); this.p = new Float64Array(m);
    this.sp = new Float64Array(m); this.df = new Float64Array(m); this.diag = new Float64Array(m);
    for (let s = 0; s < m; s++) this.diag[s] = 1 / this.Adiag[this.springs[2 * s]] + 1 / this.Adiag[this.springs[2 * s + 1]] + this.alpha[s];
    if (this.opts.precondition === 'rest') this.restPreconditioner();
    if (['woodbury', 'warped', 'primal'].includes(this.opts.precondition)) this.woodburyPreconditioner();
    if (this.opts.precondition === 'warped' || this.opts.precondition === 'primal') this.warp = { q: new Float64Array(4 * n).fill(0), R: new Float64Array(9 * n), A: new Float64Array(9 * n) };
    if (this.warp) for (let i = 0; i < n; i++) { this.warp.q[4 * i + 3] = 1; this.warp.R.set([1, 0, 0, 0, 1, 0, 0, 0, 1], 9 * i); }
    /** conjugate gradient iterations and substeps so far */
    this.cgIterations = 0;
    this.substepsRun = 0;
  }

  /**
   * The preconditioner 'rest': P = J₀·D⁻¹·J₀ᵀ + α, the Schur complement with A lumped to its diagonal D and the
   * springs' directions at rest, factored once in the springs' space (RCM, envelope Cholesky). A rigid turn of the
   * cloth leaves J·D⁻¹·Jᵀ as it is (its entries are the springs' relative angles), so it stays near the true one.
   */
  restPreconditioner() {
    const { springs, alpha, Adiag, model } = this, m = alpha.length, rest = model.restPositions;
    const dir = new Float64Array(3 * m);
    for (let s = 0; s < m; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      const d0 = rest[a] - rest[b], d1 = rest[a + 1] - rest[b + 1], d2 = rest[a + 2] - rest[b + 2], l = Math.hypot(d0, d1, d2);
      dir[3 * s] = d0 / l; dir[3 * s + 1] = d1 / l; dir[3 * s + 2] = d2 / l;
    }
    // springs by particle, for the pairs that share one
    const by = Array.from({ length: this.n }, () => []);
    for (let s = 0; s < m; s++) for (const [e, sign] of [[0, 1], [1, -1]]) { const i = springs[2 * s + e]; if (!this.pinned[i]) by[i].push([s, sign]); }
    const adj = Array.from({ length: m }, () => new Set());
    for (const list of by) for (const [s] of list) for (const [t] of list) if (s !== t) adj[s].add(t);
    const rowStart = new Int32Array(m + 1);
    for (let s = 0; s < m; s++) rowStart[s + 1] = rowStart[s] + adj[s].size;
    const cols = new Int32Array(rowStart[m]);
    for (let s = 0; s < m; s++) { let k = rowStart[s]; for (const t of adj[s]) cols[k++] = t; }
    const order = reverseCuthillMcKee(rowStart, cols);
    const row = new Int32Array(m);
    for (let r = 0; r < m; r++) row[order[r]] = r;
    const first = new Int32Array(m);
    for (let r = 0; r < m; r++) { const s = order[r]; let f = r; for (let k = rowStart[s]; k < rowStart[s + 1]; k++) f = Math.min(f, row[cols[k]]); first[r] = f; }
    const P = new Envelope(first);
    for (let s = 0; s < m; s++) P.add(row[s], row[s], alpha[s]);
    for (let i = 0; i < this.n; i++) {
      const list = by[i], w = 1 / Adiag[i];
      for (const [s, ss] of list) for (const [t, st] of list) {
        if (row[t] > row[s]) continue;
        const dot = dir[3 * s] * dir[3 * t] + dir[3 * s + 1] * dir[3 * t + 1] + dir[3 * s + 2] * dir[3 * t + 2];
        P.add(row[s], row[t], ss * st * dot * w);
      }
    }
    P.factor();
    this.pre = { P, row, b: new Float64Array(m) };
  }

  /**
   * The preconditioner 'woodbury': the Schur complement at rest, (J₀·A⁻¹·J₀ᵀ + α)⁻¹, exactly, through Woodbury's
   * identity α⁻¹ − α⁻¹·J₀·H₀⁻¹·J₀ᵀ·α⁻¹ with H₀ = A + J₀ᵀ·α⁻¹·J₀ (the Gauss–Newton matrix of the positions with the
   * springs along their rest directions: 3n × 3n, factored once, RCM order of the particles).
   */
  woodburyPreconditioner(at = this.model.restPositions) {
    const { springs, alpha, pinned, n, row, nf } = this, m = alpha.length, rest = at;
    this.refactors = (this.refactors ?? -1) + 1;
    const dir = new Float64Array(3 * m);
    for (let s = 0; s < m; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      const d0 = rest[a] - rest[b], d1 = rest[a + 1] - rest[b + 1], d2 = rest[a + 2] - rest[b + 2], l = Math.hypot(d0, d1, d2);
      dir[3 * s] = d0 / l; dir[3 * s + 1] = d1 / l; dir[3 * s + 2] = d2 / l;
    }
    // the particles' order and envelope of A's factor, widened by the springs, three rows a particle
    const adj = Array.from({ length: n }, () => new Set());
    for (const { idx } of this.stencils) for (const i of idx) for (const j of idx) if (i !== j && !pinned[i] && !pinned[j]) adj[i].add(j);
    for (let s = 0; s < m; s++) { const a = springs[2 * s], b = springs[2 * s + 1]; if (!pinned[a] && !pinned[b]) { adj[a].add(b); adj[b].add(a); } }
    const first = new Int32Array(3 * nf);
    for (let i = 0; i < n; i++) {
      if (pinned[i]) continue;
      let f = row[i];
      for (const j of adj[i]) f = Math.min(f, row[j]);
      for (let c = 0; c < 3; c++) first[3 * row[i] + c] = 3 * f;
    }
    const H = new Envelope(first);
    const inertia = 1 / (this.h * this.h);
    for (let i = 0; i < n; i++) if (!pinned[i]) for (let c = 0; c < 3; c++) H.add(3 * row[i] + c, 3 * row[i] + c, this.mass[i] * inertia);
    for (const { idx, K, w } of this.stencils) {
      for (let p = 0; p < idx.length; p++) {
        if (pinned[idx[p]]) continue;
        for (let q = 0; q <= p; q++) {
          if (pinned[idx[q]]) continue;
          for (let c = 0; c < 3; c++) H.add(3 * row[idx[p]] + c, 3 * row[idx[q]] + c, w * K[p] * K[q]);
        }
      }
    }
    for (let s = 0; s < m; s++) {
      const ends = [[springs[2 * s], 1], [springs[2 * s + 1], -1]].filter(([i]) => !pinned[i]);
      for (const [i, si] of ends) for (const [j, sj] of ends) {
        if (row[j] > row[i]) continue;
        for (let c = 0; c < 3; c++) for (let e = 0; e < 3; e++) {
          if (i === j && e > c) continue;
          H.add(3 * row[i] + c, 3 * row[j] + e, (si * sj * dir[3 * s + c] * dir[3 * s + e]) / alpha[s]);
        }
      }
    }
    H.factor();
    this.wood = { H, dir, t: new Float64Array(m), v: new Float64Array(3 * nf) };
  }

  /** z ← P⁻¹r: the diagonal's, or the factored one at rest */
  precondition(r, z) {
    if (this.warp) { this.preconditionWarped(r, z); return; }
    if (this.wood) {
      const { H, dir, t, v } = this.wood, { springs, alpha, row, pinned } = this;
      v.fill(0);
      for (let s = 0; s < r.length; s++) {
        t[s] = r[s] / alpha[s];
        const a = springs[2 * s], b = springs[2 * s + 1];
        for (let c = 0; c < 3; c++) {
          if (!pinned[a]) v[3 * row[a] + c] += t[s] * dir[3 * s + c];
          if (!pinned[b]) v[3 * row[b] + c] -= t[s] * dir[3 * s + c];
        }
      }
      H.solve(v);
      for (let s = 0; s < r.length; s++) {
        const a = springs[2 * s], b = springs[2 * s + 1];
        let u = 0;
        for (let c = 0; c < 3; c++) u += dir[3 * s + c] * ((pinned[a] ? 0 : v[3 * row[a] + c]) - (pinned[b] ? 0 : v[3 * row[b] + c]));
        z[s] = (r[s] - u) / alpha[s];
      }
      return;
    }
    if (!this.pre) { for (let s = 0; s < r.length; s++) z[s] = r[s] / this.diag[s]; return; }
    const { P, row, b } = this.pre;
    for (let s = 0; s < r.length; s++) b[row[s]] = r[s];
    P.solve(b);
    for (let s = 0; s < r.length; s++) z[s] = b[row[s]];
  }

  /**
   * The preconditioner 'warped': the Woodbury one with H₀ turned, particle by particle, to where the cloth is now
   * (stiffness warping, Müller, Dorsey, McMillan, Jagnow & Cutler 2002): H ≈ R·H₀·Rᵀ, R = diag(R_i), each R_i the
   * rotation of particle i's springs from rest (rotations), and the springs' current directions in J. For a cloth
   * turned as a whole by R it is exact: J = J₀·Rᵀ and A (a scalar matrix for the three coordinates) commutes with R.
   */
  preconditionWarped(r, z) {
    const { H, t, v } = this.wood, { R } = this.warp, { springs, alpha, row, pinned, nrm } = this, n = this.n;
    v.fill(0);
    for (let s = 0; s < r.length; s++) {
      t[s] = r[s] / alpha[s];
      const a = springs[2 * s], b = springs[2 * s + 1];
      for (let c = 0; c < 3; c++) {
        if (!pinned[a]) v[3 * row[a] + c] += t[s] * nrm[3 * s + c];
        if (!pinned[b]) v[3 * row[b] + c] -= t[s] * nrm[3 * s + c];
      }
    }
    // into each particle's rest frame (Rᵀ), solve with H₀, back (R)
    for (let i = 0; i < n; i++) {
      if (pinned[i]) continue;
      const q = 3 * row[i], o = 9 * i, x = v[q], y = v[q + 1], w = v[q + 2];
      v[q] = R[o] * x + R[o + 3] * y + R[o + 6] * w;
      v[q + 1] = R[o + 1] * x + R[o + 4] * y + R[o + 7] * w;
      v[q + 2] = R[o + 2] * x + R[o + 5] * y + R[o + 8] * w;
    }
    H.solve(v);
    for (let i = 0; i < n; i++) {
      if (pinned[i]) continue;
      const q = 3 * row[i], o = 9 * i, x = v[q], y = v[q + 1], w = v[q + 2];
      v[q] = R[o] * x + R[o + 1] * y + R[o + 2] * w;
      v[q + 1] = R[o + 3] * x + R[o + 4] * y + R[o + 5] * w;
      v[q + 2] = R[o + 6] * x + R[o + 7] * y + R[o + 8] * w;
    }
    for (let s = 0; s < r.length; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1];
      let u = 0;
      for (let c = 0; c < 3; c++) u += nrm[3 * s + c] * ((pinned[a] ? 0 : v[3 * row[a] + c]) - (pinned[b] ? 0 : v[3 * row[b] + c]));
      z[s] = (r[s] - u) / alpha[s];
    }
  }

  /**
   * Each particle's rotation from rest (row-major R_i, its quaternion warm-started from the last): the rotational
   * part of A_i = Σ d·d₀ᵀ over its springs (d the spring now, d₀ at rest) plus l²·n·n₀ᵀ (the normals of its
   * triangles, now and at rest, so that a flat one-ring has a full-rank A_i), by Müller, Bender, Chentanez & Macklin
   * 2016, "A Robust Method to Extract the Rotational Part of Deformations".
   */
  rotations(x) {
    const { A, q, R } = this.warp, { springs, model, n } = this, x0 = model.restPositions, tri = model.triangles;
    A.fill(0);
    const add = (i, d, e, w) => { const o = 9 * i; for (let r = 0; r < 3; r++) for (let c = 0; c < 3; c++) A[o + 3 * r + c] += w * d[r] * e[c]; };
    const d = [0, 0, 0], e = [0, 0, 0];
    for (let s = 0; s < this.alpha.length; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1];
      for (let c = 0; c < 3; c++) { d[c] = x[3 * a + c] - x[3 * b + c]; e[c] = x0[3 * a + c] - x0[3 * b + c]; }
      add(a, d, e, 1); add(b, d, e, 1);
    }
    const cross = (u, v, out) => { out[0] = u[1] * v[2] - u[2] * v[1]; out[1] = u[2] * v[0] - u[0] * v[2]; out[2] = u[0] * v[1] - u[1] * v[0]; };
    const u = [0, 0, 0], w = [0, 0, 0], u0 = [0, 0, 0], w0 = [0, 0, 0];
    for (let k = 0; k < tri.length; k += 3) {
      const a = 3 * tri[k], b = 3 * tri[k + 1], c3 = 3 * tri[k + 2];
      for (let c = 0; c < 3; c++) { u[c] = x[b + c] - x[a + c]; w[c] = x[c3 + c] - x[a + c]; u0[c] = x0[b + c] - x0[a + c]; w0[c] = x0[c3 + c] - x0[a + c]; }
      cross(u, w, d); cross(u0, w0, e);
      // |d|, |e| are twice the areas: d·eᵀ/|e| weighs the normal pair as one of the triangle's edges
      const l0 = Math.hypot(e[0], e[1], e[2]), l = Math.hypot(d[0], d[1], d[2]);
      if (!(l0 > 0 && l > 0)) continue;
      const scale = 1 / l;
      for (const i of [tri[k], tri[k + 1], tri[k + 2]]) add(i, d, e, scale);
    }
    const M = new Float64Array(9);
    for (let i = 0; i < n; i++) {
      if (this.pinned[i]) continue;
      const o = 9 * i;
      let qx = q[4 * i], qy = q[4 * i + 1], qz = q[4 * i + 2], qw = q[4 * i + 3];
      for (let it = 0; it < 20; it++) {
        // R from q (row-major)
        M[0] = 1 - 2 * (qy * qy + qz * qz); M[1] = 2 * (qx * qy - qz * qw); M[2] = 2 * (qx * qz + qy * qw);
        M[3] = 2 * (qx * qy + qz * qw); M[4] = 1 - 2 * (qx * qx + qz * qz); M[5] = 2 * (qy * qz - qx * qw);
        M[6] = 2 * (qx * qz - qy * qw); M[7] = 2 * (qy * qz + qx * qw); M[8] = 1 - 2 * (qx * qx + qy * qy);
        // ω = Σ_c r_c × a_c / |Σ_c r_c·a_c| (columns c of R and A)
        let ox = 0, oy = 0, oz = 0, dot = 0;
        for (let c = 0; c < 3; c++) {
          const rx = M[c], ry = M[3 + c], rz = M[6 + c], ax = A[o + c], ay = A[o + 3 + c], az = A[o + 6 + c];
          ox += ry * az - rz * ay; oy += rz * ax - rx * az; oz += rx * ay - ry * ax;
          dot += rx * ax + ry * ay + rz * az;
        }
        const inv = 1 / (Math.abs(dot) + 1e-12);
        ox *= inv; oy *= inv; oz *= inv;
        const angle = Math.hypot(ox, oy, oz);
        if (angle < 1e-9) break;
        const sn = Math.sin(angle / 2) / angle, cs = Math.cos(angle / 2);
        const px = ox * sn, py = oy * sn, pz = oz * sn, pw = cs;
        // q ← p·q
        const nx = pw * qx + px * qw + py * qz - pz * qy;
        const ny = pw * qy - px * qz + py * qw + pz * qx;
        const nz = pw * qz + px * qy - py * qx + pz * qw;
        const nw = pw * qw - px * qx - py * qy - pz * qz;
        const len = Math.hypot(nx, ny, nz, nw);
        qx = nx / len; qy = ny / len; qz = nz / len; qw = nw / len;
      }
      q[4 * i] = qx; q[4 * i + 1] = qy; q[4 * i + 2] = qz; q[4 * i + 3] = qw;
      R[o] = 1 - 2 * (qy * qy + qz * qz); R[o + 1] = 2 * (qx * qy - qz * qw); R[o + 2] = 2 * (qx * qz + qy * qw);
      R[o + 3] = 2 * (qx * qy + qz * qw); R[o + 4] = 1 - 2 * (qx * qx + qz * qz); R[o + 5] = 2 * (qy * qz - qx * qw);
      R[o + 6] = 2 * (qx * qz - qy * qw); R[o + 7] = 2 * (qy * qz + qx * qw); R[o + 8] = 1 - 2 * (qx * qx + qy * qy);
    }
  }

  /** v ← A⁻¹v (by particle, stride 3; pinned particles do not move: 0 there) */
  solveA(v) {
    const { b, row, n, pinned } = this;
    for (let i = 0; i < n; i++) if (!pinned[i]) { const q = 3 * row[i]; b[q] = v[3 * i]; b[q + 1] = v[3 * i + 1]; b[q + 2] = v[3 * i + 2]; }
    this.chol.solve3(b);
    for (let i = 0; i < n; i++) {
      if (pinned[i]) { v[3 * i] = v[3 * i + 1] = v[3 * i + 2] = 0; continue; }
      const q = 3 * row[i]; v[3 * i] = b[q]; v[3 * i + 1] = b[q + 1]; v[3 * i + 2] = b[q + 2];
    }
  }

  /** out (3n) = Jᵀq */
  jt(q, out) {
    const { springs, nrm } = this;
    out.fill(0);
    for (let s = 0; s < q.length; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1], v = q[s];
      for (let c = 0; c < 3; c++) { out[a + c] += v * nrm[3 * s + c]; out[b + c] -= v * nrm[3 * s + c]; }
    }
  }

  /** out (m) = J·u */
  j(u, out) {
    const { springs, nrm } = this;
    for (let s = 0; s < out.length; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      out[s] = nrm[3 * s] * (u[a] - u[b]) + nrm[3 * s + 1] * (u[a + 1] - u[b + 1]) + nrm[3 * s + 2] * (u[a + 2] - u[b + 2]);
    }
  }

  /** out = A·u (inertia and bending stencils; pinned particles' rows and columns left out) */
  applyA(u, out) {
    const { n, pinned, mass } = this, inertia = 1 / (this.h * this.h);
    for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) out[3 * i + c] = pinned[i] ? 0 : mass[i] * inertia * u[3 * i + c];
    for (const { idx, K, w } of this.stencils) {
      for (let c = 0; c < 3; c++) {
        let kx = 0;
        for (let a = 0; a < idx.length; a++) if (!pinned[idx[a]]) kx += K[a] * u[3 * idx[a] + c];
        for (let a = 0; a < idx.length; a++) if (!pinned[idx[a]]) out[3 * idx[a] + c] += w * K[a] * kx;
      }
    }
  }

  /**
   * One frame in the primal form (precondition 'primal'): per substep, Gauss–Newton steps on the positions,
   * H·δx = −∇E, E = ½‖x − x̃‖²_M/h² + the stencils' ½xᵀBx + Σ ½k(|x_a − x_b| − l)², H = A + Σ k·n·nᵀ (the springs'
   * directions now), by conjugate gradients preconditioned by R·H₀⁻¹·Rᵀ: H₀ the same matrix at rest (factored once,
   * woodburyPreconditioner), R the particles' rotations from rest (stiffness warping, Müller et al. 2002) — symmetric
   * positive definite whatever R is.
   */
  framePrimal() {
    const { n, x, v, xt, xOld, c0, w3, D, pinned, opts, springs, rest, alpha, nrm, mass } = this;
    const h = this.h, g = this.params.gravity, inertia = 1 / (h * h), m = alpha.length;
    const { H, v: hv } = this.wood, { R } = this.warp, row = this.row;
    const gr = this.gr ??= new Float64Array(3 * n), rr3 = this.rr3 ??= new Float64Array(3 * n), z3 = this.z3 ??= new Float64Array(3 * n);
    const p3 = this.p3 ??= new Float64Array(3 * n), q3 = this.q3 ??= new Float64Array(3 * n), len = this.len ??= new Float64Array(m);
    const precondition = (r, z) => {
      for (let i = 0; i < n; i++) {
        if (pinned[i]) continue;
        const q = 3 * row[i], o = 9 * i, a = r[3 * i], b = r[3 * i + 1], c = r[3 * i + 2];
        hv[q] = R[o] * a + R[o + 3] * b + R[o + 6] * c;
        hv[q + 1] = R[o + 1] * a + R[o + 4] * b + R[o + 7] * c;
        hv[q + 2] = R[o + 2] * a + R[o + 5] * b + R[o + 8] * c;
      }
      H.solve(hv);
      for (let i = 0; i < n; i++) {
        if (pinned[i]) { z[3 * i] = z[3 * i + 1] = z[3 * i + 2] = 0; continue; }
        const q = 3 * row[i], o = 9 * i, a = hv[q], b = hv[q + 1], c = hv[q + 2];
        z[3 * i] = R[o] * a + R[o + 1] * b + R[o + 2] * c;
        z[3 * i + 1] = R[o + 3] * a + R[o + 4] * b + R[o + 5] * c;
        z[3 * i + 2] = R[o + 6] * a + R[o + 7] * b + R[o + 8] * c;
      }
    };
    // out = H·u
    const applyH = (u, out) => {
      this.applyA(u, out);
      for (let s = 0; s < m; s++) {
        const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
        const dn = nrm[3 * s] * (u[a] - u[b]) + nrm[3 * s + 1] * (u[a + 1] - u[b + 1]) + nrm[3 * s + 2] * (u[a + 2] - u[b + 2]);
        const t = dn / alpha[s];
        for (let c = 0; c < 3; c++) { out[a + c] += t * nrm[3 * s + c]; out[b + c] -= t * nrm[3 * s + c]; }
      }
      for (let i = 0; i < n; i++) if (pinned[i]) out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = 0;
    };
    for (let sub = 0; sub < opts.substeps; sub++) {
      xOld.set(x);
      for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) xt[3 * i + c] = pinned[i] ? x[3 * i + c] : x[3 * i + c] + h * v[3 * i + c] + h * h * g[c];
      x.set(xt);
      const cg0 = this.cgIterations;
      for (let it = 0; it < opts.iterations; it++) {
        this.rotations(x);
        // ∇E = M/h²(x − x̃) + B·x + Σ k(l − l₀)·n (pinned particles: none)
        for (let k = 0; k < 3 * n; k++) w3[k] = x[k];
        this.applyA(w3, gr);
        for (let i = 0; i < n; i++) if (!pinned[i]) for (let c = 0; c < 3; c++) gr[3 * i + c] -= mass[i] * inertia * xt[3 * i + c];
        // the stencils' terms of pinned particles (applyA leaves them out): B·x over every entry
        for (const { idx, K, w } of this.stencils) {
          for (let c = 0; c < 3; c++) {
            let kx = 0;
            for (let a = 0; a < idx.length; a++) if (pinned[idx[a]]) kx += K[a] * x[3 * idx[a] + c];
            for (let a = 0; a < idx.length; a++) if (!pinned[idx[a]]) gr[3 * idx[a] + c] += w * K[a] * kx;
          }
        }
        for (let s = 0; s < m; s++) {
          const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
          const d0 = x[a] - x[b], d1 = x[a + 1] - x[b + 1], d2 = x[a + 2] - x[b + 2], l = Math.hypot(d0, d1, d2);
          len[s] = l;
          nrm[3 * s] = d0 / l; nrm[3 * s + 1] = d1 / l; nrm[3 * s + 2] = d2 / l;
          const t = (l - rest[s]) / alpha[s];
          for (let c = 0; c < 3; c++) { gr[a + c] += t * nrm[3 * s + c]; gr[b + c] -= t * nrm[3 * s + c]; }
        }
        for (let i = 0; i < n; i++) if (pinned[i]) gr[3 * i] = gr[3 * i + 1] = gr[3 * i + 2] = 0;
        // conjugate gradients on H·δx = −∇E
        let r0 = 0;
        for (let k = 0; k < 3 * n; k++) { rr3[k] = -gr[k]; r0 += rr3[k] * rr3[k]; }
        D.fill(0);
        precondition(rr3, z3);
        let rz = 0;
        for (let k = 0; k < 3 * n; k++) rz += rr3[k] * z3[k];
        p3.set(z3);
        for (let k = 0; k < opts.maxCg && rz > 0; k++) {
          this.cgIterations++;
          applyH(p3, q3);
          let pq = 0;
          for (let j = 0; j < 3 * n; j++) pq += p3[j] * q3[j];
          const ak = rz / pq;
          let rr = 0;
          for (let j = 0; j < 3 * n; j++) { D[j] += ak * p3[j]; rr3[j] -= ak * q3[j]; rr += rr3[j] * rr3[j]; }
          if (rr <= opts.tol * opts.tol * r0) break;
          precondition(rr3, z3);
          let rzNew = 0;
          for (let j = 0; j < 3 * n; j++) rzNew += rr3[j] * z3[j];
          const bk = rzNew / rz;
          rz = rzNew;
          for (let j = 0; j < 3 * n; j++) p3[j] = z3[j] + bk * p3[j];
        }
        for (let k = 0; k < 3 * n; k++) x[k] += D[k];
      }
      for (let k = 0; k < 3 * n; k++) v[k] = (x[k] - xOld[k]) / h;
      this.lastCg = this.cgIterations - cg0;
      this.substepsRun++;
    }
  }

  /** One frame of 1/60 s. */
  frame() {
    if (this.opts.precondition === 'primal') { this.framePrimal(); return; }
    const { n, x, v, xt, xOld, c0, xh, w3, D, pinned, opts, springs, rest, alpha, f, nrm, rhs, r, z, p, sp, df, diag, mass } = this;
    const h = this.h, g = this.params.gravity, inertia = 1 / (h * h), m = alpha.length;
    for (let sub = 0; sub < opts.substeps; sub++) {
      xOld.set(x);
      for (let i = 0; i < n; i++) {
        for (let c = 0; c < 3; c++) xt[3 * i + c] = pinned[i] ? x[3 * i + c] : x[3 * i + c] + h * v[3 * i + c] + h * h * g[c];
        for (let c = 0; c < 3; c++) c0[3 * i + c] = pinned[i] ? 0 : mass[i] * inertia * xt[3 * i + c];
      }
      for (const { idx, K, w } of this.stencils) {
        for (let a = 0; a < idx.length; a++) {
          if (pinned[idx[a]]) continue;
          for (let b = 0; b < idx.length; b++) if (pinned[idx[b]]) for (let c = 0; c < 3; c++) c0[3 * idx[a] + c] -= w * K[a] * K[b] * xt[3 * idx[b] + c];
        }
      }
      x.set(xt);
      // refactor the preconditioner at the cloth's directions now when the last substep needed too many iterations
      if (this.wood && this.lastCg > opts.refresh) this.woodburyPreconditioner(x);
      const cg0 = this.cgIterations;
      for (let it = 0; it < opts.iterations; it++) {
        for (let s = 0; s < m; s++) {
          const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
          const d0 = x[a] - x[b], d1 = x[a + 1] - x[b + 1], d2 = x[a + 2] - x[b + 2], l = Math.hypot(d0, d1, d2);
          nrm[3 * s] = d0 / l; nrm[3 * s + 1] = d1 / l; nrm[3 * s + 2] = d2 / l;
          rhs[s] = -(l - rest[s]) - alpha[s] * f[s];
        }
        if (this.warp) this.rotations(x);
        // x̂ = A⁻¹(c0 + Jᵀf), pinned where they are
        this.jt(f, xh);
        for (let k = 0; k < 3 * n; k++) xh[k] += c0[k];
        this.solveA(xh);
        for (let i = 0; i < n; i++) if (pinned[i]) for (let c = 0; c < 3; c++) xh[3 * i + c] = x[3 * i + c];
        for (let k = 0; k < 3 * n; k++) w3[k] = xh[k] - x[k];
        this.j(w3, sp);
        let rr0 = 0;
        for (let s = 0; s < m; s++) { rhs[s] -= sp[s]; rr0 += rhs[s] * rhs[s]; }
        // conjugate gradients on (J A⁻¹ Jᵀ + α)·δf = rhs, preconditioned by its diagonal; D accumulates A⁻¹Jᵀδf
        df.fill(0); D.fill(0); r.set(rhs);
        let rz = 0;
        this.precondition(r, z);
        for (let s = 0; s < m; s++) rz += r[s] * z[s];
        p.set(z);
        for (let k = 0; k < opts.maxCg && rz > 0; k++) {
          this.cgIterations++;
          this.jt(p, w3);
          this.solveA(w3);
          this.j(w3, sp);
          let pSp = 0;
          for (let s = 0; s < m; s++) { sp[s] += alpha[s] * p[s]; pSp += p[s] * sp[s]; }
          const ak = rz / pSp;
          let rr = 0;
          for (let s = 0; s < m; s++) { df[s] += ak * p[s]; r[s] -= ak * sp[s]; rr += r[s] * r[s]; }
          for (let q = 0; q < 3 * n; q++) D[q] += ak * w3[q];
          if (rr <= opts.tol * opts.tol * rr0) break;
          let rzNew = 0;
          this.precondition(r, z);
          for (let s = 0; s < m; s++) rzNew += r[s] * z[s];
          const bk = rzNew / rz;
          rz = rzNew;
          for (let s = 0; s < m; s++) p[s] = z[s] + bk * p[s];
        }
        for (let s = 0; s < m; s++) f[s] += df[s];
        for (let i = 0; i < n; i++) if (!pinned[i]) for (let c = 0; c < 3; c++) x[3 * i + c] = xh[3 * i + c] + D[3 * i + c];
      }
      for (let k = 0; k < 3 * n; k++) v[k] = (x[k] - xOld[k]) / h;
      this.lastCg = this.cgIterations - cg0;
      this.substepsRun++;
    }
  }
}
