/**
 * The phases every solver shares, one function each: start of step (inverse masses, tethers), external forces
 * (wind), integration, the grab, stretch limiting, contact, velocity update. reference.ts maps the schedule's phases
 * (schedule.ts) onto them and the solvers' own. None of them allocates.
 */
import { QUERY, TRIANGLE, pointQuery, triangleQuery, type ColliderShape } from './colliders/shape.js';
import { TRIANGLE_SPREAD_MOST } from './layout.generated.js';
import { BEND, type ClothModel } from './model.js';
import type { SimParams } from './params.js';
import type { ClothState } from './state.js';
import { updateTethers } from './tethers.js';
import { windVelocity } from './wind.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { WITHIN: TRIANGLE_WITHIN, D: TRIANGLE_D } = TRIANGLE;
const SPREAD_MOST = TRIANGLE_SPREAD_MOST;

const wind = new Float64Array(3);
const normal = new Float64Array(3);
const bary = new Float64Array(3);
/**
 * the contact loops' queries of the colliders, made through records (distanceIn, triangleDeepestIn), not through
 * signedDistance and triangleDeepest: a number passed to a call V8 does not inline is boxed, and whether it inlines
 * them here depends on what it has seen before (colliders/shape.ts)
 */
const contactQuery = pointQuery();
const contactTriangle = triangleQuery();
const surface = new Float64Array(3);
/** the cloth's bounding box this substep: min x, y, z, max x, y, z */
const box = new Float64Array(6);
/** a shape's world half extents (collideTriangles) */
const half = new Float64Array(3);

/**
 * Start of a step of substep length h: effective inverse masses, tethers if the pins changed, and previous
 * positions x − h·v so that the substeps can run position Verlet from the stored velocities (whatever the last
 * step's substep length was).
 */
export function beginStep(model: ClothModel, state: ClothState, params: SimParams, h: number): void {
  refreshInverseMasses(state, params);
  if (state.tethersStale) updateTethers(model, state);
  const x = state.positions, xp = state.previousPositions, v = state.velocities;
  const r = state.residuals, rp = state.previousResiduals;
  for (let j = 0; j < x.length; j++) {
    const p = x[j] + r[j] - h * v[j];
    const q = Math.fround(p);
    xp[j] = q;
    rp[j] = p - q;
  }
}

/** Effective inverse masses for this step: 0 for pinned and grabbed particles. */
export function refreshInverseMasses(state: ClothState, params: SimParams): void {
  const w = state.invMass;
  w.set(params.particleInvMass);
  const pinned = state.pinned;
  for (let i = 0; i < w.length; i++) if (pinned[i]) w[i] = 0;
  if (state.grabbed >= 0) w[state.grabbed] = 0;
}

/**
 * The air's drag factor per particle share, ¼ρ/3 [kg/m³]: ½ρ·|v|·(v·n)·area with area = |N|/2, shared by a triangle's
 * three particles (accumulateWind; the kernel's and the GPU's wind read the same).
 */
export function airFactor(params: SimParams): number {
  return (0.25 * params.wind.airDensity) / 3;
}

/**
 * Wind forces [N] into state.forces (zeroed first). Per triangle, as in the seed but on the velocity of the air
 * relative to the triangle: F = ½ρ·|v|·(v·n)·area·n, shared equally by its three particles.
 * Being a drag on the relative velocity, the force is explicit and would overshoot for a light cloth in strong
 * wind; it is capped at m̄·|v·n|/(2h) (m̄: mean particle mass of the triangle), so that a particle, which shares
 * about six triangles, never gains more normal velocity in one substep than the air has relative to it.
 * Returns false (and leaves forces untouched) when there is no wind.
 */
export function accumulateWind(model: ClothModel, state: ClothState, params: SimParams, t: number, h: number): boolean {
  if (!params.wind.enabled) return false;
  const f = state.forces;
  f.fill(0);
  windVelocity(params, t, wind);
  const x = state.positions, xp = state.previousPositions, tri = model.triangles;
  const inv3h = 1 / (3 * h);
  const k = airFactor(params);
  const im = params.particleInvMass;
  // cap per particle share: m̄·|v·n|/(2h)/3 with m̄ ≈ 3/Σw (harmonic mean of the three masses)
  const capScale = 1 / (2 * h);
  for (let t3 = 0; t3 < tri.length; t3 += 3) {
    const a = 3 * tri[t3], b = 3 * tri[t3 + 1], c = 3 * tri[t3 + 2];
    const ux = x[b] - x[a], uy = x[b + 1] - x[a + 1], uz = x[b + 2] - x[a + 2];
    const wx = x[c] - x[a], wy = x[c + 1] - x[a + 1], wz = x[c + 2] - x[a + 2];
    const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx; // |N| = 2·area
    const nl = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (nl < 1e-20) continue;
    // triangle velocity over the last substep: (Σ (x − x_prev))/(3h)
    const rx = wind[0] - (x[a] - xp[a] + x[b] - xp[b] + x[c] - xp[c]) * inv3h;
    const ry = wind[1] - (x[a + 1] - xp[a + 1] + x[b + 1] - xp[b + 1] + x[c + 1] - xp[c + 1]) * inv3h;
    const rz = wind[2] - (x[a + 2] - xp[a + 2] + x[b + 2] - xp[b + 2] + x[c + 2] - xp[c + 2]) * inv3h;
    const speed = Math.sqrt(rx * rx + ry * ry + rz * rz);
    const vn = (rx * nx + ry * ny + rz * nz) / nl; // relative air speed along the unit normal
    // per-particle force along the unit normal, and its cap
    let fn = k * speed * vn * nl;
    const cap = (Math.abs(vn) * capScale) / (im[tri[t3]] + im[tri[t3 + 1]] + im[tri[t3 + 2]]);
    if (fn > cap) fn = cap; else if (fn < -cap) fn = -cap;
    const s = fn / nl;
    const fx = s * nx, fy = s * ny, fz = s * nz;
    f[a] += fx; f[a + 1] += fy; f[a + 2] += fz;
    f[b] += fx; f[b + 1] += fy; f[b + 2] += fz;
    f[c] += fx; f[c + 1] += fy; f[c + 2] += fz;
  }
  return true;
}

/**
 * Position Verlet: x(t+h) = 2x(t) − x(t−h) + c·h²·a with a = g + w·f, and previous ← x(t). The very first substep
 * starts from rest with the Taylor term c = ½, which makes the integrator exact for constant acceleration
 * (x = x₀ + ½at²). Particles with zero inverse mass do not move (and get zero velocity).
 *
 * Positions are float32 plus their residuals (state.residuals): the step is taken on the sum in float64 and what
 * rounding the new position to float32 drops is kept as its residual. Without it, g·h² (7·10⁻⁸ m at 200 substeps)
 * is rounded away against a position's last bit and the error is integrated twice: free fall was 7 % short at 200
 * substeps near the origin, 12 % long at 100 m, and nothing fell at 300 m (docs/physics.md "Precision").
 */
export function integrate(state: ClothState, params: SimParams, h: number, withForces: boolean): void {
  const x = state.positions, xp = state.previousPositions, w = state.invMass, f = state.forces;
  const r = state.residuals, rp = state.previousResiduals;
  const c = state.substeps === 0 ? 0.5 : 1;
  const h2 = c * h * h;
  const gx = params.gravity[0] * h2, gy = params.gravity[1] * h2, gz = params.gravity[2] * h2;
  const n = w.length;
  for (let i = 0; i < n; i++) {
    const j = 3 * i;
    const wi = w[i];
    let ax = gx, ay = gy, az = gz;
    if (withForces && wi !== 0) {
      const s = wi * h2;
      ax += f[j] * s; ay += f[j + 1] * s; az += f[j + 2] * s;
    }
    verlet(x, xp, r, rp, j, wi !== 0, ax);
    verlet(x, xp, r, rp, j + 1, wi !== 0, ay);
    verlet(x, xp, r, rp, j + 2, wi !== 0, az);
  }
}

/** One coordinate of integrate(): X = x + r moves by (X − X_prev) + a when `free`; previous ← X. */
function verlet(x: Float32Array, xp: Float32Array, r: Float32Array, rp: Float32Array, j: number, free: boolean, a: number): void {
  const x0 = x[j], r0 = r[j];
  if (free) {
    const X = x0 + r0;
    const next = X + (X - (xp[j] + rp[j])) + a;
    const q = Math.fround(next);
    x[j] = q;
    r[j] = next - q;
  }
  xp[j] = x0;
  rp[j] = r0;
}

/**
 * Carries the particles pinned to colliders (params.carried) to where their colliders put them at time t1 [s], the
 * end of the substep (they are pinned: integrate left them where they were and set x_prev there, so their velocity
 * over the substep is the collider's).
 */
export function carryPinned(state: ClothState, params: SimParams, t0: number, t1: number): void {
  const { particles, collider, local } = params.carried;
  const colliders = params.colliders;
  let last = -1;
  for (let k = 0; k < particles.length; k++) {
    const shape = colliders[collider[k]];
    if (collider[k] !== last) { shape.moveTo(t0, t1); last = collider[k]; }
    const R = shape.R, o = shape.o, lx = local[3 * k], ly = local[3 * k + 1], lz = local[3 * k + 2];
    const j = 3 * particles[k];
    place(state, j, R[0] * lx + R[1] * ly + R[2] * lz + o[0]);
    place(state, j + 1, R[3] * lx + R[4] * ly + R[5] * lz + o[1]);
    place(state, j + 2, R[6] * lx + R[7] * ly + R[8] * lz + o[2]);
  }
}

/**
 * Where the grab carries its particle over this frame [m], into `out`: the grab target, or, where that is farther
 * from `from` (the particle at the frame's start) than `maxMove` [m], the point `maxMove` along the way to it — the
 * rest comes in the frames after (runFrame: params.grabSpeed × the frame's length).
 */
export function grabFrameTarget(from: ArrayLike<number>, target: ArrayLike<number>, maxMove: number, out: Float64Array): void {
  const dx = target[0] - from[0], dy = target[1] - from[1], dz = target[2] - from[2];
  const d = Math.hypot(dx, dy, dz);
  const s = d > maxMove ? maxMove / d : 1;
  out[0] = from[0] + dx * s;
  out[1] = from[1] + dy * s;
  out[2] = from[2] + dz * s;
}

/** Moves the grabbed particle a fraction of the way from `from` to `to` (kinematic). */
export function moveGrabbed(state: ClothState, from: ArrayLike<number>, to: ArrayLike<number>, fraction: number): void {
  const g = state.grabbed;
  if (g < 0) return;
  place(state, 3 * g, from[0] + (to[0] - from[0]) * fraction);
  place(state, 3 * g + 1, from[1] + (to[1] - from[1]) * fraction);
  place(state, 3 * g + 2, from[2] + (to[2] - from[2]) * fraction);
}

/**
 * Keeps the grab target out of the colliders, once per frame before the substeps (runFrame; the GPU solver's step,
 * which writes the target into its uniforms): the grabbed particle is kinematic, so contact never moves it, and a
 * pointer dragged into a collider would pull it inside. A target nearer a collider's surface than the contact
 * thickness is moved out along the surface normal to that distance, each collider posed where it is at the
 * frame's end `t1` (from `t0`); two rounds over the colliders settle a target in a corner between two. `point`
 * (default the grab target) is the point kept out: runFrame keeps the frame's own target (grabFrameTarget) out too.
 */
export function keepGrabOutside(state: ClothState, params: SimParams, t0: number, t1: number, point: Float64Array = state.grabTarget): void {
  if (state.grabbed < 0 || params.colliders.length === 0) return;
  const t = point, th = params.perCloth.thickness[params.owner[state.grabbed]];
  for (let round = 0; round < 2; round++) {
    for (const shape of params.colliders) {
      shape.moveTo(t0, t1);
      const d = shape.signedDistance(t[0], t[1], t[2], normal, th);
      if (!(d < th)) continue;
      t[0] += (th - d) * normal[0];
      t[1] += (th - d) * normal[1];
      t[2] += (th - d) * normal[2];
    }
  }
}

/** Puts coordinate j of a particle at p [m]: float32 position and its residual. */
function place(state: ClothState, j: number, p: number): void {
  const q = Math.fround(p);
  state.positions[j] = q;
  state.residuals[j] = p - q;
}

/** frictionScale's record: the tangential motion, the overlap, what moved in, the recovery [m]; the scale [-] */
const friction = new Float64Array(5);
const F_TANGENTIAL = 0, F_OVERLAP = 1, F_MOVED_IN = 2, F_RECOVER = 3, F_SCALE = 4;

/**
 * Position-based Coulomb friction (Macklin et al. 2014, "Unified Particle Physics for Real-Time Applications",
 * §6.1): the tangential displacement `d` of a contact over this substep is removed while it is within the static
 * cone (|d| < μs·depth), else reduced by μk·depth (`cloth`'s coefficients: params.perCloth). Writes the scale to
 * apply to d (subtract scale·d) to f[F_SCALE]. Its numbers come and go through the record `f` (none is boxed:
 * colliders/shape.ts).
 *
 * The depth is the part of the push-out that presses (the pressed depth): of an overlap f[F_OVERLAP] (contact
 * thickness less distance), f[F_MOVED_IN] is what the point moved into the surface this substep, the rest was there
 * before it, undone at most f[F_RECOVER] a substep. What the point moved into presses on the surface (the normal
 * impulse, times h²/m), and so does a leftover the push closes within this substep (over ≤ recover: the cloth
 * resting in contact, as before). A deeper overlap, one the push takes more than two substeps to undo, is a
 * depenetration: it moves the cloth without pressing it and gives no friction (between the two, linearly less).
 * Counted as pressure, it let static friction hold a cloth on a collider grown under it while the cloth stretched,
 * a slingshot released when the overlap closed (docs/physics.md, "Overlaps").
 */
function frictionScale(f: Float64Array, params: SimParams, cloth: number): void {
  const tangential = f[F_TANGENTIAL], overlap = f[F_OVERLAP], movedIn = f[F_MOVED_IN], recover = f[F_RECOVER];
  const over = overlap - movedIn;
  const depth = over <= 0 ? overlap : movedIn + Math.max(0, Math.min(over, 2 * recover - over));
  f[F_SCALE] = tangential < 1e-12 ? 0 : tangential < params.perCloth.staticFriction[cloth] * depth ? 1
    : Math.min((params.perCloth.friction[cloth] * depth) / tangential, 1);
}

/**
 * Whether the surface can poke between a triangle's vertices by more than half the contact thickness when the
 * vertices themselves are kept outside: the sag of a surface of curvature radius r under an edge e is
 * e²/(8(r + th)); edges are allowed to stretch to twice their rest length.
 */
export function needsTriangleContact(model: ClothModel, shape: ColliderShape, thickness: number): boolean {
  if (!shape.triangleDeepest) return false;
  const e = 2 * model.maxTriangleEdge;
  return (e * e) / (8 * (shape.minCurvatureRadius + thickness)) > 0.5 * thickness;
}

/** The box of the first n particles of x [m] into `box` (min xyz, max xyz). */
function clothBox(x: Float32Array, n: number): void {
  box[0] = box[1] = box[2] = Infinity; box[3] = box[4] = box[5] = -Infinity;
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      const v = x[3 * i + k];
      if (v < box[k]) box[k] = v;
      if (v > box[3 + k]) box[3 + k] = v;
    }
  }
}

/**
 * Particle contact against every collider, for a substep of h [s] (the `contact` phase): each particle within the
 * contact thickness of a collider is pushed out along the surface normal, with friction. `collideTriangles` (the
 * `contactTriangles` phase, next in the schedule) then does the triangles of shapes whose surface can poke between
 * vertices (the deepest point of the triangle is pushed out, its correction shared by barycentric weight and
 * inverse mass).
 *
 * Overlaps are resolved without launching the cloth. The push-out undoes at once whatever the contact point moved
 * into the surface during this substep; an overlap it did not move into (a cloth that begins inside a collider, or
 * that a collider is moved into) is undone at no more than `depenetrationSpeed` (triangles share it among the
 * triangles of a particle), so the constraints that follow drag the rest of the cloth along no faster. And of the
 * outward motion left after the push-out, the part the push-out made (at most its depth) also moves x_prev: it is
 * not velocity. A particle arriving from outside ends with zero normal velocity, as before. Friction is bounded by
 * the part of the push-out that presses on the surface (frictionScale's pressed depth), not by a depenetration.
 *
 * A moving collider is first put where it is at the substep's end (PosedCollider.moveTo), and every motion above is
 * taken relative to its surface (the surface point's own motion over the substep subtracted): a collider moving
 * into the cloth pushes it at once and gives it its speed, and friction drags the cloth along a moving surface.
 */
export function collideParticles(model: ClothModel, state: ClothState, params: SimParams, h: number): void {
  const x = state.positions, xp = state.previousPositions, w = state.invMass;
  // each particle is kept its own cloth's thickness away (params.thickness: the largest, bounds the reach)
  const owner = params.owner, thickness = params.perCloth.thickness, thMax = params.thickness;
  const recover = params.depenetrationSpeed * h;
  const n = model.particleCount;
  // the cloth's box (pinned particles too: a triangle from a pin to a free particle can touch): every particle and
  // triangle point the contact below can move lies in it
  clothBox(x, n);
  for (const shape of params.colliders) {
    shape.moveTo(state.time, state.time + h);
    // a shape whose bounding ball is farther than the thickness from that box touches nothing this substep
    const o = shape.o, reachBall = shape.boundingRadius + thMax;
    const gx = Math.max(box[0] - o[0], 0, o[0] - box[3]), gy = Math.max(box[1] - o[1], 0, o[1] - box[4]), gz = Math.max(box[2] - o[2], 0, o[2] - box[5]);
    if (gx * gx + gy * gy + gz * gz > reachBall * reachBall) continue;
    const moving = shape.moving;
    for (let i = 0; i < n; i++) {
      if (w[i] === 0) continue;
      const j = 3 * i, cloth = owner[i], th = thickness[cloth];
      const q = contactQuery;
      q[QUERY_X] = x[j]; q[QUERY_Y] = x[j + 1]; q[QUERY_Z] = x[j + 2]; q[QUERY_WITHIN] = th;
      shape.distanceIn(q, normal);
      const d = q[QUERY_D];
      if (d >= th) continue;
      // motion over the substep so far relative to the surface, its normal part, and the push-out
      let mx = x[j] - xp[j], my = x[j + 1] - xp[j + 1], mz = x[j + 2] - xp[j + 2];
      if (moving) {
        shape.surfaceMotion(x[j], x[j + 1], x[j + 2], surface);
        mx -= surface[0]; my -= surface[1]; mz -= surface[2];
      }
      const mn = mx * normal[0] + my * normal[1] + mz * normal[2];
      const movedIn = Math.max(-mn, 0);
      const depth = Math.min(th - d, movedIn + recover);
      const tx = mx - mn * normal[0], ty = my - mn * normal[1], tz = mz - mn * normal[2];
      const f = friction;
      f[F_TANGENTIAL] = Math.sqrt(tx * tx + ty * ty + tz * tz); f[F_OVERLAP] = th - d; f[F_MOVED_IN] = movedIn; f[F_RECOVER] = recover;
      frictionScale(f, params, cloth);
      const s = f[F_SCALE];
      x[j] += depth * normal[0] - s * tx;
      x[j + 1] += depth * normal[1] - s * ty;
      x[j + 2] += depth * normal[2] - s * tz;
      // the outward normal motion the push-out made (mn + depth, at most depth) is not velocity
      const made = Math.min(mn + depth, depth);
      if (made > 0) { xp[j] += made * normal[0]; xp[j + 1] += made * normal[1]; xp[j + 2] += made * normal[2]; }
      // the box still holds the cloth for the colliders after this one
      for (let k = 0; k < 3; k++) {
        if (x[j + k] < box[k]) box[k] = x[j + k];
        if (x[j + k] > box[3 + k]) box[3 + k] = x[j + k];
      }
    }
  }
}

/**
 * Triangle contact against every collider that needs it at this mesh size (needsTriangleContact), for a substep of
 * h [s] (the `contactTriangles` phase, after `contact`): the deepest point of each triangle near the surface is
 * pushed out to the contact thickness as a particle is (collideParticles), with friction relative to the surface,
 * its correction shared by barycentric weight and inverse mass so that Σ bary_i·Δx_i is the wanted displacement.
 */
export function collideTriangles(model: ClothModel, state: ClothState, params: SimParams, h: number): void {
  const x = state.positions, xp = state.previousPositions, w = state.invMass;
  // a triangle is kept its cloth's thickness away (params.thickness: the largest, bounds the reach)
  const owner = params.owner, thickness = params.perCloth.thickness, thMax = params.thickness;
  // a particle can be the contact point of every triangle around it: they share its recovery
  const triangleRecover = (params.depenetrationSpeed * h) / Math.max(1, model.maxTriangleValence);
  const reach = thMax + 2 * model.maxTriangleEdge;
  let boxed = false;
  for (const shape of params.colliders) {
    if (!needsTriangleContact(model, shape, thMax)) continue;
    // idempotent: where collideParticles put it for this substep
    shape.moveTo(state.time, state.time + h);
    // the shape's bounding ball, widened by the reach (a little more, for rounding: the test below says the same
    // for a vertex outside it): a shape whose ball misses the cloth's box is skipped, and a triangle whose vertex a
    // lies outside the ball is as far as the distance test below would find it (the mannequin's limbs: most
    // triangles are far from most of them)
    const o = shape.o, ball = (shape.boundingRadius + reach) * (1 + 1e-9), ball2 = ball * ball;
    if (ball2 < Infinity) {
      if (!boxed) { clothBox(x, model.particleCount); boxed = true; }
      const gx = Math.max(box[0] - o[0], 0, o[0] - box[3]), gy = Math.max(box[1] - o[1], 0, o[1] - box[4]), gz = Math.max(box[2] - o[2], 0, o[2] - box[5]);
      if (gx * gx + gy * gy + gz * gz > ball2) continue;
    }
    const moving = shape.moving;
    const tri = model.triangles;
    // the shape's box, widened by the thickness: a triangle whose box misses it is farther than that (a pole
    // beside a flag: its ball holds the flag, its box a few triangles)
    shape.worldHalfExtents(half);
    const lx = o[0] - half[0] - thMax, hx = o[0] + half[0] + thMax, ly = o[1] - half[1] - thMax;
    const hy = o[1] + half[1] + thMax, lz = o[2] - half[2] - thMax, hz = o[2] + half[2] + thMax;
    for (let t = 0; t < tri.length; t += 3) {
      const a = tri[t], b = tri[t + 1], c = tri[t + 2], cloth = owner[a], th = thickness[cloth];
      const ja = 3 * a, jb = 3 * b, jc = 3 * c;
      if (Math.max(x[ja], x[jb], x[jc]) < lx || Math.min(x[ja], x[jb], x[jc]) > hx ||
        Math.max(x[ja + 1], x[jb + 1], x[jc + 1]) < ly || Math.min(x[ja + 1], x[jb + 1], x[jc + 1]) > hy ||
        Math.max(x[ja + 2], x[jb + 2], x[jc + 2]) < lz || Math.min(x[ja + 2], x[jb + 2], x[jc + 2]) > hz) continue;
      const ex = x[3 * a] - o[0], ey = x[3 * a + 1] - o[1], ez = x[3 * a + 2] - o[2];
      if (ex * ex + ey * ey + ez * ez > ball2) continue;
      // the triangle's own ball (its centroid, its farthest corner from it): farther than the thickness from the
      // shape, so is every point of the triangle
      const cx = (x[3 * a] + x[3 * b] + x[3 * c]) / 3, cy = (x[3 * a + 1] + x[3 * b + 1] + x[3 * c + 1]) / 3, cz = (x[3 * a + 2] + x[3 * b + 2] + x[3 * c + 2]) / 3;
      // (each corner's squared distance written out: a helper's numbers were boxed, colliders/shape.ts)
      const ax0 = x[ja] - cx, ay0 = x[ja + 1] - cy, az0 = x[ja + 2] - cz, bx0 = x[jb] - cx, by0 = x[jb + 1] - cy, bz0 = x[jb + 2] - cz;
      const cx0 = x[jc] - cx, cy0 = x[jc + 1] - cy, cz0 = x[jc + 2] - cz;
      const r = Math.sqrt(Math.max(ax0 * ax0 + ay0 * ay0 + az0 * az0, bx0 * bx0 + by0 * by0 + bz0 * bz0, cx0 * cx0 + cy0 * cy0 + cz0 * cz0));
      const far = th + r * (1 + 1e-9), q = contactQuery;
      q[QUERY_X] = cx; q[QUERY_Y] = cy; q[QUERY_Z] = cz; q[QUERY_WITHIN] = far;
      shape.distanceIn(q, normal);
      if (q[QUERY_D] >= far) continue;
      const tq = contactTriangle;
      tq[TRIANGLE_WITHIN] = th;
      shape.triangleDeepestIn!(x, 3 * a, x, 3 * b, x, 3 * c, bary, normal, tq);
      const d = tq[TRIANGLE_D];
      if (d >= th) continue;
      const wa = w[a] * bary[0], wb = w[b] * bary[1], wc = w[c] * bary[2];
      const denom = wa * bary[0] + wb * bary[1] + wc * bary[2];
      // (not > 0: nothing free to move, or weights of a triangle too degenerate to have any)
      if (!(denom > 0)) continue;
      // corner i moves (wᵢ/denom)·Δ for the point's Δ: a point at or beside a corner that cannot move (pinned,
      // grabbed) leaves a free corner a small share and would throw it by Δ/share, across the cloth (5.6 cm in one
      // substep, a corner grabbed along a sphere): no corner moves more than TRIANGLE_SPREAD_MOST × Δ (a grid of free
      // particles spreads at most 1.82 Δ)
      const spread = Math.max(wa, wb, wc) / denom, scale = spread > SPREAD_MOST ? SPREAD_MOST / spread : 1;
      // motion of the contact point over the substep so far, treated as a particle's above
      let mx = bary[0] * (x[3 * a] - xp[3 * a]) + bary[1] * (x[3 * b] - xp[3 * b]) + bary[2] * (x[3 * c] - xp[3 * c]);
      let my = bary[0] * (x[3 * a + 1] - xp[3 * a + 1]) + bary[1] * (x[3 * b + 1] - xp[3 * b + 1]) + bary[2] * (x[3 * c + 1] - xp[3 * c + 1]);
      let mz = bary[0] * (x[3 * a + 2] - xp[3 * a + 2]) + bary[1] * (x[3 * b + 2] - xp[3 * b + 2]) + bary[2] * (x[3 * c + 2] - xp[3 * c + 2]);
      if (moving) {
        shape.surfaceMotion(
          bary[0] * x[3 * a] + bary[1] * x[3 * b] + bary[2] * x[3 * c],
          bary[0] * x[3 * a + 1] + bary[1] * x[3 * b + 1] + bary[2] * x[3 * c + 1],
          bary[0] * x[3 * a + 2] + bary[1] * x[3 * b + 2] + bary[2] * x[3 * c + 2],
          surface,
        );
        mx -= surface[0]; my -= surface[1]; mz -= surface[2];
      }
      const mn = mx * normal[0] + my * normal[1] + mz * normal[2];
      const movedIn = Math.max(-mn, 0);
      const depth = Math.min(th - d, movedIn + triangleRecover);
      const tx = mx - mn * normal[0], ty = my - mn * normal[1], tz = mz - mn * normal[2];
      const f = friction;
      f[F_TANGENTIAL] = Math.sqrt(tx * tx + ty * ty + tz * tz); f[F_OVERLAP] = th - d; f[F_MOVED_IN] = movedIn; f[F_RECOVER] = triangleRecover;
      frictionScale(f, params, cloth);
      const fs = f[F_SCALE];
      // desired displacement of the contact point, spread so that Σ bary_i·Δx_i equals it; and what of it
      // moves x_prev likewise
      const made = Math.min(mn + depth, depth);
      const dx = ((depth * normal[0] - fs * tx) / denom) * scale;
      const dy = ((depth * normal[1] - fs * ty) / denom) * scale;
      const dz = ((depth * normal[2] - fs * tz) / denom) * scale;
      x[3 * a] += wa * dx; x[3 * a + 1] += wa * dy; x[3 * a + 2] += wa * dz;
      x[3 * b] += wb * dx; x[3 * b + 1] += wb * dy; x[3 * b + 2] += wb * dz;
      x[3 * c] += wc * dx; x[3 * c + 1] += wc * dy; x[3 * c + 2] += wc * dz;
      if (made > 0) {
        const px = ((made * normal[0]) / denom) * scale, py = ((made * normal[1]) / denom) * scale, pz = ((made * normal[2]) / denom) * scale;
        xp[3 * a] += wa * px; xp[3 * a + 1] += wa * py; xp[3 * a + 2] += wa * pz;
        xp[3 * b] += wb * px; xp[3 * b + 1] += wb * py; xp[3 * b + 2] += wb * pz;
        xp[3 * c] += wc * px; xp[3 * c + 1] += wc * py; xp[3 * c + 2] += wc * pz;
      }
    }
  }
}

/**
 * End of a step: v = (x − x_prev)/h of the last substep for every particle (pinned ones get 0, a grabbed one the
 * velocity it is carried with).
 */
export function updateVelocities(state: ClothState, h: number): void {
  const x = state.positions, xp = state.previousPositions, v = state.velocities;
  const r = state.residuals, rp = state.previousResiduals;
  const inv = 1 / h;
  for (let j = 0; j < x.length; j++) v[j] = (x[j] - xp[j] + (r[j] - rp[j])) * inv;
}

/**
 * Stretch limiting (Provot 1995, "Deformation constraints in a mass-spring model to describe rigid cloth
 * behavior"): structural and shear springs longer than stretchFactor × rest are projected back, batch by batch.
 */
export function limitStretch(model: ClothModel, state: ClothState, params: SimParams): void {
  const x = state.positions, w = state.invMass;
  const springs = model.springs, rest = model.restLengths;
  const owner = params.owner, stretch = params.perCloth.stretchFactor;
  for (const batch of model.batches) {
    if (batch.kind === BEND) continue;
    for (let s = batch.start; s < batch.end; s++) {
      const pa = springs[2 * s], pb = springs[2 * s + 1], sf = stretch[owner[pa]];
      const wa = w[pa], wb = w[pb];
      const wsum = wa + wb;
      if (wsum === 0) continue;
      const a = 3 * pa, b = 3 * pb;
      const dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
      const len2 = dx * dx + dy * dy + dz * dz;
      const max = sf * rest[s];
      if (len2 <= max * max) continue;
      const len = Math.sqrt(len2);
      const scale = (len - max) / (len * wsum);
      x[a] -= wa * scale * dx; x[a + 1] -= wa * scale * dy; x[a + 2] -= wa * scale * dz;
      x[b] += wb * scale * dx; x[b + 1] += wb * scale * dy; x[b + 2] += wb * scale * dz;
    }
  }
}
