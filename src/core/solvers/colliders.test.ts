/**
 * The analytic collider shapes in the solvers, for every CPU solver and kernel: a cloth dropped on each comes to
 * rest outside it (penetration measured here against the exact shape, not with the solver's measure), and a patch
 * on a ramp slides or stays as Coulomb's law says.
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type ColliderSpec, type SolverType } from '../scene.js';
import { Simulation, type CpuKernel } from '../simulation.js';

const CASES: [SolverType, CpuKernel][] = [['xpbd', 'ts'], ['xpbd', 'wasm'], ['mass-spring', 'ts']];
const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };

type V = [number, number, number];
const dot = (a: number[], b: number[]) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const sub = (a: number[], b: number[]): V => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const len = (a: number[]) => Math.sqrt(dot(a, a));
/** the rotation Rz(z)·Ry(y)·Rx(x) [degrees], columns = the box's own axes in world coordinates */
function boxAxes(r: number[]): V[] {
  const [x, y, z] = r.map((d) => (d * Math.PI) / 180);
  const rx = (v: V): V => [v[0], Math.cos(x) * v[1] - Math.sin(x) * v[2], Math.sin(x) * v[1] + Math.cos(x) * v[2]];
  const ry = (v: V): V => [Math.cos(y) * v[0] + Math.sin(y) * v[2], v[1], -Math.sin(y) * v[0] + Math.cos(y) * v[2]];
  const rz = (v: V): V => [Math.cos(z) * v[0] - Math.sin(z) * v[1], Math.sin(z) * v[0] + Math.cos(z) * v[1], v[2]];
  return [[1, 0, 0], [0, 1, 0], [0, 0, 1]].map((e) => rz(ry(rx(e as V))));
}

/** The exact signed distance of each shape, written here from its definition (independent of colliders/). */
function exactDistance(c: ColliderSpec): (p: number[]) => number {
  switch (c.type) {
    case 'plane': { const n = c.normal.map((v) => v / len(c.normal)); return (p) => dot(sub(p, c.point), n); }
    case 'sphere': return (p) => len(sub(p, c.center)) - c.radius;
    case 'floor': return (p) => p[1] - c.height;
    case 'box': {
      const axes = boxAxes(c.rotation);
      return (p) => {
        const d = sub(p, c.center);
        const e = axes.map((a, k) => Math.abs(dot(d, a)) - c.halfExtents[k]);
        const outside = len(e.map((v) => Math.max(v, 0)));
        return outside > 0 ? outside : Math.max(...e);
      };
    }
    case 'capsule': {
      const ab = sub(c.b, c.a);
      return (p) => {
        const t = Math.min(Math.max(dot(sub(p, c.a), ab) / dot(ab, ab), 0), 1);
        return len(sub(p, [c.a[0] + t * ab[0], c.a[1] + t * ab[1], c.a[2] + t * ab[2]])) - c.radius;
      };
    }
    case 'cylinder': {
      const u = c.axis.map((v) => v / len(c.axis));
      return (p) => {
        const d = sub(p, c.center);
        const y = dot(d, u);
        const rho = len(sub(d, u.map((v) => v * y)));
        const er = rho - c.radius, ey = Math.abs(y) - c.height / 2;
        return er > 0 || ey > 0 ? Math.hypot(Math.max(er, 0), Math.max(ey, 0)) : Math.max(er, ey);
      };
    }
    case 'mesh': throw new Error('a mesh collider has no formula here (colliders/mesh-drop.test.ts measures it)');
  }
}

/** Deepest point of the cloth inside the shape [m] (0 if none), over the particles and 15 points of each triangle. */
function penetration(sim: Simulation, c: ColliderSpec): { depth: number; nearest: number } {
  const f = exactDistance(c), x = sim.state.positions, t = sim.model.triangles;
  let min = Infinity;
  for (let i = 0; i < x.length; i += 3) min = Math.min(min, f([x[i], x[i + 1], x[i + 2]]));
  for (let k = 0; k < t.length; k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1], cc = 3 * t[k + 2];
    for (let i = 0; i <= 4; i++) for (let j = 0; i + j <= 4; j++) {
      const u = i / 4, v = j / 4, w = 1 - u - v;
      min = Math.min(min, f([w * x[a] + u * x[b] + v * x[cc], w * x[a + 1] + u * x[b + 1] + v * x[cc + 1], w * x[a + 2] + u * x[b + 2] + v * x[cc + 2]]));
    }
  }
  return { depth: Math.max(0, -min), nearest: min };
}

/** RMS speed [m/s] of the particles touching the shape (within `reach` of its exact surface). */
function contactSpeed(sim: Simulation, c: ColliderSpec, reach: number): number {
  const f = exactDistance(c), x = sim.state.positions, v = sim.state.velocities;
  let s = 0, n = 0;
  for (let i = 0; i < x.length; i += 3) {
    if (f([x[i], x[i + 1], x[i + 2]]) > reach) continue;
    s += v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2];
    n++;
  }
  expect(n).toBeGreaterThan(0);
  return Math.sqrt(s / n);
}

const DROPS: [string, ColliderSpec][] = [
  ['plane (tilted 10°, under the friction angle)', { type: 'plane', point: [0, 0.2, 0], normal: [Math.sin(0.1745), Math.cos(0.1745), 0] }],
  ['box (turned 30° about y: a table)', { type: 'box', center: [0, 0.35, 0], halfExtents: [0.3, 0.35, 0.25], rotation: [0, 30, 0] }],
  ['box (tilted onto an edge)', { type: 'box', center: [0, 0.3, 0], halfExtents: [0.2, 0.2, 0.2], rotation: [45, 0, 20] }],
  ['capsule (a low bar)', { type: 'capsule', a: [-0.4, 0.25, 0.1], b: [0.4, 0.25, -0.1], radius: 0.1 }],
  ['cylinder (a pedestal)', { type: 'cylinder', center: [0, 0.25, 0], axis: [0, 1, 0], radius: 0.2, height: 0.5 }],
  ['cylinder (on its side)', { type: 'cylinder', center: [0, 0.2, 0], axis: [1, 0, 0.3], radius: 0.15, height: 0.7 }],
];

describe.each(CASES)('%s solver, %s kernel', (solver, kernel) => {
  it.each(DROPS)('a cloth dropped on a %s comes to rest outside it', (_name, shape) => {
    // 16 faces per side (6 cm triangles: triangle contact matters at edges and rims), 4 s: landed and settled where it
    // touches (corners hanging free may still swing; contact is what is tested); a floor below
    const colliders: ColliderSpec[] = shape.type === 'plane' ? [shape] : [shape, { type: 'floor', height: 0 }];
    const sc = validateScene({ cloth: { resolution: 16, position: [0, 0.9, 0] }, material: cotton, solver: { type: solver }, colliders });
    const sim = new Simulation(sc, { kernel });
    expect(sim.kernel).toBe(kernel);
    sim.advance(240);
    const x = sim.state.positions;
    expect(x.every(Number.isFinite)).toBe(true);
    const { depth, nearest } = penetration(sim, shape);
    expect(depth).toBeLessThanOrEqual(sc.cloth.thickness);
    // it lies on the shape (not beside it), and where it touches it has stopped (no jitter, no sliding off)
    expect(nearest).toBeLessThan(2 * sc.cloth.thickness);
    expect(contactSpeed(sim, shape, 2 * sc.cloth.thickness)).toBeLessThan(0.02);
  });

  // a 20 cm patch (4 faces per side) laid on a plane tilted θ about z, for 1 s at the default solver settings
  const slide = (deg: number): number => {
    const t = (deg * Math.PI) / 180, n: V = [-Math.sin(t), Math.cos(t), 0], th = 0.005;
    const sc = validateScene({
      cloth: { resolution: 4, width: 0.2, height: 0.2, position: [th * n[0], th * n[1], 0], rotation: [0, 0, deg] },
      material: cotton, solver: { type: solver }, colliders: [{ type: 'plane', point: [0, 0, 0], normal: n }],
    });
    const sim = new Simulation(sc, { kernel });
    const c0 = sim.report().centroid;
    sim.advance(60);
    const c1 = sim.report().centroid;
    expect(Math.abs(dot(c1, n) - th)).toBeLessThan(1e-4); // on the plane throughout
    return dot(sub(c1, c0), [-Math.cos(t), -Math.sin(t), 0]);
  };
  const friction = (Math.atan(cotton.staticFriction) * 180) / Math.PI; // 21.8°
  it.each([-2, -1])('on a ramp %d° under the friction angle (tan θ < μs) a patch stays', (dd) => {
    expect(Math.abs(slide(friction + dd))).toBeLessThan(1e-4);
  });
  it.each([1, 2])('on a ramp %d° over the friction angle (tan θ > μs) a patch slides, as kinetic friction says', (dd) => {
    const deg = friction + dd, t = (deg * Math.PI) / 180;
    // once slipping, ½·g(sin θ − μk cos θ)·t² down the slope in t = 1 s
    const expected = 0.5 * 9.81 * (Math.sin(t) - cotton.friction * Math.cos(t));
    expect(slide(deg) / expected).toBeGreaterThan(0.98);
    expect(slide(deg) / expected).toBeLessThan(1.02);
  });
});

describe('the placement check knows the new shapes (it uses their signed distance)', () => {
  const at = (c: ColliderSpec, pins: string[] = []) => () =>
    new Simulation(validateScene({ cloth: { resolution: 12, position: [0, 1, 0] }, colliders: [c], pins }), { kernel: 'ts' });
  it.each([
    ['box', { type: 'box', center: [0, 1, 0], halfExtents: [0.2, 0.2, 0.2], rotation: [0, 0, 0] }],
    ['capsule', { type: 'capsule', a: [-0.3, 1, 0], b: [0.3, 1, 0], radius: 0.1 }],
    ['cylinder', { type: 'cylinder', center: [0, 1, 0], axis: [0, 1, 0], radius: 0.2, height: 0.4 }],
  ] as [string, ColliderSpec][])('a %s across the cloth is refused by name; below it, not', (type, c) => {
    expect(at(c)).toThrow(`colliders[0] (${type}) cuts through the cloth where it starts`);
    const below = structuredClone(c);
    if (below.type === 'capsule') { below.a[1] -= 0.5; below.b[1] -= 0.5; } else if (below.type !== 'plane' && below.type !== 'floor' && below.type !== 'mesh') below.center[1] -= 0.5;
    expect(at(below)).not.toThrow();
  });
  it('a pinned corner inside a box is refused by name; a plane under the cloth lifts it', () => {
    expect(at({ type: 'box', center: [-0.5, 1, -0.5], halfExtents: [0.05, 0.05, 0.05], rotation: [0, 0, 0] }, ['top-left'])).toThrow('colliders[0] (box): pinned particle 0 starts inside it');
    const sim = at({ type: 'plane', point: [0, 1.02, 0], normal: [0, 1, 0] })();
    sim.advance(30);
    const y = sim.report().bounds.min[1];
    expect(y).toBeGreaterThan(1.02);
    expect(y).toBeLessThan(1.03);
  });
});
