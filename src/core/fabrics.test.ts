/**
 * Materials in measured units (fabrics.ts, scene.ts): a named fabric fills what a scene does not set, the older
 * paths `mass` and `bendStiffness` keep their meaning, one path of a pair at a time, and the cloth weighs its areal
 * density × its area.
 */
import { describe, expect, it } from 'vitest';
import { BEND_SPRING_PER_RIGIDITY, FABRICS, FABRIC_NAMES } from './fabrics.js';
import { setScenePath, validateScene } from './scene.js';
import { builtinScene } from './scenes.js';
import { Simulation } from './simulation.js';

describe('named fabrics', () => {
  it.each(FABRIC_NAMES)('%s fills every material field the scene leaves out', (name) => {
    const m = validateScene({ material: { fabric: name } }).material;
    expect(m).toMatchObject({ fabric: name, ...FABRICS[name] });
    expect(m.mass).toBeUndefined();
  });

  it('what the scene sets wins; a schema default never counts as set', () => {
    const m = validateScene({ material: { fabric: 'leather', damping: 0.9 } }).material;
    expect(m.damping).toBe(0.9);
    // the schema's defaults are cotton's: leather's values, not those, fill the rest
    expect(m.bendingRigidity).toBe(FABRICS.leather.bendingRigidity);
    expect(m.arealDensity).toBe(FABRICS.leather.arealDensity);
    // the older path stands for its field: a bend spring given keeps the fabric's B out, a mass its density
    const old = validateScene({ material: { fabric: 'leather', bendStiffness: 2, mass: 0.3 } }).material;
    expect(old.bendingRigidity).toBeCloseTo(2 / BEND_SPRING_PER_RIGIDITY, 15);
    expect(old).not.toHaveProperty('bendStiffness');
    expect(old.mass).toBe(0.3);
    expect(old).not.toHaveProperty('arealDensity');
  });

  it('--set material.fabric changes the cloth, whatever the scene set before; later --sets still apply', () => {
    const cotton = builtinScene('cotton-basic');
    expect(cotton.material.fabric).toBe('cotton');
    const silk = setScenePath(cotton, 'material.fabric', 'silk');
    expect(silk.material).toMatchObject(FABRICS.silk);
    const tuned = validateScene({ material: { damping: 0.9, mass: 2, bendStiffness: 5 } });
    const denim = setScenePath(setScenePath(tuned, 'material.fabric', 'denim'), 'material.damping', 0.4);
    expect(denim.material).toMatchObject({ ...FABRICS.denim, damping: 0.4 });
    expect(denim.material.mass).toBeUndefined();
  });

  it('a resolved scene validates to itself, so a link, an export or the app can hand it on', () => {
    for (const doc of [{ material: { fabric: 'silk' } }, { material: { mass: 0.4, bendStiffness: 3 } }, {}]) {
      const once = validateScene(doc);
      expect(validateScene(once)).toEqual(once);
    }
  });

  it('one path of a pair at a time: both in a file is an error naming the field; a --set replaces the other', () => {
    expect(() => validateScene({ material: { mass: 0.2, arealDensity: 0.1 } }))
      .toThrow(/^scene: material\.arealDensity: give either material\.mass or material\.arealDensity, not both/);
    expect(() => validateScene({ material: { bendStiffness: 1, bendingRigidity: 1e-5 } }))
      .toThrow(/^scene: material\.bendingRigidity: give either material\.bendStiffness or material\.bendingRigidity, not both/);
    const s = validateScene({ material: { mass: 0.2 } });
    const byDensity = setScenePath(s, 'material.arealDensity', 0.3);
    expect(byDensity.material).toMatchObject({ arealDensity: 0.3 });
    expect(byDensity.material.mass).toBeUndefined();
    const byMass = setScenePath(byDensity, 'material.mass', 0.5).material;
    expect(byMass.mass).toBe(0.5);
    expect(byMass.arealDensity).toBeUndefined();
    expect(setScenePath(s, 'material.bendStiffness', 0.74).material.bendingRigidity).toBeCloseTo(0.74 / BEND_SPRING_PER_RIGIDITY, 15);
    expect(() => validateScene({ material: { fabric: 'tweed' } })).toThrow(/^scene: material\.fabric: must be one of "cotton", "silk", "leather", "rubber", "denim", "wool"$/);
  });

  it('a cloth weighs its areal density × its rest area; a mass given is the whole cloth\'s', () => {
    const disc = new Simulation(validateScene({ cloth: { shape: 'disc', width: 0.3, resolution: 24 }, material: { fabric: 'cotton' } }), { kernel: 'ts' });
    expect(disc.params.mass).toBeCloseTo(0.12 * disc.model.area, 12);
    expect(disc.model.area / (Math.PI * 0.15 ** 2)).toBeGreaterThan(0.98);
    const flag = new Simulation(builtinScene('wind'), { kernel: 'ts' });
    expect(flag.params.mass).toBeCloseTo(0.12 * 1.5, 6);
    const given = new Simulation(validateScene({ material: { mass: 0.5 } }), { kernel: 'ts' });
    expect(given.params.mass).toBe(0.5);
  });

  it('the older paths are the same cloth: bendStiffness k and bendingRigidity k / 94 372 m⁻² step alike', () => {
    const a = new Simulation(validateScene({ cloth: { resolution: 12 }, material: { bendStiffness: 3, mass: 0.12 } }), { kernel: 'ts' });
    const b = new Simulation(validateScene({ cloth: { resolution: 12 }, material: { bendingRigidity: 3 / BEND_SPRING_PER_RIGIDITY, mass: 0.12 } }), { kernel: 'ts' });
    a.advance(30);
    b.advance(30);
    expect([...b.state.positions]).toEqual([...a.state.positions]);
  });
});
