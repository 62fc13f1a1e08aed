import { describe, expect, it } from 'vitest';
import { Simulation, builtinScene, validateScene } from '../core/index.js';
import { trianglesByCloth } from './cloth-parts.js';

/** the triangles as sorted strings, to compare sets */
const set = (t: ArrayLike<number>) => Array.from({ length: t.length / 3 }, (_, k) => `${t[3 * k]},${t[3 * k + 1]},${t[3 * k + 2]}`).sort();

describe("a model's triangles cloth by cloth", () => {
  // cloths of different sizes, so that a mix-up of the runs shows
  const scene = validateScene({
    cloths: [
      { name: 'a', cloth: { resolution: 4, position: [0, 1, 0] } },
      { name: 'b', cloth: { resolution: 2, position: [0, 1.5, 0] } },
      { name: 'c', cloth: { shape: 'disc', resolution: 6, position: [0, 2, 0] } },
    ],
  });
  const model = new Simulation(scene, { kernel: 'ts' }).model;

  it('runs of one cloth each, holding every triangle of the model once', () => {
    const parts = trianglesByCloth(model);
    const starts = model.clothStarts;
    expect(parts.first.length).toBe(4);
    expect(parts.first[3]).toBe(model.triangles.length / 3);
    for (let c = 0; c < 3; c++) {
      const own = model.clothParts![c].triangles.length / 3;
      expect(parts.first[c + 1] - parts.first[c], `cloth ${c}`).toBe(own);
      const run = parts.indices.subarray(3 * parts.first[c], 3 * parts.first[c + 1]);
      for (const i of run) {
        expect(i).toBeGreaterThanOrEqual(starts[c]);
        expect(i).toBeLessThan(starts[c + 1]);
      }
    }
    expect(set(parts.indices)).toEqual(set(model.triangles));
    // the colour sort interleaves the cloths: the model's own order is not in runs (else this test shows nothing)
    const clothOf = (i: number) => (i < starts[1] ? 0 : i < starts[2] ? 1 : 2);
    const order = Array.from({ length: model.triangles.length / 3 }, (_, k) => clothOf(model.triangles[3 * k]));
    expect(order.some((c, k) => k > 0 && c < order[k - 1])).toBe(true);
  });

  it('one cloth: one run, the model itself', () => {
    const one = new Simulation(builtinScene('cotton-basic'), { kernel: 'ts' }).model;
    const parts = trianglesByCloth(one);
    expect(Array.from(parts.first)).toEqual([0, one.triangles.length / 3]);
    expect(Array.from(parts.indices)).toEqual(Array.from(one.triangles));
  });
});
