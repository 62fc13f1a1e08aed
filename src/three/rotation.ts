/**
 * Rotations between three.js and the core: the core's Euler angles (scene `rotation` fields, collider poses) are
 * degrees about x, then y, then z, R = Rz·Ry·Rx (core/mesh/generators.ts eulerXYZ), which is three.js's Euler order
 * 'ZYX'.
 */
import { Euler, type Matrix4 } from 'three';
import type { Vec3 } from '../core/index.js';

const DEG = 180 / Math.PI;
const euler = new Euler();

/** The core's Euler angles [degrees] of a rotation matrix (the rotation part of `m`, which must have no scale). */
export function coreEuler(m: Matrix4, out: Vec3 = [0, 0, 0]): Vec3 {
  euler.setFromRotationMatrix(m, 'ZYX');
  out[0] = euler.x * DEG; out[1] = euler.y * DEG; out[2] = euler.z * DEG;
  return out;
}
