/**
 * The GPU solver with every analytic collider, moving colliders and carried pins, against the TypeScript reference
 * stepped alongside (parity) and against the motion's own numbers (as core/solvers/moving-colliders.test.ts holds
 * the CPU solvers to them). Same adapter rule as gpu.test.ts; small cloths, at most 1.75 s simulated (SwiftShader).
 *
 * Tolerances (docs/gpu.md, "Parity"): a few times the larger of the GPU–CPU difference seen on SwiftShader and the
 * CPU's own spread when its start is nudged by 1e-7 (relative), over the same frames.
 */
import { afterAll, describe, expect, it } from 'vitest';
import type {} from 'webgpu';
import {
  Simulation, centroid, maxPenetration, validateScene, type ClothState, type Scene,
} from '../core/index.js';
import { GpuBackend } from './backend.js';
import { centroidDistance, maxDistance, testDevice } from './test-device.js';

const gpu = await testDevice('src/gpu/moving-colliders.test.ts');
const sims: Simulation[] = [];
afterAll(() => {
  for (const s of sims) s.dispose();
});

const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };

/**
 * The scene on the CPU (TypeScript reference) and on the GPU, both from its start, their springs swept alone
 * (solver.stretch 'gauss-seidel'): the coarse correction has its own tests (coarse-stretch.test.ts), and its ten more
 * dispatches a substep added half to these files' time on SwiftShader.
 */
async function pair(scene: Scene): Promise<{ cpu: Simulation; gpu: Simulation }> {
  scene.solver.stretch = 'gauss-seidel';
  const cpu = new Simulation(scene, { kernel: 'ts' });
  const g = new Simulation(scene, { kernel: 'ts' });
  g.useBackend(await GpuBackend.create(gpu!.device, g.model));
  sims.push(cpu, g);
  return { cpu, gpu: g };
}

/** A 0.6 m cloth of 12 faces a side dropped from 20 cm or less onto `colliders`. */
function drop(y: number, colliders: object[]): Scene {
  return validateScene({ name: 'drop', cloth: { resolution: 12, width: 0.6, height: 0.6, position: [0, y, 0] }, material: cotton, colliders });
}

const floor = { type: 'floor', height: 0 };

// Dropped for 0.75 s (45 frames: it lands at about 0.15 s), the cloth checked every 15: GPU–CPU seen ≤ 2.5e-3 m per particle (capsule; box
// 1.5e-3, cylinder 1.0e-3, its side 9.5e-5, plane 2.8e-5) and ≤ 3.9e-5 m centroid, the CPU's own spread ≤ 1.2e-2 m
// (capsule) and ≤ 2.1e-4 m centroid (scripts/gpu-collider-parity.mjs) → 2 cm and 1 mm. Penetration into the exact shape (maxPenetration: particles,
// and triangles by the reference's own triangle contact) seen 0 → ≤ 1 mm, a fifth of the contact thickness.
const DROPS: [string, Scene][] = [
  ['a tilted plane', drop(0.5, [{ type: 'plane', point: [0, 0.3, 0], normal: [0.3, 1, 0.1] }])],
  ['a box turned 30°', drop(0.55, [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.15, 0.2, 0.15], rotation: [0, 30, 0] }, floor])],
  ['a slanted capsule', drop(0.5, [{ type: 'capsule', a: [-0.2, 0.3, 0.05], b: [0.2, 0.3, -0.05], radius: 0.08 }, floor])],
  ['an upright cylinder', drop(0.5, [{ type: 'cylinder', center: [0, 0.2, 0], axis: [0, 1, 0], radius: 0.15, height: 0.4 }, floor])],
  ['a cylinder on its side', drop(0.5, [{ type: 'cylinder', center: [0, 0.3, 0], axis: [1, 0, 0.2], radius: 0.1, height: 0.5 }, floor])],
];

describe.skipIf(!gpu)('the GPU with every analytic collider, as the TypeScript reference', () => {
  it.each(DROPS)('a cloth dropped on %s: 2 cm, centroid 1 mm, penetration ≤ 1 mm', async (_name, scene) => {
    const { cpu, gpu: g } = await pair(scene);
    let worst = 0;
    for (let k = 0; k < 3; k++) {
      cpu.advance(15);
      g.advance(15);
      await g.sync();
      expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(2e-2);
      expect(centroidDistance(g.state, cpu.state)).toBeLessThan(1e-3);
      worst = Math.max(worst, maxPenetration(g.model, g.state, g.params));
    }
    expect(worst).toBeLessThanOrEqual(1e-3);
    // it lies on the shape: below where it started, above the floor
    expect(centroid(g.state)[1]).toBeLessThan(scene.cloth.position[1] - 0.1);
    expect(centroid(g.state)[1]).toBeGreaterThan(0.1);
  });
});

/** A 0.4 m cloth resting on a 0.6 m box table, the box moving as `motion` says (or not at all). */
function onTable(motion?: object): Scene {
  return validateScene({
    name: 'carried',
    cloth: { resolution: 12, width: 0.4, height: 0.4, position: [0, 0.45, 0] },
    material: cotton,
    colliders: [{ type: 'box', center: [0, 0.2, 0], halfExtents: [0.3, 0.2, 0.3], ...(motion ? { motion } : {}) }, floor],
  });
}

/** Lowest point of the cloth above an axis-aligned box's top, or how deep it is inside the box (negative) [m]. */
function clearanceAboveBox(state: ClothState, center: number[], half: number[]): number {
  const x = state.positions;
  let worst = Infinity;
  for (let i = 0; i < x.length; i += 3) {
    const e = [0, 1, 2].map((k) => Math.abs(x[i + k] - center[k]) - half[k]);
    const d = e.some((v) => v > 0) ? Math.hypot(...e.map((v) => Math.max(v, 0))) : Math.max(...e);
    worst = Math.min(worst, d);
  }
  return worst;
}

describe.skipIf(!gpu)('moving colliders and carried pins on the GPU', () => {
  // GPU–CPU seen ≤ 2.0e-6 m (the cloth rides the box: no chaos; the CPU's own spread 1.8e-6 m) → 1e-4 m.
  it('a cloth lying on a box that moves 0.2 m (keyframes, 0.2 m/s) moves with it, on top of it, as on the CPU', async () => {
    const { cpu, gpu: g } = await pair(onTable({ keyframes: [{ time: 0.5 }, { time: 1.5, translation: [0.2, 0, 0] }] }));
    cpu.advance(30);
    g.advance(30);
    await g.sync();
    const before = centroid(g.state);
    cpu.advance(75);
    g.advance(75);
    await g.sync();
    const after = centroid(g.state);
    expect(after[0] - before[0]).toBeCloseTo(0.2, 2);
    expect(Math.abs(after[2] - before[2])).toBeLessThan(0.005);
    // resting on the moved box's top at the contact thickness (5 mm), not in it
    const clearance = clearanceAboveBox(g.state, [0.2, 0.2, 0], [0.3, 0.2, 0.3]);
    expect(clearance).toBeGreaterThan(0);
    expect(clearance).toBeLessThan(0.01);
    expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(1e-4);
  });

  it('and with a pose and velocity the library sets each frame (Simulation.setColliderPose on the GPU backend)', async () => {
    const { cpu, gpu: g } = await pair(onTable());
    for (const sim of [cpu, g]) {
      sim.advance(30);
      for (let f = 0; f < 60; f++) {
        // 0.2 m/s for 1 s, set as a pose each frame (the frame's start) with its velocity
        sim.setColliderPose(0, { translation: [0.2 * (f / 60), 0, 0], velocity: [0.2, 0, 0] });
        sim.advance(1);
      }
      sim.setColliderPose(0, { translation: [0.2, 0, 0] });
      sim.advance(15);
    }
    await g.sync();
    expect(centroid(g.state)[0]).toBeCloseTo(0.2, 2);
    const clearance = clearanceAboveBox(g.state, [0.2, 0.2, 0], [0.3, 0.2, 0.3]);
    expect(clearance).toBeGreaterThan(0);
    expect(clearance).toBeLessThan(0.01);
    expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(1e-4);
  });

  // Pins: where the turn puts them, to f32 rounding (seen ≤ 2.1e-8 m) → 1e-5 m. The cape: GPU–CPU seen ≤ 6.4e-3 m,
  // centroid ≤ 2.9e-4 m, the CPU's own spread ≤ 4.9e-3 m, ≤ 1.5e-4 m → 2 cm, 2 mm. Nearest the capsule: seen 5.4 mm
  // from its surface (the contact thickness is 5 mm) → outside it.
  it('a cape pinned to a capsule that turns 90° in 0.75 s: its pins exactly where the turn puts them, out of it, as on the CPU', async () => {
    const scene = validateScene({
      name: 'cape',
      cloth: { resolution: 12, width: 0.4, height: 0.5, orientation: 'hanging', position: [0, 0.95, -0.16] },
      material: cotton,
      colliders: [
        { type: 'capsule', a: [0, 0.6, 0], b: [0, 1.2, 0], radius: 0.12, pins: ['top-edge'], motion: { keyframes: [{ time: 0.25 }, { time: 1, rotation: [0, 90, 0] }] } },
      ],
    });
    const { cpu, gpu: g } = await pair(scene);
    const rest = g.model.restPositions;
    let worstPin = 0, deepest = Infinity;
    for (let f = 0; f < 18; f++) {
      cpu.advance(5);
      g.advance(5);
      await g.sync();
      // the capsule's turn about the vertical through its centre at this time
      const angle = (Math.min(Math.max((g.state.time - 0.25) / 0.75, 0), 1) * Math.PI) / 2;
      const x = g.state.positions;
      for (let i = 0; i <= 12; i++) {
        const px = rest[3 * i], pz = rest[3 * i + 2];
        const ex = Math.cos(angle) * px + Math.sin(angle) * pz, ez = -Math.sin(angle) * px + Math.cos(angle) * pz;
        worstPin = Math.max(worstPin, Math.hypot(x[3 * i] - ex, x[3 * i + 1] - rest[3 * i + 1], x[3 * i + 2] - ez));
      }
      for (let i = 0; i < x.length; i += 3) {
        const t = Math.min(Math.max((x[i + 1] - 0.6) / 0.6, 0), 1);
        deepest = Math.min(deepest, Math.hypot(x[i], x[i + 1] - (0.6 + 0.6 * t), x[i + 2]) - 0.12);
      }
      expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(2e-2);
      expect(centroidDistance(g.state, cpu.state)).toBeLessThan(2e-3);
    }
    expect(g.state.time).toBeCloseTo(1.5, 9);
    expect(worstPin).toBeLessThan(1e-5);
    expect(deepest).toBeGreaterThan(0);
    // the free hem turned with it: behind the capsule's new back (−x), not where it hung (−z)
    const hem = 12 * 13 + 6, x = g.state.positions;
    expect(x[3 * hem]).toBeLessThan(-0.12);
    expect(Math.abs(x[3 * hem + 2])).toBeLessThan(0.03);
  });
});
