/**
 * Self-contact on the GPU (solver.selfContact, the selfContact phase: docs/gpu.md, "Self-contact"), on whatever
 * adapter `createNodeDevice` finds: SwiftShader on the build machines, so small cloths and few frames. Each scene is
 * run with self-contact and without it, so that every test shows what the phase changes. No adapter: as in
 * gpu.test.ts, the tests fail in CI and are skipped (saying why) elsewhere.
 */
import { afterAll, describe, expect, test } from 'vitest';
import type {} from 'webgpu';
import { Simulation, builtinScene, countIntersections, grab, validateScene, type Scene } from '../core/index.js';
import { selfContactDistance } from '../core/self-contact.js';
import { SELF_EDGE_SHARE } from '../core/layout.generated.js';
import { crossedStrips, stripGap } from '../core/test-strips.js';
import { GpuBackend } from './backend.js';
import type { GpuSolverOptions } from './solver.js';
import { sceneRefusal } from './encoder.js';
import { BUFFERS } from './layout.js';
import { testDevice } from './test-device.js';

const gpu = await testDevice('src/gpu/self-contact.test.ts');

const sims: Simulation[] = [];
afterAll(() => {
  for (const s of sims) s.dispose();
});

/**
 * A Simulation of `scene` on the GPU (its state read back by `sync`), on the test's device or `device`. Its springs
 * are swept alone (solver.stretch 'gauss-seidel', the default when these were measured): the coarse correction has
 * its own tests (coarse-stretch.test.ts), and its ten more dispatches a substep doubled these frames on SwiftShader.
 */
async function onGpu(scene: Scene, options?: GpuSolverOptions, device: GPUDevice = gpu!.device): Promise<Simulation> {
  scene.solver.stretch = 'gauss-seidel';
  expect(sceneRefusal(scene)).toBeNull();
  const sim = new Simulation(scene, { kernel: 'ts' });
  sim.useBackend(await GpuBackend.create(device, sim.model, options));
  sims.push(sim);
  return sim;
}

/** The crossing pairs of `sim` at every 10th of the next `frames` frames (read back each time); `at10` gets frame 10's positions. */
async function crossings(sim: Simulation, frames: number, at10?: Float32Array): Promise<number[]> {
  const out: number[] = [];
  for (let f = 10; f <= frames; f += 10) {
    sim.advance(10);
    await sim.sync();
    expect(sim.state.positions.every(Number.isFinite), `finite at frame ${f}`).toBe(true);
    out.push(countIntersections(sim.model.triangles, sim.state.positions));
    if (f === 10) at10?.set(sim.state.positions);
  }
  return out;
}

/**
 * The built-in fold at 16² (corner first onto the floor, landing in layers), its sheet bulged 1 cm out of its plane
 * (cloth.imperfection): exactly flat, the sheet without self-contact lands on its corner and stays standing on it (it
 * has nothing to buckle it out of its plane), crossing nothing, so the comparison needs the bulge. Measured on
 * SwiftShader: without self-contact 72–101 crossing pairs from frame 30 to 60 and 29 at frame 90 (at 32²: 1228 at
 * frame 300), with it 0 at every 10th frame up to 90.
 */
function fold(selfContact: boolean): Scene {
  const s = builtinScene('fold');
  s.cloth.resolution = 16;
  s.cloth.imperfection = 0.01;
  s.solver.selfContact = selfContact;
  // 10 substeps, as asked (selfContactSpeed 0: none added for self-contact, which would take 20): a GPU frame on
  // SwiftShader costs its dispatches, twice as many at 20; at 16² the fold crosses nowhere at 10 all the same
  s.solver.substeps = 10;
  s.solver.selfContactSpeed = 0;
  return validateScene(s);
}

/** Two cotton sheets stacked over a sphere of radius 0.5 (cloths.test.ts's, in one fabric, which the GPU takes). */
function stacked(selfContact: boolean): Scene {
  return validateScene({
    name: 'stacked',
    // (the default 20 substeps: at 10 the upper sheet crosses the lower at 4–8 pairs from frame 20)
    solver: { selfContact },
    colliders: [{ type: 'sphere', center: [0, 0, 0], radius: 0.5 }],
    cloths: [
      { name: 'under', cloth: { resolution: 10, position: [0, 0.6, 0] }, material: { fabric: 'cotton' } },
      { name: 'over', cloth: { resolution: 10, width: 0.6, height: 0.6, position: [0, 0.75, 0], rotation: [0, 30, 0] }, material: { fabric: 'cotton' } },
    ],
  });
}

/** The highest point of cloth c of `sim` now [m]. */
function top(sim: Simulation, c: number): number {
  const x = sim.state.positions, s = sim.model.clothStarts;
  let y = -Infinity;
  for (let i = s[c]; i < s[c + 1]; i++) y = Math.max(y, x[3 * i + 1]);
  return y;
}

describe.skipIf(!gpu)('self-contact on the GPU', () => {
  test('the fold at 16²: with it no two triangles cross at any 10th frame of 2/3 s, without it they do; a run repeats to the bit', async () => {
    const without = await onGpu(fold(false));
    const free = await crossings(without, 40);
    expect(free[free.length - 1]).toBeGreaterThan(20);
    const sim = await onGpu(fold(true));
    const at10 = new Float32Array(3 * sim.model.particleCount);
    expect(await crossings(sim, 40, at10)).toEqual(Array(4).fill(0));
    // the corrections are summed in integers (fixed point), which no thread order changes: a second run is the same
    const again = await onGpu(fold(true));
    again.advance(10);
    await again.sync();
    expect(again.state.positions).toEqual(at10);
  });

  test('the built-in fold at 32², as it is (the coarse correction too): its landing corner crosses itself nowhere', async () => {
    // with two Jacobi passes of the edge pairs two triangles one apart at the landing corner crossed from frame 8 on
    // (SELF_EDGE_PASSES); read back at frames 8–10, where that was first seen
    const s = builtinScene('fold');
    s.cloth.resolution = 32;
    const sim = new Simulation(validateScene(s), { kernel: 'ts' });
    expect(sim.params.stretch).toBe('two-level');
    sim.useBackend(await GpuBackend.create(gpu!.device, sim.model));
    sims.push(sim);
    sim.advance(7);
    for (let f = 8; f <= 10; f++) {
      sim.advance(1);
      await sim.sync();
      expect(countIntersections(sim.model.triangles, sim.state.positions), `frame ${f}`).toBe(0);
    }
  });

  test('two sheets dropped on a sphere stay layered, the upper one a contact distance above the lower', async () => {
    const sim = await onGpu(stacked(true));
    expect(await crossings(sim, 40)).toEqual(Array(4).fill(0));
    // the candidates' list held every pair of every pass: nothing to report
    const solver = (sim.backend as GpuBackend).solver;
    expect(solver.selfPairsMost).toBeGreaterThan(0);
    expect(solver.selfPairsMost).toBeLessThanOrEqual(solver.selfPairCapacity);
    expect(sim.notes).toEqual([]);
    const h = selfContactDistance(sim.model, sim.params);
    expect(h).toBe(0.005);
    // the lower sheet on the sphere's top (within three thicknesses: a coarse sheet tents, 0.509 m without the upper
    // one), the upper one on it: measured 0.510 and 5.0 mm above (the CPU: 0.508 and 5.1 mm at frame 90, at 12²)
    const under = top(sim, 0), over = top(sim, 1);
    expect(under).toBeGreaterThan(0.5);
    expect(under).toBeLessThan(0.5 + 3 * 0.005);
    expect(over - under).toBeGreaterThan(0.8 * h);
    expect(over - under).toBeLessThan(2 * h);
    // (without it the upper sheet falls through: measured 223 crossing pairs at frame 60, its top 2.5 mm under the
    // other's; the fold above and cloths.test.ts on the CPU show what is lost without it)
  });

  test('a pass that finds more candidate pairs than its list holds is reported in the notes, with how many, and the list grows to hold them', async () => {
    // a list with room for 1 pair in 20 triangles or edges (the default 8 per one): the landing overflows it
    const sim = await onGpu(stacked(true), { selfPairsPerPrimitive: 0.05 });
    const solver = (sim.backend as GpuBackend).solver;
    const first = Math.floor(0.05 * Math.max(sim.model.triangles.length / 3, sim.model.edges.length / 2));
    sim.advance(15);
    await sim.sync();
    const over = solver.selfPairsOverflow!;
    expect(over.held).toBe(first);
    expect(over.found).toBe(solver.selfPairsMost);
    expect(over.found).toBeGreaterThan(first);
    // the readback that saw it made the list half as large again as what was found
    expect(solver.selfPairCapacity).toBe(Math.ceil(1.5 * over.found));
    expect(sim.notes).toEqual([
      `GPU self-contact: a pass found ${over.found.toLocaleString('en')} candidate pairs, more than its list held (${first}); ` +
      `the ${(over.found - first).toLocaleString('en')} past it went unresolved in that substep, so the cloth may have passed ` +
      `through itself there — the list has grown to ${solver.selfPairCapacity.toLocaleString('en')} since`,
    ]);
    // the frames after it hold every pair their passes find (the sheets still landing on each other): no pass since
    // left any unresolved; and they ran, with the new list bound (a destroyed buffer in a submit runs nothing)
    const before = sim.state.positions.slice();
    sim.advance(5);
    await sim.sync();
    expect(solver.selfPairsOverflow).toEqual(over);
    expect(sim.state.positions.some((v, i) => Math.abs(v - before[i]) > 1e-4)).toBe(true);
    expect(sim.state.positions.every(Number.isFinite)).toBe(true);
    // a reset starts the count again: nothing to report, the list as large as it has grown
    const room = solver.selfPairCapacity;
    sim.reset();
    expect(sim.notes).toEqual([]);
    expect(solver.selfPairCapacity).toBe(room);
  });

  test('a list that cannot grow as far as it would, for what the device binds in one buffer, says so and holds that many', async () => {
    // the test's device, whose limits say what the test sets once self-contact's buffers are made
    const real = gpu!.device;
    const limits: Record<string, unknown> = {};
    for (const k in real.limits) limits[k] = real.limits[k as keyof GPUSupportedLimits];
    const device = new Proxy(real, {
      get: (target, key) => {
        if (key === 'limits') return limits;
        const v = Reflect.get(target, key);
        return typeof v === 'function' ? v.bind(target) : v;
      },
    });
    const sim = await onGpu(stacked(true), { selfPairsPerPrimitive: 0.05 }, device);
    const solver = (sim.backend as GpuBackend).solver;
    // the first frame makes the buffers and overflows the list (1 pair in 20 primitives: the sheets' own
    // neighbours fill it); before its readback grows the list, the device is made to bind 10 pairs more than it holds
    sim.advance(1);
    const first = solver.selfPairCapacity;
    const most = first + 10;
    limits.maxStorageBufferBindingSize = BUFFERS.selfPairs.bytes * (1 + 2 * most);
    await sim.sync();
    const over = solver.selfPairsOverflow!;
    expect(over.held).toBe(first);
    expect(over.found).toBeGreaterThan(most);
    expect(solver.selfPairCapacity).toBe(most);
    expect(sim.notes).toEqual([
      `GPU self-contact: a pass found ${over.found.toLocaleString('en')} candidate pairs, more than its list held (${first}); ` +
      `the ${(over.found - first).toLocaleString('en')} past it went unresolved in that substep, so the cloth may have passed ` +
      `through itself there — the list holds ${most}, the most this device binds in one buffer`,
    ]);
    // it stays that size, and the frames after it run with it
    sim.advance(5);
    await sim.sync();
    expect(solver.selfPairCapacity).toBe(most);
    expect(sim.state.positions.every(Number.isFinite)).toBe(true);
    expect(sim.notes[0]).toMatch(/the list holds \d+, the most this device binds in one buffer$/);
  });

  // scripts/grab-drag.mjs at 24² (docs/physics.md, "A fast grab"): the wind scene's flag with a sphere 2 cm behind
  // it, its lower free corner grabbed after 10 frames and dragged at solver.selfContactSpeed (6 m/s, 0.1 m a frame)
  // toward a point 0.96 m away, on a straight line through the sphere. Each frame's end short of the target was kept
  // out of the colliders only on the CPU: the GPU carried the corner 8 cm deep into the sphere (frames 13–18), contact
  // pushed its neighbours out through the layer folded over them, and side memory kept them there: 2 crossing pairs
  // at frame 14, 10–15 from frame 16 on. With that kept out but one Jacobi pass of the edge pairs a substep: 1 pair at
  // frame 20 and 4 at 21 (SELF_EDGE_PASSES). 16² crosses nowhere either way
  test('a grab dragged fast past the sphere behind the flag goes round it, and the fold it pulls up crosses nothing', async () => {
    const doc = builtinScene('wind');
    doc.cloth.resolution = 24;
    doc.colliders = [{ type: 'sphere', center: [0.2, 1.6, 0.62], radius: 0.6 }, { type: 'floor', height: 0 }];
    const sim = await onGpu(validateScene(doc));
    const p = 25 * 25 - 1, x = sim.state.positions;
    sim.advance(10);
    await sim.sync();
    grab(sim.state, p, [0.2, 2.2, 0.3]);
    const seen: number[] = [], outside: number[] = [];
    for (let f = 11; f <= 22; f++) {
      sim.advance(1);
      await sim.sync();
      seen.push(countIntersections(sim.model.triangles, x));
      outside.push(Math.hypot(x[3 * p] - 0.2, x[3 * p + 1] - 1.6, x[3 * p + 2] - 0.62) - 0.6);
    }
    expect(seen).toEqual(Array(12).fill(0));
    // at every frame's end the corner is outside the sphere by the thickness (5 mm; f32 rounding aside)
    expect(Math.min(...outside)).toBeGreaterThan(0.005 - 1e-5);
  });

  // two thin strips crossing like an X, the upper one falling on the pinned lower one (self-contact.test.ts in core):
  // every vertex stays far outside the other strip's triangles, so only the edge pass can hold it
  test('edges that cross with no vertex near the other strip are kept apart (edge–edge contact), half the contact distance apart at rest', async () => {
    // 10 substeps as asked (the strips fall 3 cm: under 1 m/s)
    const scene = (selfContact: boolean) => crossedStrips({ selfContact, substeps: 10, selfContactSpeed: 0 });
    const heights = async (sim: Simulation) => {
      // read back every 4th frame (each readback waits for the GPU)
      for (let f = 4; f <= 40; f += 4) {
        sim.advance(4);
        await sim.sync();
        if (sim.params.selfContact) expect(countIntersections(sim.model.triangles, sim.state.positions), `frame ${f}`).toBe(0);
      }
      const x = sim.state.positions;
      let lowest = Infinity, highest = -Infinity;
      for (let i = 4; i < 8; i++) { lowest = Math.min(lowest, x[3 * i + 1]); highest = Math.max(highest, x[3 * i + 1]); }
      return { lowest, highest, gap: stripGap(sim.model.edges, x), h: selfContactDistance(sim.model, sim.params) };
    };
    // the upper strip lies across the lower one, below where it started, the edges' contact distance at rest apart
    // (SELF_EDGE_SHARE of h, and a substep's motion: the CPU's rule), not h
    const held = await heights(await onGpu(scene(true)));
    expect(held.lowest).toBeGreaterThan(0.25);
    expect(held.highest).toBeLessThan(0.33);
    expect(held.h).toBe(0.005);
    expect(held.gap).toBeGreaterThanOrEqual(SELF_EDGE_SHARE * held.h - 1e-5);
    expect(held.gap).toBeLessThan(SELF_EDGE_SHARE * held.h + 2e-4);
    // without, it falls through to the floor
    const fell = await heights(await onGpu(scene(false)));
    expect(fell.highest).toBeLessThan(0.05);
  });
});
