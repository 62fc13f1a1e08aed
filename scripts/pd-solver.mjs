// A Projective Dynamics prototype (Bouaziz, Martin, Liu, Kavan & Pauly 2014, "Projective Dynamics: Fusing
// Constraint Projections for Fast Simulation"; for mass-springs Liu, Bargteil, O'Brien & Kavan 2013) over Drape's
// own model and parameters, for scripts/pd-study.mjs. Standalone: it only reads a ClothModel and SimParams built by
// the library (dist/), and steps its own float64 arrays. Not integrated into the core.
//
// Per substep h, with x̃ = x + h·v + h²·g the prediction, it minimises
//   (1/2h²)·|M^½(x − x̃)|² + Σ_springs ½·k_s·|x_a − x_b − d_s|² + Σ_stencils ½·(B/A)·|Σ K_i x_i|²
// over x, and over d_s with |d_s| = L_s (the local step: d_s = L_s·(x_a − x_b)/|x_a − x_b|). The springs are the
// model's springs with params.stiffness (structural, shear, and the skip-one bend springs unless solver.bending
// is a stencil model, where params gives them 0); the bending stencils (model.stencils: Bergou et al. 2006's hinges
// or the cotangent Laplacian's vertices, CSR) are quadratic in x, so they sit in the system matrix exactly and need
// no local step. Pinned particles are not unknowns: their terms
// go to the right-hand side. The global step solves
//   A·x = M/h²·x̃ + Σ k_s·S_sᵀ·d_s + (pinned terms),   A = M/h² + Σ k_s·S_sᵀS_s + Σ (B/A_e)·K_eK_eᵀ,
// one scalar matrix for the three coordinates, constant while the mesh, h, the stiffnesses and the pins are:
// ordered once by reverse Cuthill–McKee and factored once (envelope / skyline Cholesky, written here).
// Instead of the direct solve, `global: 'jacobi'` takes one Jacobi sweep of the same A per local step, accelerated
// by Chebyshev's semi-iterative method (Wang 2015, "A Chebyshev Semi-Iterative Approach for Accelerating Projective
// and Position-Based Dynamics"): the GPU-friendly path.
// Material damping is not modelled: implicit Euler's own damping is all there is.
import { heldHingeShare } from '../dist/core/solvers/global-bending.js';

/**
 * `params` with the hinges beside a held triangle (edge and one wing pinned in `pinned`) counted on their free side,
 * as the global bending step counts them (heldHingeShare); params itself where the bending is not the hinges.
 */
export function withHeldHinges(model, params, pinned) {
  if (params.bending !== 'hinges') return params;
  const { vertices, offsets } = model.stencils.hinges;
  const compliance = Float64Array.from(params.stencilCompliance, (a, e) => a * heldHingeShare(model.restPositions, vertices, offsets[e], pinned));
  return { ...params, stencilCompliance: compliance };
}

/** Reverse Cuthill–McKee order of a graph given as adjacency lists (arrays of neighbour indices). */
export function rcm(adj) {
  const n = adj.length;
  const deg = adj.map((a) => a.length);
  const order = [];
  const seen = new Uint8Array(n);
  const bfs = (start, mark) => {
    // returns the last level
    const visited = new Uint8Array(n);
    let level = [start];
    visited[start] = 1;
    let last = level;
    while (level.length) {
      last = level;
      const next = [];
      for (const u of level) for (const v of adj[u]) if (!visited[v] && !mark[v]) { visited[v] = 1; next.push(v); }
      level = next;
    }
    return last;
  };
  for (let s0 = 0; s0 < n; s0++) {
    if (seen[s0]) continue;
    // pseudo-peripheral start: the lowest-degree node of the last BFS level, twice
    let start = s0;
    for (let k = 0; k < 2; k++) {
      const last = bfs(start, seen);
      start = last.reduce((a, b) => (deg[b] < deg[a] ? b : a), last[0]);
    }
    const queue = [start];
    seen[start] = 1;
    for (let q = 0; q < queue.length; q++) {
      const u = queue[q];
      order.push(u);
      const nb = adj[u].filter((v) => !seen[v]).sort((a, b) => deg[a] - deg[b]);
      for (const v of nb) { seen[v] = 1; queue.push(v); }
    }
  }
  return Int32Array.from(order.reverse());
}

/**
 * Envelope (skyline) Cholesky of a symmetric positive definite matrix given as a map of lower entries in a
 * permuted numbering: row i holds columns first[i] … i. Factor in place; solve three right-hand sides at once.
 */
export class EnvelopeCholesky {
  constructor(n, first) {
    this.n = n;
    this.first = first;
    this.start = new Int32Array(n + 1);
    for (let i = 0; i < n; i++) this.start[i + 1] = this.start[i] + (i - first[i] + 1);
    this.L = new Float64Array(this.start[n]);
  }
  /** entry (i, j), j ≤ i, of the matrix before factoring */
  add(i, j, v) {
    if (j > i) [i, j] = [j, i];
    this.L[this.start[i] + (j - this.first[i])] += v;
  }
  factor() {
    const { n, first, start, L } = this;
    for (let i = 0; i < n; i++) {
      const fi = first[i], si = start[i] - fi; // L[si + k] is L(i, k)
      for (let j = fi; j < i; j++) {
        const fj = first[j], sj = start[j] - fj;
        const k0 = fi > fj ? fi : fj;
        let s = L[si + j];
        for (let k = k0; k < j; k++) s -= L[si + k] * L[sj + k];
        L[si + j] = s / L[sj + j];
      }
      let d = L[si + i];
      for (let k = fi; k < i; k++) d -= L[si + k] * L[si + k];
      if (!(d > 0)) throw new Error(`EnvelopeCholesky: not positive definite at row ${i}`);
      L[si + i] = Math.sqrt(d);
    }
  }
  /** solves A·x = b for three interleaved right-hand sides (b, stride 3, overwritten by x) */
  solve3(b) {
    const { n, first, start, L } = this;
    for (let i = 0; i < n; i++) {
      const fi = first[i], si = start[i] - fi;
      let s0 = b[3 * i], s1 = b[3 * i + 1], s2 = b[3 * i + 2];
      for (let k = fi; k < i; k++) {
        const l = L[si + k];
        s0 -= l * b[3 * k]; s1 -= l * b[3 * k + 1]; s2 -= l * b[3 * k + 2];
      }
      const d = 1 / L[si + i];
      b[3 * i] = s0 * d; b[3 * i + 1] = s1 * d; b[3 * i + 2] = s2 * d;
    }
    for (let i = n - 1; i >= 0; i--) {
      const fi = first[i], si = start[i] - fi;
      const d = 1 / L[si + i];
      const x0 = (b[3 * i] *= d), x1 = (b[3 * i + 1] *= d), x2 = (b[3 * i + 2] *= d);
      for (let k = fi; k < i; k++) {
        const l = L[si + k];
        b[3 * k] -= l * x0; b[3 * k + 1] -= l * x1; b[3 * k + 2] -= l * x2;
      }
    }
  }
}

export class PDSolver {
  /**
   * model, params: the library's; pinned: Uint8Array (1 = fixed); x0: start positions (stride 3).
   * opts: { substeps, iterations, global: 'direct' | 'jacobi', rho (Chebyshev), gamma (under-relaxation), static }
   * static: no inertia (a static equilibrium solve; substeps and the time step are then meaningless).
   */
  constructor(model, params, pinned, x0, opts) {
    this.model = model;
    this.params = params;
    this.opts = { substeps: 1, iterations: 10, global: 'direct', gamma: 0.9, chebyshevDelay: 5, ...opts };
    const n = model.particleCount;
    this.n = n;
    this.x = Float64Array.from(x0);
    this.v = new Float64Array(3 * n);
    this.pinned = pinned;
    this.mass = new Float64Array(n);
    for (let i = 0; i < n; i++) this.mass[i] = params.mass * model.massWeights[i];
    // springs with stiffness, hinges with rigidity
    const sp = [], sk = [], sl = [];
    for (let s = 0; s < model.restLengths.length; s++) {
      const k = params.stiffness[s];
      if (!(k > 0)) continue;
      const a = model.springs[2 * s], b = model.springs[2 * s + 1];
      if (pinned[a] && pinned[b]) continue;
      sp.push(a, b); sk.push(k); sl.push(model.restLengths[s]);
    }
    this.springs = Int32Array.from(sp); this.k = Float64Array.from(sk); this.rest = Float64Array.from(sl);
    // the bending stencils of params.bending (CSR: stencil e over hinges[hOff[e]] … hinges[hOff[e + 1] − 1])
    const hs = [], hw = [], hK = [], ho = [0];
    if (params.bending !== 'springs') {
      const st = model.stencils[params.bending];
      for (let e = 0; e < st.areas.length; e++) {
        const a = params.stencilCompliance[e];
        if (!(a < Infinity) || !(a > 0)) continue;
        const idx = st.vertices.subarray(st.offsets[e], st.offsets[e + 1]);
        if (idx.every((i) => pinned[i])) continue;
        hs.push(...idx); hw.push(1 / a); hK.push(...st.weights.subarray(st.offsets[e], st.offsets[e + 1])); ho.push(hs.length);
      }
    }
    this.hinges = Int32Array.from(hs); this.hw = Float64Array.from(hw); this.hK = Float64Array.from(hK); this.hOff = Int32Array.from(ho);
    // free particles, in RCM order
    const adj = Array.from({ length: n }, () => new Set());
    const link = (a, b) => { if (!pinned[a] && !pinned[b] && a !== b) { adj[a].add(b); adj[b].add(a); } };
    for (let s = 0; s < this.k.length; s++) link(this.springs[2 * s], this.springs[2 * s + 1]);
    for (let e = 0; e < this.hw.length; e++) for (let p = ho[e]; p < ho[e + 1]; p++) for (let q = p + 1; q < ho[e + 1]; q++) link(this.hinges[p], this.hinges[q]);
    const freeIds = [];
    for (let i = 0; i < n; i++) if (!pinned[i]) freeIds.push(i);
    const local = new Int32Array(n).fill(-1);
    freeIds.forEach((i, k) => { local[i] = k; });
    const order = rcm(freeIds.map((i) => [...adj[i]].map((j) => local[j])));
    this.nf = freeIds.length;
    this.perm = new Int32Array(this.nf); // new index → particle
    this.iperm = new Int32Array(n).fill(-1); // particle → new index
    for (let r = 0; r < this.nf; r++) { this.perm[r] = freeIds[order[r]]; this.iperm[freeIds[order[r]]] = r; }
    this.adj = adj;
    this.b = new Float64Array(3 * this.nf);
    this.xt = new Float64Array(3 * n);
    this.xOld = new Float64Array(3 * n);
    this.setStep();
  }

  /** (Re)builds and factors the system matrix for the current substep length, pins and stiffnesses. */
  setStep() {
    const { model, n, nf, iperm, pinned, opts } = this;
    const h = (1 / 60) / opts.substeps;
    this.h = h;
    const inertia = opts.static ? 0 : 1 / (h * h);
    this.inertia = inertia;
    const first = new Int32Array(nf);
    for (let r = 0; r < nf; r++) {
      let f = r;
      for (const j of this.adj[this.perm[r]]) { const c = iperm[j]; if (c < f) f = c; }
      first[r] = f;
    }
    const t0 = performance.now();
    // diagonal and off-diagonal entries, in CSR too for the Jacobi path
    const diag = new Float64Array(nf);
    const off = Array.from({ length: nf }, () => new Map());
    const put = (i, j, v) => { // i, j particles, both free
      const a = iperm[i], c = iperm[j];
      if (a === c) diag[a] += v; else { off[a].set(c, (off[a].get(c) ?? 0) + v); }
    };
    for (let i = 0; i < n; i++) if (!pinned[i]) put(i, i, this.mass[i] * inertia);
    // constant right-hand side from pins: for spring terms k·x_b (handled per iteration with d), hinge terms here
    this.bPin = new Float64Array(3 * nf);
    const x = this.x;
    for (let s = 0; s < this.k.length; s++) {
      const a = this.springs[2 * s], b = this.springs[2 * s + 1], k = this.k[s];
      if (!pinned[a]) put(a, a, k);
      if (!pinned[b]) put(b, b, k);
      if (!pinned[a] && !pinned[b]) { put(a, b, -k); put(b, a, -k); }
      else {
        const f = pinned[a] ? b : a, p = pinned[a] ? a : b, r = iperm[f];
        for (let c = 0; c < 3; c++) this.bPin[3 * r + c] += k * x[3 * p + c];
      }
    }
    const ho = this.hOff;
    for (let e = 0; e < this.hw.length; e++) {
      const w = this.hw[e];
      for (let p = ho[e]; p < ho[e + 1]; p++) {
        const i = this.hinges[p];
        if (pinned[i]) continue;
        for (let q = ho[e]; q < ho[e + 1]; q++) {
          const j = this.hinges[q], v = w * this.hK[p] * this.hK[q];
          if (!pinned[j]) put(i, j, v);
          else for (let c = 0; c < 3; c++) this.bPin[3 * iperm[i] + c] -= v * x[3 * j + c];
        }
      }
    }
    this.diag = diag;
    if (opts.global === 'direct') {
      const chol = new EnvelopeCholesky(nf, first);
      for (let r = 0; r < nf; r++) {
        chol.add(r, r, diag[r]);
        for (const [c, v] of off[r]) if (c < r) chol.add(r, c, v);
      }
      chol.factor();
      this.chol = chol;
      this.envelope = chol.L.length;
    } else {
      const rowStart = new Int32Array(nf + 1);
      for (let r = 0; r < nf; r++) rowStart[r + 1] = rowStart[r] + off[r].size;
      const cols = new Int32Array(rowStart[nf]), vals = new Float64Array(rowStart[nf]);
      for (let r = 0; r < nf; r++) { let k = rowStart[r]; for (const [c, v] of off[r]) { cols[k] = c; vals[k++] = v; } }
      this.csr = { rowStart, cols, vals };
      if (opts.rho === undefined) opts.rho = this.jacobiRadius();
      this.xPrevIt = new Float64Array(3 * nf);
      this.xCur = new Float64Array(3 * nf);
      this.xNew = new Float64Array(3 * nf);
    }
    this.factorMs = performance.now() - t0;
  }

  /** Spectral radius of the Jacobi iteration matrix D⁻¹(D − A) by power iteration (Chebyshev's ρ). */
  jacobiRadius() {
    const { nf, diag } = this, { rowStart, cols, vals } = this.csr;
    let v = new Float64Array(nf).map(() => Math.random() - 0.5), w = new Float64Array(nf), lam = 0;
    for (let it = 0; it < 300; it++) {
      let norm = 0;
      for (let r = 0; r < nf; r++) {
        let s = 0;
        for (let k = rowStart[r]; k < rowStart[r + 1]; k++) s -= vals[k] * v[cols[k]];
        w[r] = s / diag[r]; norm += w[r] * w[r];
      }
      norm = Math.sqrt(norm);
      lam = norm / Math.sqrt(v.reduce((a, b) => a + b * b, 0));
      for (let r = 0; r < nf; r++) v[r] = w[r] / norm;
    }
    return lam;
  }

  /** The right-hand side M/h²·x̃ + Σ k·Sᵀd + pinned terms, from the current positions' local step. */
  assemble() {
    const { b, x, xt, iperm, pinned, springs, k, rest, nf } = this;
    b.set(this.bPin);
    const inertia = this.inertia;
    for (let r = 0; r < nf; r++) {
      const i = this.perm[r], m = this.mass[i] * inertia;
      b[3 * r] += m * xt[3 * i]; b[3 * r + 1] += m * xt[3 * i + 1]; b[3 * r + 2] += m * xt[3 * i + 2];
    }
    if (this.opts.static) {
      const g = this.params.gravity;
      for (let r = 0; r < nf; r++) { const m = this.mass[this.perm[r]]; b[3 * r] += m * g[0]; b[3 * r + 1] += m * g[1]; b[3 * r + 2] += m * g[2]; }
    }
    for (let s = 0; s < k.length; s++) {
      const a = springs[2 * s], c = springs[2 * s + 1];
      const dx = x[3 * a] - x[3 * c], dy = x[3 * a + 1] - x[3 * c + 1], dz = x[3 * a + 2] - x[3 * c + 2];
      const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
      const f = len > 1e-12 ? (k[s] * rest[s]) / len : 0;
      if (!pinned[a]) { const r = 3 * iperm[a]; b[r] += f * dx; b[r + 1] += f * dy; b[r + 2] += f * dz; }
      if (!pinned[c]) { const r = 3 * iperm[c]; b[r] -= f * dx; b[r + 1] -= f * dy; b[r + 2] -= f * dz; }
    }
  }

  /** One frame of 1/60 s. */
  frame() {
    const { n, x, v, xt, xOld, pinned, opts, perm, nf } = this;
    const h = this.h, g = this.params.gravity;
    for (let sub = 0; sub < opts.substeps; sub++) {
      xOld.set(x);
      for (let i = 0; i < n; i++) {
        if (pinned[i]) { for (let c = 0; c < 3; c++) xt[3 * i + c] = x[3 * i + c]; continue; }
        for (let c = 0; c < 3; c++) xt[3 * i + c] = x[3 * i + c] + h * v[3 * i + c] + h * h * g[c];
      }
      x.set(xt);
      if (opts.global === 'direct') {
        for (let it = 0; it < opts.iterations; it++) {
          this.assemble();
          this.chol.solve3(this.b);
          for (let r = 0; r < nf; r++) { const i = perm[r]; x[3 * i] = this.b[3 * r]; x[3 * i + 1] = this.b[3 * r + 1]; x[3 * i + 2] = this.b[3 * r + 2]; }
        }
      } else this.chebyshevJacobi();
      if (!opts.static) for (let j = 0; j < 3 * n; j++) v[j] = (x[j] - xOld[j]) / h;
    }
  }

  /** opts.iterations local steps, each followed by one Chebyshev-accelerated Jacobi sweep (Wang 2015). */
  chebyshevJacobi() {
    const { x, perm, nf, diag, opts } = this, { rowStart, cols, vals } = this.csr;
    const cur = this.xCur, prev = this.xPrevIt, nw = this.xNew, b = this.b;
    for (let r = 0; r < nf; r++) { const i = perm[r]; for (let c = 0; c < 3; c++) cur[3 * r + c] = prev[3 * r + c] = x[3 * i + c]; }
    const rho2 = opts.rho * opts.rho, gamma = opts.gamma;
    let omega = 1;
    for (let it = 0; it < opts.iterations; it++) {
      this.assemble();
      if (it < opts.chebyshevDelay) omega = 1;
      else if (it === opts.chebyshevDelay) omega = 2 / (2 - rho2);
      else omega = 4 / (4 - rho2 * omega);
      for (let r = 0; r < nf; r++) {
        let s0 = b[3 * r], s1 = b[3 * r + 1], s2 = b[3 * r + 2];
        for (let k = rowStart[r]; k < rowStart[r + 1]; k++) {
          const c = 3 * cols[k], a = vals[k];
          s0 -= a * cur[c]; s1 -= a * cur[c + 1]; s2 -= a * cur[c + 2];
        }
        const d = 1 / diag[r], q = 3 * r;
        nw[q] = omega * (gamma * (s0 * d - cur[q]) + cur[q] - prev[q]) + prev[q];
        nw[q + 1] = omega * (gamma * (s1 * d - cur[q + 1]) + cur[q + 1] - prev[q + 1]) + prev[q + 1];
        nw[q + 2] = omega * (gamma * (s2 * d - cur[q + 2]) + cur[q + 2] - prev[q + 2]) + prev[q + 2];
      }
      prev.set(cur); cur.set(nw);
      for (let r = 0; r < nf; r++) { const i = perm[r]; x[3 * i] = cur[3 * r]; x[3 * i + 1] = cur[3 * r + 1]; x[3 * i + 2] = cur[3 * r + 2]; }
    }
  }
}

/**
 * The static equilibrium of the same energy (springs, hinges, gravity; pins fixed) by Newton's method with a line
 * search: the converged answer the dynamic solvers should settle to. The spring Hessian's transverse part
 * k·(1 − L/l) is clamped at 0 (a descent direction whatever the state); the 3n × 3n system uses the envelope
 * Cholesky in the RCM order of the particles. Returns { energy, gradient norm, iterations } and leaves pd.x at the
 * minimum it finds from pd.x.
 */
export function newtonStatic(pd, maxIt = 60, tol = 1e-10) {
  const { nf, perm, iperm, pinned, springs, k, rest, hinges, hw, hK, hOff, mass } = pd;
  const x = pd.x, g = pd.params.gravity;
  const energy = (y) => {
    let e = 0;
    for (let s = 0; s < k.length; s++) {
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      const l = Math.hypot(y[a] - y[b], y[a + 1] - y[b + 1], y[a + 2] - y[b + 2]);
      e += 0.5 * k[s] * (l - rest[s]) ** 2;
    }
    for (let h = 0; h < hw.length; h++) for (let c = 0; c < 3; c++) {
      let C = 0;
      for (let p = hOff[h]; p < hOff[h + 1]; p++) C += hK[p] * y[3 * hinges[p] + c];
      e += 0.5 * hw[h] * C * C;
    }
    for (let i = 0; i < pd.n; i++) e -= mass[i] * (g[0] * y[3 * i] + g[1] * y[3 * i + 1] + g[2] * y[3 * i + 2]);
    return e;
  };
  const firstBlock = new Int32Array(nf);
  for (let r = 0; r < nf; r++) { let f = r; for (const j of pd.adj[perm[r]]) f = Math.min(f, iperm[j]); firstBlock[r] = f; }
  const first = new Int32Array(3 * nf);
  for (let q = 0; q < 3 * nf; q++) first[q] = 3 * firstBlock[Math.floor(q / 3)];
  let E = energy(x), gnorm = Infinity, it = 0;
  const grad = new Float64Array(3 * nf), trial = new Float64Array(3 * pd.n);
  for (; it < maxIt; it++) {
    const H = new EnvelopeCholesky(3 * nf, first);
    grad.fill(0);
    for (let r = 0; r < nf; r++) { const i = perm[r]; for (let c = 0; c < 3; c++) { grad[3 * r + c] -= mass[i] * g[c]; H.add(3 * r + c, 3 * r + c, 1e-9); } }
    for (let s = 0; s < k.length; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1];
      const d = [x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]];
      const l = Math.hypot(...d), n = d.map((v) => v / l);
      const f = k[s] * (l - rest[s]), t = Math.max(0, k[s] * (1 - rest[s] / l));
      const blk = (p, q) => (p === q ? 1 : 0);
      const ends = [[a, 1], [b, -1]].filter(([i]) => !pinned[i]);
      for (const [i, si] of ends) for (let c = 0; c < 3; c++) grad[3 * iperm[i] + c] += si * f * n[c];
      for (const [i, si] of ends) for (const [j, sj] of ends) {
        const ri = iperm[i], rj = iperm[j];
        if (rj > ri) continue;
        for (let c = 0; c < 3; c++) for (let e = 0; e < 3; e++) {
          if (ri === rj && e > c) continue;
          H.add(3 * ri + c, 3 * rj + e, si * sj * (k[s] * n[c] * n[e] + t * (blk(c, e) - n[c] * n[e])));
        }
      }
    }
    for (let h = 0; h < hw.length; h++) {
      const C = [0, 0, 0];
      for (let p = hOff[h]; p < hOff[h + 1]; p++) for (let c = 0; c < 3; c++) C[c] += hK[p] * x[3 * hinges[p] + c];
      for (let p = hOff[h]; p < hOff[h + 1]; p++) {
        const i = hinges[p];
        if (pinned[i]) continue;
        for (let c = 0; c < 3; c++) grad[3 * iperm[i] + c] += hw[h] * hK[p] * C[c];
        for (let q = hOff[h]; q < hOff[h + 1]; q++) {
          const j = hinges[q];
          if (pinned[j] || iperm[j] > iperm[i]) continue;
          for (let c = 0; c < 3; c++) H.add(3 * iperm[i] + c, 3 * iperm[j] + c, hw[h] * hK[p] * hK[q]);
        }
      }
    }
    gnorm = Math.sqrt(grad.reduce((s, v) => s + v * v, 0));
    if (gnorm < tol) break;
    H.factor();
    const p = Float64Array.from(grad, (v) => -v);
    // solve3 works on triples of right-hand sides; here one system of size 3nf: a scalar solve
    solveScalar(H, p);
    let step = 1;
    for (; step > 1e-8; step /= 2) {
      trial.set(x);
      for (let r = 0; r < nf; r++) for (let c = 0; c < 3; c++) trial[3 * perm[r] + c] += step * p[3 * r + c];
      const Et = energy(trial);
      if (Et < E) { x.set(trial); E = Et; break; }
    }
    if (step <= 1e-8) break;
  }
  return { energy: E, gnorm, iterations: it };
}

function solveScalar(chol, b) {
  const { n, first, start, L } = chol;
  for (let i = 0; i < n; i++) {
    const fi = first[i], si = start[i] - fi;
    let s = b[i];
    for (let k = fi; k < i; k++) s -= L[si + k] * b[k];
    b[i] = s / L[si + i];
  }
  for (let i = n - 1; i >= 0; i--) {
    const fi = first[i], si = start[i] - fi;
    const xi = (b[i] /= L[si + i]);
    for (let k = fi; k < i; k++) b[k] -= L[si + k] * xi;
  }
}
