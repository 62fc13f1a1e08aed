import { describe, expect, it } from 'vitest';
import { testLine } from './hud-feed.js';

describe("the HUD's fabric-test line", () => {
  it('shows a value that is not finite (an unstable cloth) as —, never NaN or Infinity', () => {
    expect(testLine({ type: 'cantilever', overhang: -Infinity, chordAngle: NaN, bendingLength: NaN }))
      .toBe('cantilever: tip —° below the edge, — cm out → bending length — cm');
    expect(testLine({ type: 'cusick', projectedArea: NaN, drapeCoefficient: NaN, folds: NaN })).toBe('Cusick drape: coefficient —, — folds');
    expect(testLine({ type: 'cantilever', overhang: 0.04, chordAngle: 41.5, bendingLength: 0.02 }))
      .toBe('cantilever: tip 41.5° below the edge, 4.00 cm out → bending length 2.00 cm');
  });
});
