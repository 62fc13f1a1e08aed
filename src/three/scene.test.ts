import { Mesh, Object3D, SphereGeometry } from 'three';
import { describe, expect, it } from 'vitest';
import { Simulation, clothEntries, modelFor, validateScene, type ClothEntry } from '../core/index.js';
import { colliderOfMesh } from './colliders.js';
import { Follower } from './follow.js';
import { ANCHOR_DEPTH, anchorOf, worldScene, type SceneCloth, type WorldCollider } from './scene.js';

/** a cloth of the scene: a small rectangle at `y`, its particle count as the core builds it */
function cloth(y: number, resolution = 4): SceneCloth {
  const entry = { cloth: { resolution, width: 0.5, height: 0.5, position: [0, y, 0] }, material: { fabric: 'cotton' }, pins: [] } as unknown as ClothEntry;
  const one = validateScene({ cloths: [entry] });
  return { part: { entry }, particleCount: modelFor(one).particleCount };
}

describe('a world\'s scene', () => {
  it('the floor, the meshes\' colliders, then the anchors; self-contact by default with two cloths', () => {
    const ball = new Mesh(new SphereGeometry(0.2));
    ball.position.set(0, 0.5, 0);
    ball.updateMatrixWorld(true);
    const made = colliderOfMesh(ball, 'auto', 'x');
    const collider: WorldCollider = { object: ball, spec: made.spec, follower: new Follower(ball, made.pivot) };
    const hook = new Object3D();
    hook.position.set(0, 2, 0);
    const a = cloth(1.5), b = cloth(1.8);
    const anchors = new Map([[hook, anchorOf(hook)]]);
    const { scene, colliders } = worldScene({ floor: 0 }, [a, b], [collider], anchors, [
      { cloth: b, particles: [0, 4], to: hook },
      { cloth: a, particles: [24], to: ball },
    ]);
    expect(scene.colliders.map((c) => c.type)).toEqual(['floor', 'sphere', 'plane']);
    expect(colliders).toEqual([null, collider, anchors.get(hook)]);
    // pins count through the cloths in order: b's particles come after a's 25
    expect(scene.colliders[1].pins).toEqual([24]);
    expect(scene.colliders[2].pins).toEqual([25, 29]);
    expect((scene.colliders[2] as { point: number[] }).point).toEqual([0, 2 - ANCHOR_DEPTH, 0]);
    expect(clothEntries(scene).length).toBe(2);
    expect(scene.solver.selfContact).toBe(true);
    // one cloth: none unless asked; asked: as asked
    expect(worldScene({}, [a], [], new Map(), []).scene.solver.selfContact).toBe(false);
    expect(worldScene({ solver: { selfContact: true } }, [a], [], new Map(), []).scene.solver.selfContact).toBe(true);
    // the air: none unless `wind` is given; given at strength 0, still air (its drag alone)
    expect(worldScene({}, [a], [], new Map(), []).scene.wind.enabled).toBe(false);
    expect(worldScene({ wind: {} }, [a], [], new Map(), []).scene.wind).toMatchObject({ enabled: true, strength: 0 });
    expect(worldScene({ wind: { strength: 4 } }, [a], [], new Map(), []).scene.wind).toMatchObject({ enabled: true, strength: 4 });
    // an anchor without pins is left out
    expect(worldScene({}, [a], [], anchors, []).scene.colliders).toEqual([]);
  });

  it('pins on an object that is no collider follow it: its anchor carries them in the core\'s Simulation', () => {
    const hook = new Object3D();
    hook.position.set(0.25, 1.5, 0.25);
    const a = cloth(1.5);
    const anchor = anchorOf(hook);
    // particle 24 is the corner at (0.25, 1.5, 0.25), where the hook is
    const { scene } = worldScene({}, [a], [], new Map([[hook, anchor]]), [{ cloth: a, particles: [24], to: hook }]);
    const sim = new Simulation(scene, { kernel: 'ts' });
    const start = Array.from(sim.state.positions.subarray(72, 75));
    // the hook rises 0.2 m over 12 frames and turns a quarter about y (about itself): the pin goes with it
    for (let f = 1; f <= 12; f++) {
      hook.position.y = 1.5 + (0.2 * f) / 12;
      hook.rotation.y = (Math.PI / 2) * f / 12;
      hook.updateMatrixWorld(true);
      const pose = anchor.follower!.look(1 / 60);
      if (pose) sim.setColliderPose(0, pose);
      sim.advance(1);
    }
    const p = sim.state.positions;
    expect(p[73]).toBeCloseTo(start[1] + 0.2, 3);
    expect(p[72]).toBeCloseTo(0.25, 3); // at the hook: turning about it leaves it there
    expect(p[74]).toBeCloseTo(0.25, 3);
    // the rest of the cloth hangs from it, below
    expect(p[3 * 12 + 1]).toBeLessThan(p[73]);
  });
});
