#!/usr/bin/env node
// The ADMM coupling of scripts/coupled-study.mjs on a linear model: two random symmetric positive semi-definite
// stiffnesses S (the springs) and Q (the stencils) over n unknowns, in units of M/h², that do not commute; the substep
// y = 2·x_n − x_{n−1}, then per iteration the bending copy z = ((1 − a)·y + c·(from + u)) / ((1 − a + c) + Q), the
// stretch copy x = (a·y + c·(z − u)) / ((a + c) + S), u += x − z, from ← x, the result x. The first iteration's
// `from` is the prediction y, or the substep's start x_n. Prints, for each variant, the largest growth per substep of
// the state (x_n, x_{n−1}, u) over the trials (power iteration: ≤ 1 stable, > 1 a growing mode).
//   node scripts/admm-linear.mjs [--trials 300] [--n 3] [--steps 3000]
const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? Number(process.argv[i + 1]) : fallback;
};
const TRIALS = arg('trials', 300), N = arg('n', 3), STEPS = arg('steps', 3000);
let seed = 1;
const rnd = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
const gauss = () => Math.sqrt(-2 * Math.log(rnd() + 1e-300)) * Math.cos(2 * Math.PI * rnd());

/** n × n matrices as arrays of rows */
const mul = (A, B) => A.map((row) => B[0].map((_, j) => row.reduce((s, v, k) => s + v * B[k][j], 0)));
const apply = (A, v) => A.map((row) => row.reduce((s, x, k) => s + x * v[k], 0));
function inverse(A) {
  const n = A.length, M = A.map((row, i) => [...row, ...row.map((_, j) => (i === j ? 1 : 0))]);
  for (let c = 0; c < n; c++) {
    let p = c;
    for (let r = c + 1; r < n; r++) if (Math.abs(M[r][c]) > Math.abs(M[p][c])) p = r;
    [M[c], M[p]] = [M[p], M[c]];
    const d = M[c][c];
    for (let j = 0; j < 2 * n; j++) M[c][j] /= d;
    for (let r = 0; r < n; r++) if (r !== c) { const f = M[r][c]; for (let j = 0; j < 2 * n; j++) M[r][j] -= f * M[c][j]; }
  }
  return M.map((row) => row.slice(n));
}
/** a random positive semi-definite matrix of rank r, its largest eigenvalue about `scale` */
function randomStiffness(n, r, scale) {
  const G = Array.from({ length: n }, () => Array.from({ length: r }, gauss));
  const M = mul(G, G[0].map((_, j) => G.map((row) => row[j])));
  let v = Array(n).fill(1), norm = 1;
  for (let k = 0; k < 100; k++) { v = apply(M, v); norm = Math.hypot(...v); v = v.map((x) => x / norm); }
  return M.map((row) => row.map((x) => (scale * x) / norm));
}
const plus = (A, s) => A.map((row, i) => row.map((x, j) => x + (i === j ? s : 0)));

/** the largest growth per substep of the state over STEPS substeps */
function growth(S, Q, a, c, from, iterations) {
  const n = S.length, Az = inverse(plus(Q, 1 - a + c)), Ax = inverse(plus(S, a + c));
  let xn = Array.from({ length: n }, gauss), xp = Array.from({ length: n }, gauss), u = Array.from({ length: n }, gauss);
  let log = 0;
  for (let step = 0; step < STEPS; step++) {
    const y = xn.map((v, i) => 2 * v - xp[i]);
    let f = from === 'start' ? xn : y, x = xn;
    for (let it = 0; it < iterations; it++) {
      const z = apply(Az, y.map((v, i) => (1 - a) * v + c * (f[i] + u[i])));
      x = apply(Ax, y.map((v, i) => a * v + c * (z[i] - u[i])));
      u = u.map((v, i) => v + x[i] - z[i]);
      f = x;
    }
    xp = xn; xn = x;
    const size = Math.hypot(...xn, ...xp, ...u);
    log += Math.log(size);
    xn = xn.map((v) => v / size); xp = xp.map((v) => v / size); u = u.map((v) => v / size);
  }
  return Math.exp(log / STEPS);
}

const cases = Array.from({ length: TRIALS }, () => [
  randomStiffness(N, 1 + Math.floor(rnd() * N), 10 ** (4 * rnd())), randomStiffness(N, 1 + Math.floor(rnd() * N), 10 ** (4 * rnd())),
]);
console.log(`${TRIALS} random pairs S, Q (${N} unknowns, largest stiffness 1–10⁴ × M/h², ranks 1–${N}), a = 0.5: the largest growth per substep`);
console.log('| first iteration from | c | iterations | largest growth |');
console.log('|---|---|---|---|');
for (const from of ['prediction', 'start']) {
  for (const [c, iterations] of [[0.5, 1], [1, 1], [10, 1], [10, 3]]) {
    let worst = 0;
    for (const [S, Q] of cases) worst = Math.max(worst, growth(S, Q, 0.5, c, from, iterations));
    console.log(`| ${from} | ${c} | ${iterations} | ${worst.toFixed(4)} |`);
  }
}
