/**
 * Colliders that move, for every CPU solver and kernel: a cloth lying on a moving box moves with it (keyframes, and
 * a pose the library sets each frame), pins carried by a turning capsule follow it, a turning cylinder winds the
 * cloth lying on it by friction. Measured against the motion's own numbers, not the solver's measures.
 */
import { describe, expect, it } from 'vitest';
import { createColliders, PosedCollider } from '../colliders/index.js';
import { validateScene, SceneError, type Scene, type SolverType } from '../scene.js';
import { Simulation, type CpuKernel } from '../simulation.js';

const CASES: [SolverType, CpuKernel][] = [['xpbd', 'ts'], ['xpbd', 'wasm'], ['mass-spring', 'ts']];
const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };

function centroid(sim: Simulation): number[] {
  const x = sim.state.positions, c = [0, 0, 0];
  for (let i = 0; i < x.length; i += 3) { c[0] += x[i]; c[1] += x[i + 1]; c[2] += x[i + 2]; }
  return c.map((v) => (3 * v) / x.length);
}

/** Lowest point of the cloth above an axis-aligned box's top, or how deep it is inside the box (negative) [m]. */
function clearanceAboveBox(sim: Simulation, center: number[], half: number[]): number {
  const x = sim.state.positions;
  let worst = Infinity;
  for (let i = 0; i < x.length; i += 3) {
    const e = [0, 1, 2].map((k) => Math.abs(x[i + k] - center[k]) - half[k]);
    const d = e.some((v) => v > 0) ? Math.hypot(...e.map((v) => Math.max(v, 0))) : Math.max(...e);
    worst = Math.min(worst, d);
  }
  return worst;
}

/** A 0.4 m cloth at rest on a 0.6 m box table (after 1 s), the box moving as `motion` says (or not at all). */
function onTable(solver: SolverType, motion?: object): Scene {
  return validateScene({
    name: 'carried',
    cloth: { resolution: 16, width: 0.4, height: 0.4, position: [0, 0.45, 0] },
    material: cotton,
    solver: { type: solver },
    colliders: [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.3, 0.2, 0.3], ...(motion ? { motion } : {}) }, { type: 'floor', height: 0 }],
  });
}

describe.each(CASES)('%s (%s kernel): moving colliders', (solver, kernel) => {
  it('a cloth lying on a box that moves 0.4 m (keyframes, 0.2 m/s) moves with it, on top of it', () => {
    const sim = new Simulation(onTable(solver, { keyframes: [{ time: 1 }, { time: 3, translation: [0.4, 0, 0] }] }), { kernel });
    sim.advance(60);
    const before = centroid(sim);
    sim.advance(150);
    const after = centroid(sim);
    expect(after[0] - before[0]).toBeCloseTo(0.4, 2);
    expect(Math.abs(after[2] - before[2])).toBeLessThan(0.005);
    // resting on the moved box's top at the contact thickness (5 mm), not in it
    const clearance = clearanceAboveBox(sim, [0.4, 0.2, 0], [0.3, 0.2, 0.3]);
    expect(clearance).toBeGreaterThan(0);
    expect(clearance).toBeLessThan(0.01);
  });

  it('and with a pose and velocity the library sets each frame', () => {
    const sim = new Simulation(onTable(solver), { kernel });
    sim.advance(60);
    const before = centroid(sim);
    for (let f = 0; f < 120; f++) {
      // 0.2 m/s for 2 s, set as a pose each frame (the frame's start) with its velocity
      sim.setColliderPose(0, { translation: [0.2 * (f / 60), 0, 0], velocity: [0.2, 0, 0] });
      sim.advance(1);
    }
    sim.setColliderPose(0, { translation: [0.4, 0, 0] });
    sim.advance(30);
    const after = centroid(sim);
    expect(after[0] - before[0]).toBeCloseTo(0.4, 2);
    const clearance = clearanceAboveBox(sim, [0.4, 0.2, 0], [0.3, 0.2, 0.3]);
    expect(clearance).toBeGreaterThan(0);
    expect(clearance).toBeLessThan(0.01);
  });

  it('a cape pinned to a capsule that turns 90° follows it within 1 cm at the pins, and stays out of it', () => {
    const scene = validateScene({
      name: 'cape',
      cloth: { resolution: 16, width: 0.4, height: 0.5, orientation: 'hanging', position: [0, 0.95, -0.16] },
      material: cotton,
      solver: { type: solver },
      colliders: [
        { type: 'capsule', a: [0, 0.6, 0], b: [0, 1.2, 0], radius: 0.12, pins: ['top-edge'], motion: { keyframes: [{ time: 0.5 }, { time: 2, rotation: [0, 90, 0] }] } },
      ],
    });
    const sim = new Simulation(scene, { kernel });
    const rest = sim.model.restPositions;
    let worstPin = 0, deepest = Infinity;
    for (let f = 0; f < 150; f++) {
      sim.advance(1);
      // the capsule's turn about the vertical through its centre at this time
      const angle = (Math.min(Math.max((sim.state.time - 0.5) / 1.5, 0), 1) * Math.PI) / 2;
      const x = sim.state.positions;
      for (let i = 0; i <= 16; i++) {
        const px = rest[3 * i], pz = rest[3 * i + 2];
        const ex = Math.cos(angle) * px + Math.sin(angle) * pz, ez = -Math.sin(angle) * px + Math.cos(angle) * pz;
        worstPin = Math.max(worstPin, Math.hypot(x[3 * i] - ex, x[3 * i + 1] - rest[3 * i + 1], x[3 * i + 2] - ez));
      }
      for (let i = 0; i < x.length; i += 3) {
        const t = Math.min(Math.max((x[i + 1] - 0.6) / 0.6, 0), 1);
        deepest = Math.min(deepest, Math.hypot(x[i], x[i + 1] - (0.6 + 0.6 * t), x[i + 2]) - 0.12);
      }
    }
    expect(worstPin).toBeLessThan(0.01);
    expect(deepest).toBeGreaterThan(-0.005);
    // the free hem turned with it: behind the capsule's new back (−x), not where it hung (−z)
    const hem = 16 * 17 + 8, x = sim.state.positions;
    expect(x[3 * hem]).toBeLessThan(-0.12);
    expect(Math.abs(x[3 * hem + 2])).toBeLessThan(0.03);
  });

  it('a cylinder turning at 1 rad/s winds a strip lying over it along by friction', () => {
    const scene = validateScene({
      name: 'winding',
      cloth: { resolution: 24, width: 0.8, height: 0.1, position: [0, 0.62, 0] },
      material: { ...cotton, friction: 0.6, staticFriction: 0.8 },
      solver: { type: solver },
      colliders: [{ type: 'cylinder', center: [0, 0.5, 0], axis: [0, 0, 1], radius: 0.1, height: 0.4, motion: { keyframes: [{ time: 1 }, { time: 1 + 2 * Math.PI, rotation: [0, 0, -360] }] } }],
    });
    const sim = new Simulation(scene, { kernel });
    // the middle column, third row (a rectangle's particles: row-major, 25 a row)
    const mid = 12 + 25 * 2;
    const angle = () => Math.atan2(sim.state.positions[3 * mid + 1] - 0.5, sim.state.positions[3 * mid]);
    sim.advance(60);
    const a0 = angle();
    sim.advance(60);
    // the strip's middle went round with the surface: −1 rad in 1 s
    expect(angle() - a0).toBeCloseTo(-1, 1);
    expect(sim.report().finite).toBe(true);
  });
});

describe('keyframes and drives (colliders/pose.ts)', () => {
  const sphere = (motion: object) => createColliders(validateScene({ colliders: [{ type: 'sphere', center: [1, 2, 3], radius: 0.5, motion }] }).colliders)[0];
  const at = (c: PosedCollider, t: number) => {
    const R = new Float64Array(9), o = new Float64Array(3);
    c.poseAt(t, R, o);
    return { R: [...R], o: [...o] };
  };

  it('translations interpolate linearly between keys and hold outside them; loop repeats them', () => {
    const keys = [{ time: 1, translation: [0, 0, 0] }, { time: 3, translation: [2, 0, -4] }];
    const c = sphere({ keyframes: keys });
    expect(at(c, 0).o).toEqual([1, 2, 3]);
    expect(at(c, 2).o).toEqual([2, 2, 1]);
    expect(at(c, 9).o).toEqual([3, 2, -1]);
    // a loop starts at 0 and ends where it starts: out 2 s, back 2 s
    const looped = sphere({ keyframes: [{ time: 0 }, { time: 2, translation: [2, 0, -4] }, { time: 4 }], loop: true });
    for (const [t, want] of [[4.5, [1.5, 2, 2]], [5, [2, 2, 1]], [7, [2, 2, 1]], [9, [2, 2, 1]]] as const) {
      at(looped, t).o.forEach((v, k) => expect(v).toBeCloseTo(want[k], 12));
    }
  });

  it('a rotation turns the shape about the pivot (default: its centre); Euler angles interpolate, so 360° is one turn', () => {
    const c = sphere({ keyframes: [{ time: 0 }, { time: 4, rotation: [0, 360, 0] }], pivot: [1, 2, 2] });
    // a quarter turn about y through (1, 2, 2): the centre, 1 m along +z from the pivot, goes 1 m along +x
    at(c, 1).o.forEach((v, k) => expect(v).toBeCloseTo([2, 2, 2][k], 12));
    at(c, 2).o.forEach((v, k) => expect(v).toBeCloseTo([1, 2, 1][k], 12));
    at(c, 4).o.forEach((v, k) => expect(v).toBeCloseTo([1, 2, 3][k], 12));
  });

  it('over a substep the surface moves by ω × r·h for a spinning shape, nothing for a still one', () => {
    const [box] = createColliders(validateScene({ colliders: [{ type: 'box', center: [0, 0, 0], halfExtents: [1, 1, 1] }] }).colliders);
    box.moveTo(0, 0.01);
    expect(box.moving).toBe(false);
    box.setDrive(0, { angularVelocity: [0, 2, 0], velocity: [0.5, 0, 0] });
    box.moveTo(1, 1.001);
    expect(box.moving).toBe(true);
    const out = new Float64Array(3);
    // a surface point at (1, 0, 0) from the centre, which is at (0.5·1.001, 0, 0) by then
    box.surfaceMotion(0.5005 + 1, 0, 0, out);
    // v + ω × r = (0.5, 0, 0) + (0, 2, 0) × (1, 0, 0) = (0.5, 0, −2) [m/s] for 1 ms, and the turn's second-order
    // part: the point went round an arc of 2 mrad, so it also came in by 1 − cos(0.002) = 2·10⁻⁶ m
    expect(out[0]).toBeCloseTo(0.0005 + (1 - Math.cos(0.002)), 12);
    expect(out[1]).toBeCloseTo(0, 12);
    expect(out[2]).toBeCloseTo(-Math.sin(0.002), 12);
  });

  it.each([
    [{ keyframes: [{ time: 2 }, { time: 1 }] }, 'colliders[0].motion.keyframes[1].time: must not be before the previous key\'s (2 s)'],
    [{ keyframes: [{ time: 0 }], loop: true }, 'colliders[0].motion.loop: needs a last key after time 0'],
    [{ keyframes: [] }, 'colliders[0].motion.keyframes: must NOT have fewer than 1 items'],
    [{ keyframes: [{ time: 0, rotation: [0, 0] }] }, 'colliders[0].motion.keyframes[0].rotation: must NOT have fewer than 3 items'],
    [{ keys: [] }, 'colliders[0].motion.keyframes: required'],
    [{ keyframes: [{ time: 1 }, { time: 1, translation: [0, 0.1, 0] }] }, 'colliders[0].motion.keyframes[1]: at the time of the key before it, it must be that pose (a collider cannot jump)'],
    [{ keyframes: [{ time: 0 }, { time: 1, translation: [0.1, 0, 0] }], loop: true }, 'colliders[0].motion.loop: the keys must start at time 0 and end in the pose they start in'],
  ])('%j is refused in one line naming the field', (motion, message) => {
    expect(() => validateScene({ colliders: [{ type: 'sphere', motion }] })).toThrow(SceneError);
    expect(() => validateScene({ colliders: [{ type: 'sphere', motion }] })).toThrow(message);
  });

  it('pins carried by a collider: an index the cloth lacks, or one carried twice, is refused naming it', () => {
    expect(() => new Simulation(validateScene({ colliders: [{ type: 'floor', height: -1, pins: [5000] }] }))).toThrow('colliders[0].pins[0]: particle 5000 does not exist');
    const twice = validateScene({ colliders: [{ type: 'floor', height: -1, pins: ['top-left'] }, { type: 'floor', height: -2, pins: [0] }] });
    expect(() => new Simulation(twice)).toThrow('colliders[1].pins: particle 0 is carried by colliders[0] already');
  });

  it('setColliderPose checks its arguments; a drive survives scene changes that keep the collider, reset() ends it', () => {
    const sim = new Simulation(onTable('xpbd'), { kernel: 'ts' });
    expect(() => sim.setColliderPose(2, {})).toThrow(/index must be an integer 0…1/);
    expect(() => sim.setColliderPose(0, { velocity: [0, Number.NaN, 0] })).toThrow(/pose.velocity must be three finite numbers/);
    expect(() => sim.setColliderPose(0, { rotation: [0, 1] as unknown as [number, number, number] })).toThrow(/pose.rotation/);
    sim.setColliderPose(0, { translation: [0.1, 0, 0] });
    sim.set('material.damping', 0.2);
    expect(sim.params.colliders[0].o[0]).toBeCloseTo(0.1, 12);
    sim.reset();
    expect(sim.params.colliders[0].o[0]).toBe(0);
  });
});
