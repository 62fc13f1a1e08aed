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
   * 'rest': J₀·D⁻¹·J₀ᵀ + α factored once; 'woodbury': the Schur complement at rest, exactly), refresh (with
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
    if (this.opts.precondition === 'woodbury') this.woodburyPreconditioner();
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

  /** One frame of 1/60 s. */
  frame() {
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
