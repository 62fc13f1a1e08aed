import { Mesh, SphereGeometry, Vector3 } from 'three';
import { describe, expect, it } from 'vitest';
import { createColliders, type ColliderSpec } from '../core/index.js';
import { Follower } from './follow.js';

describe('a collider following its object', () => {
  it('glides the core\'s collider from where the object was to where it is now, turned about its pivot', () => {
    const obj = new Mesh(new SphereGeometry(0.3));
    obj.position.set(0.2, 1, 0);
    obj.updateMatrixWorld(true);
    // a box-like frame: a point of the object off its centre, to see the rotation
    const spec: ColliderSpec = { type: 'box', center: [0.2, 1, 0], halfExtents: [0.3, 0.1, 0.2], rotation: [0, 0, 0] };
    const follow = new Follower(obj, [0.2, 1, 0]);
    expect(follow.look(1 / 60)).toBeNull(); // not moved: nothing to say

    obj.position.set(0.3, 1.1, -0.1);
    obj.rotation.set(0.2, 0.9, -0.4);
    obj.updateMatrixWorld(true);
    const pose = follow.look(0.1)!;
    expect(pose.velocity![0]).toBeCloseTo(1, 9);
    expect(pose.velocity![1]).toBeCloseTo(1, 9);
    expect(pose.velocity![2]).toBeCloseTo(-1, 9);
    const [c] = createColliders([spec]);
    c.setDrive(0, pose);
    const R = new Float64Array(9), o = new Float64Array(3);
    // at the start of the 0.1 s: where the object was (its start)
    c.poseAt(0, R, o);
    expect(Array.from(o)).toEqual([0.2, 1, 0]);
    expect(R[0]).toBeCloseTo(1, 12);
    // at its end: a corner of the box in the object's frame where the object puts it now
    const local = new Vector3(0.3, 0.1, 0.2);
    const want = local.clone().applyMatrix4(obj.matrixWorld);
    c.poseAt(0.1, R, o);
    const got = [0, 1, 2].map((i) => R[3 * i] * local.x + R[3 * i + 1] * local.y + R[3 * i + 2] * local.z + o[i]);
    expect(got[0]).toBeCloseTo(want.x, 6);
    expect(got[1]).toBeCloseTo(want.y, 6);
    expect(got[2]).toBeCloseTo(want.z, 6);
  });

  it('a turn at constant rate gives that angular velocity, and stopping sends one pose at rest', () => {
    const obj = new Mesh(new SphereGeometry(0.3));
    obj.updateMatrixWorld(true);
    const follow = new Follower(obj, [0, 0, 0]);
    obj.rotation.y = 0.1;
    obj.updateMatrixWorld(true);
    const turning = follow.look(0.05)!;
    expect(turning.angularVelocity![1]).toBeCloseTo(2, 6);
    expect(turning.rotation![1]).toBeCloseTo(0, 12); // from where it was
    obj.rotation.y = 0.2;
    obj.updateMatrixWorld(true);
    expect(follow.look(0.05)!.rotation![1]).toBeCloseTo(0.1 * 180 / Math.PI, 6);
    // stopped: one pose where it is, at rest; then nothing
    const still = follow.look(0.05)!;
    expect(still.rotation![1]).toBeCloseTo(0.2 * 180 / Math.PI, 6);
    expect(still.angularVelocity).toEqual([0, 0, 0]);
    expect(still.velocity).toEqual([0, 0, 0]);
    expect(follow.look(0.05)).toBeNull();
    // a jump (no time): the pose now, at rest
    obj.position.x = 1;
    obj.updateMatrixWorld(true);
    const jump = follow.look(0)!;
    expect(jump.translation![0]).toBeCloseTo(1, 12);
    expect(jump.velocity).toEqual([0, 0, 0]);
  });

  it('says when the object\'s world scale is no longer the collider\'s, and takes a new one when told', () => {
    const parent = new Mesh(new SphereGeometry(0.3));
    const obj = new Mesh(new SphereGeometry(0.3));
    parent.add(obj);
    parent.updateMatrixWorld(true);
    const follow = new Follower(obj, [0, 0, 0]);
    expect(follow.rescaled()).toBe(false);
    // moved and turned: a motion, not a new size
    obj.position.set(1, 2, 3);
    obj.rotation.set(0.3, 0.2, 0.1);
    parent.updateMatrixWorld(true);
    expect(follow.rescaled()).toBe(false);
    // a parent's scale is the object's world scale
    parent.scale.set(1, 1.001, 1);
    parent.updateMatrixWorld(true);
    expect(follow.rescaled()).toBe(true);
    follow.adoptScale();
    expect(follow.rescaled()).toBe(false);
  });
});
