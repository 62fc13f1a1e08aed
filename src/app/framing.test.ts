import { describe, expect, it } from 'vitest';
import { SceneError, Simulation, builtinScene, setScenePath, type TriangleMesh } from '../core/index.js';
import { emptyBounds, frameBounds } from './framing.js';

/** a box from (0, 0, 0) to (2, 1, 0.5) in file units: its origin at a corner, as files often have it */
const BOX: TriangleMesh = {
  positions: new Float32Array([0, 0, 0, 2, 0, 0, 0, 1, 0, 2, 1, 0, 0, 0, 0.5, 2, 0, 0.5, 0, 1, 0.5, 2, 1, 0.5]),
  triangles: new Uint32Array([0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6]),
};
const meshes = (path: string): TriangleMesh => {
  if (path !== 'box.obj') throw new SceneError(`no ${path}`);
  return BOX;
};

describe('what the camera frames', () => {
  it('holds the cloth and a mesh collider\'s box, scaled, turned and moved as the scene places it', () => {
    // the box at scale 0.5 is 1 × 0.5 × 0.25 m; turned 90° about y, its x runs along −z; moved to (3, 0, 0)
    const scene = setScenePath(builtinScene('cotton-basic'), 'colliders', [
      { type: 'floor', height: 0 },
      { type: 'mesh', mesh: 'box.obj', scale: 0.5, rotation: [0, 90, 0], position: [3, 0, 0] },
    ]);
    const sim = new Simulation(scene, { kernel: 'ts', meshes });
    const b = emptyBounds();
    frameBounds(sim.model.restPositions, sim.scene.colliders, sim.params.colliders, b);
    // the cloth: 1 m square at y 1.2 about the origin; the box: x 3 … 3.25, y 0 … 0.5, z −1 … 0
    expect(b.min[0]).toBeCloseTo(-0.5, 5);
    expect(b.max[0]).toBeCloseTo(3.25, 5);
    expect(b.min[1]).toBeCloseTo(0, 5);
    expect(b.max[1]).toBeCloseTo(1.2, 5);
    expect(b.min[2]).toBeCloseTo(-1, 5);
    expect(b.max[2]).toBeCloseTo(0.5, 5);
  });

  it('holds each analytic shape by a ball around it; a floor and a plane are everywhere', () => {
    const sim = new Simulation(builtinScene('cotton-basic'), { kernel: 'ts' });
    const b = emptyBounds();
    frameBounds(new Float32Array(0), sim.scene.colliders, sim.params.colliders, b);
    const s = sim.scene.colliders.find((c) => c.type === 'sphere');
    if (s?.type !== 'sphere') throw new Error('cotton-basic has a sphere');
    expect(b.min).toEqual(s.center.map((v) => v - s.radius));
    expect(b.max).toEqual(s.center.map((v) => v + s.radius));
  });
});
