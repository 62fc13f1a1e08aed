// Positions to finer than float32 (phases.ts integrate): a position is positions[i] + residuals[i], the residual
// holding what rounding the position to float32 dropped. Knuth's TwoSum gives that rounding error exactly in
// float32 arithmetic, so the sums below lose nothing the float64 of the CPU keeps.

/** a + b as the float32 sum s and its exact rounding error e: a + b = s + e (Knuth's TwoSum, per component). */
fn twoSum(a: vec3f, b: vec3f, e: ptr<function, vec3f>) -> vec3f {
  let s = a + b;
  let bb = s - a;
  *e = (a - (s - bb)) + (b - bb);
  return s;
}
