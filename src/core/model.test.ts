import { describe, expect, it } from 'vitest';
import { BEND, buildGridModel, SHEAR, STRUCTURAL, type GridClothSpec } from './model.js';

const spec = (resolution: number, extra: Partial<GridClothSpec> = {}): GridClothSpec => ({
  resolution, width: 1, height: 1, orientation: 'horizontal', position: [0, 1, 0], rotation: [0, 0, 0], scaleWithResolution: true, ...extra,
});

describe('grid cloth model', () => {
  it('resolution 1 is one quad: 4 particles, 4 structural + 2 shear springs, no bend, 2 triangles', () => {
    const m = buildGridModel(spec(1));
    expect(m.particleCount).toBe(4);
    expect(m.springCounts).toEqual([4, 2, 0]);
    expect(m.triangles.length / 3).toBe(2);
  });

  it('resolution 64 is 4096 faces: 65² particles, 8192 triangles, all three spring kinds', () => {
    const m = buildGridModel(spec(64));
    expect(m.particleCount).toBe(65 * 65);
    expect(m.triangles.length / 3).toBe(8192);
    expect(m.springCounts).toEqual([2 * 64 * 65, 2 * 64 * 64, 2 * 63 * 65]);
  });

  it('rest lengths come from the start pose', () => {
    const m = buildGridModel(spec(4, { width: 2, height: 1 }));
    for (let s = 0; s < m.restLengths.length; s++) {
      const expected = { [STRUCTURAL]: [0.5, 0.25], [SHEAR]: [Math.hypot(0.5, 0.25)], [BEND]: [1, 0.5] }[m.springKinds[s]]!;
      expect(expected.some((e) => Math.abs(e - m.restLengths[s]) < 1e-6)).toBe(true);
    }
  });

  it('cloth.imperfection bulges a grid out of its plane by sin(πu)·sin(πv) × its height, zero on the edges; 0 is exactly flat', () => {
    const flat = buildGridModel(spec(8, { orientation: 'hanging', imperfection: 0 }));
    const plain = buildGridModel(spec(8, { orientation: 'hanging' }));
    expect(flat.restPositions).toEqual(plain.restPositions);
    for (let p = 0; p < 81; p++) expect(flat.restPositions[3 * p + 2]).toBe(0);
    const bulged = buildGridModel(spec(8, { orientation: 'hanging', imperfection: 0.002 }));
    for (let j = 0; j <= 8; j++) for (let i = 0; i <= 8; i++) {
      const p = 9 * j + i;
      expect(bulged.restPositions[3 * p + 2]).toBeCloseTo(0.002 * Math.sin((Math.PI * i) / 8) * Math.sin((Math.PI * j) / 8), 9);
      expect(bulged.restPositions[3 * p]).toBe(plain.restPositions[3 * p]);
      expect(bulged.restPositions[3 * p + 1]).toBe(plain.restPositions[3 * p + 1]);
    }
    const lying = buildGridModel(spec(8, { imperfection: 0.002 }));
    expect(lying.restPositions[3 * 40 + 1]).toBeCloseTo(1.002, 6); // the centre, along +y when horizontal
  });

  it('colour batches hold one kind each and no two springs of a batch share a particle', () => {
    const m = buildGridModel(spec(16));
    let covered = 0;
    for (const b of m.batches) {
      const seen = new Set<number>();
      for (let s = b.start; s < b.end; s++) {
        expect(m.springKinds[s]).toBe(b.kind);
        for (const p of [m.springs[2 * s], m.springs[2 * s + 1]]) {
          expect(seen.has(p)).toBe(false);
          seen.add(p);
        }
      }
      covered += b.end - b.start;
    }
    expect(covered).toBe(m.restLengths.length);
    expect(m.batches.length).toBe(12); // 2 colours per direction: the greedy order keeps grids minimal
  });

  it('mass weights are lumped areas that sum to one (corner ¼, edge ½, interior 1 of a cell share)', () => {
    const m = buildGridModel(spec(4));
    const sum = m.massWeights.reduce((a, b) => a + b, 0);
    expect(sum).toBeCloseTo(1, 6);
    expect(m.massWeights[0] * 16).toBeCloseTo(1 / 3, 6); // a corner touching one triangle... of 2 per cell: ⅓ of ½ cell
    expect(m.massWeights[2 * 5 + 2] * 16).toBeCloseTo(1, 6); // interior particle: six triangles × ⅓ × ½ cell
  });

  it('hanging orientation puts row 0 at the top; rotation and position move the cloth', () => {
    const m = buildGridModel(spec(2, { orientation: 'hanging', position: [1, 2, 3] }));
    expect(m.restPositions[1]).toBeCloseTo(2.5, 6); // row 0 at the top
    expect(m.restPositions[3 * 8 + 1]).toBeCloseTo(1.5, 6);
    const r = buildGridModel(spec(2, { rotation: [0, 90, 0] }));
    expect(r.restPositions[0]).toBeCloseTo(-0.5, 5); // (-0.5, 1, -0.5) turned 90° about y → (-0.5, 1, 0.5)
    expect(r.restPositions[2]).toBeCloseTo(0.5, 5);
  });

  it('with scaleWithResolution, bend springs scale with the fourth power of the spacing; without, not at all', () => {
    const coarse = buildGridModel(spec(32)), fine = buildGridModel(spec(64)), seed = buildGridModel(spec(64, { scaleWithResolution: false }));
    const bendScale = (m: typeof coarse) => m.stiffnessScales[m.springKinds.indexOf(BEND)];
    expect(bendScale(coarse)).toBeCloseTo(1, 6); // reference spacing 1/32 m
    expect(bendScale(fine)).toBeCloseTo(16, 4);
    expect(bendScale(seed)).toBe(1);
    expect(fine.stiffnessScales[fine.springKinds.indexOf(STRUCTURAL)]).toBeCloseTo(1, 6);
  });

  it('rejects resolutions outside 1…1024', () => {
    expect(() => buildGridModel(spec(0))).toThrow(/resolution/);
    expect(() => buildGridModel(spec(1025))).toThrow(/resolution/);
  });

  it('triangle colour batches cover every triangle once and share no vertex within a batch; a grid needs 6–8', () => {
    const m = buildGridModel(spec(12));
    const batches = m.triangleBatches;
    expect(batches.length).toBeGreaterThanOrEqual(6);
    expect(batches.length).toBeLessThanOrEqual(8);
    expect(batches[0].start).toBe(0);
    expect(batches[batches.length - 1].end).toBe(m.triangles.length / 3);
    for (let c = 0; c < batches.length; c++) {
      if (c > 0) expect(batches[c].start).toBe(batches[c - 1].end);
      const seen = new Set<number>();
      for (let t = batches[c].start; t < batches[c].end; t++) {
        for (let j = 0; j < 3; j++) {
          const v = m.triangles[3 * t + j];
          expect(seen.has(v), `colour ${c}, triangle ${t}`).toBe(false);
          seen.add(v);
        }
      }
    }
  });
});
