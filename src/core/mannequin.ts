/**
 * A virtual mannequin (the seed's "virtual mannequin project", as colliders): an articulated human figure about
 * 1.75 m tall standing on y = 0, made of a sphere (the head) and capsules (neck, chest, belly, pelvis, upper and
 * lower arms, thighs, shins, feet), hung on a skeleton of joints, posed by joint angles and moved by forward
 * kinematics.
 *
 * It faces +z with its left on +x. Each joint turns its children by Euler XYZ angles [degrees] in its parent's
 * frame (R = Rz·Ry·Rx, as the scene's rotations), and sits at a fixed offset from its parent: the bones keep their
 * lengths whatever the angles. A pose is a set of angles ('stand': arms a little away from the body, elbows a little
 * bent; 't-pose': arms out level); an animation changes them with time ('walk': a walk cycle in place, legs and arms
 * swinging, the hips turning a little; 'turn': the whole figure turning about the vertical through its pelvis, 70°
 * to either side and back).
 *
 * `mannequinColliders` turns a posed, animated mannequin into the scene's colliders: each part is a capsule or a
 * sphere placed where it is at time 0, and, when animated, a looping `motion` whose keys (KEY_RATE per second over
 * one cycle) are that part's rigid motion from the forward kinematics: its centre's displacement and its rotation
 * about its centre (the default pivot), as continuous Euler angles. Between keys the scene interpolates linearly
 * (colliders/pose.ts). Pure: no DOM, no state.
 */
import { eulerXYZ } from './mesh/generators.js';
import type { ColliderSpec, Vec3 } from './scene.js';
import { shownValue } from './text.js';

/** The mannequin's named poses. */
export const MANNEQUIN_POSES = ['stand', 't-pose'] as const;
export type MannequinPose = (typeof MANNEQUIN_POSES)[number];
/** Its animations ('none': it holds the pose). */
export const MANNEQUIN_ANIMATIONS = ['none', 'walk', 'turn'] as const;
export type MannequinAnimation = (typeof MANNEQUIN_ANIMATIONS)[number];

/** How a mannequin stands and moves. */
export interface MannequinOptions {
  /** the pose its joints hold (default 'stand') */
  pose?: MannequinPose;
  /** how it moves (default 'none') */
  animation?: MannequinAnimation;
  /** where it stands: the point on the floor between its feet [m] (default [0, 0, 0]) */
  position?: Vec3;
  /** which way it faces: degrees about +y from facing +z (90: facing +x) [degrees] (default 0) */
  heading?: number;
  /** size as a multiple of the 1.75 m figure [-] (default 1; MANNEQUIN_SCALE_RANGE) */
  scale?: number;
}

/** The sizes a mannequin can have, as multiples of the 1.75 m figure [-]: a doll to a giant. */
export const MANNEQUIN_SCALE_RANGE: readonly [number, number] = [0.1, 10];

/**
 * Throws a TypeError or RangeError naming the option of `options` that is not one a mannequin takes (the library's
 * callers: a scene file's colliders are checked by the schema).
 */
function checkOptions(options: MannequinOptions): void {
  const fn = 'mannequinColliders';
  if (options === null || typeof options !== 'object') throw new TypeError(`${fn}: options must be an object, got ${shownValue(options)}`);
  const { pose, animation, position, heading, scale } = options;
  const name = shownValue;
  if (pose !== undefined && !(MANNEQUIN_POSES as readonly unknown[]).includes(pose)) {
    throw new RangeError(`${fn}: pose must be one of ${MANNEQUIN_POSES.join(', ')}, got ${name(pose)}`);
  }
  if (animation !== undefined && !(MANNEQUIN_ANIMATIONS as readonly unknown[]).includes(animation)) {
    throw new RangeError(`${fn}: animation must be one of ${MANNEQUIN_ANIMATIONS.join(', ')}, got ${name(animation)}`);
  }
  if (position !== undefined && !(Array.isArray(position) && position.length === 3 && position.every((v) => typeof v === 'number' && Math.abs(v) <= 1000))) {
    throw new RangeError(`${fn}: position must be [x, y, z] of finite numbers within ±1000 m`);
  }
  if (heading !== undefined && !(typeof heading === 'number' && Number.isFinite(heading))) {
    throw new RangeError(`${fn}: heading must be a finite number of degrees, got ${name(heading)}`);
  }
  const [lo, hi] = MANNEQUIN_SCALE_RANGE;
  if (scale !== undefined && !(typeof scale === 'number' && scale >= lo && scale <= hi)) {
    throw new RangeError(`${fn}: scale must be a number in ${lo}…${hi}, got ${name(scale)}`);
  }
}

/** Keys per second of an animated part's motion [1/s]. */
export const KEY_RATE = 30;
/** Length of one walk cycle (two steps) [s]. */
export const WALK_PERIOD = 1.2;
/** Length of one turn (to one side, to the other, back) [s]. */
export const TURN_PERIOD = 4;
/** How far the turn goes to either side [degrees]: below 90°, where Euler XYZ angles lose a degree of freedom. */
export const TURN_ANGLE = 70;

type JointName =
  | 'pelvis' | 'spine' | 'chest' | 'neck'
  | 'shoulderL' | 'elbowL' | 'shoulderR' | 'elbowR'
  | 'hipL' | 'kneeL' | 'ankleL' | 'hipR' | 'kneeR' | 'ankleR';

interface Joint {
  name: JointName;
  /** parent joint (null: the root, placed in the world) */
  parent: JointName | null;
  /** where the joint sits in its parent's frame, for the 1.75 m figure [m] */
  offset: Vec3;
}

/** The skeleton, parents before children. The pelvis (the root) is 0.95 m above the floor. */
const JOINTS: readonly Joint[] = [
  { name: 'pelvis', parent: null, offset: [0, 0.95, 0] },
  { name: 'spine', parent: 'pelvis', offset: [0, 0.08, 0] },
  { name: 'chest', parent: 'spine', offset: [0, 0.28, 0] },
  { name: 'neck', parent: 'chest', offset: [0, 0.13, 0] },
  { name: 'shoulderL', parent: 'chest', offset: [0.19, 0.08, 0] },
  { name: 'elbowL', parent: 'shoulderL', offset: [0, -0.28, 0] },
  { name: 'shoulderR', parent: 'chest', offset: [-0.19, 0.08, 0] },
  { name: 'elbowR', parent: 'shoulderR', offset: [0, -0.28, 0] },
  { name: 'hipL', parent: 'pelvis', offset: [0.09, -0.05, 0] },
  { name: 'kneeL', parent: 'hipL', offset: [0, -0.42, 0] },
  { name: 'ankleL', parent: 'kneeL', offset: [0, -0.41, 0] },
  { name: 'hipR', parent: 'pelvis', offset: [-0.09, -0.05, 0] },
  { name: 'kneeR', parent: 'hipR', offset: [0, -0.42, 0] },
  { name: 'ankleR', parent: 'kneeR', offset: [0, -0.41, 0] },
];

/** One body part in its joint's frame, for the 1.75 m figure: a capsule from a to b, or (no b) a sphere centred at a. */
interface Part {
  name: string;
  joint: JointName;
  /** capsule axis ends, or the sphere's centre (a only) [m] */
  a: Vec3;
  b?: Vec3;
  radius: number;
}

/** The parts, in the order of the colliders they become. */
const PARTS: readonly Part[] = [
  { name: 'head', joint: 'neck', a: [0, 0.205, 0.01], radius: 0.105 },
  { name: 'neck', joint: 'neck', a: [0, -0.03, 0], b: [0, 0.09, 0], radius: 0.05 },
  { name: 'chest', joint: 'chest', a: [-0.11, 0, 0], b: [0.11, 0, 0], radius: 0.1 },
  { name: 'belly', joint: 'spine', a: [0, 0, 0], b: [0, 0.2, 0], radius: 0.12 },
  { name: 'pelvis', joint: 'pelvis', a: [-0.06, 0, 0], b: [0.06, 0, 0], radius: 0.11 },
  { name: 'upper arm L', joint: 'shoulderL', a: [0, 0, 0], b: [0, -0.28, 0], radius: 0.045 },
  { name: 'forearm L', joint: 'elbowL', a: [0, 0, 0], b: [0, -0.3, 0], radius: 0.038 },
  { name: 'upper arm R', joint: 'shoulderR', a: [0, 0, 0], b: [0, -0.28, 0], radius: 0.045 },
  { name: 'forearm R', joint: 'elbowR', a: [0, 0, 0], b: [0, -0.3, 0], radius: 0.038 },
  { name: 'thigh L', joint: 'hipL', a: [0, 0, 0], b: [0, -0.42, 0], radius: 0.07 },
  { name: 'shin L', joint: 'kneeL', a: [0, 0, 0], b: [0, -0.41, 0], radius: 0.05 },
  { name: 'foot L', joint: 'ankleL', a: [0, -0.03, -0.03], b: [0, -0.03, 0.13], radius: 0.035 },
  { name: 'thigh R', joint: 'hipR', a: [0, 0, 0], b: [0, -0.42, 0], radius: 0.07 },
  { name: 'shin R', joint: 'kneeR', a: [0, 0, 0], b: [0, -0.41, 0], radius: 0.05 },
  { name: 'foot R', joint: 'ankleR', a: [0, -0.03, -0.03], b: [0, -0.03, 0.13], radius: 0.035 },
];

/** Names of the mannequin's parts, in the order of its colliders. */
export const MANNEQUIN_PARTS: readonly string[] = PARTS.map((p) => p.name);
/** Index of the chest among the mannequin's colliders: what a cape's pins hang from. */
export const MANNEQUIN_CHEST = MANNEQUIN_PARTS.indexOf('chest');
/** Index of the pelvis among the mannequin's colliders: what a skirt's waistband is carried by. */
export const MANNEQUIN_PELVIS = MANNEQUIN_PARTS.indexOf('pelvis');

/** Joint angles: Euler XYZ [degrees] of each joint in its parent's frame (absent: 0). */
export type JointAngles = Partial<Record<JointName, Vec3>>;

/** The angles of a pose. */
function poseAngles(pose: MannequinPose): JointAngles {
  if (pose === 't-pose') return { shoulderL: [0, 0, 90], shoulderR: [0, 0, -90] };
  // arms 12° out from the body, elbows bent 10° forward
  return { shoulderL: [0, 0, 12], shoulderR: [0, 0, -12], elbowL: [-10, 0, 0], elbowR: [-10, 0, 0] };
}

/** The period of an animation [s] (0 for none). */
export function animationPeriod(animation: MannequinAnimation): number {
  return animation === 'walk' ? WALK_PERIOD : animation === 'turn' ? TURN_PERIOD : 0;
}

/**
 * Joint angles of a pose under an animation at time t [s]. Walk: each hip swings ±25° (negative x: forward), the
 * knee bends up to 55° while its leg swings forward, the ankle keeps the foot level with the pelvis (so the feet
 * never dip below where they stand), the arms swing ±18° against the legs, the hips turn ±6° and the chest turns
 * back. Turn: the pelvis turns TURN_ANGLE·sin(2πt/TURN_PERIOD) about the vertical.
 */
export function mannequinAngles(pose: MannequinPose, animation: MannequinAnimation, t: number): JointAngles {
  const a = poseAngles(pose);
  const add = (j: JointName, d: Vec3) => {
    const v = a[j] ?? [0, 0, 0];
    a[j] = [v[0] + d[0], v[1] + d[1], v[2] + d[2]];
  };
  if (animation === 'walk') {
    const ph = (2 * Math.PI * t) / WALK_PERIOD, s = Math.sin(ph), c = Math.cos(ph);
    for (const [side, sign] of [['L', 1], ['R', -1]] as const) {
      const hip = -25 * sign * s;
      // the knee bends as the leg swings through (its hip angle moving forward)
      const knee = 5 + 50 * Math.max(0, sign * c) ** 2;
      add(`hip${side}`, [hip, 0, 0]);
      add(`knee${side}`, [knee, 0, 0]);
      add(`ankle${side}`, [-(hip + knee), 0, 0]);
      add(`shoulder${side}`, [18 * sign * s, 0, 0]);
      add(`elbow${side}`, [-8 - 8 * Math.max(0, sign * s), 0, 0]);
    }
    add('pelvis', [0, 6 * s, 0]);
    add('chest', [0, -9 * s, 0]);
  } else if (animation === 'turn') {
    add('pelvis', [0, TURN_ANGLE * Math.sin((2 * Math.PI * t) / TURN_PERIOD), 0]);
  }
  return a;
}

/** A rigid frame: world = R·local + o (R row-major). */
export interface Frame {
  R: number[];
  o: number[];
}

const mul = (a: readonly number[], b: readonly number[]): number[] => {
  const r = new Array<number>(9);
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return r;
};
const apply = (f: Frame, p: readonly number[]): number[] =>
  [0, 1, 2].map((i) => f.R[3 * i] * p[0] + f.R[3 * i + 1] * p[1] + f.R[3 * i + 2] * p[2] + f.o[i]);

/**
 * Forward kinematics: each joint's frame in the world for the given angles, the figure standing at `position`,
 * facing `heading`, scaled by `scale`. A joint's frame is its parent's, moved by its offset and turned by its angles.
 */
export function forwardKinematics(angles: JointAngles, options: MannequinOptions = {}): Record<JointName, Frame> {
  const s = options.scale ?? 1, pos = options.position ?? [0, 0, 0];
  const out = {} as Record<JointName, Frame>;
  for (const j of JOINTS) {
    const local = eulerXYZ(angles[j.name] ?? [0, 0, 0]);
    const off = j.offset.map((v) => v * s);
    if (j.parent === null) {
      // (turns are modulo 360°: a heading of 1e308° is a direction, not an overflow)
      const face = eulerXYZ([0, ((options.heading ?? 0) % 360 + 360) % 360, 0]);
      out[j.name] = { R: mul(face, local), o: apply({ R: face, o: [...pos] }, off) };
    } else {
      const p = out[j.parent];
      out[j.name] = { R: mul(p.R, local), o: apply(p, off) };
    }
  }
  return out;
}

/** A part's world shape for given joint frames: capsule ends, or a sphere's centre (b = a). */
export function partShape(frames: Record<JointName, Frame>, index: number, scale = 1): { a: number[]; b: number[]; radius: number } {
  const part = PARTS[index], f = frames[part.joint];
  const a = apply(f, part.a.map((v) => v * scale));
  const b = part.b ? apply(f, part.b.map((v) => v * scale)) : a;
  return { a, b, radius: part.radius * scale };
}

/** v rounded to 1/per (the keys' precision: 10 µm, 0.001°; round-off in JSON would only make the scenes long). */
const round = (v: number, per = 1e5) => Math.round(v * per) / per;

/** Euler XYZ angles [degrees] of a rotation (R = Rz·Ry·Rx), the solution nearest `near` (continuous keys). */
function eulerOf(R: readonly number[], near: readonly number[]): Vec3 {
  const deg = 180 / Math.PI;
  const y = Math.asin(Math.max(-1, Math.min(1, -R[6])));
  const x = Math.atan2(R[7], R[8]), z = Math.atan2(R[3], R[0]);
  // the two solutions of the same rotation; each angle moved by whole turns to the previous key's
  const candidates = [[x, y, z], [x + Math.PI, Math.PI - y, z + Math.PI]].map((c) => c.map((v, k) => {
    const d = v * deg;
    return d + 360 * Math.round((near[k] - d) / 360);
  }));
  const dist = (c: number[]) => Math.abs(c[0] - near[0]) + Math.abs(c[1] - near[1]) + Math.abs(c[2] - near[2]);
  const best = dist(candidates[0]) <= dist(candidates[1]) ? candidates[0] : candidates[1];
  return [round(best[0], 1e3), round(best[1], 1e3), round(best[2], 1e3)];
}


/**
 * The mannequin as scene colliders (MANNEQUIN_PARTS order: the head a sphere, the rest capsules), placed where the
 * pose puts them at time 0; when animated each has a looping motion of one cycle (see the file's comment). Pins
 * are for the caller to add (a cape on MANNEQUIN_CHEST, a skirt on MANNEQUIN_PELVIS).
 */
export function mannequinColliders(options: MannequinOptions = {}): ColliderSpec[] {
  checkOptions(options);
  const pose = options.pose ?? 'stand', animation = options.animation ?? 'none', scale = options.scale ?? 1;
  const period = animationPeriod(animation);
  const keys = period > 0 ? Math.round(period * KEY_RATE) : 0;
  const frames = [forwardKinematics(mannequinAngles(pose, animation, 0), options)];
  for (let k = 1; k <= keys; k++) frames.push(forwardKinematics(mannequinAngles(pose, animation, (k * period) / keys), options));
  return PARTS.map((part, index) => {
    const shape0 = partShape(frames[0], index, scale);
    const centre0 = shape0.a.map((v, k) => (v + shape0.b[k]) / 2);
    const spec: ColliderSpec = part.b
      ? { type: 'capsule', a: shape0.a.map((v) => round(v)) as Vec3, b: shape0.b.map((v) => round(v)) as Vec3, radius: round(shape0.radius) }
      : { type: 'sphere', center: shape0.a.map((v) => round(v)) as Vec3, radius: round(shape0.radius) };
    if (keys === 0) return spec;
    const R0 = frames[0][part.joint].R;
    let last: Vec3 = [0, 0, 0];
    const keyframes = frames.map((f, k) => {
      const shape = partShape(f, index, scale);
      const centre = shape.a.map((v, i) => (v + shape.b[i]) / 2);
      // the motion relative to the placement: R(t)·R(0)ᵀ about the centre, and the centre's displacement
      const Rt = f[part.joint].R;
      const rel = mul(Rt, [R0[0], R0[3], R0[6], R0[1], R0[4], R0[7], R0[2], R0[5], R0[8]]);
      last = eulerOf(rel, last);
      return { time: round((k * period) / keys), translation: centre.map((v, i) => round(v - centre0[i])) as Vec3, rotation: last };
    });
    return { ...spec, motion: { keyframes, loop: true } };
  });
}
