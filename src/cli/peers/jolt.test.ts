import { describe, it, expect } from 'vitest';
import { runJoltCloth, type PeerClothSpec } from './jolt.js';

/** A size x size particle grid, `width` m wide, horizontal at height y, centred on x = z = 0. */
function gridCloth(size: number, width: number, y: number, compliance: number): PeerClothSpec {
  const n = size * size;
  const positions = new Float32Array(3 * n);
  const invMass = new Float32Array(n);
  const h = width / (size - 1);
  const massPerParticle = 0.5 / n; // 0.5 kg cloth
  const id = (i: number, j: number): number => j * size + i;
  for (let j = 0; j < size; j++) {
    for (let i = 0; i < size; i++) {
      const k = id(i, j);
      positions[3 * k] = -width / 2 + i * h;
      positions[3 * k + 1] = y;
      positions[3 * k + 2] = -width / 2 + j * h;
      invMass[k] = 1 / massPerParticle;
    }
  }
  const edges: number[] = [];
  const triangles: number[] = [];
  for (let j = 0; j < size; j++) {
    for (let i = 0; i < size; i++) {
      if (i + 1 < size) edges.push(id(i, j), id(i + 1, j)); // structural
      if (j + 1 < size) edges.push(id(i, j), id(i, j + 1));
      if (i + 1 < size && j + 1 < size) {
        edges.push(id(i, j), id(i + 1, j + 1)); // shear
        edges.push(id(i + 1, j), id(i, j + 1));
        triangles.push(id(i, j), id(i, j + 1), id(i + 1, j + 1));
        triangles.push(id(i, j), id(i + 1, j + 1), id(i + 1, j));
      }
    }
  }
  return {
    positions,
    invMass,
    edges: Uint32Array.from(edges),
    compliance: new Float32Array(edges.length / 2).fill(compliance),
    triangles: Uint32Array.from(triangles),
    sphere: { center: [0, 0.5, 0], radius: 0.3 },
    floorY: 0,
    gravity: [0, -9.81, 0],
    iterations: 5,
    friction: 0.3,
    vertexRadius: 0.005,
  };
}

describe('runJoltCloth (Jolt soft body peer)', () => {
  it('drops a 16x16 cloth onto a sphere: finite, fallen, above the floor', async () => {
    const spec = gridCloth(16, 1, 1.5, 1e-4);
    const result = await runJoltCloth(spec, 100, 20);
    expect(result.finite).toBe(true);
    expect(result.msPerFrame).toBeGreaterThan(0);
    expect(result.name).toMatch(/jolt/i);
    const [cx, cy, cz] = result.centroid;
    expect(cy).toBeLessThan(1.5 - 0.1);
    expect(cy).toBeGreaterThan(0);
    // draped over the sphere at the origin: it should not have slid far away
    expect(Math.abs(cx)).toBeLessThan(0.5);
    expect(Math.abs(cz)).toBeLessThan(0.5);
  }, 20_000);

  it('can run twice in one process (resources are freed, results are reproducible)', async () => {
    const spec = gridCloth(8, 1, 1.5, 1e-4);
    const a = await runJoltCloth(spec, 10, 0);
    const b = await runJoltCloth(spec, 10, 0);
    expect(a.finite && b.finite).toBe(true);
    expect(b.centroid[1]).toBeCloseTo(a.centroid[1], 5);
    // after 10 frames of free fall (~0.14 m) the cloth is still well above the sphere
    expect(a.centroid[1]).toBeLessThan(1.5);
    expect(a.centroid[1]).toBeGreaterThan(1.2);
  }, 20_000);

  it('rejects inconsistent specs with a one-line error', async () => {
    const spec = gridCloth(4, 1, 1.5, 1e-4);
    await expect(runJoltCloth({ ...spec, compliance: new Float32Array(1) }, 1, 0)).rejects.toThrow(/compliance/);
  });
});
