/**
 * The mannequin (mannequin.ts): its forward kinematics and keys, measured on the colliders the scene builds from
 * them; and the `cape` and `skirt` scenes on every CPU solver and kernel, measured against the exact primitives
 * where their keys put them (not against the solver's own distance code).
 */
import { describe, expect, it } from 'vitest';
import { createColliders, type PosedCollider } from './colliders/index.js';
import { eulerXYZ } from './mesh/generators.js';
import {
  MANNEQUIN_ANIMATIONS, MANNEQUIN_CHEST, MANNEQUIN_PARTS, MANNEQUIN_PELVIS, MANNEQUIN_POSES, animationPeriod,
  forwardKinematics, mannequinAngles, mannequinColliders, type MannequinOptions,
} from './mannequin.js';
import { validateScene, type SolverType } from './scene.js';
import { builtinMannequin, builtinScene, sceneMannequin, withMannequin } from './scenes.js';
import { Simulation, type CpuKernel } from './simulation.js';

const CASES: [SolverType, CpuKernel][] = [['xpbd', 'ts'], ['xpbd', 'wasm'], ['mass-spring', 'ts']];
const part = (name: string) => MANNEQUIN_PARTS.indexOf(name);

/** A posed collider's primitive at time t: capsule ends (equal for a sphere) and radius, from its pose alone. */
function primitiveAt(c: PosedCollider, t: number): { a: number[]; b: number[]; r: number } {
  const R = new Float64Array(9), o = new Float64Array(3);
  c.poseAt(t, R, o);
  const at = (y: number) => [0, 1, 2].map((i) => R[3 * i + 1] * y + o[i]);
  if (c.type === 'sphere') return { a: at(0), b: at(0), r: c.shapeParams[0] };
  return { a: at(-c.shapeParams[0]), b: at(c.shapeParams[0]), r: c.shapeParams[1] };
}

/** Exact signed distance of p from a capsule (a sphere when a = b). */
function exactDistance(p: ArrayLike<number>, { a, b, r }: { a: number[]; b: number[]; r: number }): number {
  const ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
  const l2 = ab[0] ** 2 + ab[1] ** 2 + ab[2] ** 2;
  const t = l2 > 0 ? Math.min(Math.max((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2, 0), 1) : 0;
  return Math.hypot(ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]) - r;
}

/** Angle between two rotations [degrees]. */
function angleBetween(A: readonly number[], B: readonly number[]): number {
  let tr = 0;
  for (let i = 0; i < 3; i++) for (let k = 0; k < 3; k++) tr += A[3 * k + i] * B[3 * k + i];
  return (Math.acos(Math.max(-1, Math.min(1, (tr - 1) / 2))) * 180) / Math.PI;
}

describe('the mannequin (forward kinematics and keys)', () => {
  it('stands 1.75 m tall on the floor (scaled, moved, turned as asked), arms away from the body', () => {
    const top = (o: MannequinOptions) => {
      const cs = createColliders(mannequinColliders(o));
      const head = primitiveAt(cs[part('head')], 0);
      return { head: head.a[1] + head.r, cs };
    };
    expect(top({}).head).toBeCloseTo(1.75, 3);
    expect(top({ scale: 0.9 }).head).toBeCloseTo(0.9 * 1.75, 3);
    const { cs } = top({ position: [1, 0, 2], heading: 90 });
    // facing +x: the left foot's toe end is ahead along +x, the figure 1 m along x and 2 m along z
    const foot = primitiveAt(cs[part('foot L')], 0);
    expect(foot.b[0] - foot.a[0]).toBeCloseTo(0.16, 3);
    expect(foot.a[2]).toBeCloseTo(2 - 0.09, 3);
    // standing: the hands clear the pelvis and thighs by more than 3 cm
    const stand = createColliders(mannequinColliders({}));
    const hand = primitiveAt(stand[part('forearm L')], 0);
    for (const other of ['pelvis', 'thigh L']) {
      expect(exactDistance(hand.b, primitiveAt(stand[part(other)], 0)) - hand.r).toBeGreaterThan(0.03);
    }
  });

  it.each(MANNEQUIN_POSES.flatMap((p) => MANNEQUIN_ANIMATIONS.map((a) => [p, a] as const)))(
    '%s, %s: limbs keep their lengths and stay joined, feet on or above the floor, no key jumps',
    (pose, animation) => {
      const specs = mannequinColliders({ pose, animation, heading: 30 });
      const cs = createColliders(validateScene({ colliders: specs }).colliders);
      const period = animationPeriod(animation) || 1;
      const joined: [string, string][] = [['upper arm L', 'forearm L'], ['upper arm R', 'forearm R'], ['thigh L', 'shin L'], ['thigh R', 'shin R']];
      const lengths0 = cs.map((c) => { const p = primitiveAt(c, 0); return Math.hypot(p.b[0] - p.a[0], p.b[1] - p.a[1], p.b[2] - p.a[2]); });
      let worstGap = 0, worstLength = 0, lowest = Infinity;
      // 2 cycles, between keys as well as on them
      for (let t = 0; t <= 2 * period; t += period / 97) {
        const ps = cs.map((c) => primitiveAt(c, t));
        ps.forEach((p, k) => {
          worstLength = Math.max(worstLength, Math.abs(Math.hypot(p.b[0] - p.a[0], p.b[1] - p.a[1], p.b[2] - p.a[2]) - lengths0[k]));
          lowest = Math.min(lowest, p.a[1] - p.r, p.b[1] - p.r);
        });
        for (const [upper, lower] of joined) {
          const u = ps[part(upper)], l = ps[part(lower)];
          worstGap = Math.max(worstGap, Math.hypot(u.b[0] - l.a[0], u.b[1] - l.a[1], u.b[2] - l.a[2]));
        }
      }
      expect(worstLength).toBeLessThan(1e-6);
      // joints apart by at most a few mm between keys (the keys interpolate each part on its own)
      expect(worstGap).toBeLessThan(0.004);
      expect(lowest).toBeGreaterThan(-1e-4);
      // the FK's own bones: the elbow stays 0.28 m from the shoulder, the knee 0.42 m from the hip
      for (let t = 0; t < period; t += period / 13) {
        const f = forwardKinematics(mannequinAngles(pose, animation, t));
        expect(Math.hypot(...[0, 1, 2].map((i) => f.elbowL.o[i] - f.shoulderL.o[i]))).toBeCloseTo(0.28, 9);
        expect(Math.hypot(...[0, 1, 2].map((i) => f.kneeR.o[i] - f.hipR.o[i]))).toBeCloseTo(0.42, 9);
      }
      // consecutive keys: each rotation within 30° of the last (no ±180° Euler jumps), angles continuous too
      for (const s of specs) {
        const keys = s.motion?.keyframes ?? [];
        expect(keys.length > 0).toBe(animation !== 'none');
        for (let k = 1; k < keys.length; k++) {
          expect(angleBetween(eulerXYZ(keys[k - 1].rotation), eulerXYZ(keys[k].rotation))).toBeLessThan(30);
          for (let i = 0; i < 3; i++) expect(Math.abs(keys[k].rotation[i] - keys[k - 1].rotation[i])).toBeLessThan(30);
        }
      }
    },
  );

  it('walks: the feet swing apart and back; turns: the chest faces up to 70° either way and back', () => {
    const walk = createColliders(mannequinColliders({ animation: 'walk' }));
    const footZ = (t: number) => primitiveAt(walk[part('foot L')], t).a[2] - primitiveAt(walk[part('foot R')], t).a[2];
    const zs = Array.from({ length: 24 }, (_, k) => footZ((k * 1.2) / 24));
    expect(Math.max(...zs)).toBeGreaterThan(0.25);
    expect(Math.min(...zs)).toBeLessThan(-0.25);
    expect(footZ(1.2)).toBeCloseTo(footZ(0), 4);
    const turn = createColliders(mannequinColliders({ animation: 'turn' }));
    const chestAngle = (t: number) => {
      const c = primitiveAt(turn[MANNEQUIN_CHEST], t);
      // the chest's axis runs from the right shoulder to the left: along +x when facing +z
      return (Math.atan2(-(c.b[2] - c.a[2]), c.b[0] - c.a[0]) * 180) / Math.PI;
    };
    expect(chestAngle(1)).toBeCloseTo(70, 1);
    expect(chestAngle(3)).toBeCloseTo(-70, 1);
    expect(chestAngle(4)).toBeCloseTo(0, 1);
  });

  it('the skirt is carried by its whole top ring at the waist, the cape by its top edge at the shoulders', () => {
    for (const [name, carrier, y] of [['skirt', MANNEQUIN_PELVIS, 1.03], ['cape', MANNEQUIN_CHEST, 1.42]] as const) {
      const sim = new Simulation(builtinScene(name), { kernel: 'ts' });
      const x = sim.model.restPositions, { particles, collider } = sim.params.carried;
      let top = -Infinity;
      for (let i = 1; i < x.length; i += 3) top = Math.max(top, x[i]);
      const ring = Array.from({ length: x.length / 3 }, (_, i) => i).filter((i) => x[3 * i + 1] > top - 1e-6);
      expect(top).toBeCloseTo(y, 5);
      expect([...particles]).toEqual(ring);
      expect(new Set(collider)).toEqual(new Set([carrier]));
    }
  });

  it('withMannequin re-poses a scene\'s mannequin and keeps its cloth, pins and other colliders', () => {
    const scene = builtinScene('skirt');
    const m = builtinMannequin('skirt')!;
    expect(builtinMannequin('tablecloth')).toBeUndefined();
    const still = withMannequin(scene, m, { animation: 'none' });
    expect(still.cloth).toEqual(scene.cloth);
    expect(still.colliders.length).toBe(scene.colliders.length);
    expect(still.colliders[MANNEQUIN_PELVIS].pins).toEqual(scene.colliders[MANNEQUIN_PELVIS].pins);
    expect(still.colliders.every((c) => c.motion === undefined)).toBe(true);
    expect(still.colliders.at(-1)).toEqual(scene.colliders.at(-1));
    // read back from the colliders (as the app does for a link): the pose and animation they were made with
    expect(sceneMannequin(scene, 'skirt')?.options).toMatchObject({ pose: 'stand', animation: 'walk' });
    expect(sceneMannequin(withMannequin(scene, m, { pose: 't-pose', animation: 'turn' }), 'skirt')?.options).toMatchObject({ pose: 't-pose', animation: 'turn' });
    expect(sceneMannequin({ ...scene, colliders: scene.colliders.slice(1) }, 'skirt')).toBeUndefined();
    expect(sceneMannequin(scene, 'cape')).toBeUndefined();
  });

  it('an option a mannequin does not take is named, never a figure of NaN or a silent default', () => {
    expect(() => mannequinColliders({ pose: 'x' as MannequinOptions['pose'] })).toThrow('mannequinColliders: pose must be one of stand, t-pose, got "x"');
    expect(() => mannequinColliders({ animation: 'dance' as MannequinOptions['animation'] })).toThrow('mannequinColliders: animation must be one of none, walk, turn, got "dance"');
    // a string from outside is printed safely: no escape reaches a terminal
    expect(() => mannequinColliders({ pose: '\u001b[2J' as MannequinOptions['pose'] })).toThrow('mannequinColliders: pose must be one of stand, t-pose, got "\ufffd[2J"');
    expect(() => mannequinColliders({ scale: NaN })).toThrow('mannequinColliders: scale must be a number in 0.1…10, got NaN');
    expect(() => mannequinColliders({ scale: -1 })).toThrow(RangeError);
    expect(() => mannequinColliders({ heading: NaN })).toThrow('mannequinColliders: heading must be a finite number of degrees, got NaN');
    expect(() => mannequinColliders({ position: [0, NaN, 0] })).toThrow(/position must be \[x, y, z\]/);
    expect(() => mannequinColliders(null as unknown as MannequinOptions)).toThrow('mannequinColliders: options must be an object, got null');
    expect(mannequinColliders({ scale: 2, heading: 90 })).toHaveLength(MANNEQUIN_PARTS.length);
    // a heading is a direction: any finite number of degrees is one, modulo 360 (1e308 overflowed to NaN centres)
    expect(mannequinColliders({ heading: 1e308 })).toEqual(mannequinColliders({ heading: 1e308 % 360 }));
    expect(JSON.stringify(mannequinColliders({ heading: -1e308 }))).not.toMatch(/null|NaN/);
  });

  // the app's Mannequin folder offers every pose and animation: each must start (the cape once started inside a
  // walking shin: refused, 'cuts through the cloth where it starts')
  it.each(['cape', 'skirt'])('%s: every pose and animation the panel offers starts, and steps a second outside the figure', (name) => {
    for (const pose of MANNEQUIN_POSES) {
      for (const animation of MANNEQUIN_ANIMATIONS) {
        const sim = new Simulation(withMannequin(builtinScene(name), builtinMannequin(name)!, { pose, animation }), { kernel: 'wasm', threads: 1 });
        sim.advance(60);
        const r = sim.report();
        expect([pose, animation, r.finite, r.maxPenetration <= 1e-3]).toEqual([pose, animation, true, true]);
        sim.dispose();
      }
    }
  });
});

/** The mannequin scenes for 3 s: finite, outside every part at every sampled frame, the carried pins in place. */
describe.each(CASES)('%s (%s kernel): the mannequin scenes', (solver, kernel) => {
  it.each(['cape', 'skirt'])('%s: 3 s, finite, no particle deeper than the thickness in any part, pins carried within 1 cm', (name) => {
    const scene = builtinScene(name);
    scene.solver.type = solver;
    const sim = new Simulation(scene, { kernel });
    const parts = sim.params.colliders.slice(0, MANNEQUIN_PARTS.length);
    const th = scene.cloth.thickness;
    const { particles, collider } = sim.params.carried;
    expect(particles.length).toBeGreaterThan(10);
    // each carried particle's place in its collider's frame at time 0 (from the rest shape)
    const R = new Float64Array(9), o = new Float64Array(3), rest = sim.model.restPositions;
    const local = Array.from(particles, (p, k) => {
      parts[collider[k]].poseAt(0, R, o);
      const d = [0, 1, 2].map((i) => rest[3 * p + i] - o[i]);
      return [0, 1, 2].map((j) => R[j] * d[0] + R[3 + j] * d[1] + R[6 + j] * d[2]);
    });
    let deepest = Infinity, worstPin = 0;
    for (let f = 1; f <= 180; f++) {
      sim.advance(1);
      if (f % 10 !== 0) continue;
      const x = sim.state.positions, t = sim.state.time;
      const prims = parts.map((c) => primitiveAt(c, t));
      for (let i = 0; i < x.length; i += 3) for (const p of prims) deepest = Math.min(deepest, exactDistance(x.subarray(i, i + 3), p));
      particles.forEach((p, k) => {
        parts[collider[k]].poseAt(t, R, o);
        const l = local[k];
        const want = [0, 1, 2].map((i) => R[3 * i] * l[0] + R[3 * i + 1] * l[1] + R[3 * i + 2] * l[2] + o[i]);
        worstPin = Math.max(worstPin, Math.hypot(x[3 * p] - want[0], x[3 * p + 1] - want[1], x[3 * p + 2] - want[2]));
      });
    }
    expect(sim.report().finite).toBe(true);
    expect(deepest).toBeGreaterThan(-th);
    expect(worstPin).toBeLessThan(0.01);
    // at the end, the triangles too (15 points of each)
    const x = sim.state.positions, tri = sim.model.triangles, prims = parts.map((c) => primitiveAt(c, sim.state.time));
    let inside = Infinity;
    for (let k = 0; k < tri.length; k += 3) {
      const a = 3 * tri[k], b = 3 * tri[k + 1], c = 3 * tri[k + 2];
      for (let i = 0; i <= 4; i++) for (let j = 0; i + j <= 4; j++) {
        const u = i / 4, v = j / 4, w = 1 - u - v;
        const q = [0, 1, 2].map((d) => w * x[a + d] + u * x[b + d] + v * x[c + d]);
        for (const p of prims) inside = Math.min(inside, exactDistance(q, p));
      }
    }
    expect(Math.max(0, -inside)).toBeLessThanOrEqual(th);
  });
});
