import { describe, expect, it } from 'vitest';
import {
  Simulation, builtinScene, clothCount, clothEntries, clothModelOf, clothParticle, clothPath, clothScene, editCloth, pathCloth,
  resolvePins, sceneParticle, setScenePath,
} from './index.js';

describe('one cloth of a scene, addressed', () => {
  const layers = builtinScene('layers');
  const cotton = builtinScene('cotton-basic');

  it('the path of a field of cloth k: the field itself for one cloth, cloths[k].field in a list', () => {
    expect(clothCount(cotton)).toBe(1);
    expect(clothCount(layers)).toBe(3);
    expect(clothPath(cotton, 0, 'material.damping')).toBe('material.damping');
    expect(clothPath(layers, 2, 'material.fabric')).toBe('cloths[2].material.fabric');
    expect(clothPath(layers, 0, 'pins')).toBe('cloths[0].pins');
    expect(() => clothPath(layers, 3, 'pins')).toThrow(RangeError);
    expect(() => clothPath(cotton, 1, 'pins')).toThrow(RangeError);
    // the path it gives is one setScenePath takes, and it edits that cloth only
    const next = setScenePath(layers, clothPath(layers, 1, 'material.fabric'), 'silk');
    expect(clothEntries(next).map((e) => e.material.fabric)).toEqual(['leather', 'silk', 'silk']);
  });

  it('which cloth a path is in', () => {
    expect(pathCloth('cloths[2].material.damping')).toEqual({ cloth: 2, field: 'material.damping' });
    expect(pathCloth('cloths.1.cloth.resolution')).toEqual({ cloth: 1, field: 'cloth.resolution' });
    expect(pathCloth('cloths[0].pins')).toEqual({ cloth: 0, field: 'pins' });
    expect(pathCloth('material.scaleWithResolution')).toEqual({ cloth: 0, field: 'material.scaleWithResolution' });
    expect(pathCloth('pins')).toEqual({ cloth: 0, field: 'pins' });
    expect(pathCloth('pins[3]')).toEqual({ cloth: 0, field: 'pins[3]' });
    for (const p of ['solver.substeps', 'cloths', 'cloths[1]', 'colliders[0].pins', 'clothing.x']) expect(pathCloth(p), p).toBeNull();
  });

  it("a particle of the merged model as its cloth's own, and back", () => {
    const model = new Simulation(layers, { kernel: 'ts' }).model;
    const n = 21 * 21;
    expect(Array.from(model.clothStarts)).toEqual([0, n, 2 * n, 3 * n]);
    expect(clothParticle(model, 0)).toEqual({ cloth: 0, index: 0 });
    expect(clothParticle(model, n - 1)).toEqual({ cloth: 0, index: n - 1 });
    expect(clothParticle(model, n)).toEqual({ cloth: 1, index: 0 });
    expect(clothParticle(model, 2 * n + 5)).toEqual({ cloth: 2, index: 5 });
    expect(() => clothParticle(model, 3 * n)).toThrow(RangeError);
    for (const i of [0, n - 1, n, 2 * n + 5, 3 * n - 1]) {
      const { cloth, index } = clothParticle(model, i);
      expect(sceneParticle(model, cloth, index)).toBe(i);
    }
    // no cloth 3, and no particle past a cloth's last (it gave NaN, or another cloth's particle)
    expect(() => sceneParticle(model, 3, 0)).toThrow(/^no cloth 3 \(the model has 3\)$/);
    expect(() => sceneParticle(model, 0, n)).toThrow(/^cloth 0 has no particle \d+/);
    // a cloth's own model numbers its particles from 0: its own pins resolve there
    expect(clothModelOf(model, 2).particleCount).toBe(n);
    expect(resolvePins(clothModelOf(model, 2), ['top-left'])).toEqual([0]);
    const one = new Simulation(cotton, { kernel: 'ts' }).model;
    expect(clothModelOf(one, 0)).toBe(one);
  });

  it('an edit of cloth k made on the scene as that cloth alone, written back into the list', () => {
    const alone = clothScene(layers, 1);
    expect(alone.cloths).toBeUndefined();
    expect(alone.material.fabric).toBe('cotton');
    expect(alone.cloth.position).toEqual([0, 1, 0]);
    expect(clothScene(cotton, 0)).toBe(cotton);
    expect(() => clothScene(cotton, 99)).toThrow(/has no cloth 99 \(it has one cloth, 0\)/);

    const next = editCloth(layers, 1, (one) => setScenePath({ ...one, pins: ['top-left'] }, 'cloth.resolution', 8));
    const entries = clothEntries(next);
    expect(entries.map((e) => e.name)).toEqual(['leather', 'cotton', 'silk']);
    expect(entries.map((e) => e.cloth.resolution)).toEqual([20, 8, 20]);
    expect(entries[1].pins).toEqual(['top-left']);
    expect(next.solver).toEqual(layers.solver);
    expect(next.colliders).toEqual(layers.colliders);
    // the one-cloth scene: the edit is the result
    expect(editCloth(cotton, 0, (one) => setScenePath(one, 'material.damping', 0.3)).material.damping).toBe(0.3);
    expect(() => editCloth(cotton, 1, (one) => one)).toThrow(RangeError);
  });

  it('colliders that carry pins (numbered through the cloths) are left out of the cloth alone, and kept by the edit', () => {
    const carried = setScenePath(layers, 'colliders[0].pins', [900]);
    expect(clothScene(carried, 0).colliders[0].pins).toBeUndefined();
    const next = editCloth(carried, 0, (one) => setScenePath(one, 'material.damping', 0.4));
    expect(next.colliders[0].pins).toEqual([900]);
  });
});
