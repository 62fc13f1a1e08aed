/**
 * A collider where it is now: its shape in the shape's own frame (colliders/*.ts built at the origin: a sphere's
 * centre, a box's centre and axes, a capsule's or cylinder's axis along y, a plane through the origin facing +y),
 * placed in the world by the scene (centre, rotation, axis…) and moved by its motion: keyframes from the scene
 * (`colliders[k].motion`) or a pose and velocity the library sets each frame (Simulation.setColliderPose).
 *
 * The motion is a rigid transform relative to the scene's placement, turning about `pivot` (default: the
 * collider's centre) and then translating: M(t)·p = R_m(t)·(p − pivot) + pivot + T(t). World = M(t)·placement·local.
 * Keyframes interpolate translation and Euler XYZ angles linearly (so one key at 0° and one at 360° spin the
 * collider once at constant angular velocity about one axis), hold the first and last key outside their range, or
 * repeat with `loop`. A drive from the library moves on with constant velocity and angular velocity [rad/s]
 * (about the pivot, world axes) from the time it was set.
 *
 * The contact phase calls `moveTo(t0, t1)` once per substep: the collider is where it is at the substep's end t1,
 * and `surfaceMotion` says how far the surface point now at p moved over the substep (p minus where that material
 * point was at t0), so friction acts on the cloth's motion relative to the surface and a collider moving into the
 * cloth carries it along (phases.ts collideParticles()).
 */
import {
  COLLIDER_BOX, COLLIDER_CAPSULE, COLLIDER_CYLINDER, COLLIDER_FLOOR, COLLIDER_MESH, COLLIDER_PLANE, COLLIDER_RECORD_EXACT, COLLIDER_RECORD_MOVING, COLLIDER_RECORD_O,
  COLLIDER_RECORD_OD, COLLIDER_RECORD_R, COLLIDER_RECORD_RD, COLLIDER_RECORD_SHAPE, COLLIDER_RECORD_TYPE, COLLIDER_SPHERE,
} from '../layout.generated.js';
import { BoxCollider } from './box.js';
import { CapsuleCollider } from './capsule.js';
import { CylinderCollider } from './cylinder.js';
import { MeshCollider } from './mesh.js';
import { PlaneCollider } from './plane.js';
import { eulerXYZInto } from '../mesh/generators.js';
import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery, triangleQuery, type ColliderShape } from './shape.js';
import { FloorCollider } from './floor.js';
import { SphereCollider } from './sphere.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { WITHIN: TRIANGLE_WITHIN, D: TRIANGLE_D } = TRIANGLE;

export type Vec3 = readonly [number, number, number];

/** One key of a collider's motion (the scene's `colliders[k].motion.keyframes`). */
export interface ColliderKeyframe {
  /** time [s] */
  time: number;
  /** translation from the scene's placement [m] */
  translation: Vec3;
  /** rotation about the pivot, Euler XYZ [degrees] */
  rotation: Vec3;
}

/** A collider's keyframed motion (the scene's `colliders[k].motion`). */
export interface ColliderMotion {
  keyframes: ColliderKeyframe[];
  /** the point the rotation turns about [m]; absent: the collider's centre */
  pivot?: Vec3;
  /** repeat the keys with the last key's time as the period */
  loop: boolean;
}

/** A collider's pose and velocity set through the library: where it is now, and how it moves from now on. */
export interface ColliderPose {
  /** translation from the scene's placement [m] (default 0) */
  translation?: Vec3;
  /** rotation about the pivot, Euler XYZ [degrees] (default 0) */
  rotation?: Vec3;
  /** velocity of the translation [m/s] (default 0) */
  velocity?: Vec3;
  /** angular velocity about the pivot, world axes [rad/s] (default 0) */
  angularVelocity?: Vec3;
}

/** Where a drive started: the motion at time t0 and its velocities. */
interface Drive {
  t0: number;
  translation: Float64Array;
  rotation: Float64Array;
  velocity: Float64Array;
  angularVelocity: Float64Array;
}

/** r = a·b for row-major 3×3 matrices (r may not alias a or b). */
function mul3(a: ArrayLike<number>, b: ArrayLike<number>, r: Float64Array): void {
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  }
}

/** Rotation by |w|·dt about w (Rodrigues) into r. */
function axisAngle(wx: number, wy: number, wz: number, dt: number, r: Float64Array): void {
  const l = Math.hypot(wx, wy, wz);
  const angle = l * dt;
  if (!(l > 0) || angle === 0) { r.set(IDENTITY); return; }
  const x = wx / l, y = wy / l, z = wz / l, c = Math.cos(angle), s = Math.sin(angle), k = 1 - c;
  r[0] = c + k * x * x; r[1] = k * x * y - s * z; r[2] = k * x * z + s * y;
  r[3] = k * y * x + s * z; r[4] = c + k * y * y; r[5] = k * y * z - s * x;
  r[6] = k * z * x - s * y; r[7] = k * z * y + s * x; r[8] = c + k * z * z;
}

const IDENTITY = [1, 0, 0, 0, 1, 0, 0, 0, 1];
const scratchN = new Float64Array(3);
const scratchTri = new Float32Array(9);
const scratchR = new Float64Array(9);
const scratchR2 = new Float64Array(9);
const scratchE = new Float64Array(3);
const scratchT = new Float64Array(3);
const scratchE9 = new Float64Array(9);
/** the queries a posed collider makes of its shape in its own frame */
const localQuery = pointQuery();
const localTriangle = triangleQuery();

/** The type id and numbers of a shape built in its own frame by createColliders (colliders/index.ts). */
function kernelShape(l: ColliderShape): [number, [number, number, number]] {
  if (l instanceof SphereCollider) return [COLLIDER_SPHERE, [l.radius, 0, 0]];
  if (l instanceof FloorCollider) return [COLLIDER_FLOOR, [0, 0, 0]];
  if (l instanceof PlaneCollider) return [COLLIDER_PLANE, [0, 0, 0]];
  if (l instanceof BoxCollider) return [COLLIDER_BOX, [l.halfExtents[0], l.halfExtents[1], l.halfExtents[2]]];
  if (l instanceof CapsuleCollider) return [COLLIDER_CAPSULE, [l.b[1], l.radius, 0]];
  if (l instanceof CylinderCollider) return [COLLIDER_CYLINDER, [l.radius, l.halfHeight, 0]];
  // its hierarchy, triangles and pseudo-normals are tables of their own (the GPU's meshNodes and meshTriangles)
  if (l instanceof MeshCollider) return [COLLIDER_MESH, [0, 0, 0]];
  return [0, [0, 0, 0]];
}

/** A collider shape in its own frame, placed and moved in the world (see the file's comment). */
export class PosedCollider implements ColliderShape {
  readonly type: string;
  readonly minCurvatureRadius: number;
  /** the shape's type id (COLLIDER_* of layout.generated.ts), what a kernel's record says first */
  readonly typeId: number;
  /**
   * the shape's numbers in its own frame, as kernels read them: a sphere's radius; a box's half extents; a capsule's
   * half length (its axis runs along y from −that to +that) and radius; a cylinder's radius and half height; none
   * for a floor or a plane (the half-space y < 0), nor for a mesh (its tables are its own)
   */
  readonly shapeParams: readonly [number, number, number];
  /** radius of a ball about `o` that holds the whole shape [m] (Infinity for a floor, a plane or a mesh: none is kept) */
  readonly boundingRadius: number;
  /** half extents of the shape's box about `o` in its own frame [m] (Infinity for a floor, a plane or a mesh) */
  private readonly localHalf: Float64Array;
  /** world = R·local + o at the end of the current substep; R row-major */
  readonly R = new Float64Array(9);
  readonly o = new Float64Array(3);
  /** where a surface point now at p was at the substep's start: RD·p + oD (identity while it does not move) */
  readonly RD = new Float64Array(IDENTITY);
  readonly oD = new Float64Array(3);
  /** whether the surface moved over the current substep */
  moving = false;
  private readonly placeR: Float64Array;
  private readonly placeO: Float64Array;
  readonly pivot: Float64Array;
  private readonly keyTimes: Float64Array;
  private readonly keyValues: Float64Array;
  private readonly loop: boolean;
  private drive: Drive | null = null;
  private readonly R0 = new Float64Array(9);
  private readonly o0 = new Float64Array(3);

  constructor(
    /** the shape in its own frame */
    readonly local: ColliderShape,
    /** the scene's placement: world = placeR·local + placeO before any motion */
    placeR: ArrayLike<number>, placeO: Vec3,
    motion?: ColliderMotion,
  ) {
    this.type = local.type;
    this.minCurvatureRadius = local.minCurvatureRadius;
    [this.typeId, this.shapeParams] = kernelShape(local);
    const [p0, p1, p2] = this.shapeParams;
    this.boundingRadius = this.typeId === COLLIDER_SPHERE ? p0 : this.typeId === COLLIDER_BOX ? Math.hypot(p0, p1, p2)
      : this.typeId === COLLIDER_CAPSULE ? p0 + p1 : this.typeId === COLLIDER_CYLINDER ? Math.hypot(p0, p1) : Infinity;
    this.localHalf = new Float64Array(this.typeId === COLLIDER_SPHERE ? [p0, p0, p0] : this.typeId === COLLIDER_BOX ? [p0, p1, p2]
      : this.typeId === COLLIDER_CAPSULE ? [p1, p0 + p1, p1] : this.typeId === COLLIDER_CYLINDER ? [p0, p1, p0] : [Infinity, Infinity, Infinity]);
    this.placeR = new Float64Array(placeR);
    this.placeO = new Float64Array(placeO);
    this.pivot = new Float64Array(motion?.pivot ?? placeO);
    const keys = motion?.keyframes ?? [];
    this.keyTimes = new Float64Array(keys.map((k) => k.time));
    this.keyValues = new Float64Array(keys.flatMap((k) => [...k.translation, ...k.rotation]));
    this.loop = (motion?.loop ?? false) && keys.length > 1 && keys[keys.length - 1].time > 0;
    if (!local.triangleDeepestIn) { this.triangleDeepest = undefined; this.triangleDeepestIn = undefined; }
    this.poseAt(0, this.R, this.o);
  }

  /** Whether the library drives it (setDrive). */
  get driven(): boolean {
    return this.drive !== null;
  }

  /** Takes over the drive of `other` (the same collider in params rebuilt for a changed scene). */
  takeDrive(other: PosedCollider): void {
    this.drive = other.drive;
    this.R.set(other.R); this.o.set(other.o);
  }

  /** Whether the collider can move: it has keyframes or a drive. */
  get animated(): boolean {
    return this.keyTimes.length > 0 || this.drive !== null;
  }

  /**
   * Drives the collider from time t [s] on: the pose (motion from the scene's placement) at t, and the velocities it
   * keeps until the next call; null gives it back to its scene motion. Every field of `pose` must be finite (the
   * caller checks).
   */
  setDrive(t: number, pose: ColliderPose | null): void {
    if (!pose) { this.drive = null; this.poseAt(t, this.R, this.o); return; }
    const v = (a: Vec3 | undefined) => new Float64Array(a ?? [0, 0, 0]);
    this.drive = { t0: t, translation: v(pose.translation), rotation: v(pose.rotation), velocity: v(pose.velocity), angularVelocity: v(pose.angularVelocity) };
    this.poseAt(t, this.R, this.o);
  }

  /** The motion at time t: translation to `tr`, rotation matrix to `rm`. */
  private motionAt(t: number, tr: Float64Array, rm: Float64Array): void {
    const d = this.drive;
    if (d) {
      const dt = t - d.t0;
      for (let k = 0; k < 3; k++) tr[k] = d.translation[k] + d.velocity[k] * dt;
      axisAngle(d.angularVelocity[0], d.angularVelocity[1], d.angularVelocity[2], dt, scratchR2);
      eulerXYZInto(d.rotation, scratchE9);
      mul3(scratchR2, scratchE9, rm);
      return;
    }
    const times = this.keyTimes, vals = this.keyValues, n = times.length;
    if (n === 0) { tr.fill(0); rm.set(IDENTITY); return; }
    if (this.loop) {
      const period = times[n - 1];
      t -= Math.floor(t / period) * period;
    }
    // the key at or before t (binary search), and the fraction towards the next
    let lo = 0, hi = n - 1;
    if (t <= times[0]) hi = 0;
    else if (t >= times[n - 1]) lo = hi = n - 1;
    else {
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (times[mid] <= t) lo = mid; else hi = mid;
      }
    }
    const f = hi === lo || times[hi] === times[lo] ? 0 : (t - times[lo]) / (times[hi] - times[lo]);
    const a = 6 * (hi === 0 ? 0 : lo), b = 6 * hi;
    for (let k = 0; k < 3; k++) {
      tr[k] = vals[a + k] + f * (vals[b + k] - vals[a + k]);
      scratchE[k] = vals[a + 3 + k] + f * (vals[b + 3 + k] - vals[a + 3 + k]);
    }
    eulerXYZInto(scratchE, rm);
  }

  /** The world transform of the shape's frame at time t: world = r·local + o. */
  poseAt(t: number, r: Float64Array, o: Float64Array): void {
    const pr = this.placeR, po = this.placeO, c = this.pivot;
    if (!this.animated) { r.set(pr); o.set(po); return; }
    const rm = scratchR;
    this.motionAt(t, scratchT, rm);
    mul3(rm, pr, r);
    const qx = po[0] - c[0], qy = po[1] - c[1], qz = po[2] - c[2];
    for (let k = 0; k < 3; k++) o[k] = rm[3 * k] * qx + rm[3 * k + 1] * qy + rm[3 * k + 2] * qz + c[k] + scratchT[k];
  }

  /** Puts the collider where it is at the end t1 of a substep that began at t0 [s], and its surface motion over it. */
  moveTo(t0: number, t1: number): void {
    if (!this.animated) { this.moving = false; return; }
    const R = this.R, o = this.o, R0 = this.R0, o0 = this.o0, RD = this.RD, oD = this.oD;
    this.poseAt(t0, R0, o0);
    this.poseAt(t1, R, o);
    // p at t1 came from R0·Rᵀ·(p − o) + o0
    for (let i = 0; i < 3; i++) {
      for (let j = 0; j < 3; j++) RD[3 * i + j] = R0[3 * i] * R[3 * j] + R0[3 * i + 1] * R[3 * j + 1] + R0[3 * i + 2] * R[3 * j + 2];
    }
    for (let i = 0; i < 3; i++) oD[i] = o0[i] - (RD[3 * i] * o[0] + RD[3 * i + 1] * o[1] + RD[3 * i + 2] * o[2]);
    let moved = false;
    for (let k = 0; k < 9 && !moved; k++) moved = RD[k] !== IDENTITY[k];
    this.moving = moved || oD[0] !== 0 || oD[1] !== 0 || oD[2] !== 0;
  }

  /**
   * Half extents of the world box about `o` that holds the shape where it is now (after moveTo) [m], to out[0..2]:
   * its own frame's box turned by R (Infinity for a floor, a plane or a mesh).
   */
  worldHalfExtents(out: Float64Array): void {
    const R = this.R, e = this.localHalf;
    for (let i = 0; i < 3; i++) {
      out[i] = e[0] === Infinity ? Infinity : Math.abs(R[3 * i]) * e[0] + Math.abs(R[3 * i + 1]) * e[1] + Math.abs(R[3 * i + 2]) * e[2];
    }
  }

  /** How far the surface point now at p moved over the current substep [m], to out[0..2]. */
  surfaceMotion(px: number, py: number, pz: number, out: Float64Array): void {
    const D = this.RD, oD = this.oD;
    out[0] = px - (D[0] * px + D[1] * py + D[2] * pz + oD[0]);
    out[1] = py - (D[3] * px + D[4] * py + D[5] * pz + oD[1]);
    out[2] = pz - (D[6] * px + D[7] * py + D[8] * pz + oD[2]);
  }

  /**
   * The WebAssembly kernel's record of the collider for the current substep (after moveTo) to out[at…]: the fields
   * of COLLIDER_RECORD (gen-layout.mjs), COLLIDER_RECORD_FLOATS numbers. `exact`: the collider also has triangle
   * contact (its particle contact then runs in f64).
   */
  writeRecord(out: Float64Array, at: number, exact: boolean): void {
    out[at + COLLIDER_RECORD_TYPE] = this.typeId;
    out[at + COLLIDER_RECORD_MOVING] = this.moving ? 1 : 0;
    out[at + COLLIDER_RECORD_EXACT] = exact ? 1 : 0;
    const p = this.shapeParams;
    out[at + COLLIDER_RECORD_SHAPE] = p[0]; out[at + COLLIDER_RECORD_SHAPE + 1] = p[1]; out[at + COLLIDER_RECORD_SHAPE + 2] = p[2];
    out.set(this.R, at + COLLIDER_RECORD_R);
    out.set(this.o, at + COLLIDER_RECORD_O);
    out.set(this.RD, at + COLLIDER_RECORD_RD);
    out.set(this.oD, at + COLLIDER_RECORD_OD);
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    const R = this.R, within = q[QUERY_WITHIN];
    const dx = q[QUERY_X] - this.o[0], dy = q[QUERY_Y] - this.o[1], dz = q[QUERY_Z] - this.o[2];
    const n = scratchN, l = localQuery;
    l[QUERY_X] = R[0] * dx + R[3] * dy + R[6] * dz; l[QUERY_Y] = R[1] * dx + R[4] * dy + R[7] * dz; l[QUERY_Z] = R[2] * dx + R[5] * dy + R[8] * dz;
    l[QUERY_WITHIN] = within;
    this.local.distanceIn(l, n);
    const d = l[QUERY_D];
    if (d < within) {
      normal[0] = R[0] * n[0] + R[1] * n[1] + R[2] * n[2];
      normal[1] = R[3] * n[0] + R[4] * n[1] + R[5] * n[2];
      normal[2] = R[6] * n[0] + R[7] * n[1] + R[8] * n[2];
    }
    q[QUERY_D] = d;
  }

  triangleDeepest?(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, within = Infinity,
  ): number {
    return deepestOf(this, a, ia, b, ib, c, ic, bary, normal, within);
  }

  triangleDeepestIn?(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, t: Float64Array,
  ): void {
    const within = t[TRIANGLE_WITHIN];
    const R = this.R, o = this.o, s = scratchTri;
    // the three corners in the shape's frame, written out here: as a call per corner (a helper) the numbers were
    // boxed, 144 bytes of garbage per triangle tested (node's sampling heap profiler, the default scene)
    const o0 = o[0], o1 = o[1], o2 = o[2];
    for (let k = 0; k < 3; k++) {
      const v = k === 0 ? a : k === 1 ? b : c, iv = k === 0 ? ia : k === 1 ? ib : ic, at = 3 * k;
      const dx = v[iv] - o0, dy = v[iv + 1] - o1, dz = v[iv + 2] - o2;
      s[at] = R[0] * dx + R[3] * dy + R[6] * dz;
      s[at + 1] = R[1] * dx + R[4] * dy + R[7] * dz;
      s[at + 2] = R[2] * dx + R[5] * dy + R[8] * dz;
    }
    const n = scratchN, l = localTriangle;
    l[TRIANGLE_WITHIN] = within;
    this.local.triangleDeepestIn!(s, 0, s, 3, s, 6, bary, n, l);
    const d = l[TRIANGLE_D];
    // (not d >= within: a NaN's normal is written, as it was with no bound)
    if (!(d >= within)) {
      normal[0] = R[0] * n[0] + R[1] * n[1] + R[2] * n[2];
      normal[1] = R[3] * n[0] + R[4] * n[1] + R[5] * n[2];
      normal[2] = R[6] * n[0] + R[7] * n[1] + R[8] * n[2];
    }
    t[TRIANGLE_D] = d;
  }
}
