/**
 * A collider following a three.js object: the drive the core's `Simulation.setColliderPose` takes — the rigid
 * motion that takes the object from where it stood when the collider was made to where it stands (translation of
 * the collider's pivot, rotation about it, Euler degrees as the core's), and the velocity and angular velocity of
 * that motion since the last look — so that over the frames stepped for the time since, the collider glides from
 * the object's last pose to its pose now, and friction drags the cloth with it. A change of the object's scale is
 * not a motion: `rescaled` says the collider is to be made again at the new size (DrapeWorld does). Pure.
 */
import { Matrix4, Quaternion, Vector3, type Object3D } from 'three';
import type { ColliderPose, Vec3 } from '../core/index.js';
import { coreEuler } from './rotation.js';

const ot = new Vector3(), qt = new Quaternion(), st = new Vector3(), dq = new Quaternion(), arm = new Vector3(), m = new Matrix4();

export class Follower {
  /** the object's world rotation and position when the collider was made */
  private readonly q0Inverse = new Quaternion();
  private readonly o0 = new Vector3();
  /** the object's world scale the collider's size is of */
  private readonly s0 = new Vector3();
  private readonly pivot: Vector3;
  /** the motion at the last look: translation, rotation */
  private readonly t = new Vector3();
  private readonly q = new Quaternion();
  private moving = false;

  /** `pivot`: the point [m] the collider's scene entry turns about (its centre, a mesh's origin) */
  constructor(readonly object: Object3D, pivot: Vec3) {
    object.updateWorldMatrix(true, false);
    object.matrixWorld.decompose(this.o0, this.q0Inverse, this.s0);
    this.q0Inverse.invert();
    this.pivot = new Vector3(...pivot);
  }

  /**
   * Whether the object's world scale is no longer the one the collider was made with (by more than a millionth):
   * the collider's size is then wrong. Reads `object.matrixWorld`, as `look` does.
   */
  rescaled(): boolean {
    this.object.matrixWorld.decompose(ot, qt, st);
    const s0 = this.s0;
    return Math.abs(st.x - s0.x) > 1e-6 * Math.abs(s0.x) || Math.abs(st.y - s0.y) > 1e-6 * Math.abs(s0.y) || Math.abs(st.z - s0.z) > 1e-6 * Math.abs(s0.z);
  }

  /** Takes the object's world scale now as the collider's (a collider that could not be made at it keeps its size). */
  adoptScale(): void {
    this.object.matrixWorld.decompose(ot, qt, this.s0);
  }

  /** The next `look` tells the simulation the pose even if the object has not moved (a new simulation, a reset). */
  resend(): void {
    this.moving = true;
  }

  /**
   * The drive over the next `dt` seconds [s] of simulation, which stand for the `dt` of wall time since the last
   * look: the pose the object had at the last look, and the velocity and angular velocity that bring the collider
   * to where the object is now by their end. So the collider ends each stepped interval where its object is, and
   * moves smoothly across it. `dt` 0 or less: the pose now, at rest (a jump). Null when the object has not moved
   * since the last look and was at rest then (nothing to tell the simulation). Reads `object.matrixWorld`: bring it
   * up to date first (the renderer does each frame; `updateWorldMatrix` otherwise).
   */
  look(dt: number): ColliderPose | null {
    this.object.matrixWorld.decompose(ot, qt, st);
    // rotation of the motion now: R = Rt·R0ᵀ; translation of the pivot c: T = ot − c + R·(c − o0)
    qt.multiply(this.q0Inverse);
    arm.copy(this.pivot).sub(this.o0).applyQuaternion(qt).add(ot).sub(this.pivot);
    const moved = arm.distanceToSquared(this.t) > 1e-18 || Math.abs(Math.abs(qt.dot(this.q)) - 1) > 1e-12;
    if (!moved && !this.moving) return null;
    const velocity: Vec3 = [0, 0, 0], angularVelocity: Vec3 = [0, 0, 0];
    const glide = dt > 0 && moved;
    if (glide) {
      velocity[0] = (arm.x - this.t.x) / dt; velocity[1] = (arm.y - this.t.y) / dt; velocity[2] = (arm.z - this.t.z) / dt;
      // the turn since the last look, the short way round, as an axis × angle
      dq.copy(this.q).invert().premultiply(qt);
      if (dq.w < 0) dq.set(-dq.x, -dq.y, -dq.z, -dq.w);
      const s = Math.hypot(dq.x, dq.y, dq.z);
      if (s > 1e-12) {
        const w = (2 * Math.atan2(s, dq.w)) / (s * dt);
        angularVelocity[0] = dq.x * w; angularVelocity[1] = dq.y * w; angularVelocity[2] = dq.z * w;
      }
    }
    // from where it was (gliding) or where it is (a jump, or at rest)
    const from = glide ? this.t : arm, turn = glide ? this.q : qt;
    const pose: ColliderPose = { translation: [from.x, from.y, from.z], rotation: coreEuler(m.makeRotationFromQuaternion(turn)), velocity, angularVelocity };
    this.t.copy(arm);
    this.q.copy(qt);
    this.moving = moved;
    return pose;
  }
}
