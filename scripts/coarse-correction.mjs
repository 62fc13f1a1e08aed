// Issue 10 prototype (scripts/coupled-study.mjs --mode two-level): a coarse-space Gauss–Newton correction for the
// springs, beside XPBD's sweep. Not a script of its own.
//
// The substep's implicit-Euler objective for the springs is
//   G(x) = (1/2h²)·|x − y|²_M + Σ_s ½·k_s·(|x_a − x_b| − L_s)²,     k_s = 1/α_s,
// y the prediction (what XPBD converged would minimise). One Gauss–Seidel sweep leaves the smooth part of its
// residual (a load carried a few springs per substep), which is what biases the sweep's statics. The correction
// takes one Gauss–Newton step of G restricted to a coarse space of smooth displacements, x ← x + P·δ with
//   (Pᵀ·H·P)·δ = −Pᵀ·∇G(x),   H = M/h² + Σ_s k_s·J_sᵀJ_s,   J_s = n_sᵀ·[I, −I],
// the springs' directions n_s where the cloth is now (so a turn of the whole cloth costs nothing: J_s·δ = 0 for a
// rigid rotation to first order, unlike a constant Projective Dynamics matrix). P is bilinear interpolation from a
// G × G grid of nodes over the cloth's texture coordinates (a partition of unity, so a translation is in the space and
// free fall is left alone: ∇G = 0 at x = y with the springs at rest). Pinned particles (inverse mass 0) are not
// moved. The coarse system is dense (3 per node in use) and solved by Cholesky each time it is applied.

export class CoarseCorrection {
  constructor(model, G) {
    const n = model.particleCount, uv = model.uvs;
    let u0 = Infinity, u1 = -Infinity, v0 = Infinity, v1 = -Infinity;
    for (let i = 0; i < n; i++) {
      u0 = Math.min(u0, uv[2 * i]); u1 = Math.max(u1, uv[2 * i]);
      v0 = Math.min(v0, uv[2 * i + 1]); v1 = Math.max(v1, uv[2 * i + 1]);
    }
    this.node = new Int32Array(4 * n);
    this.weight = new Float64Array(4 * n);
    const used = new Int32Array(G * G).fill(-1);
    let count = 0;
    for (let i = 0; i < n; i++) {
      const gu = ((uv[2 * i] - u0) / (u1 - u0 || 1)) * (G - 1), gv = ((uv[2 * i + 1] - v0) / (v1 - v0 || 1)) * (G - 1);
      const iu = Math.min(Math.floor(gu), G - 2), iv = Math.min(Math.floor(gv), G - 2), fu = gu - iu, fv = gv - iv;
      const corners = [[iu, iv, (1 - fu) * (1 - fv)], [iu + 1, iv, fu * (1 - fv)], [iu, iv + 1, (1 - fu) * fv], [iu + 1, iv + 1, fu * fv]];
      corners.forEach(([a, b, wgt], k) => {
        const g = a + G * b;
        if (wgt > 0 && used[g] < 0) used[g] = count++;
        this.node[4 * i + k] = wgt > 0 ? used[g] : 0;
        this.weight[4 * i + k] = wgt;
      });
    }
    this.nodes = count;
    const N = 3 * count;
    this.A = new Float64Array(N * N);
    this.b = new Float64Array(N);
    this.coef = new Float64Array(8);
    this.ids = new Int32Array(8);
  }

  /**
   * One Gauss–Newton step of the springs' objective over the coarse space, from state.positions, prediction y
   * (Float32Array or Float64Array), substep h [s]; `damping`: the springs' damping term (XPBD's β, as a force
   * β·k·(rate of stretching)) in the step too. Returns the largest move [m].
   */
  /** The springs' objective G at positions x [J·s²/s²: J] (no damping term). */
  objective(model, params, x, w, y, h) {
    const n = model.particleCount, ih2 = 1 / (h * h);
    let e = 0;
    for (let i = 0; i < n; i++) {
      if (!(w[i] > 0)) continue;
      const dx = x[3 * i] - y[3 * i], dy = x[3 * i + 1] - y[3 * i + 1], dz = x[3 * i + 2] - y[3 * i + 2];
      e += (0.5 * ih2 / w[i]) * (dx * dx + dy * dy + dz * dz);
    }
    const springs = model.springs, rest = model.restLengths, compliance = params.compliance;
    for (let s = 0; s < rest.length; s++) {
      if (!(compliance[s] < Infinity)) continue;
      const a = 3 * springs[2 * s], b = 3 * springs[2 * s + 1];
      const d = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]) - rest[s];
      e += (0.5 * d * d) / compliance[s];
    }
    return e;
  }

  apply(model, state, params, h, y, damping = false, geometric = false, search = false) {
    const x = state.positions, xp = state.previousPositions, w = state.invMass, n = model.particleCount;
    const A = this.A, b = this.b, N = 3 * this.nodes, node = this.node, weight = this.weight;
    A.fill(0); b.fill(0);
    const ih2 = 1 / (h * h);
    for (let i = 0; i < n; i++) {
      if (!(w[i] > 0)) continue;
      const m = ih2 / w[i];
      for (let k = 0; k < 4; k++) {
        const wk = weight[4 * i + k];
        if (!(wk > 0)) continue;
        const r = 3 * node[4 * i + k];
        for (let c = 0; c < 3; c++) b[r + c] -= m * wk * (x[3 * i + c] - y[3 * i + c]);
        for (let l = 0; l < 4; l++) {
          const wl = weight[4 * i + l];
          if (!(wl > 0)) continue;
          const s = 3 * node[4 * i + l], v = m * wk * wl;
          for (let c = 0; c < 3; c++) A[(r + c) * N + s + c] += v;
        }
      }
    }
    const springs = model.springs, rest = model.restLengths, compliance = params.compliance, beta = params.springDamping;
    const coef = this.coef, ids = this.ids;
    const unit = this.unit ??= new Float64Array(3);
    for (let s = 0; s < rest.length; s++) {
      const len = springDirection(springs, compliance, w, x, s, unit);
      if (!(len > 0)) continue;
      const alpha = compliance[s], pa = springs[2 * s], pb = springs[2 * s + 1], ja = 3 * pa, jb = 3 * pb;
      const nx = unit[0], ny = unit[1], nz = unit[2];
      let k = 1 / alpha, force = k * (len - rest[s]);
      if (damping && beta[s] > 0) {
        // Rayleigh damping of the stretching rate, as XPBD's: force β·k·(dl/dt), stiffness β·k/h more along n
        const rate = ((x[ja] - xp[ja] - x[jb] + xp[jb]) * nx + (x[ja + 1] - xp[ja + 1] - x[jb + 1] + xp[jb + 1]) * ny + (x[ja + 2] - xp[ja + 2] - x[jb + 2] + xp[jb + 2]) * nz) / h;
        force += beta[s] * k * rate;
        k *= 1 + beta[s] / h;
      }
      // the spring's row of J·P over the nodes: +P_a − P_b (free particles only)
      let m = 0;
      for (const [p, sign] of [[pa, 1], [pb, -1]]) {
        if (!(w[p] > 0)) continue;
        for (let q = 0; q < 4; q++) {
          const wq = weight[4 * p + q];
          if (!(wq > 0)) continue;
          const id = node[4 * p + q];
          let found = -1;
          for (let t = 0; t < m; t++) if (ids[t] === id) found = t;
          if (found >= 0) coef[found] += sign * wq;
          else { ids[m] = id; coef[m] = sign * wq; m++; }
        }
      }
      const nn = [nx * nx, nx * ny, nx * nz, ny * ny, ny * nz, nz * nz];
      // with `geometric`, a stretched spring's transverse stiffness k·(1 − L/l)·(I − n·nᵀ) too (Newton's Hessian with
      // the compressed springs' negative part left out): Gauss–Newton alone takes a move across a taut spring as free
      const g = geometric && len > rest[s] ? (1 - rest[s] / len) : 0;
      if (g > 0) for (let q = 0; q < 6; q++) nn[q] *= 1 - g;
      const gi = g;
      for (let t = 0; t < m; t++) {
        const r = 3 * ids[t], ct = coef[t];
        b[r] -= ct * force * nx; b[r + 1] -= ct * force * ny; b[r + 2] -= ct * force * nz;
        for (let u = 0; u < m; u++) {
          const c = 3 * ids[u], v = k * ct * coef[u];
          A[r * N + c] += v * (nn[0] + gi); A[r * N + c + 1] += v * nn[1]; A[r * N + c + 2] += v * nn[2];
          A[(r + 1) * N + c] += v * nn[1]; A[(r + 1) * N + c + 1] += v * (nn[3] + gi); A[(r + 1) * N + c + 2] += v * nn[4];
          A[(r + 2) * N + c] += v * nn[2]; A[(r + 2) * N + c + 1] += v * nn[4]; A[(r + 2) * N + c + 2] += v * (nn[5] + gi);
        }
      }
    }
    if (!solveDense(A, b, N)) return 0; // a node no free particle weighs: leave the cloth as it is
    let most = 0, step = 1;
    if (this.omega !== undefined && this.omega !== 1) for (let j = 0; j < N; j++) b[j] *= this.omega;
    if (search) {
      // backtracking on the true objective: the step is kept only as far as it lowers G
      const before = this.objective(model, params, x, w, y, h);
      const trial = this.trial ??= new Float64Array(3 * n);
      for (; step > 1 / 64; step *= 0.5) {
        for (let i = 0; i < n; i++) {
          let mx = 0, my = 0, mz = 0;
          if (w[i] > 0) for (let k = 0; k < 4; k++) {
            const wk = weight[4 * i + k], r = 3 * node[4 * i + k];
            if (wk > 0) { mx += wk * b[r]; my += wk * b[r + 1]; mz += wk * b[r + 2]; }
          }
          trial[3 * i] = x[3 * i] + step * mx; trial[3 * i + 1] = x[3 * i + 1] + step * my; trial[3 * i + 2] = x[3 * i + 2] + step * mz;
        }
        if (this.objective(model, params, trial, w, y, h) < before) break;
      }
      if (!(step > 1 / 64)) return 0;
      for (let j = 0; j < N; j++) b[j] *= step;
    }
    for (let i = 0; i < n; i++) {
      if (!(w[i] > 0)) continue;
      let mx = 0, my = 0, mz = 0;
      for (let k = 0; k < 4; k++) {
        const wk = weight[4 * i + k];
        if (!(wk > 0)) continue;
        const r = 3 * node[4 * i + k];
        mx += wk * b[r]; my += wk * b[r + 1]; mz += wk * b[r + 2];
      }
      x[3 * i] += mx; x[3 * i + 1] += my; x[3 * i + 2] += mz;
      if (this.positionOnly) { xp[3 * i] += mx; xp[3 * i + 1] += my; xp[3 * i + 2] += mz; }
      most = Math.max(most, Math.hypot(mx, my, mz));
    }
    return most;
  }
}

// The same idea on XPBD's own (dual) side: after the sweep, one correction of the springs' multipliers over a coarse
// space of aggregates, each aggregate the springs of one cell of a G × G grid over the texture coordinates whose rest
// direction falls in one of `bins` directions (so a column's tension and a row's are separate unknowns). With Δλ = R·μ
// (R: each spring to its aggregate) and the springs' directions now,
//   R·(J·M⁻¹·Jᵀ + α̃)·Rᵀ·μ = R·(−C(x) − α̃·λ),   x ← x + M⁻¹·Jᵀ·R·μ,
// a Galerkin coarse step of the same linearised system each constraint's projection solves alone: a subspace
// correction on the multipliers, as the sweep is one spring at a time.
export class DualCoarse {
  constructor(model, G, bins = 4) {
    const uv = model.uvs, springs = model.springs, ns = springs.length / 2, n = model.particleCount;
    let u0 = Infinity, u1 = -Infinity, v0 = Infinity, v1 = -Infinity;
    for (let i = 0; i < n; i++) {
      u0 = Math.min(u0, uv[2 * i]); u1 = Math.max(u1, uv[2 * i]);
      v0 = Math.min(v0, uv[2 * i + 1]); v1 = Math.max(v1, uv[2 * i + 1]);
    }
    const ids = new Map();
    this.aggregate = new Int32Array(ns);
    for (let s = 0; s < ns; s++) {
      const a = springs[2 * s], b = springs[2 * s + 1];
      const mu = ((uv[2 * a] + uv[2 * b]) / 2 - u0) / (u1 - u0 || 1), mv = ((uv[2 * a + 1] + uv[2 * b + 1]) / 2 - v0) / (v1 - v0 || 1);
      const cu = Math.min(Math.floor(mu * G), G - 1), cv = Math.min(Math.floor(mv * G), G - 1);
      let angle = Math.atan2(uv[2 * b + 1] - uv[2 * a + 1], uv[2 * b] - uv[2 * a]);
      if (angle < 0) angle += Math.PI;
      const bin = Math.round(angle / (Math.PI / bins)) % bins;
      const key = (cu + G * cv) * bins + bin;
      if (!ids.has(key)) ids.set(key, ids.size);
      this.aggregate[s] = ids.get(key);
    }
    this.count = ids.size;
    this.A = new Float64Array(this.count * this.count);
    this.b = new Float64Array(this.count);
    // the springs at each particle (for the products J_s·M⁻¹·J_tᵀ, which share a particle)
    const deg = new Int32Array(n + 1);
    for (let s = 0; s < ns; s++) { deg[springs[2 * s] + 1]++; deg[springs[2 * s + 1] + 1]++; }
    for (let i = 0; i < n; i++) deg[i + 1] += deg[i];
    this.start = deg;
    this.list = new Int32Array(2 * ns);
    const fill = deg.slice(0, n);
    for (let s = 0; s < ns; s++) { this.list[fill[springs[2 * s]]++] = s; this.list[fill[springs[2 * s + 1]]++] = s; }
    this.dir = new Float64Array(3 * ns);
    this.omega = 1;
  }

  apply(model, state, params, h) {
    const x = state.positions, w = state.invMass, lambdas = state.lambdas, n = model.particleCount;
    const springs = model.springs, rest = model.restLengths, compliance = params.compliance, ns = rest.length;
    const A = this.A, b = this.b, N = this.count, agg = this.aggregate, dir = this.dir, start = this.start, list = this.list;
    A.fill(0); b.fill(0);
    const ih2 = 1 / (h * h);
    const unit = this.unit ??= new Float64Array(3);
    for (let s = 0; s < ns; s++) {
      dir[3 * s] = 0; dir[3 * s + 1] = 0; dir[3 * s + 2] = 0;
      const len = springDirection(springs, compliance, w, x, s, unit);
      if (!(len > 0)) continue;
      dir.set(unit, 3 * s);
      const at = compliance[s] * ih2, a = agg[s];
      b[a] += -(len - rest[s]) - at * lambdas[s];
      A[a * N + a] += at;
    }
    // J·M⁻¹·Jᵀ: springs s and t meeting at particle i, each signed + at its first particle, − at its second
    for (let i = 0; i < n; i++) {
      const wi = w[i];
      if (!(wi > 0)) continue;
      for (let p = start[i]; p < start[i + 1]; p++) {
        const s = list[p], ss = springs[2 * s] === i ? 1 : -1, as = agg[s];
        if (dir[3 * s] === 0 && dir[3 * s + 1] === 0 && dir[3 * s + 2] === 0) continue;
        for (let q = start[i]; q < start[i + 1]; q++) {
          const t = list[q], tt = springs[2 * t] === i ? 1 : -1;
          const dot = dir[3 * s] * dir[3 * t] + dir[3 * s + 1] * dir[3 * t + 1] + dir[3 * s + 2] * dir[3 * t + 2];
          if (dot !== 0) A[as * N + agg[t]] += wi * ss * tt * dot;
        }
      }
    }
    // an aggregate of springs without stiffness (the skip-one springs under a stencil bending model) has no row: μ = 0
    for (let j = 0; j < N; j++) if (A[j * N + j] === 0) A[j * N + j] = 1;
    if (!solveDense(A, b, N)) return 0;
    let most = 0;
    for (let i = 0; i < n; i++) {
      const wi = w[i];
      if (!(wi > 0)) continue;
      let mx = 0, my = 0, mz = 0;
      for (let p = start[i]; p < start[i + 1]; p++) {
        const s = list[p], sign = springs[2 * s] === i ? 1 : -1, dl = this.omega * b[agg[s]] * sign * wi;
        mx += dl * dir[3 * s]; my += dl * dir[3 * s + 1]; mz += dl * dir[3 * s + 2];
      }
      x[3 * i] += mx; x[3 * i + 1] += my; x[3 * i + 2] += mz;
      most = Math.max(most, Math.hypot(mx, my, mz));
    }
    for (let s = 0; s < ns; s++) lambdas[s] += this.omega * b[agg[s]];
    return most;
  }
}

/** Solves A·x = b for the N × N symmetric positive definite A (lower triangle read) by Cholesky, in place; false if not. */
function solveDense(A, b, N) {
  for (let j = 0; j < N; j++) {
    let d = A[j * N + j];
    for (let k = 0; k < j; k++) d -= A[j * N + k] * A[j * N + k];
    if (!(d > 0)) return false;
    d = Math.sqrt(d);
    A[j * N + j] = d;
    for (let i = j + 1; i < N; i++) {
      let v = A[i * N + j];
      for (let k = 0; k < j; k++) v -= A[i * N + k] * A[j * N + k];
      A[i * N + j] = v / d;
    }
  }
  for (let i = 0; i < N; i++) {
    let v = b[i];
    for (let k = 0; k < i; k++) v -= A[i * N + k] * b[k];
    b[i] = v / A[i * N + i];
  }
  for (let i = N - 1; i >= 0; i--) {
    let v = b[i];
    for (let k = i + 1; k < N; k++) v -= A[k * N + i] * b[k];
    b[i] = v / A[i * N + i];
  }
  return true;
}

/**
 * Spring s's unit direction x_a − x_b into `out` and its length [m], or 0 where it takes no part: no stiffness (α
 * infinite), both ends pinned, or its ends on one point.
 */
function springDirection(springs, compliance, w, x, s, out) {
  if (!(compliance[s] < Infinity)) return 0;
  const pa = springs[2 * s], pb = springs[2 * s + 1];
  if (!(w[pa] > 0) && !(w[pb] > 0)) return 0;
  const ja = 3 * pa, jb = 3 * pb;
  const dx = x[ja] - x[jb], dy = x[ja + 1] - x[jb + 1], dz = x[ja + 2] - x[jb + 2];
  const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
  if (len < 1e-12) return 0;
  out[0] = dx / len; out[1] = dy / len; out[2] = dz / len;
  return len;
}
