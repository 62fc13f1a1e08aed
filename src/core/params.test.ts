import { describe, expect, it } from 'vitest';
import { buildGridModel } from './model.js';
import { axisSpringStiffness, resolveParams } from './params.js';
import { validateScene } from './scene.js';
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
