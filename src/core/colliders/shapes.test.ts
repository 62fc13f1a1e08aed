/**
 * The analytic collider shapes: signed distance and normal against hand-computed values, and the triangle's deepest
 * point against brute-force sampling of the triangle.
 */
import { describe, expect, it } from 'vitest';
import { COLLIDER_TYPES, validateScene, SceneError } from '../scene.js';
import { sceneSchema } from '../scene-schema.js';
import { BoxCollider } from './box.js';
import { CapsuleCollider } from './capsule.js';
import { segmentSegmentClosest, segmentTriangleClosest } from './convex.js';
import { CylinderCollider } from './cylinder.js';
import { createColliders, type ColliderShape } from './index.js';
import { PlaneCollider } from './plane.js';
import { closestPointOnTriangle } from './sphere.js';

/** the scene schema's fields, read as a tree (its declared type is any JSON Schema document) */
type SchemaTree = { properties: Record<string, any> };

const n = new Float64Array(3);
function sd(shape: ColliderShape, p: number[]): [number, number[]] {
  const d = shape.signedDistance(p[0], p[1], p[2], n);
  return [d, [n[0], n[1], n[2]]];
}
function expectSd(shape: ColliderShape, p: number[], d: number, normal?: number[]): void {
  const [got, gn] = sd(shape, p);
  expect(got).toBeCloseTo(d, 12);
  if (normal) for (let k = 0; k < 3; k++) expect(gn[k]).toBeCloseTo(normal[k], 12);
  // the early out never claims a point is farther than it is, and never makes a near point far
  const far = shape.signedDistance(p[0], p[1], p[2], n, 0.01);
  if (d < 0.01) expect(far).toBeCloseTo(d, 12);
  else expect(far).toBeGreaterThanOrEqual(0.01);
}
const s2 = Math.SQRT1_2;

describe('signed distance and normal, hand-computed', () => {
  it('plane: any normal length, any angle', () => {
    const flat = new PlaneCollider([0, 1, 0], [0, 2, 0]);
    expectSd(flat, [3, 4, 5], 3, [0, 1, 0]);
    expectSd(flat, [3, 0.5, 5], -0.5, [0, 1, 0]);
    const ramp = new PlaneCollider([0, 0, 0], [1, 1, 0]);
    expectSd(ramp, [1, 0, 0], s2, [s2, s2, 0]);
    expectSd(ramp, [-1, 0, 7], -s2, [s2, s2, 0]);
    expect(ramp.minCurvatureRadius).toBe(Infinity);
    expect((ramp as ColliderShape).triangleDeepest).toBeUndefined();
  });

  it('box: inside (nearest face), faces, edges, corners; rotated by Euler XYZ degrees', () => {
    const box = new BoxCollider([1, 2, 3], [0.5, 1, 2]);
    expectSd(box, [1, 2, 3], -0.5, [1, 0, 0]);
    expectSd(box, [0.8, 2, 3], -0.3, [-1, 0, 0]);
    expectSd(box, [1, 2.9, 3], -0.1, [0, 1, 0]);
    expectSd(box, [2, 2, 3], 0.5, [1, 0, 0]);
    expectSd(box, [1, 2, 0.5], 0.5, [0, 0, -1]);
    // an edge: 0.3 beyond x, 0.4 beyond y
    expectSd(box, [1.8, 3.4, 3], 0.5, [0.6, 0.8, 0]);
    // a corner: (1, 2, 2) beyond it
    expectSd(box, [2.5, 5, 7], 3, [1 / 3, 2 / 3, 2 / 3]);
    expect(box.minCurvatureRadius).toBe(0);
    // turned 90° about z: its own x axis is the world's y
    const tall = new BoxCollider([0, 0, 0], [2, 0.5, 0.5], [0, 0, 90]);
    expectSd(tall, [0, 1.9, 0], -0.1, [0, 1, 0]);
    expectSd(tall, [0.7, 0, 0], 0.2, [1, 0, 0]);
    expectSd(tall, [0, 2.3, 0.9], 0.5, [0, 0.6, 0.8]);
  });

  it('capsule: side, caps, inside, on the axis', () => {
    const cap = new CapsuleCollider([0, 0, 0], [0, 2, 0], 0.5);
    expectSd(cap, [1, 1, 0], 0.5, [1, 0, 0]);
    expectSd(cap, [0, 3, 0], 0.5, [0, 1, 0]);
    expectSd(cap, [0.6, -0.8, 0], 0.5, [0.6, -0.8, 0]);
    expectSd(cap, [0.3, 1, 0], -0.2, [1, 0, 0]);
    const [d, a] = sd(cap, [0, 1, 0]);
    expect(d).toBeCloseTo(-0.5, 12);
    expect(Math.hypot(a[0], a[1], a[2])).toBeCloseTo(1, 12);
    expect(a[1]).toBeCloseTo(0, 12); // perpendicular to the axis
    expect(cap.minCurvatureRadius).toBe(0.5);
  });

  it('cylinder: side, caps, rim, inside near the side and near a cap; any axis', () => {
    const cyl = new CylinderCollider([0, 0, 0], [0, 2, 0], 1, 2);
    expectSd(cyl, [2, 0, 0], 1, [1, 0, 0]);
    expectSd(cyl, [0, 3, 0], 2, [0, 1, 0]);
    expectSd(cyl, [0.2, -1.5, 0.1], 0.5, [0, -1, 0]);
    expectSd(cyl, [1.3, 1.4, 0], 0.5, [0.6, 0.8, 0]);
    expectSd(cyl, [0.5, 0, 0], -0.5, [1, 0, 0]);
    expectSd(cyl, [0, 0.9, 0], -0.1, [0, 1, 0]);
    expectSd(cyl, [0, -0.95, 0.2], -0.05, [0, -1, 0]);
    expect(cyl.minCurvatureRadius).toBe(0);
    const lying = new CylinderCollider([0, 0, 0], [1, 0, 0], 1, 3);
    expectSd(lying, [0, 2, 0], 1, [0, 1, 0]);
    expectSd(lying, [2, 0, 0], 0.5, [1, 0, 0]);
    expectSd(lying, [-1.6, 0, -1.8], Math.hypot(0.1, 0.8), [-0.1 / Math.hypot(0.1, 0.8), 0, -0.8 / Math.hypot(0.1, 0.8)]);
  });
});

describe('closest points of segments and triangles', () => {
  it('segment–segment: crossing, skew, parallel, end points', () => {
    const st = new Float64Array(2);
    expect(segmentSegmentClosest(-1, 0, 0, 1, 0, 0, 0, -1, 1, 0, 1, 1, st)).toBeCloseTo(1, 12);
    expect([...st]).toEqual([0.5, 0.5]);
    expect(segmentSegmentClosest(0, 0, 0, 1, 0, 0, 2, 0, 1, 3, 0, 1, st)).toBeCloseTo(2, 12); // (1,0,0)–(2,0,1)
    expect(segmentSegmentClosest(0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, st)).toBeCloseTo(1, 12); // parallel
  });
  it('segment–triangle: crossing, above the face, beside an edge', () => {
    const bary = new Float64Array(3), seg = new Float64Array(1);
    // the triangle (0,0,0), (2,0,0), (0,2,0); a segment through it at (0.5, 0.5)
    expect(segmentTriangleClosest(0.5, 0.5, -1, 0.5, 0.5, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0, bary, seg)).toBe(0);
    expect(bary[1]).toBeCloseTo(0.25, 12); expect(bary[2]).toBeCloseTo(0.25, 12); expect(seg[0]).toBeCloseTo(0.5, 12);
    // above the face: the lower end point
    expect(segmentTriangleClosest(0.5, 0.5, 0.3, 0.5, 0.5, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0, bary, seg)).toBeCloseTo(0.09, 12);
    // crossing past the hypotenuse, 0.5 from it in the plane: the edge
    const d2 = segmentTriangleClosest(1.5, 1.5, -1, 1.5, 1.5, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0, bary, seg);
    expect(d2).toBeCloseTo(0.5, 12);
    expect(bary[1]).toBeCloseTo(0.5, 12); expect(bary[2]).toBeCloseTo(0.5, 12);
  });
});

/** a small seeded generator: the same triangles every run */
function rng(seed: number): () => number {
  let s = seed >>> 0;
  return () => {
    s = (s + 0x6d2b79f5) >>> 0;
    let t = s;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

describe('the deepest point of a triangle, against sampling the triangle', () => {
  it('cylinder: triangles of a cloth lying over the rim (3 cm, tilted, just clear of it) are met exactly', () => {
    const cyl = new CylinderCollider([0, 0.25, 0], [0, 1, 0], 0.2, 0.5);
    const rand = rng(5);
    const x = new Float32Array(9), bary = new Float64Array(3), normal = new Float64Array(3), nn = new Float64Array(3);
    const N = 200;
    for (let trial = 0; trial < 100; trial++) {
      // a rim point, a plane through a point 1–6 mm outside it, tilted 0–40° down and outwards
      const phi = rand() * 2 * Math.PI, tilt = rand() * 0.7, gap = 0.001 + 0.005 * rand();
      const r = [Math.cos(phi), 0, Math.sin(phi)];
      const n = [r[0] * Math.sin(tilt), Math.cos(tilt), r[2] * Math.sin(tilt)];
      const o = [0.2 * r[0] + gap * n[0], 0.5 + gap * n[1], 0.2 * r[2] + gap * n[2]];
      const t1 = [-r[2], 0, r[0]], t2 = [n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]];
      for (let v = 0; v < 3; v++) {
        const u = (rand() - 0.5) * 0.03, w = (rand() - 0.5) * 0.03;
        for (let k = 0; k < 3; k++) x[3 * v + k] = o[k] + u * t1[k] + w * t2[k];
      }
      let brute = Infinity;
      for (let i = 0; i <= N; i++) {
        for (let j = 0; i + j <= N; j++) {
          const u = i / N, w = j / N, t = 1 - u - w;
          brute = Math.min(brute, cyl.signedDistance(t * x[0] + u * x[3] + w * x[6], t * x[1] + u * x[4] + w * x[7], t * x[2] + u * x[5] + w * x[8], nn));
        }
      }
      const d = cyl.triangleDeepest(x, 0, x, 3, x, 6, bary, normal);
      expect(d).toBeLessThanOrEqual(brute + 3e-6);
      expect(d).toBeGreaterThanOrEqual(brute - 0.03 / N);
    }
  });

  const shapes: [string, ColliderShape][] = [
    ['box', new BoxCollider([0.1, 0.3, -0.2], [0.3, 0.2, 0.25], [20, 35, -10])],
    ['capsule', new CapsuleCollider([-0.3, 0.2, 0.1], [0.25, 0.4, -0.1], 0.15)],
    ['cylinder', new CylinderCollider([0, 0.25, 0.05], [0.2, 1, 0.1], 0.2, 0.5)],
    ['cylinder on its side', new CylinderCollider([0, 0.25, 0], [1, 0, 0], 0.12, 0.6)],
  ];
  it.each(shapes)('%s: 600 triangles across the surface, edges, corners and rims', (_name, shape) => {
    const rand = rng(11);
    const x = new Float32Array(9), bary = new Float64Array(3), normal = new Float64Array(3), nn = new Float64Array(3);
    const N = 60;
    let worst = 0, crossed = 0, bounded = 0, clear = 0;
    for (let trial = 0; trial < 600; trial++) {
      // a centre near the shape's surface (within 10 cm of the bounding region), vertices up to 12 cm from it
      const c = [(rand() - 0.5) * 0.9, 0.25 + (rand() - 0.5) * 0.8, (rand() - 0.5) * 0.9];
      for (let v = 0; v < 3; v++) for (let k = 0; k < 3; k++) x[3 * v + k] = c[k] + (rand() - 0.5) * 0.24;
      let brute = Infinity;
      for (let i = 0; i <= N; i++) {
        for (let j = 0; i + j <= N; j++) {
          const u = i / N, w = j / N, t = 1 - u - w;
          const d = shape.signedDistance(t * x[0] + u * x[3] + w * x[6], t * x[1] + u * x[4] + w * x[7], t * x[2] + u * x[5] + w * x[8], nn);
          brute = Math.min(brute, d);
        }
      }
      const edge = Math.max(Math.hypot(x[3] - x[0], x[4] - x[1], x[5] - x[2]), Math.hypot(x[6] - x[3], x[7] - x[4], x[8] - x[5]), Math.hypot(x[0] - x[6], x[1] - x[7], x[2] - x[8]));
      const d = shape.triangleDeepest!(x, 0, x, 3, x, 6, bary, normal);
      // never shallower than a sample (beyond the search's tolerance: 3·10⁻³ of an edge) …
      expect(d).toBeLessThanOrEqual(brute + 3e-3 * edge + 1e-9);
      // … and never deeper than the triangle is: the sampled minimum is within a grid step of the true one
      expect(d).toBeGreaterThanOrEqual(brute - edge / N - 1e-9);
      worst = Math.max(worst, d - brute);
      // clear of the shape the answer is exact (the searches along edges close to 7·10⁻⁵ of an edge)
      if (brute > 1e-3) { expect(d).toBeLessThanOrEqual(brute + 1e-4 * edge + 1e-9); clear++; }
      // the point returned is on the triangle, and d and the normal are the shape's there
      expect(Math.min(bary[0], bary[1], bary[2])).toBeGreaterThanOrEqual(-1e-12);
      expect(bary[0] + bary[1] + bary[2]).toBeCloseTo(1, 12);
      const px = bary[0] * x[0] + bary[1] * x[3] + bary[2] * x[6], py = bary[0] * x[1] + bary[1] * x[4] + bary[2] * x[7], pz = bary[0] * x[2] + bary[1] * x[5] + bary[2] * x[8];
      expect(shape.signedDistance(px, py, pz, nn)).toBeCloseTo(d, 9);
      if (Math.hypot(normal[0] - nn[0], normal[1] - nn[1], normal[2] - nn[2]) > 1e-9) crossed++; // an axis through the triangle
      // the normal is a unit direction out of the shape: moving along it gains distance at rate 1
      expect(Math.hypot(normal[0], normal[1], normal[2])).toBeCloseTo(1, 12);
      const e = 1e-4;
      expect(shape.signedDistance(px + e * normal[0], py + e * normal[1], pz + e * normal[2], nn) - d).toBeCloseTo(e, 7);
      if (brute < 0) bounded++;
      // with `within`, a value at least `within` means the whole triangle is at least that far
      const far = shape.triangleDeepest!(x, 0, x, 3, x, 6, bary, normal, 0.005);
      if (far >= 0.005) expect(brute).toBeGreaterThanOrEqual(0.005 - 1e-9);
      else expect(far).toBeCloseTo(d, 12);
    }
    // the sample exercises penetrating triangles too
    expect(bounded).toBeGreaterThan(30);
    expect(clear).toBeGreaterThan(100);
    expect(crossed).toBeLessThan(60);
    expect(worst).toBeLessThan(0.003);
  });
});

describe('degenerate triangles', () => {
  it('the closest point of a triangle with two vertices at one point (a cloth crushed flat) is a finite point of it', () => {
    const bary = new Float64Array(3);
    // a = b: the face region's weights were 0/0 (NaN, which then moved the cloth to NaN)
    const a = [0.32964012026786804, 0.10480558127164841, 0.6883440017700195];
    closestPointOnTriangle(-0.664289659299075, -0.8352917385227836, -0.3671013275764734,
      a[0], a[1], a[2], a[0], a[1], a[2], -1.9578124284744263, 0.4629322290420532, -0.6855067610740662, bary);
    expect([...bary].every(Number.isFinite)).toBe(true);
    expect(bary[0] + bary[1] + bary[2]).toBeCloseTo(1, 12);
    for (let k = 0; k < 3; k++) expect(bary[k]).toBeGreaterThanOrEqual(0);
  });
});

describe('scenes name the shapes', () => {
  it('COLLIDER_TYPES is the schema\'s list, and every field of every shape has a description and a default', () => {
    const items = ((sceneSchema as SchemaTree).properties.colliders as unknown as { items: { oneOf: { required: string[]; properties: Record<string, { const?: string; description?: string; default?: unknown }> }[] } }).items;
    expect(items.oneOf.map((o) => o.properties.type.const)).toEqual([...COLLIDER_TYPES]);
    for (const o of items.oneOf) {
      for (const [key, field] of Object.entries(o.properties)) {
        // motion and pins are every collider's (checked below)
        if (key === 'type' || key === 'motion' || key === 'pins') continue;
        // a required field (a mesh collider's file) has no default, and no unit
        if (o.required.includes(key)) { expect(field.description).toBeTruthy(); expect(field.default).toBeUndefined(); continue; }
        expect(field.description, `${o.properties.type.const}.${key}`).toMatch(/\[.+\]$/); // ends with its unit
        expect(field.default, `${o.properties.type.const}.${key}`).toBeDefined();
      }
    }
  });
  it('every collider may move and carry pins: the motion\'s fields have units, the keys defaults', () => {
    const items = ((sceneSchema as SchemaTree).properties.colliders as unknown as { items: { oneOf: { properties: Record<string, unknown> }[] } }).items;
    type Field = { description?: string; default?: unknown; properties?: Record<string, Field>; items?: Field };
    for (const o of items.oneOf) {
      const motion = o.properties.motion as Field;
      const key = motion.properties!.keyframes.items!.properties!;
      expect(key.time.description).toMatch(/\[s\]/);
      for (const f of ['translation', 'rotation']) {
        expect(key[f].description).toMatch(/\[.+\]$/);
        expect(key[f].default).toEqual([0, 0, 0]);
      }
      expect(motion.properties!.pivot.description).toMatch(/\[m\]/);
      expect(motion.properties!.loop.default).toBe(false);
      expect((o.properties.pins as Field).default).toEqual([]);
    }
  });
  it('every field has its default, and createColliders builds each', () => {
    const s = validateScene({ colliders: [{ type: 'plane' }, { type: 'box' }, { type: 'capsule' }, { type: 'cylinder' }] });
    expect(s.colliders).toEqual([
      { type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], pins: [] },
      { type: 'box', center: [0, 0.35, 0], halfExtents: [0.4, 0.35, 0.4], rotation: [0, 0, 0], pins: [] },
      { type: 'capsule', a: [-0.4, 0.5, 0], b: [0.4, 0.5, 0], radius: 0.1, pins: [] },
      { type: 'cylinder', center: [0, 0.25, 0], axis: [0, 1, 0], radius: 0.2, height: 0.5, pins: [] },
    ]);
    expect(createColliders(s.colliders).map((c) => c.type)).toEqual(['plane', 'box', 'capsule', 'cylinder']);
  });
  it.each([
    [{ type: 'cone' }, 'colliders[0].type: must be one of "sphere", "floor", "plane", "box", "capsule", "cylinder", "mesh"'],
    [{ type: 'box', halfExtents: [0.1, 0, 0.1] }, 'colliders[0].halfExtents[1]: must be >= 0.001'],
    [{ type: 'box', size: 1 }, 'colliders[0].size: unknown key'],
    [{ type: 'capsule', radius: -1 }, 'colliders[0].radius: must be >= 0.001'],
    [{ type: 'cylinder', height: 0 }, 'colliders[0].height: must be >= 0.001'],
    [{ type: 'cylinder', axis: [0, 0, 0] }, 'colliders[0].axis: must not be zero (a direction)'],
    [{ type: 'plane', normal: [0, 0, 0] }, 'colliders[0].normal: must not be zero (a direction)'],
    [{ type: 'plane', normal: [0, 1] }, 'colliders[0].normal: must NOT have fewer than 3 items'],
  ])('%j is refused in one line naming the field', (collider, message) => {
    expect(() => validateScene({ colliders: [collider] })).toThrow(SceneError);
    expect(() => validateScene({ colliders: [collider] })).toThrow(`scene: ${message}`);
  });
});
