import { describe, expect, it } from 'vitest';
import { SceneError, validateScene } from './scene.js';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';

const refusal = (edit: (s: ReturnType<typeof builtinScene>) => void): string => {
  const s = builtinScene('cotton-basic');
  s.cloth.resolution = 16;
  edit(s);
  try {
    new Simulation(s);
  } catch (e) {
    expect(e).toBeInstanceOf(SceneError);
    return (e as Error).message;
  }
  return '';
};

describe('where a cloth may start among its colliders', () => {
  it('touching or slightly sunk in is fine: the first contact lifts it out at rest', () => {
    expect(refusal((s) => { s.colliders = [{ type: 'floor', height: 1.25 }]; })).toBe(''); // 5 cm under a floor
    expect(refusal((s) => { s.colliders[0] = { type: 'sphere', center: [0, 0.91, 0], radius: 0.3 }; })).toBe(''); // 1 cm dip
  });

  it('a collider that cuts through the cloth is refused, naming it and the stretch it would need', () => {
    expect(refusal((s) => { s.colliders[0] = { type: 'sphere', center: [0, 1.2, 0], radius: 0.3 }; }))
      .toMatch(/^scene 'cotton-basic': colliders\[0\] \(sphere\) cuts through the cloth where it starts: pushed out of it, the cloth would stretch \d+ %, past its stretch limit of 5\.0 %; move the collider or the cloth$/);
    expect(refusal((s) => { s.colliders[0] = { type: 'sphere', center: [0, 1.2, 0], radius: 5 }; })).toMatch(/colliders\[0\] \(sphere\) cuts through/);
  });

  it('a pin inside a collider, or a cloth inside two colliders at once, is refused by name', () => {
    expect(refusal((s) => { s.pins = ['top-left']; s.colliders[1] = { type: 'floor', height: 2 }; }))
      .toMatch(/colliders\[1\] \(floor\): pinned particle 0 starts inside it, and a pin cannot be pushed out/);
    expect(refusal((s) => { s.colliders = [{ type: 'floor', height: 1.3 }, { type: 'sphere', center: [0, 1.4, 0], radius: 0.2 }]; }))
      .toMatch(/colliders\[0\] \(floor\) and colliders\[1\] \(sphere\): the cloth starts inside both and cannot be outside both at once/);
  });

  it('a live change that would make the scene unstartable is refused and changes nothing', () => {
    const sim = new Simulation(validateScene({ cloth: { resolution: 8 } }));
    sim.advance(5);
    const before = [...sim.state.positions];
    expect(() => sim.set('colliders[0].center', [0, 1.2, 0])).toThrow(/colliders\[0\] \(sphere\) cuts through/);
    expect(sim.scene.colliders[0]).toMatchObject({ center: [0, 0.5, 0] });
    expect([...sim.state.positions]).toEqual(before);
    // moved where the cloth has been but not where it starts: accepted (the cloth is pushed out, not thrown)
    expect(() => sim.set('colliders[0].center', [0, 0.7, 0])).not.toThrow();
  });
});
