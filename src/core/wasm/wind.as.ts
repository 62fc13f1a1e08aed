// The air on the cloth (the wind phase; phases.ts accumulateWind is the reference and says what it models): per
// triangle, the drag of the air moving at WIND relative to the triangle's mean velocity over the last substep,
// capped, a third of it onto each corner's force. The same operations in the same order, f64 on the f32 arrays and
// each force rounded to f32 as the reference's Float32Array is, so the same forces bit for bit. One thread, the
// triangles in order (the corners' forces are sums in that order).
import { BASE_W, F, N, TRIANGLE_COUNT, TRIANGLES, X, XP } from './arrays.as';
import { AIR_K, H, WIND } from './layout.generated.as';

@inline function at(base: usize, j: usize): f64 { return <f64>load<f32>(base + j); }

/** Adds (fx, fy, fz) [N] to the force at byte j, each coordinate rounded to f32 (the reference's `f[j] += fx`). */
@inline function addForce(j: usize, fx: f64, fy: f64, fz: f64): void {
  const q = F + j;
  store<f32>(q, <f32>(<f64>load<f32>(q) + fx));
  store<f32>(q, <f32>(<f64>load<f32>(q, 4) + fy), 4);
  store<f32>(q, <f32>(<f64>load<f32>(q, 8) + fz), 8);
}

/** Every particle's force from the air this substep (phases.ts accumulateWind), over the forces before. */
export function accumulateWind(): void {
  memory.fill(F, 0, <usize>N * 12);
  const h = load<f64>(H), k = load<f64>(AIR_K);
  const wx = load<f64>(WIND), wy = load<f64>(WIND, 8), wz = load<f64>(WIND, 16);
  const inv3h = 1 / (3 * h), capScale = 1 / (2 * h);
  for (let t = 0; t < TRIANGLE_COUNT; t++) {
    const tr = TRIANGLES + <usize>t * 12;
    const ia = load<u32>(tr), ib = load<u32>(tr, 4), ic = load<u32>(tr, 8);
    const a = <usize>ia * 12, b = <usize>ib * 12, c = <usize>ic * 12;
    const ux = at(X, b) - at(X, a), uy = at(X, b + 4) - at(X, a + 4), uz = at(X, b + 8) - at(X, a + 8);
    const vx = at(X, c) - at(X, a), vy = at(X, c + 4) - at(X, a + 4), vz = at(X, c + 8) - at(X, a + 8);
    // |N| = 2·area
    const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const nl = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (nl < 1e-20) continue;
    // the air relative to the triangle's velocity over the last substep, (Σ (x − x_prev))/(3h)
    const rx = wx - (at(X, a) - at(XP, a) + at(X, b) - at(XP, b) + at(X, c) - at(XP, c)) * inv3h;
    const ry = wy - (at(X, a + 4) - at(XP, a + 4) + at(X, b + 4) - at(XP, b + 4) + at(X, c + 4) - at(XP, c + 4)) * inv3h;
    const rz = wz - (at(X, a + 8) - at(XP, a + 8) + at(X, b + 8) - at(XP, b + 8) + at(X, c + 8) - at(XP, c + 8)) * inv3h;
    const speed = Math.sqrt(rx * rx + ry * ry + rz * rz);
    const vn = (rx * nx + ry * ny + rz * nz) / nl;
    // per particle along the unit normal, and its cap
    let fn = k * speed * vn * nl;
    const wsum = <f64>load<f32>(BASE_W + (<usize>ia << 2)) + <f64>load<f32>(BASE_W + (<usize>ib << 2)) + <f64>load<f32>(BASE_W + (<usize>ic << 2));
    const cap = (Math.abs(vn) * capScale) / wsum;
    if (fn > cap) fn = cap; else if (fn < -cap) fn = -cap;
    const s = fn / nl;
    const fx = s * nx, fy = s * ny, fz = s * nz;
    addForce(a, fx, fy, fz); addForce(b, fx, fy, fz); addForce(c, fx, fy, fz);
  }
}
