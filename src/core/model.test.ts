import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { parseMeshFile } from './cloth-shape.js';
import { discMesh, tubeMesh } from './mesh/generators.js';
import { prepareMesh } from './mesh/triangle-mesh.js';
import { BEND, buildGridModel, buildMeshModel, lumpedMassWeights, SHEAR, STRUCTURAL, type GridClothSpec } from './model.js';

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

  it('mass weights are mixed Voronoi areas that sum to one (corner ¼, edge ½, interior 1 of a cell)', () => {
    for (const [width, height] of [[1, 1], [2, 1]]) {
      const m = buildGridModel(spec(4, { width, height }));
      const sum = m.massWeights.reduce((a, b) => a + b, 0);
      expect(sum).toBeCloseTo(1, 6);
      const cell = (i: number, j: number) => m.massWeights[5 * j + i] * 16;
      // all four corners alike, whichever way the cells' diagonals run (a third of each triangle gave ⅙ and ⅓)
      for (const [i, j] of [[0, 0], [4, 0], [0, 4], [4, 4]]) expect(cell(i, j), `corner ${i},${j}`).toBeCloseTo(1 / 4, 6);
      for (const [i, j] of [[2, 0], [0, 2], [4, 1], [3, 4]]) expect(cell(i, j), `edge ${i},${j}`).toBeCloseTo(1 / 2, 6);
      expect(cell(2, 2)).toBeCloseTo(1, 6);
      expect(cell(1, 3)).toBeCloseTo(1, 6);
    }
  });

  it('the lumping does not depend on the way a cell is split, nor on the order of a triangle\'s corners', () => {
    const p = new Float32Array([0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0]);
    const one = lumpedMassWeights(p, new Uint32Array([0, 1, 2, 0, 2, 3]), 4);
    const other = lumpedMassWeights(p, new Uint32Array([1, 3, 0, 3, 1, 2]), 4);
    expect(one.area).toBeCloseTo(2, 12);
    for (let i = 0; i < 4; i++) {
      expect(one.weights[i]).toBeCloseTo(1 / 4, 7);
      expect(other.weights[i]).toBeCloseTo(1 / 4, 7);
    }
  });

  it('one triangle: acute parts are its Voronoi regions, an obtuse corner gets ½ and the others ¼ (Meyer et al. 2003)', () => {
    // equilateral: a third each
    const eq = lumpedMassWeights(new Float32Array([0, 0, 0, 1, 0, 0, 0.5, Math.sqrt(3) / 2, 0]), new Uint32Array([0, 1, 2]), 3);
    for (let i = 0; i < 3; i++) expect(eq.weights[i]).toBeCloseTo(1 / 3, 6);
    // an acute scalene triangle, (0,0), (4,0), (1,3): the Voronoi parts (|PR|²·cot Q + |PQ|²·cot R)/8 of area 6
    const sc = lumpedMassWeights(new Float32Array([0, 0, 0, 4, 0, 0, 1, 3, 0]), new Uint32Array([0, 1, 2]), 3);
    // cot at (0,0) = 1/3, at (4,0) = 1, at (1,3) = 1/2; |ab|² = 16, |bc|² = 18, |ca|² = 10
    const want = [(10 * 1 + 16 * 0.5) / 8, (16 * 0.5 + 18 / 3) / 8, (18 / 3 + 10 * 1) / 8];
    for (let i = 0; i < 3; i++) expect(sc.weights[i]).toBeCloseTo(want[i] / 6, 6);
    // obtuse at (0,0): (0,0), (3,0), (−1,1)
    const ob = lumpedMassWeights(new Float32Array([0, 0, 0, 3, 0, 0, -1, 1, 0]), new Uint32Array([2, 0, 1]), 3);
    expect([...ob.weights].map((w) => +w.toFixed(6))).toEqual([0.5, 0.25, 0.25]);
    expect(ob.area).toBeCloseTo(1.5, 12);
  });

  it('mass shares sum to 1 on a rectangle, a disc, a tube and a mesh file; a particle outside every triangle gets the mean', () => {
    const rect = buildGridModel(spec(37, { width: 1.3, height: 0.7, rotation: [20, 30, 40] }));
    const disc = buildMeshModel(prepareMesh(discMesh({ ...spec(24), width: 1.1 }), 'disc'), true);
    const tube = buildMeshModel(prepareMesh(tubeMesh({ ...spec(24), width: 0.4, height: 0.6, orientation: 'hanging' }), 'tube'), true);
    const shirt = buildMeshModel(prepareMesh(parseMeshFile(readFileSync(new URL('../../examples/tshirt.obj', import.meta.url)), 'tshirt.obj'), 'tshirt.obj'), true);
    for (const [name, m] of [['rectangle', rect], ['disc', disc], ['tube', tube], ['tshirt.obj', shirt]] as const) {
      let sum = 0, min = Infinity;
      for (const w of m.massWeights) { sum += w; min = Math.min(min, w); }
      // stored as float32: each share to 2⁻²⁴ of itself
      expect(Math.abs(sum - 1), name).toBeLessThan(2e-7 * Math.sqrt(m.particleCount));
      expect(min, name).toBeGreaterThan(0);
      // and each share is the particle's part of the area, which adds up to the model's area
      const { area } = lumpedMassWeights(m.restPositions, m.triangles, m.particleCount);
      expect(area, name).toBeCloseTo(m.area, 10);
    }
    // hand-built: a triangle and a particle of its own
    const stray = lumpedMassWeights(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5]), new Uint32Array([0, 1, 2]), 4);
    expect(stray.weights.reduce((a, b) => a + b, 0)).toBeCloseTo(1, 7);
    expect(stray.weights[3]).toBeCloseTo(1 / 4, 7); // the mean of the other three
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
