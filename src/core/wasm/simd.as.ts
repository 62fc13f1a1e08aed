// Four particles or springs at once in f32x4 lanes: gathers, scatters and the xyz transposes the SIMD phases share.

/** Four f32 at byte offsets o0…o3 from base, as the lanes of one vector. */
@inline export function gather(base: usize, o0: usize, o1: usize, o2: usize, o3: usize): v128 {
  let v = v128.load32_zero(base + o0);
  v = v128.load32_lane(base + o1, v, 1);
  v = v128.load32_lane(base + o2, v, 2);
  return v128.load32_lane(base + o3, v, 3);
}

/** The lanes of `v` to four f32 at byte offsets o0…o3 from base. */
@inline export function scatter(base: usize, o0: usize, o1: usize, o2: usize, o3: usize, v: v128): void {
  v128.store32_lane(base + o0, v, 0);
  v128.store32_lane(base + o1, v, 1);
  v128.store32_lane(base + o2, v, 2);
  v128.store32_lane(base + o3, v, 3);
}

// Four particles' xyz as one v128 load each (x, y, z and the next float, never used), transposed to x, y, z lanes:
// lo2/hi2 interleave two loads, lanesXY0/lanesXY1 pick the x (or z) and y lanes of two interleaved pairs.
/** Lanes 0, 1 of a and b interleaved: a0 b0 a1 b1. */
@inline export function lo2(a: v128, b: v128): v128 { return v128.shuffle<f32>(a, b, 0, 4, 1, 5); }
/** Lanes 2, 3 of a and b interleaved: a2 b2 a3 b3. */
@inline export function hi2(a: v128, b: v128): v128 { return v128.shuffle<f32>(a, b, 2, 6, 3, 7); }
/** Lanes 0, 1 of t0 and of t1: the first component of four particles. */
@inline export function lanesXY0(t0: v128, t1: v128): v128 { return v128.shuffle<f32>(t0, t1, 0, 1, 4, 5); }
/** Lanes 2, 3 of t0 and of t1: the second component of four particles. */
@inline export function lanesXY1(t0: v128, t1: v128): v128 { return v128.shuffle<f32>(t0, t1, 2, 3, 6, 7); }

/** Writes lanes x, y, z back to four particles: x and y as one 8-byte store, z as a 4-byte store (never past z). */
@inline export function store4(base: usize, o0: usize, o1: usize, o2: usize, o3: usize, x: v128, y: v128, z: v128): void {
  const u0 = lo2(x, y), u1 = hi2(x, y);
  v128.store64_lane(base + o0, u0, 0); v128.store32_lane(base + o0 + 8, z, 0);
  v128.store64_lane(base + o1, u0, 1); v128.store32_lane(base + o1 + 8, z, 1);
  v128.store64_lane(base + o2, u1, 0); v128.store32_lane(base + o2 + 8, z, 2);
  v128.store64_lane(base + o3, u1, 1); v128.store32_lane(base + o3 + 8, z, 3);
}

/** The dot products of four vector pairs, lane by lane. */
@inline export function dot3(ax: v128, ay: v128, az: v128, bx: v128, by: v128, bz: v128): v128 {
  return f32x4.add(f32x4.add(f32x4.mul(ax, bx), f32x4.mul(ay, by)), f32x4.mul(az, bz));
}
