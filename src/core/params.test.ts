import { describe, expect, it } from 'vitest';
import { buildGridModel } from './model.js';
import { GLOBAL_SOLVE_MOST_PARTICLES, axisSpringStiffness, resolveParams } from './params.js';
import { validateScene } from './scene.js';
import { modelFor } from './cloth-shape.js';
import { STRUCTURAL, SHEAR } from './layout.generated.js';

describe('the grid\'s axis springs leave the diagonals their share of the tensile stiffness', () => {
  it.each([[600, 200], [8600, 56], [5000, 1700], [86.4, 94300], [1e5, 1e-3]])('k = %d N/m, k_d = %d N/m: k_s + k_d·k_s/(k_s + k_d) = k', (k, kd) => {
    const ks = axisSpringStiffness(k, kd);
    expect(ks).toBeGreaterThan(0);
    expect(ks).toBeLessThanOrEqual(k);
    expect((ks + (kd * ks) / (ks + kd)) / k).toBeCloseTo(1, 12);
  });

  it('applies to a grid in fabric units, not to raw spring constants (scaleWithResolution false) or without diagonals', () => {
    const scene = validateScene({ material: { fabric: 'rubber' } });
    const model = buildGridModel({ resolution: 4, width: 1, height: 1, orientation: 'horizontal', position: [0, 0, 0], rotation: [0, 0, 0], scaleWithResolution: true });
    const first = (params: ReturnType<typeof resolveParams>, kind: number) => params.stiffness[model.springKinds.indexOf(kind)];
    const fabric = resolveParams(model, scene);
    expect(first(fabric, STRUCTURAL)).toBeCloseTo(axisSpringStiffness(600, 200), 3);
    expect(first(fabric, SHEAR)).toBeCloseTo(200, 3);
    const raw = resolveParams(model, validateScene({ material: { fabric: 'rubber', scaleWithResolution: false } }));
    expect(first(raw, STRUCTURAL)).toBe(600);
    const noShear = resolveParams(model, validateScene({ material: { fabric: 'rubber', shearStiffness: 0 } }));
    expect(first(noShear, STRUCTURAL)).toBe(600);
  });
});

describe('substeps for self-contact (solver.selfContactSpeed)', () => {
  const params = (res: number, solver: object, cloth: object = {}) => {
    const scene = validateScene({ cloth: { resolution: res, ...cloth }, solver: { selfContact: true, ...solver } });
    return resolveParams(modelFor(scene), scene);
  };

  it('raise the substeps, with a note, until cloth at that speed moves at most the contact distance in a substep', () => {
    // a 1 m grid: h is the 5 mm thickness up to 64² faces a side (20 substeps: 6 m/s moves 5 mm), then half the
    // smallest rest altitude, (1 m / N)/√2 / 2 — 3.68 mm at 96², 2.76 mm at 128²
    for (const [res, n] of [[32, 20], [64, 20], [96, 28], [128, 37]]) {
      const p = params(res, {});
      expect(p.substeps, `${res}²`).toBe(n);
      expect(p.substeps).toBe(Math.ceil((6 / 60) / Math.min(0.005, 1 / res / Math.SQRT2 / 2) - 1e-9));
      expect(p.clamps.length).toBe(n > 20 ? 1 : 0);
    }
    expect(params(128, {}).clamps[0]).toBe('self-contact at 20 substeps: cloth moving at 6 m/s (solver.selfContactSpeed) would travel 1.81 times ' +
      'the contact distance (2.76 mm) in one substep and could pass through itself, so it runs at 37 substeps — fewer with a thicker ' +
      'cloth (cloth.thickness), a coarser mesh (h is at most half the thinnest triangle\'s smallest altitude: one sliver sets it), a lower solver.selfContactSpeed, or self-contact off');
  });

  it('a thinner cloth needs more; more than the schema allows stops at its most and says how many it needed', () => {
    expect(params(32, {}, { thickness: 0.001 }).substeps).toBe(100);
    const p = params(32, {}, { thickness: 0.0002 });
    expect(p.substeps).toBe(200);
    expect(p.clamps[0]).toContain('so it runs at 200 substeps (the most there can be; 500 would keep it apart)');
  });

  it('keep what the scene asks when it is enough, when the speed is 0, without self-contact and with a zero thickness', () => {
    expect(params(128, { substeps: 50 }).substeps).toBe(50);
    expect(params(128, { selfContactSpeed: 3 }).substeps).toBe(20);
    expect(params(128, { selfContactSpeed: 0, substeps: 7 })).toMatchObject({ substeps: 7, clamps: [] });
    expect(params(128, { selfContact: false, substeps: 7 })).toMatchObject({ substeps: 7, clamps: [] });
    expect(params(128, { substeps: 7 }, { thickness: 0 })).toMatchObject({ substeps: 7, clamps: [] });
  });

  it('between two cloths the thinner one sets it', () => {
    const scene = validateScene({ solver: { selfContact: true }, cloths: [{ cloth: { resolution: 8 } }, { cloth: { resolution: 8, thickness: 0.002, position: [0, 1, 0] } }] });
    expect(resolveParams(modelFor(scene), scene).substeps).toBe(50);
  });
});

describe('the solves together have a size limit (GLOBAL_SOLVE_MOST_PARTICLES)', () => {
  const params = (res: number) => {
    const scene = validateScene({ cloth: { resolution: res }, solver: { bending: 'hinges', bendingSolve: 'global', stretch: 'global' } });
    return resolveParams(modelFor(scene), scene);
  };

  it('up to 257 × 257 particles both are solved together; past it one constraint at a time, each saying so', () => {
    expect(GLOBAL_SOLVE_MOST_PARTICLES).toBe(257 * 257);
    expect(params(256)).toMatchObject({ stretch: 'global', bendingSolve: 'global', clamps: [] });
    const p = params(257);
    expect(p).toMatchObject({ stretch: 'gauss-seidel', bendingSolve: 'gauss-seidel' });
    expect(p.clamps).toHaveLength(2);
    expect(p.clamps[0]).toBe("solver.stretch 'global' at 66,564 particles: a cloth solved together has at most 66,049 (257 × 257), " +
      'whose factor takes seconds to make on the CPU whenever a parameter or a pin changes, and a larger one far more time and memory — ' +
      "so this one is solved one constraint at a time ('gauss-seidel'); for the solve together, a coarser mesh (cloth.resolution)");
    expect(p.clamps[1]).toMatch(/^solver\.bendingSolve 'global' at 66,564 particles: /);
  });
});

describe('what a cloth asks that its shape does not do is said in the clamps, not dropped in silence', () => {
  const clamps = (doc: object) => { const s = validateScene(doc); return resolveParams(modelFor(s), s).clamps; };
  it('a field of another shape, and a resolution below the shape\'s fewest faces', () => {
    expect(clamps({ cloth: { lattice: 'weave' } })).toEqual(["cloth.lattice 'weave': a disc's lattice, and this cloth is a 'rectangle': not used"]);
    expect(clamps({ cloth: { shape: 'disc', imperfection: 0.05 } })).toEqual(["cloth.imperfection 0.05: a rectangle's bulge, and this cloth is a 'disc': not used"]);
    expect(clamps({ cloth: { shape: 'disc', resolution: 1 } })).toEqual(['cloth.resolution 1: a disc of rings has at least 2 faces across, so it has 2']);
    expect(clamps({ cloth: { shape: 'disc', lattice: 'weave', resolution: 3 } })).toEqual(['cloth.resolution 3: a woven disc has at least 4 faces across, so it has 4']);
    // a 1 m tube is 3.14 m round: resolution 1 and 2 give the fewest, 3 around and 1 along; 3 is that, asked for
    expect(clamps({ cloth: { shape: 'tube', resolution: 2 } })).toEqual(['cloth.resolution 2: a tube has at least 3 faces around and 1 along, so it has 3 around and 1 along']);
    expect(clamps({ cloth: { shape: 'tube', resolution: 3 } })).toEqual([]);
    // what a shape does take says nothing
    for (const cloth of [{}, { imperfection: 0.01 }, { shape: 'disc', lattice: 'weave', resolution: 4 }, { shape: 'disc', resolution: 2 }, { shape: 'tube', resolution: 32 }]) {
      expect(clamps({ cloth }), JSON.stringify(cloth)).toEqual([]);
    }
    // in a list of cloths, named by the entry
    expect(clamps({ cloths: [{ cloth: {} }, { cloth: { shape: 'tube', imperfection: 0.01, position: [0, 3, 0] } }] }))
      .toEqual(["cloths[1].cloth.imperfection 0.01: a rectangle's bulge, and this cloth is a 'tube': not used"]);
  });
});
