import { BufferAttribute, BufferGeometry, Matrix4, PlaneGeometry } from 'three';
import { describe, expect, it } from 'vitest';
import { meshOfGeometry } from './geometry.js';

describe('a BufferGeometry as a triangle mesh', () => {
  it('takes an indexed geometry\'s positions (transformed), triangles and uvs', () => {
    const g = new PlaneGeometry(2, 1, 2, 1);
    const m = meshOfGeometry(g, 'test', new Matrix4().makeTranslation(0, 3, 0));
    expect(m.positions.length).toBe(3 * 6);
    expect(m.triangles).toEqual(new Uint32Array(g.getIndex()!.array));
    expect(m.uvs!.length).toBe(12);
    expect(m.positions[1]).toBeCloseTo(3.5, 6); // the first vertex: (−1, 0.5, 0) moved up 3
  });

  it('numbers a non-indexed geometry\'s vertices in order, and refuses what is not triangles', () => {
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), 3));
    expect(Array.from(meshOfGeometry(g, 'test').triangles)).toEqual([0, 1, 2]);
    const lines = new BufferGeometry();
    lines.setAttribute('position', new BufferAttribute(new Float32Array([0, 0, 0, 1, 0, 0]), 3));
    expect(() => meshOfGeometry(lines, 'DrapeWorld.addCloth(x)')).toThrow('DrapeWorld.addCloth(x): the geometry is not triangles (2 indices)');
    expect(() => meshOfGeometry(new BufferGeometry(), 'x')).toThrow(/no position attribute/);
  });
});
