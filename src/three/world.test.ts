import { BoxGeometry, BufferGeometry, Float32BufferAttribute, Mesh, Object3D, PlaneGeometry, SphereGeometry, Vector3, type WebGLRenderer } from 'three';
import { describe, expect, it } from 'vitest';
import { SceneError, type Scene } from '../core/index.js';
import type { DrapeWorldOptions } from './options.js';
import { DrapeWorld } from './world.js';

// (what Node can check: the options, the cloths and colliders a world is made of; it simulates in a browser: e2e/three.e2e.ts)
describe('DrapeWorld: options and what it is made of', () => {
  it('refuses a bad option with one line naming it', async () => {
    expect(() => new DrapeWorld({ backend: 'fast' as never })).toThrow("DrapeWorld: options.backend must be 'auto', 'gpu', 'cpu', got \"fast\"");
    expect(() => new DrapeWorld({ gravity: [0, -9.81] as never })).toThrow(/^DrapeWorld: gravity: /);
    expect(() => new DrapeWorld({ solver: { substeps: 0 } })).toThrow(/^DrapeWorld: solver\.substeps: must be >= 1/);
    expect(() => new DrapeWorld({ floor: NaN })).toThrow(/options\.floor/);
    // the wind's options are flat: named as given, not as the scene's wind.gusts.seed
    expect(() => new DrapeWorld({ wind: { seed: -1 } })).toThrow(/^DrapeWorld: wind\.seed: must be >= 0$/);
    expect(() => new DrapeWorld({ wind: { gusts: 'yes' as never } })).toThrow(/^DrapeWorld: wind\.gusts: must be boolean$/);
    const world = new DrapeWorld();
    expect(() => world.addCloth({ resolution: 2.5 })).toThrow(SceneError);
    expect(() => world.addCloth({ resolution: 2.5 })).toThrow(/^DrapeWorld\.addCloth\('cloth 0'\): resolution: must be integer/);
    expect(() => world.addCloth({ fabricValues: { damping: -1 } })).toThrow(/: fabricValues\.damping: must be >= 0/);
    expect(() => world.addCloth({ fabric: 'tweed' as never })).toThrow(/: fabric: /);
    expect(() => world.addCloth({ pins: [99999] })).toThrow(/pins\[0\]/);
    expect(() => world.addCloth({ shape: 'disc', geometry: new PlaneGeometry() })).toThrow(/geometry or shape, not both/);
    expect(() => world.addCollider({} as Mesh)).toThrow(/must be a THREE\.Mesh/);
    expect(() => world.addCollider(new Mesh(new BoxGeometry()), { shape: 'cone' as never })).toThrow(/options\.shape must be 'auto', 'sphere'/);
    expect(() => world.update(-1)).toThrow(/dt must be a finite number of seconds/);
    // a string is quoted, so that "got 2" cannot read as if the number were refused
    expect(() => world.update('1' as unknown as number)).toThrow(/dt must be a finite number of seconds ≥ 0, got "1"$/);
    await expect(world.step('2' as unknown as number)).rejects.toThrow(/step: frames must be an integer ≥ 0, got "2"$/);
    // nothing refused was kept
    expect(world.cloths).toEqual([]);
  });

  it('names the argument that is wrong: a cloth\'s name, geometry, its faces and pins, a ray, a grab or drag target', () => {
    const world = new DrapeWorld();
    expect(() => world.addCloth({ name: 5 as never })).toThrow(/^DrapeWorld\.addCloth: name must be a string, got 5$/);
    // a name with a control character is shown safely, and the call is named once
    expect(() => world.addCloth({ name: 'a\tb', resolution: 2.5 })).toThrow(/^DrapeWorld\.addCloth\('a\ufffdb'\): resolution: must be integer$/);
    expect(() => world.addCloth({ geometry: {} as never })).toThrow(/^DrapeWorld\.addCloth: geometry must be a THREE\.BufferGeometry/);
    expect(() => world.addCloth({ geometry: new Mesh(new PlaneGeometry()) as never })).toThrow(/geometry must be a THREE\.BufferGeometry \(a mesh's is its \.geometry\)/);
    // the geometry's faces, and pins that miss, named as the option, after the call (not by the world's own mesh names)
    const flat = new BufferGeometry();
    flat.setAttribute('position', new Float32BufferAttribute([0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0], 3));
    flat.setIndex([0, 1, 2, 0, 1, 3]);
    expect(() => world.addCloth({ name: 'sheet', geometry: flat })).toThrow(/^DrapeWorld\.addCloth\('sheet'\): geometry: face 2 is degenerate/);
    expect(() => world.addCloth({ geometry: new PlaneGeometry(0.001, 0.001) }))
      .toThrow(/^DrapeWorld\.addCloth\('cloth 0'\): scale: the geometry is 0\.00100 m across .*metres per unit of the geometry/);
    expect(() => world.addCloth({ pins: [{ min: [5, 5, 5], max: [6, 6, 6] }] })).toThrow(/^DrapeWorld\.addCloth\('cloth 0'\): pins\[0\]: no particle starts in the region/);
    expect(() => world.pick(undefined as never)).toThrow(/^DrapeWorld\.pick: the ray must be a THREE\.Raycaster or \{ origin, direction \}/);
    expect(() => world.pick({ origin: [0, 5, 0], direction: [0, -1, 0] } as never)).toThrow(/^DrapeWorld\.pick: the ray must be/);
    expect(world.pick({ origin: new Vector3(0, 5, 0), direction: new Vector3(0, -1, 0) })).toBeNull(); // not started
    expect(() => world.grab(undefined as never)).toThrow(/^DrapeWorld\.grab: hit must be a pick result/);
    expect(() => world.drag(undefined as never)).toThrow(/^DrapeWorld\.drag: target must be a THREE\.Vector3$/);
    expect(() => world.drag(new Vector3(NaN, 1, 0))).toThrow(/^DrapeWorld\.drag: target must have finite coordinates \[m\], got \(NaN, 1, 0\)$/);
    // default names count the cloths added, so that they do not repeat after one is taken out
    const [a, b] = [world.addCloth({ position: [0, 1, 0] }), world.addCloth({ position: [0, 3, 0] })];
    world.removeCloth(a);
    expect([b.name, world.addCloth({ position: [0, 5, 0] }).name]).toEqual(['cloth 1', 'cloth 2']);
    world.dispose();
  });

  it('takes the options docs/three.md lists, a WebGLRenderer and the solver\'s speeds and stretch among them', () => {
    // (type-checked: a renderer type whose members are all optional refused a WebGLRenderer, which has none of them)
    const webgl = null as unknown as WebGLRenderer;
    const options: DrapeWorldOptions = { renderer: webgl, solver: { selfContactSpeed: 0, depenetrationSpeed: 1, stretch: 'global' } };
    expect(() => new DrapeWorld({ solver: options.solver })).not.toThrow();
    // and the scene schema checks them, naming them
    expect(() => new DrapeWorld({ solver: { selfContactSpeed: -1 } })).toThrow(/^DrapeWorld: solver\.selfContactSpeed: must be >= 0/);
    expect(() => new DrapeWorld({ solver: { depenetrationSpeed: 0 } })).toThrow(/^DrapeWorld: solver\.depenetrationSpeed: must be >= 0\.01/);
    expect(() => new DrapeWorld({ solver: { stretch: 'vbd' as never } })).toThrow(/^DrapeWorld: solver\.stretch: /);
  });

  it('a cloth from a generator or a geometry is a mesh of its particles, drawn from its own attributes on the CPU path', () => {
    const world = new DrapeWorld();
    const a = world.addCloth({ resolution: 8, position: [0, 1.5, 0], fabric: 'silk' });
    expect(a.particleCount).toBe(81);
    expect(a.isMesh).toBe(true);
    expect(a.geometry.getIndex()!.count).toBe(8 * 8 * 6);
    // a three.js plane turned flat: its 5 × 5 vertices are the particles, centred at `position`
    const b = world.addCloth({ geometry: new PlaneGeometry(1, 1, 4, 4), rotation: [-90, 0, 0], position: [0, 2, 0], name: 'sheet' });
    expect(b.particleCount).toBe(25);
    expect(b.name).toBe('sheet');
    const y = b.positions.filter((_, k) => k % 3 === 1);
    expect(Math.min(...y)).toBeCloseTo(2, 5);
    expect(Math.max(...y)).toBeCloseTo(2, 5);
    // a non-indexed sphere's seams and duplicate corners are welded into one closed cloth
    const c = world.addCloth({ geometry: new SphereGeometry(0.2, 8, 6).toNonIndexed(), position: [0, 3, 0] });
    expect(c.particleCount).toBe(8 * 5 + 2);
    expect(world.cloths).toEqual([a, b, c]);
    world.dispose();
    expect(() => world.addCloth()).toThrow(/disposed/);
  });

  it('colliders from meshes and pins on objects: a refused one changes nothing', () => {
    const world = new DrapeWorld({ floor: 0 });
    const ball = new Mesh(new SphereGeometry(0.3));
    ball.position.set(0, 0.5, 0);
    world.addCollider(ball);
    expect(() => world.addCollider(ball)).toThrow(/a collider already/);
    const hook = new Object3D();
    hook.position.set(0.5, 1.5, 0.5);
    const cloth = world.addCloth({ resolution: 4, position: [0, 1.5, 0], pins: [{ at: 'top-left', to: hook }, { at: 'top-right', to: hook }, 0] });
    expect(cloth.particleCount).toBe(25);
    expect(() => world.addCloth({ pins: [{ at: 0, to: {} as Object3D }] })).toThrow(/pins\[0\]\.to must be a THREE\.Object3D/);
    expect(() => world.addCloth({ pins: [0, { at: 'middle' as never, to: hook }] })).toThrow(/^DrapeWorld\.addCloth\('cloth 1'\): pins\[1\]: /);
    expect(world.cloths.length).toBe(1);
  });

  it('a cloth or a collider taken out is gone from the simulated scene; its pins on objects go with the cloth, stay with the mesh', () => {
    const world = new DrapeWorld({ floor: 0 });
    // (the scene the world would simulate, as it is now)
    const scene = () => (world as unknown as { scene(): Scene }).scene();
    const ball = new Mesh(new SphereGeometry(0.3));
    ball.position.set(0, 0.5, 0);
    const box = new Mesh(new BoxGeometry(0.4, 0.4, 0.4));
    box.position.set(1.5, 0.2, 0);
    world.addCollider(ball);
    world.addCollider(box, { shape: 'mesh' });
    const hook = new Object3D();
    hook.position.set(0.5, 1.5, 0.5);
    const a = world.addCloth({ resolution: 4, position: [0, 1.5, 0], pins: [{ at: 'top-left', to: hook }] });
    const b = world.addCloth({ geometry: new PlaneGeometry(0.5, 0.5, 2, 2), position: [0, 2.2, 0], pins: [{ at: 0, to: ball }] });
    const c = world.addCloth({ resolution: 2, position: [0, 3, 0] });
    // floor, ball (carrying b's pin), box, the hook's anchor (carrying a's pin)
    expect(scene().cloths!.length).toBe(3);
    expect(scene().colliders.map((k) => [k.type, k.pins?.length])).toEqual([['floor', 0], ['sphere', 1], ['mesh', 0], ['plane', 1]]);

    let freed = 0;
    a.geometry.addEventListener('dispose', () => freed++);
    world.removeCloth(a);
    expect(world.cloths).toEqual([b, c]);
    expect(() => world.removeCloth(a)).toThrow('DrapeWorld.removeCloth: this cloth is not in the world');
    // the hook carried only a's pin: no anchor now; b's pin (its particle 0, the world's 0 now) rides on the ball
    expect(scene().colliders.map((k) => [k.type, k.pins])).toEqual([['floor', []], ['sphere', [0]], ['mesh', []]]);
    // the geometry the world made for it is freed (three.js drops its GPU buffers)
    expect(freed).toBe(1);

    world.removeCollider(ball);
    expect(() => world.removeCollider(ball)).toThrow('DrapeWorld.removeCollider: this mesh is no collider of the world');
    // b's pin still follows the ball, carried by an anchor like any object's
    expect(scene().colliders.map((k) => [k.type, k.pins])).toEqual([['floor', []], ['mesh', []], ['plane', [0]]]);
    world.removeCollider(box);
    expect(scene().colliders.map((k) => k.type)).toEqual(['floor', 'plane']);
    // a mesh taken out can be a collider again
    expect(() => world.addCollider(box)).not.toThrow();

    // a following collider whose mesh is scaled is made again at the new size, where the mesh is now
    const rescale = () => (world as unknown as { rescale(): void }).rescale();
    const sphere = () => scene().colliders.find((k) => k.type === 'sphere') as { radius: number; center: number[] } | undefined;
    world.addCollider(ball);
    expect(sphere()!.radius).toBeCloseTo(0.3, 6);
    rescale();
    expect(sphere()!.radius).toBeCloseTo(0.3, 6);
    ball.scale.setScalar(1.5);
    ball.position.set(0.1, 0.6, 0);
    ball.updateMatrixWorld(true);
    rescale();
    expect(sphere()!.radius).toBeCloseTo(0.45, 6);
    expect(sphere()!.center.map((v) => +v.toFixed(6))).toEqual([0.1, 0.6, 0]);
    // (the box added again above, a box now: its shape inferred) stretched along x
    const boxOf = () => scene().colliders.find((k) => k.type === 'box') as { halfExtents: number[] } | undefined;
    expect(boxOf()!.halfExtents.map((v) => +v.toFixed(6))).toEqual([0.2, 0.2, 0.2]);
    box.scale.set(2, 1, 1);
    box.updateMatrixWorld(true);
    rescale();
    expect(boxOf()!.halfExtents.map((v) => +v.toFixed(6))).toEqual([0.4, 0.2, 0.2]);

    world.removeCloth(b);
    world.removeCloth(c);
    expect(world.cloths).toEqual([]);
    expect(world.backend).toBeNull();
    // a world emptied can be filled again
    expect(world.addCloth({ resolution: 3 }).particleCount).toBe(16);
    world.dispose();
    expect(() => world.removeCloth(c)).toThrow(/disposed/);
  });
});
