import { describe, expect, it } from 'vitest';
import { pickParticle } from './pick.js';
import { presetParticles, resolvePins } from './pins.js';
import { modelFor } from './cloth-shape.js';
import { builtinScene } from './scenes.js';
import { validateScene } from './scene.js';
import { Simulation } from './simulation.js';
import { grab, setPinned } from './state.js';

describe('picking, pins and live changes', () => {
  const sim = () => new Simulation(builtinScene('custom')!); // 33×33 horizontal cloth at y = 1.2

  it('a ray from above picks the particle under it; a ray beside the cloth misses', () => {
    const s = sim();
    const p = 17 * 33 + 5;
    const [x, , z] = s.state.positions.subarray(3 * p, 3 * p + 3);
    const hit = pickParticle(s.model, s.state, [x + 0.004, 5, z - 0.003], [0, -1, 0])!;
    expect(hit.particle).toBe(p);
    expect(hit.point[1]).toBeCloseTo(1.2, 5);
    expect(hit.t).toBeCloseTo(3.8, 5);
    expect(pickParticle(s.model, s.state, [2, 5, 0], [0, -1, 0])).toBeNull();
    expect(pickParticle(s.model, s.state, [x, 5, z], [0, 1, 0])).toBeNull(); // pointing away
  });

  it('pin presets name the corners, the centre and the edges', () => {
    const s = sim();
    expect(presetParticles(s.model, 'top-left')).toEqual([0]);
    expect(presetParticles(s.model, 'bottom-right')).toEqual([33 * 33 - 1]);
    expect(presetParticles(s.model, 'center')).toEqual([16 * 33 + 16]);
    expect(presetParticles(s.model, 'left-edge')).toHaveLength(33);
    expect(resolvePins(s.model, ['top-left', 0, 'top-right'])).toEqual([0, 32]);
  });

  it('an edge preset on a cloth that is not a rectangle: the message names the entry and what to give instead (the pin tool only for the cloth\'s own pins)', () => {
    const scene = builtinScene('custom')!;
    scene.cloth.shape = 'disc';
    const disc = modelFor(scene);
    expect(() => resolvePins(disc, ['center', 'top-edge'])).toThrow("pins[1]: pin preset 'top-edge' names a corner or an edge of a rectangle, and this cloth is not one; pin particles by index (in the app: click them with the pin tool)");
    expect(() => resolvePins(disc, ['top-edge'], 'colliders[2].pins')).toThrow("colliders[2].pins[0]: pin preset 'top-edge' names a corner or an edge of a rectangle, and this cloth is not one; give the collider's pins as particle indices or regions");
    // a list of one cloth names its entry, as a list of two does (it said 'pins[0]')
    for (const count of [1, 2]) {
      const cloths = Array.from({ length: count }, (_, k) => ({ cloth: { resolution: 3, shape: 'disc', position: [0, 1 + k, 0] }, pins: ['top-left'] }));
      expect(() => new Simulation(validateScene({ cloths }), { kernel: 'ts' })).toThrow(/^cloths\[0\]\.pins\[0\]: pin preset 'top-left' names a corner/);
    }
  });

  // a pointer dragged into the sphere: the grabbed particle is kinematic (contact skips it), so the target itself is
  // kept outside, on every CPU kernel (the GPU solver's own test: gpu.test.ts)
  it.each(['ts', 'wasm'] as const)('%s: a grab pulled into the sphere holds the particle outside it', (kernel) => {
    const scene = builtinScene('custom')!;
    scene.cloth.resolution = 8;
    const s = new Simulation(scene, { kernel });
    const sphere = scene.colliders.find((c) => c.type === 'sphere')!;
    if (sphere.type !== 'sphere') throw new Error('custom has a sphere');
    const [cx, cy, cz] = sphere.center;
    const p = 4 * 9 + 4; // the middle particle
    s.advance(10);
    grab(s.state, p, [cx + 0.01, cy + 0.05, cz]); // near the centre, deep inside
    s.advance(5);
    const x = s.state.positions;
    const r = Math.hypot(x[3 * p] - cx, x[3 * p + 1] - cy, x[3 * p + 2] - cz);
    const th = s.params.thickness;
    expect(r).toBeGreaterThanOrEqual(sphere.radius + th - 1e-6);
    expect(r).toBeLessThan(sphere.radius + th + 1e-4);
    // out along the normal through the asked point: above the centre, a little to +x
    expect(x[3 * p + 1]).toBeGreaterThan(cy + 0.9 * sphere.radius);
    expect(x[3 * p]).toBeGreaterThan(cx);
    s.dispose();
  });

  // dragged from the sphere's top to below it, the grab goes at solver.selfContactSpeed (self-contact is on), so
  // each frame ends short of the target, somewhere on the line through the sphere: that point is kept out too, and
  // the particle goes round the sphere instead of through it
  it.each(['ts', 'wasm'] as const)('%s: a grab dragged through the sphere goes round it, outside it at every frame', (kernel) => {
    const scene = builtinScene('custom')!;
    scene.cloth.resolution = 8;
    const s = new Simulation(scene, { kernel });
    expect(s.params.grabSpeed).toBe(scene.solver.selfContactSpeed);
    const sphere = scene.colliders.find((c) => c.type === 'sphere')!;
    if (sphere.type !== 'sphere') throw new Error('custom has a sphere');
    const [cx, cy, cz] = sphere.center;
    const p = 4 * 9 + 4, x = s.state.positions, th = s.params.thickness;
    s.advance(30); // lying on the sphere's top
    grab(s.state, p, [cx, cy - sphere.radius - 0.05, cz + 0.01]);
    let least = Infinity;
    for (let f = 0; f < 30; f++) {
      s.advance(1);
      least = Math.min(least, Math.hypot(x[3 * p] - cx, x[3 * p + 1] - cy, x[3 * p + 2] - cz));
    }
    expect(least).toBeGreaterThanOrEqual(sphere.radius + th - 1e-6);
    expect(x[3 * p + 1]).toBeLessThan(cy - sphere.radius); // under it by now
    s.dispose();
  });

  it('a particle pinned at run time stops, and moves again when unpinned', () => {
    const s = sim();
    s.advance(5);
    setPinned(s.state, 100, true);
    const y = s.state.positions[301];
    s.advance(10);
    expect(s.state.positions[301]).toBe(y);
    setPinned(s.state, 100, false);
    s.advance(10);
    expect(s.state.positions[301]).toBeLessThan(y);
  });

  it('stiffness, wind and pins change on the next step; resolution rebuilds the cloth', () => {
    const s = sim();
    const model = s.model;
    expect(s.set('material.bendStiffness', 5)).toBe(false);
    expect(s.set('wind.enabled', true)).toBe(false);
    expect(s.set('pins', ['center'])).toBe(false);
    expect(s.model).toBe(model);
    expect(s.state.pinned[16 * 33 + 16]).toBe(1);
    expect(s.set('cloth.resolution', 8)).toBe(true);
    expect(s.model.particleCount).toBe(81);
    expect(s.state.pinned[40]).toBe(1); // the centre pin follows the new grid
    expect(() => s.set('material.mass', -1)).toThrow(/^Simulation\.set\('material\.mass'\): must be >= 0\.00001$/);
    expect(s.scene.material.arealDensity).toBeGreaterThan(0); // a rejected change leaves the scene as it was
    expect(s.scene.material.mass).toBeUndefined();
  });
});
