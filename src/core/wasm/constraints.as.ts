// The constraint phases: distance constraints and stretch limiting (four springs of a colour batch at once in f32x4
// lanes: springs of a batch share no particle, so the lanes never write the same particle), and tethers (scalar f64
// on f32 data, as the TypeScript reference).
import { ALPHA, ANCHOR, LAMBDA, REST, SPRINGS, TLEN, W, X, XP } from './arrays.as';
import { dot3, gather, hi2, lanesXY0, lanesXY1, lo2, scatter, store4 } from './simd.as';

/**
 * Distance constraints [s0, s1) of one batch, as solvers/xpbd.ts solveDistanceConstraints() in f32:
 * Δλ = (−C − α̃λ − γ∇C·(x − x_prev)) / ((1 + γ)(w_a + w_b) + α̃), added whole to λ, with the hard cap at capFactor
 * × rest (not added to λ).
 * Four springs per step; the last 1–3 repeat the last spring in the spare lanes (same values written twice).
 * λ is read only when it accumulates and written only when `storeLambda` (several iterations, or the frame's last
 * substep: what is read of λ after a frame is that substep's).
 */
export function solveDistance(
  s0: i32, s1: i32, invH2: f32, betaOverH: f32, capFactor: f32, accumulate: bool, storeLambda: bool,
): void {
  // the layout's globals in locals: V8 keeps them in registers across the loop
  const x = X, xp = XP, w = W, sp = SPRINGS, restP = REST, alphaP = ALPHA, lamP = LAMBDA;
  const vInvH2 = f32x4.splat(invH2), vBeta = f32x4.splat(betaOverH), vCap = f32x4.splat(capFactor);
  const one = f32x4.splat(1), zero = f32x4.splat(0), tiny = f32x4.splat(1e-12), inf = f32x4.splat(Infinity);
  const damped = betaOverH > 0;
  for (let s = s0; s < s1; s += 4) {
    const k1 = min(s + 1, s1 - 1), k2 = min(s + 2, s1 - 1), k3 = min(s + 3, s1 - 1);
    const full = s + 4 <= s1;
    const pa0 = <usize>load<u32>(sp + (<usize>s << 3)), pb0 = <usize>load<u32>(sp + (<usize>s << 3), 4);
    const pa1 = <usize>load<u32>(sp + (<usize>k1 << 3)), pb1 = <usize>load<u32>(sp + (<usize>k1 << 3), 4);
    const pa2 = <usize>load<u32>(sp + (<usize>k2 << 3)), pb2 = <usize>load<u32>(sp + (<usize>k2 << 3), 4);
    const pa3 = <usize>load<u32>(sp + (<usize>k3 << 3)), pb3 = <usize>load<u32>(sp + (<usize>k3 << 3), 4);
    const a0 = pa0 * 12, a1 = pa1 * 12, a2 = pa2 * 12, a3 = pa3 * 12;
    const b0 = pb0 * 12, b1 = pb1 * 12, b2 = pb2 * 12, b3 = pb3 * 12;
    let rest: v128, alpha: v128, lambda = zero;
    const useLambda = accumulate || storeLambda;
    if (full) {
      rest = v128.load(restP + (<usize>s << 2));
      alpha = v128.load(alphaP + (<usize>s << 2));
      if (useLambda) lambda = v128.load(lamP + (<usize>s << 2));
    } else {
      const o0 = <usize>s << 2, o1 = <usize>k1 << 2, o2 = <usize>k2 << 2, o3 = <usize>k3 << 2;
      rest = gather(restP, o0, o1, o2, o3);
      alpha = gather(alphaP, o0, o1, o2, o3);
      if (useLambda) lambda = gather(lamP, o0, o1, o2, o3);
    }
    const wa = gather(w, pa0 << 2, pa1 << 2, pa2 << 2, pa3 << 2);
    const wb = gather(w, pb0 << 2, pb1 << 2, pb2 << 2, pb3 << 2);
    const qa0 = v128.load(x + a0), qa1 = v128.load(x + a1), qa2 = v128.load(x + a2), qa3 = v128.load(x + a3);
    const qb0 = v128.load(x + b0), qb1 = v128.load(x + b1), qb2 = v128.load(x + b2), qb3 = v128.load(x + b3);
    const ta0 = lo2(qa0, qa1), ta1 = lo2(qa2, qa3), tb0 = lo2(qb0, qb1), tb1 = lo2(qb2, qb3);
    const axv = lanesXY0(ta0, ta1), ayv = lanesXY1(ta0, ta1), azv = lanesXY0(hi2(qa0, qa1), hi2(qa2, qa3));
    const bxv = lanesXY0(tb0, tb1), byv = lanesXY1(tb0, tb1), bzv = lanesXY0(hi2(qb0, qb1), hi2(qb2, qb3));
    const dx = f32x4.sub(axv, bxv), dy = f32x4.sub(ayv, byv), dz = f32x4.sub(azv, bzv);
    const len0 = f32x4.sqrt(dot3(dx, dy, dz, dx, dy, dz));
    const wsum = f32x4.add(wa, wb);
    // skipped as in the TypeScript solver: no stiffness, both particles fixed, coincident particles
    const valid = v128.and(v128.and(f32x4.ne(alpha, inf), f32x4.ne(wsum, zero)), f32x4.ge(len0, tiny));
    const len = f32x4.max(len0, tiny);
    const alphaT = f32x4.mul(alpha, vInvH2);
    const gamma = f32x4.mul(alpha, vBeta);
    const D = f32x4.add(f32x4.mul(f32x4.add(one, gamma), wsum), alphaT);
    const q = f32x4.div(one, f32x4.mul(len, D));
    const lam = accumulate ? lambda : zero;
    let dl = f32x4.mul(f32x4.mul(f32x4.sub(f32x4.sub(rest, len), f32x4.mul(alphaT, lam)), len), q);
    if (damped) {
      // x_prev of a and b, transposed as above: r = d − (x_prev,a − x_prev,b) is the relative motion
      const ea0 = v128.load(xp + a0), ea1 = v128.load(xp + a1), ea2 = v128.load(xp + a2), ea3 = v128.load(xp + a3);
      const eb0 = v128.load(xp + b0), eb1 = v128.load(xp + b1), eb2 = v128.load(xp + b2), eb3 = v128.load(xp + b3);
      const da0 = f32x4.sub(ea0, eb0), da1 = f32x4.sub(ea1, eb1), da2 = f32x4.sub(ea2, eb2), da3 = f32x4.sub(ea3, eb3);
      const u0 = lo2(da0, da1), u1 = lo2(da2, da3);
      const rx = f32x4.sub(dx, lanesXY0(u0, u1)), ry = f32x4.sub(dy, lanesXY1(u0, u1));
      const rz = f32x4.sub(dz, lanesXY0(hi2(da0, da1), hi2(da2, da3)));
      dl = f32x4.sub(dl, f32x4.mul(f32x4.mul(gamma, q), dot3(rx, ry, rz, dx, dy, dz)));
    }
    if (storeLambda) {
      const lamNew = v128.bitselect(f32x4.add(lam, dl), lambda, valid);
      if (full) v128.store(lamP + (<usize>s << 2), lamNew);
      else scatter(lamP, <usize>s << 2, <usize>k1 << 2, <usize>k2 << 2, <usize>k3 << 2, lamNew);
    }
    // hard stretch limit: the new length len + wsum·dl may not exceed cap × rest (bend: cap ∞, and as in
    // TypeScript a NaN excess — ∞ × a zero rest length — does not count as over)
    const over = f32x4.sub(f32x4.add(len, f32x4.mul(wsum, dl)), f32x4.mul(vCap, rest));
    dl = f32x4.sub(dl, v128.and(f32x4.div(over, wsum), f32x4.gt(over, zero)));
    dl = v128.and(dl, valid);
    const invLen = v128.and(f32x4.mul(D, q), valid);
    const nx = f32x4.mul(dx, invLen), ny = f32x4.mul(dy, invLen), nz = f32x4.mul(dz, invLen);
    const sa = f32x4.mul(wa, dl), sb = f32x4.mul(wb, dl);
    store4(x, a0, a1, a2, a3, f32x4.add(axv, f32x4.mul(sa, nx)), f32x4.add(ayv, f32x4.mul(sa, ny)), f32x4.add(azv, f32x4.mul(sa, nz)));
    store4(x, b0, b1, b2, b3, f32x4.sub(bxv, f32x4.mul(sb, nx)), f32x4.sub(byv, f32x4.mul(sb, ny)), f32x4.sub(bzv, f32x4.mul(sb, nz)));
  }
}

/** Tethers as tethers.ts solveTethers(), f64 on f32 data. */
export function solveTethers(p0: i32, p1: i32, sf: f64): void {
  for (let i = p0; i < p1; i++) {
    const a = load<i32>(ANCHOR + (<usize>i << 2));
    if (a < 0 || load<f32>(W + (<usize>i << 2)) == 0) continue;
    const j = X + <usize>i * 12, k = X + <usize>a * 12;
    const kx = <f64>load<f32>(k), ky = <f64>load<f32>(k, 4), kz = <f64>load<f32>(k, 8);
    const dx = <f64>load<f32>(j) - kx, dy = <f64>load<f32>(j, 4) - ky, dz = <f64>load<f32>(j, 8) - kz;
    const d2 = dx * dx + dy * dy + dz * dz;
    const max = sf * <f64>load<f32>(TLEN + (<usize>i << 2));
    if (d2 <= max * max) continue;
    const s = max / Math.sqrt(d2);
    store<f32>(j, <f32>(kx + dx * s)); store<f32>(j, <f32>(ky + dy * s), 4); store<f32>(j, <f32>(kz + dz * s), 8);
  }
}

/** Stretch limiting of springs [s0, s1) of one batch, as phases.ts limitStretch(), in f32. */
export function limitStretch(s0: i32, s1: i32, sf: f32): void {
  // the layout's globals in locals: V8 keeps them in registers across the loop
  const x = X, w = W, sp = SPRINGS, restP = REST;
  const vSf = f32x4.splat(sf), zero = f32x4.splat(0);
  for (let s = s0; s < s1; s += 4) {
    const k1 = min(s + 1, s1 - 1), k2 = min(s + 2, s1 - 1), k3 = min(s + 3, s1 - 1);
    const pa0 = <usize>load<u32>(sp + (<usize>s << 3)), pb0 = <usize>load<u32>(sp + (<usize>s << 3), 4);
    const pa1 = <usize>load<u32>(sp + (<usize>k1 << 3)), pb1 = <usize>load<u32>(sp + (<usize>k1 << 3), 4);
    const pa2 = <usize>load<u32>(sp + (<usize>k2 << 3)), pb2 = <usize>load<u32>(sp + (<usize>k2 << 3), 4);
    const pa3 = <usize>load<u32>(sp + (<usize>k3 << 3)), pb3 = <usize>load<u32>(sp + (<usize>k3 << 3), 4);
    const a0 = pa0 * 12, a1 = pa1 * 12, a2 = pa2 * 12, a3 = pa3 * 12;
    const b0 = pb0 * 12, b1 = pb1 * 12, b2 = pb2 * 12, b3 = pb3 * 12;
    const rest = s + 4 <= s1 ? v128.load(restP + (<usize>s << 2))
      : gather(restP, <usize>s << 2, <usize>k1 << 2, <usize>k2 << 2, <usize>k3 << 2);
    const qa0 = v128.load(x + a0), qa1 = v128.load(x + a1), qa2 = v128.load(x + a2), qa3 = v128.load(x + a3);
    const qb0 = v128.load(x + b0), qb1 = v128.load(x + b1), qb2 = v128.load(x + b2), qb3 = v128.load(x + b3);
    const ta0 = lo2(qa0, qa1), ta1 = lo2(qa2, qa3), tb0 = lo2(qb0, qb1), tb1 = lo2(qb2, qb3);
    const axv = lanesXY0(ta0, ta1), ayv = lanesXY1(ta0, ta1), azv = lanesXY0(hi2(qa0, qa1), hi2(qa2, qa3));
    const bxv = lanesXY0(tb0, tb1), byv = lanesXY1(tb0, tb1), bzv = lanesXY0(hi2(qb0, qb1), hi2(qb2, qb3));
    const dx = f32x4.sub(axv, bxv), dy = f32x4.sub(ayv, byv), dz = f32x4.sub(azv, bzv);
    const len2 = dot3(dx, dy, dz, dx, dy, dz);
    const max = f32x4.mul(vSf, rest);
    const long = f32x4.gt(len2, f32x4.mul(max, max));
    if (!v128.any_true(long)) continue; // the common case: no spring of the four is too long
    const wa = gather(w, pa0 << 2, pa1 << 2, pa2 << 2, pa3 << 2);
    const wb = gather(w, pb0 << 2, pb1 << 2, pb2 << 2, pb3 << 2);
    const wsum = f32x4.add(wa, wb);
    const over = v128.and(long, f32x4.ne(wsum, zero));
    if (!v128.any_true(over)) continue;
    const len = f32x4.sqrt(len2);
    const scale = v128.and(f32x4.div(f32x4.sub(len, max), f32x4.mul(len, wsum)), over);
    const sa = f32x4.mul(wa, scale), sb = f32x4.mul(wb, scale);
    store4(x, a0, a1, a2, a3, f32x4.sub(axv, f32x4.mul(sa, dx)), f32x4.sub(ayv, f32x4.mul(sa, dy)), f32x4.sub(azv, f32x4.mul(sa, dz)));
    store4(x, b0, b1, b2, b3, f32x4.add(bxv, f32x4.mul(sb, dx)), f32x4.add(byv, f32x4.mul(sb, dy)), f32x4.add(bzv, f32x4.mul(sb, dz)));
  }
}
