import { mulberry32 } from './random.js';
import type { SimParams } from './params.js';

const GUST_TERMS = 3;
/** [frequency multiplier, phase] per term, for strength then direction; cached per seed */
let gustSeed = -1;
const gustTable = new Float64Array(4 * GUST_TERMS);

function gustTerms(seed: number): Float64Array {
  if (seed !== gustSeed) {
    const rnd = mulberry32(seed);
    for (let k = 0; k < 2 * GUST_TERMS; k++) {
      gustTable[2 * k] = 0.6 + 0.8 * rnd(); // frequency spread around the nominal one
      gustTable[2 * k + 1] = 2 * Math.PI * rnd();
    }
    gustSeed = seed;
  }
  return gustTable;
}

/**
 * Wind velocity at time t [s] written to `out` [m/s]: the scene's strength and direction, modulated by gusts —
 * a seeded sum of sines, smooth in time — when they are on. Returns the speed [m/s].
 */
export function windVelocity(params: SimParams, t: number, out: Float64Array): number {
  const w = params.wind;
  let speed = w.strength;
  let dx = w.direction[0], dy = w.direction[1], dz = w.direction[2];
  if (w.gusts.enabled && w.gusts.amplitude > 0) {
    const g = gustTerms(w.gusts.seed);
    let s = 0, a = 0;
    for (let k = 0; k < GUST_TERMS; k++) {
      s += Math.sin(2 * Math.PI * w.gusts.frequency * g[2 * k] * t + g[2 * k + 1]);
      const j = k + GUST_TERMS;
      a += Math.sin(2 * Math.PI * w.gusts.frequency * g[2 * j] * t + g[2 * j + 1]);
    }
    speed *= Math.max(0, 1 + (w.gusts.amplitude * s) / GUST_TERMS);
    // turn the direction about the vertical by up to amplitude × 45°
    const ang = (w.gusts.amplitude * (Math.PI / 4) * a) / GUST_TERMS;
    const c = Math.cos(ang), sn = Math.sin(ang);
    const rx = c * dx + sn * dz;
    const rz = -sn * dx + c * dz;
    dx = rx; dz = rz;
  }
  out[0] = dx * speed; out[1] = dy * speed; out[2] = dz * speed;
  return speed;
}
