/**
 * The standard fabric tests a scene can be (`test` in the scene): what they measure on a running cloth.
 *
 * - **Cantilever** (ASTM D1388, Peirce 1930, "The 'handle' of cloth as a measurable quantity"): a strip clamped
 *   flat (pinned) with an overhang L beyond the clamp's last row bends under its own weight; the chord from that row
 *   to the tip falls θ below the horizontal. The bending length c = (B/(ρ_A·g))^(1/3) follows from θ and L through the
 *   heavy elastica (an inextensible strip of rigidity B and weight ρ_A·g per area, clamped horizontally), solved
 *   here numerically: the standard's rule, θ = 41.5° at L = 2c, is one point of that curve (tested).
 * - **Cusick drape** (BS 5058, ISO 9073-9): a disc on a smaller pedestal; the drape coefficient is (projected area −
 *   pedestal area) / (specimen area − pedestal area), the projected area being the union of the cloth's triangles
 *   seen from above, and `folds` the number of folds round its rim.
 */
import type { ClothModel } from './model.js';
import { SceneError, type Scene } from './scene.js';
import type { ClothState } from './state.js';

/** What a cantilever scene reports. */
export interface CantileverResult {
  type: 'cantilever';
  /** length of strip beyond where the clamp holds it (its last pinned particles behind the edge), at rest [m] */
  overhang: number;
  /** angle of the chord from the clamp's last row to the tip below the horizontal [degrees] */
  chordAngle: number;
  /**
   * the bending length the chord angle says, c = (B/(ρ_A·g))^(1/3) [m]; null while the tip has not dropped below the
   * edge (a chord at 0° or above: a strip that has not bent says nothing of its bending length)
   */
  bendingLength: number | null;
}

/** What a Cusick drape scene reports. */
export interface CusickResult {
  type: 'cusick';
  /** area of the cloth seen from above [m²] */
  projectedArea: number;
  /** (projected area − pedestal area) / (specimen area − pedestal area) [-] */
  drapeCoefficient: number;
  /** folds round the rim (peaks of the silhouette's radius, 2 mm or more above the valleys beside them) [-] */
  folds: number;
}

export type TestResult = CantileverResult | CusickResult;

/**
 * Refuses a scene's `test` that cannot be measured on `model`: a Cusick pedestal whose top is not smaller than the
 * specimen (the drape coefficient divides by their difference). `source` names the scene in the message.
 */
export function checkTest(model: ClothModel, scene: Scene, source: string): void {
  const t = scene.test;
  if (t?.type !== 'cusick') return;
  const pedestal = Math.PI * t.pedestalRadius * t.pedestalRadius;
  if (!(pedestal < model.area)) {
    throw new SceneError(`${source}: test.pedestalRadius: the pedestal's top (${pedestal.toPrecision(3)} m²) must be smaller than the cloth (${model.area.toPrecision(3)} m²), which drapes over it`);
  }
}

/** The measurement a scene's `test` asks for, on the cloth as it is now (NaN where the cloth is not finite). */
export function measureTest(model: ClothModel, state: ClothState, scene: Scene): TestResult | undefined {
  const t = scene.test;
  if (!t) return undefined;
  return t.type === 'cantilever' ? cantilever(model, state, t.edge, t.direction) : cusick(model, state, t.center, t.pedestalRadius);
}

function cantilever(model: ClothModel, state: ClothState, edge: readonly number[], direction: readonly number[]): CantileverResult {
  const dl = Math.hypot(direction[0], direction[2]) || 1;
  const ux = direction[0] / dl, uz = direction[2] / dl;
  const rest = model.restPositions, x = state.positions;
  const out = (i: number) => (rest[3 * i] - edge[0]) * ux + (rest[3 * i + 2] - edge[2]) * uz;
  // where the strip stops being held: the pinned particles farthest out that are not beyond the scene's edge (1 µm
  // spare for rounding, as the built-in scene's clamp region has). A clamp made by a pin region holds every particle
  // behind the edge, so on a grid whose rows miss the edge the last held row lies behind it, and the strip bends
  // from there: the overhang and the chord are measured from that row.
  let clamp = -Infinity;
  for (let i = 0; i < model.particleCount; i++) {
    if (state.pinned[i] && out(i) <= 1e-6 && out(i) > clamp) clamp = out(i);
  }
  if (clamp === -Infinity) clamp = 0;
  // the tip: the free particles farthest out along the strip at rest (a row of them on a grid)
  let far = -Infinity;
  for (let i = 0; i < model.particleCount; i++) if (!state.pinned[i]) far = Math.max(far, out(i));
  let along = 0, drop = 0, count = 0;
  for (let i = 0; i < model.particleCount; i++) {
    if (state.pinned[i] || out(i) < far - 1e-6) continue;
    along += (x[3 * i] - edge[0]) * ux + (x[3 * i + 2] - edge[2]) * uz - clamp;
    drop += edge[1] - x[3 * i + 1];
    count++;
  }
  // every particle held: nothing overhangs, and no tip has dropped
  if (count === 0) return { type: 'cantilever', overhang: 0, chordAngle: 0, bendingLength: null };
  const theta = Math.atan2(drop / count, along / count);
  const overhang = far - clamp;
  const load = elasticaLoad(theta);
  return { type: 'cantilever', overhang, chordAngle: (theta * 180) / Math.PI, bendingLength: load > 0 ? overhang / Math.cbrt(load) : null };
}

/**
 * The heavy elastica, clamped horizontally at s = 0 and free at s = L, in units of L (σ = s/L): φ the slope below
 * the horizontal and m = φ′ the bending moment over B obey φ′ = m, m′ = −λ·(1 − σ)·cos φ (the weight beyond σ, times
 * its lever), with φ(0) = 0 and no moment at the free end, m(1) = 0; ξ′ = cos φ, η′ = −sin φ. λ = ρ_A·g·L³/B =
 * (L/c)³. Solved by shooting on the clamp's moment m(0) ∈ [0, λ/2] (RK4, N steps: 200 put θ(8) within 0.01° of 1000; bisection on the sign of m(1), a
 * moment that turns negative before the tip counting as too small and a slope past vertical as too large). Returns the
 * chord angle atan(−η(1)/ξ(1)) [rad].
 */
export function elasticaChordAngle(lambda: number, N = 200): number {
  const shoot = (m0: number, out?: Float64Array): number => {
    let phi = 0, m = m0, xi = 0, eta = 0;
    const h = 1 / N;
    const fm = (sig: number, p: number) => -lambda * (1 - sig) * Math.cos(p);
    for (let j = 0; j < N; j++) {
      const sig = j * h;
      const k1p = m, k1m = fm(sig, phi);
      const k2p = m + 0.5 * h * k1m, k2m = fm(sig + 0.5 * h, phi + 0.5 * h * k1p);
      const k3p = m + 0.5 * h * k2m, k3m = fm(sig + 0.5 * h, phi + 0.5 * h * k2p);
      const k4p = m + h * k3m, k4m = fm(sig + h, phi + h * k3p);
      const dphi = (h / 6) * (k1p + 2 * k2p + 2 * k3p + k4p);
      // the position follows the slope's midpoint over the step
      const mid = phi + 0.5 * dphi;
      xi += h * Math.cos(mid);
      eta -= h * Math.sin(mid);
      phi += dphi;
      m += (h / 6) * (k1m + 2 * k2m + 2 * k3m + k4m);
      // the strip bends one way, never past hanging straight down, and its moment falls to zero at the tip: a
      // moment gone negative early says the clamp's was too small, a slope past vertical that it was too large
      if (!out && m < 0 && j < N - 1) return -1;
      if (!out && phi > Math.PI / 2) return 1;
    }
    if (out) { out[0] = xi; out[1] = eta; }
    return m;
  };
  let lo = 0, hi = lambda / 2;
  for (let k = 0; k < 56; k++) {
    const mid = 0.5 * (lo + hi);
    if (shoot(mid) < 0) lo = mid; else hi = mid;
  }
  const end = new Float64Array(2);
  shoot(0.5 * (lo + hi), end);
  return Math.atan2(-end[1], end[0]);
}

/**
 * λ = (L/c)³ for which the heavy elastica's chord falls θ [rad] (θ grows with λ; solved in log λ), within
 * 10⁻⁴ … 10³ (chords of 0.007° … 82°: beyond, the strip hangs straight down and the angle says little).
 */
export function elasticaLoad(theta: number): number {
  if (!(theta > 0)) return 0;
  // regula falsi (Illinois) in log λ: the chord is smooth and monotone there, ~10 solves instead of bisection's 40
  let a = Math.log(1e-4), b = Math.log(1e3);
  let fa = elasticaChordAngle(Math.exp(a)) - theta, fb = elasticaChordAngle(Math.exp(b)) - theta;
  if (fb <= 0) return Math.exp(b);
  if (fa >= 0) return Math.exp(a);
  let last = 0, c = b;
  for (let k = 0; k < 100; k++) {
    c = b - (fb * (b - a)) / (fb - fa);
    const fc = elasticaChordAngle(Math.exp(c)) - theta;
    if (fc === 0 || Math.abs(fc) < 1e-13) break;
    // the end on c's side moves to c; an end kept twice in a row has its value halved (so both ends close in)
    if (fc > 0) { b = c; fb = fc; if (last === 1) fa /= 2; last = 1; }
    else { a = c; fa = fc; if (last === -1) fb /= 2; last = -1; }
    if (b - a < 1e-12) break;
  }
  return Math.exp(c);
}

/**
 * Side of the cells the projected area is counted on [m]: 0.5 mm, a 30 cm specimen in 600 × 600 cells; for a cloth
 * spread over more than 1 m × 1 m, as much more as keeps the count to about CELLS_MOST (a 5 m cloth: 2.5 mm cells).
 */
const CELL_SIDE = 5e-4;
const CELLS_MOST = 4e6;

function cusick(model: ClothModel, state: ClothState, center: readonly number[], pedestalRadius: number): CusickResult {
  const x = state.positions, t = model.triangles;
  let x0 = Infinity, z0 = Infinity, x1 = -Infinity, z1 = -Infinity;
  for (let i = 0; i < model.particleCount; i++) {
    x0 = Math.min(x0, x[3 * i]); x1 = Math.max(x1, x[3 * i]);
    z0 = Math.min(z0, x[3 * i + 2]); z1 = Math.max(z1, x[3 * i + 2]);
  }
  const nan: CusickResult = { type: 'cusick', projectedArea: NaN, drapeCoefficient: NaN, folds: NaN };
  if (![x0, x1, z0, z1].every(Number.isFinite)) return nan;
  const CELL = Math.max(CELL_SIDE, Math.sqrt(((x1 - x0 + CELL_SIDE) * (z1 - z0 + CELL_SIDE)) / CELLS_MOST));
  const nx = Math.ceil((x1 - x0) / CELL) + 1, nz = Math.ceil((z1 - z0) / CELL) + 1;
  // (a cloth flung kilometres long and thin, which no cell size fits: nothing to measure)
  if (nx * nz > 16 * CELLS_MOST) return nan;
  const covered = new Uint8Array(nx * nz);
  // every cell whose centre lies in a triangle seen from above
  for (let k = 0; k < t.length; k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1], c = 3 * t[k + 2];
    const ax = x[a], az = x[a + 2], bx = x[b], bz = x[b + 2], cx = x[c], cz = x[c + 2];
    const det = (bx - ax) * (cz - az) - (cx - ax) * (bz - az);
    if (det === 0) continue;
    const i0 = Math.max(0, Math.floor((Math.min(ax, bx, cx) - x0) / CELL)), i1 = Math.min(nx - 1, Math.ceil((Math.max(ax, bx, cx) - x0) / CELL));
    const j0 = Math.max(0, Math.floor((Math.min(az, bz, cz) - z0) / CELL)), j1 = Math.min(nz - 1, Math.ceil((Math.max(az, bz, cz) - z0) / CELL));
    for (let j = j0; j <= j1; j++) {
      const pz = z0 + (j + 0.5) * CELL;
      for (let i = i0; i <= i1; i++) {
        const px = x0 + (i + 0.5) * CELL;
        const u = ((px - ax) * (cz - az) - (cx - ax) * (pz - az)) / det;
        const v = ((bx - ax) * (pz - az) - (px - ax) * (bz - az)) / det;
        if (u >= 0 && v >= 0 && u + v <= 1) covered[j * nx + i] = 1;
      }
    }
  }
  // the silhouette's radius round the pedestal's axis, per degree
  const BINS = 360;
  const radius = new Float64Array(BINS);
  let cells = 0;
  for (let j = 0; j < nz; j++) {
    for (let i = 0; i < nx; i++) {
      if (!covered[j * nx + i]) continue;
      cells++;
      const dx = x0 + (i + 0.5) * CELL - center[0], dz = z0 + (j + 0.5) * CELL - center[2];
      const bin = Math.min(BINS - 1, Math.floor(((Math.atan2(dz, dx) + Math.PI) / (2 * Math.PI)) * BINS));
      radius[bin] = Math.max(radius[bin], Math.hypot(dx, dz));
    }
  }
  const projectedArea = cells * CELL * CELL;
  const pedestal = Math.PI * pedestalRadius * pedestalRadius;
  return { type: 'cusick', projectedArea, drapeCoefficient: (projectedArea - pedestal) / (model.area - pedestal), folds: countFolds(radius) };
}

/** Peaks of a closed profile (smoothed over 7 bins) that stand 2 mm or more above the lowest point on each side before a higher peak. */
export function countFolds(radius: Float64Array): number {
  const n = radius.length, r = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    let s = 0;
    for (let d = -3; d <= 3; d++) s += radius[(k + d + n) % n];
    r[k] = s / 7;
  }
  const PROMINENCE = 2e-3;
  let folds = 0;
  for (let k = 0; k < n; k++) {
    const v = r[k];
    // a strict local maximum (the first of a flat top)
    if (!(v > r[(k - 1 + n) % n] && v >= r[(k + 1) % n])) continue;
    // the deepest valley on each side before a higher point
    let left = v, right = v;
    for (let d = 1; d < n; d++) { const w = r[(k - d + n) % n]; if (w > v) break; left = Math.min(left, w); }
    for (let d = 1; d < n; d++) { const w = r[(k + d) % n]; if (w > v) break; right = Math.min(right, w); }
    if (v - Math.max(left, right) >= PROMINENCE) folds++;
  }
  return folds;
}
