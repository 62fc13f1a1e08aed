/**
 * The WebGPU solver against the CPU solver (parity) and against physics, on whatever adapter `createNodeDevice`
 * finds: SwiftShader on the build machines (slow: small cloths, short runs).
 *
 * No adapter: in CI (process.env.CI set) the file fails with the reason; locally it is skipped with the reason
 * printed. It never passes without running.
 */
import { afterAll, describe, expect, test, vi } from 'vitest';
import type {} from 'webgpu';
import {
  FRAME_DT, SCENE_NAMES, Simulation, applyPins, builtinScene, centroid, copyState, createState, energy, grab, isFinite3,
  maxPenetration, measureTest, modelFor, release, resolveParams, step, validateScene,
  type Scene,
} from '../core/index.js';
import { centroidDistance, gpuPair, maxDistance, testDevice, type Pair } from './test-device.js';
import { benchGpu } from './bench.js';
import { GpuClothSolver } from './solver.js';
import { sceneRefusal } from './encoder.js';

const gpu = await testDevice('src/gpu/gpu.test.ts');
if (gpu) console.log(`GPU tests on: ${gpu.adapter}`);

/** faces per side of the parity cloths: 169 particles, quick on SwiftShader */
const RES = 12;

/** Largest distance between corresponding particles [m]. */
function scene(name: string, change?: (s: Scene) => void): Scene {
  const s = builtinScene(name)!;
  s.cloth.resolution = RES;
  // the phases but self-contact, which the built-in scenes have on: its GPU tests are src/gpu/self-contact.test.ts;
  // the springs swept alone, as the tolerances below were measured: the coarse correction, the default since
  // 2026-12-06, is held to the CPU in coarse-stretch.test.ts (with it the cape's two CPU kernels end 2.6 times as far
  // apart at frame 20 as with the sweep alone: 1.4e-3 m against 5.5e-4, at 12², self-contact off)
  s.solver.selfContact = false;
  s.solver.stretch = 'gauss-seidel';
  change?.(s);
  return validateScene(s);
}

const solvers: GpuClothSolver[] = [];
afterAll(() => {
  for (const s of solvers) s.destroy();
});

/** A CPU and a GPU cloth of one scene, in the same start state (test-device.ts gpuPair). */
const pair = (sc: Scene): Promise<Pair> => gpuPair(gpu!.device, sc, solvers);

async function readBuffer(buffer: GPUBuffer, bytes: number): Promise<Float32Array> {
  const device = gpu!.device;
  const staging = device.createBuffer({ size: bytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const enc = device.createCommandEncoder();
  enc.copyBufferToBuffer(buffer, 0, staging, 0, bytes);
  device.queue.submit([enc.finish()]);
  await staging.mapAsync(GPUMapMode.READ);
  const out = new Float32Array(staging.getMappedRange().slice(0));
  staging.unmap();
  staging.destroy();
  return out;
}

const DROPS = ['cotton-basic', 'silk-drape', 'leather-stiff', 'rubber-stretch', 'custom', 'resolution'];
/** the mannequin's scenes: 15 moving capsules and a sphere, pins carried by the chest or the pelvis */
const MANNEQUIN = ['cape', 'skirt'];
/** the standard fabric tests: a clamped strip, a disc on a pedestal (a cylinder: its rim is triangle contact) */
const FABRIC_TESTS = ['cantilever', 'cusick'];
/** the scenes with self-contact on (self-contact.test.ts): the GPU takes fold, and refuses layers' cloths of three fabrics */
const SELF_CONTACT = ['fold', 'layers'];

describe.skipIf(!gpu)('GPU vs CPU parity', () => {
  test('every built-in scene is covered, and the GPU takes each but layers, whose cloths differ, which it refuses by name', () => {
    expect([...DROPS, 'wind', 'pins', 'tablecloth', ...MANNEQUIN, ...FABRIC_TESTS, ...SELF_CONTACT].sort()).toEqual([...SCENE_NAMES].sort());
    for (const name of SCENE_NAMES) {
      expect(sceneRefusal(scene(name)), name).toBe(name === 'layers' ? 'cloths that differ in their contact or spring values run on the CPU only (cloths[1].material.damping)' : null);
    }
  });

  // Tolerances: a few times the larger of the GPU–CPU difference seen on SwiftShader and the CPU's own spread when
  // its start is nudged by 1e-7 (relative, f32 rounding): the GPU computes in f32, the CPU in f64 stored as f32, and
  // contact, friction and the stretch caps amplify rounding like any other nudge (docs/gpu.md, "Parity").
  //
  // Dropped on the sphere: the cloth touches it around frame 18. Before: ≤ 4e-9 m seen → 1e-5 m. At frame 30: seen
  // ≤ 2.0e-2 m (leather; the others ≤ 3.8e-3 m; CPU's own spread ≤ 3.2e-3 m) → 5e-2 m; centroid seen ≤ 1.8e-3 m
  // → 5e-3 m (docs/gpu.md, "Parity": contact with friction and damping amplifies f32 rounding after impact).
  test.each(DROPS)('%s: 1e-5 m before contact, 5 cm and centroid 5 mm at frame 30', async (name) => {
    const p = await pair(scene(name));
    await p.advance(16);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-5);
    await p.advance(14);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(5e-2);
    expect(centroidDistance(p.gpu, p.cpu)).toBeLessThan(5e-3);
    expect(p.gpu.time).toBe(p.cpu.time);
    expect(p.gpu.substeps).toBe(p.cpu.substeps);
  });

  // The fabric tests at RES faces: what the scene measures, from the GPU's cloth and the CPU's, after 40 frames (the
  // strip bent, the disc over the rim). Seen (SwiftShader): the strip 2.4e-5 m apart and its chord 0.012°; the disc
  // 4.9e-4 m, its centroid 7.5e-6 m, its drape coefficient 3e-4 and the same folds. With the scenes' still air the
  // disc's skirt slides off the rim more slowly, and where it leaves the rim (r = 12–15 cm) the two part by 2.5e-4 m
  // at frame 10, 1.5e-3 at 20, 4.2e-3 at 40, while its centroid stays 5.7e-5 m apart, its drape coefficient 1.9e-3
  // and its folds the same → 1e-4 m and 0.1°; 6e-3 m, 2e-4 m, 3e-3, ±1
  test.each(FABRIC_TESTS)('%s: the GPU follows the CPU for 40 frames and measures alike', async (name) => {
    const sc = scene(name);
    const p = await pair(sc);
    await p.advance(40);
    const a = measureTest(p.model, p.gpu, sc)!, b = measureTest(p.model, p.cpu, sc)!;
    if (a.type === 'cantilever' && b.type === 'cantilever') {
      expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-4);
      expect(Math.abs(a.chordAngle - b.chordAngle)).toBeLessThan(0.1);
    } else if (a.type === 'cusick' && b.type === 'cusick') {
      expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(6e-3);
      expect(centroidDistance(p.gpu, p.cpu)).toBeLessThan(2e-4);
      expect(Math.abs(a.drapeCoefficient - b.drapeCoefficient)).toBeLessThan(3e-3);
      expect(Math.abs(a.folds - b.folds)).toBeLessThanOrEqual(1);
    } else throw new Error(`${name}: not a fabric test`);
  });

  // The mannequin's scenes, moving colliders and carried pins at once. Seen at frame 20 (SwiftShader, Voronoi masses):
  // the cape 1.1e-4 m and a centroid 9.9e-7 m off, the skirt 3.9e-6 m and 6.4e-8 m. The cape's shoulders stick and
  // slip on the turning body, and which particle is furthest off changes every few frames: the CPU's own kernels
  // differ by 3.1e-5 m there (ts against wasm) and the CPU by 1.1e-5–4.9e-5 m from start positions nudged by 1e-7
  // (relative, six draws), so rounding grows ~100× in 20 frames → 5e-4 m and 5e-6 m.
  test.each(MANNEQUIN)('%s: the GPU follows the CPU for 20 frames, the carried pins with it', async (name) => {
    const p = await pair(scene(name));
    expect(p.params.carried.particles.length).toBeGreaterThan(0);
    await p.advance(20);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(5e-4);
    expect(centroidDistance(p.gpu, p.cpu)).toBeLessThan(5e-6);
  });

  // A tablecloth on a box table: it lands around frame 10, so contact (box triangle contact: closest features and
  // the golden-section search) is on from there. At frame 30: seen 1.1e-2 m, centroid 4.2e-4 m; the CPU's own spread
  // 2.5e-2 m, 6.3e-4 m (scripts/gpu-collider-parity.mjs) → 5 cm and 5 mm, the drop scenes' tolerances.
  test('tablecloth (a box): 5 cm and centroid 5 mm at frame 30', async () => {
    const p = await pair(scene('tablecloth'));
    await p.advance(30);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(5e-2);
    expect(centroidDistance(p.gpu, p.cpu)).toBeLessThan(5e-3);
    expect(maxPenetration(p.model, p.gpu, p.params)).toBeLessThanOrEqual(1e-3);
  });

  // Four pinned corners (tethers, stretch limit), no contact: seen ≤ 8e-5 m (CPU spread ≤ 1.4e-4 m) → 1 mm.
  test('pins: 1 mm after 30 frames', async () => {
    const p = await pair(scene('pins'));
    await p.advance(30);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
    expect(maxDistance(p.gpu.velocities, p.cpu.velocities)).toBeLessThan(0.1);
  });

  // A flag flapping in gusts: seen ≤ 1.2e-4 m at frame 10, ≤ 3.2e-3 m up to frame 30, centroid ≤ 1.7e-4 m.
  test('wind: 1 mm at frame 10, 1 cm and centroid 1 mm at frame 30', async () => {
    const p = await pair(scene('wind'));
    await p.advance(10);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
    await p.advance(20);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-2);
    expect(centroidDistance(p.gpu, p.cpu)).toBeLessThan(1e-3);
  });

  test('resolution scene at its own resolution (1 face, no bend springs)', async () => {
    const sc = builtinScene('resolution')!;
    sc.solver.selfContact = false;
    const p = await pair(sc);
    await p.advance(15);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-5);
    // then the one triangle tips over the sphere's top, which multiplies a difference by ~4 every 5 frames
    // (float32 against float64: measured 3·10⁻⁷ m at frame 15, 1.5·10⁻⁵ at 25, 2·10⁻⁴ at 30)
    await p.advance(15);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
  });

  // The GPU stepping a Simulation's own model and params, as the app and the CLI use it.
  test.each(['cotton-basic', 'leather-stiff'])('%s through Simulation: centroid within 5 mm at frame 30', async (name) => {
    const sim = new Simulation(scene(name));
    const g = createState(sim.model);
    copyState(sim.state, g);
    const solver = await GpuClothSolver.create(gpu!.device, sim.model);
    solvers.push(solver);
    solver.upload(g);
    for (let f = 0; f < 30; f++) {
      sim.advance(1);
      solver.step(g, sim.params, FRAME_DT);
      if (f === 15) {
        await solver.read(g);
        expect(maxDistance(g.positions, sim.state.positions)).toBeLessThan(1e-5);
      }
    }
    await solver.read(g);
    expect(centroidDistance(g, sim.state)).toBeLessThan(5e-3);
  });

  // Overlaps without chaos: a cloth that starts 3 cm under a floor plane is lifted onto it at depenetrationSpeed
  // (0.25 m/s: 8 frames), then rests; a floor raised into the resting cloth lifts it again. Seen 1e-12 m → 1e-6 m.
  test('a cloth lifted out of a floor it starts in, and by a floor raised into it: as on the CPU', async () => {
    const p = await pair(scene('cotton-basic', (s) => { s.colliders = [{ type: 'floor', height: 1.23 }]; }));
    await p.advance(40);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-6);
    p.params = resolveParams(p.model, scene('cotton-basic', (s) => { s.colliders = [{ type: 'floor', height: 1.3 }]; }));
    await p.advance(40);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-6);
    expect(centroid(p.gpu)[1]).toBeCloseTo(1.3 + 0.005, 4); // on the floor at the contact thickness
    for (const v of p.gpu.velocities) expect(Math.abs(v)).toBeLessThan(1e-3); // lifted, not thrown
  });

  // A sphere grown at once under a draped cloth (physics.test.ts, the slingshot): from the CPU's draped rubber, the
  // GPU lifts it onto the new top as the CPU does, its friction bounded by what presses (frictionScale's pressed depth), not thrown.
  // Seen (SwiftShader): 3.2e-4 m apart after 30 frames, the top 5.4 mm over the new one (12² sags); with friction
  // from the whole push on the GPU alone, 0.36 m apart and 12 cm → 1e-3 m, 2.5 cm.
  test('a sphere grown at once under draped rubber: lifted onto its new top as on the CPU, not thrown', async () => {
    const sc = scene('rubber-stretch');
    const p = await pair(sc);
    for (let f = 0; f < 120; f++) step(p.model, p.cpu, p.params, FRAME_DT);
    copyState(p.cpu, p.gpu);
    p.solver.upload(p.gpu);
    const radius = 0.36;
    p.params = resolveParams(p.model, scene('rubber-stretch', (s) => { if (s.colliders[0].type === 'sphere') s.colliders[0].radius = radius; }));
    const sphere = sc.colliders[0];
    const top = (sphere.type === 'sphere' ? sphere.center[1] : NaN) + radius + sc.cloth.thickness;
    let highest = -Infinity;
    for (let f = 0; f < 30; f++) {
      await p.advance(1);
      for (let i = 1; i < p.gpu.positions.length; i += 3) highest = Math.max(highest, p.gpu.positions[i]);
    }
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
    expect(highest).toBeGreaterThan(top - 2e-3);
    expect(highest - top).toBeLessThan(0.025);
  });

  test('3 iterations (λ accumulation): positions and elastic energy', async () => {
    const p = await pair(scene('cotton-basic', (s) => { s.solver.iterations = 3; }));
    await p.advance(12);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-5);
    const ec = energy(p.model, p.cpu, p.params).elastic, eg = energy(p.model, p.gpu, p.params).elastic;
    expect(Math.abs(eg - ec)).toBeLessThanOrEqual(1e-3 * Math.abs(ec) + 1e-9);
  });

  test('grab and release', async () => {
    const p = await pair(scene('pins'));
    const mid = (RES / 2) * (RES + 1) + RES / 2;
    await p.advance(5);
    for (const s of [p.cpu, p.gpu]) grab(s, mid, [0.1, 1.8, 0.05]);
    await p.advance(10);
    const at = p.gpu.positions.slice(3 * mid, 3 * mid + 3);
    expect(Math.hypot(at[0] - 0.1, at[1] - 1.8, at[2] - 0.05)).toBeLessThan(1e-6);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
    for (const s of [p.cpu, p.gpu]) release(s);
    await p.advance(10);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
  });

  test('a grab pulled into the sphere holds the particle outside it, as on the CPU', async () => {
    const sc = scene('custom');
    const sphere = sc.colliders.find((c) => c.type === 'sphere')!;
    if (sphere.type !== 'sphere') throw new Error('custom has a sphere');
    const [cx, cy, cz] = sphere.center;
    const p = await pair(sc);
    const mid = (RES / 2) * (RES + 1) + RES / 2;
    await p.advance(5);
    for (const s of [p.cpu, p.gpu]) grab(s, mid, [cx + 0.01, cy + 0.05, cz]);
    await p.advance(5);
    for (const s of [p.cpu, p.gpu]) {
      const x = s.positions;
      const r = Math.hypot(x[3 * mid] - cx, x[3 * mid + 1] - cy, x[3 * mid + 2] - cz);
      expect(r).toBeGreaterThanOrEqual(sphere.radius + p.params.thickness - 1e-5);
    }
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
  });

  test('live parameter change (gravity, wind, stiffness) without a rebuild', async () => {
    const sc = scene('pins');
    const p = await pair(sc);
    await p.advance(10);
    sc.gravity = [0, -3, 0];
    sc.material.structuralStiffness = 2000;
    sc.wind = { ...sc.wind, enabled: true, strength: 6, direction: [0, 0, 1] };
    p.params = resolveParams(p.model, sc); // step() sees a new params object and calls setParams
    await p.advance(10);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
  });

  test('pins changed between frames (tethers recomputed)', async () => {
    const p = await pair(scene('pins'));
    await p.advance(5);
    for (const s of [p.cpu, p.gpu]) applyPins(s, [0, RES]); // only the two top corners
    await p.advance(10);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-3);
  });
});

describe.skipIf(!gpu)('GPU physics', () => {
  // Verlet on f32 positions drifts: v = (x − x_prev)/h loses digits to cancellation, ~3 mm over 0.5 s at y ≈ 1 m
  // for the CPU solver as much as for this one. Falling from y = 0 keeps |y| ≤ 1.2 m and the drift ≲ 0.3 mm.
  test('free fall: every particle falls ½gt² (Taylor start), no drift sideways', async () => {
    const sc = scene('cotton-basic', (s) => { s.colliders = []; s.cloth.resolution = 8; s.cloth.position = [0, 0, 0]; });
    const p = await pair(sc);
    const x0 = p.gpu.positions.slice();
    await p.advance(30);
    const t = 30 * FRAME_DT;
    const drop = 0.5 * 9.81 * t * t;
    const vy = p.gpu.velocities[1];
    for (let i = 0; i < x0.length; i += 3) {
      expect(Math.abs(p.gpu.positions[i + 1] - (x0[i + 1] - drop))).toBeLessThan(5e-4);
      expect(Math.abs(p.gpu.positions[i] - x0[i])).toBeLessThan(1e-5);
      expect(Math.abs(p.gpu.positions[i + 2] - x0[i + 2])).toBeLessThan(1e-5);
      expect(p.gpu.velocities[i + 1]).toBeCloseTo(vy, 3); // the cloth falls as one
    }
    expect(Math.abs(vy + 9.81 * t)).toBeLessThan(2e-2);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-4); // the same drift, rounded differently
  });

  // (1.2 m with 200 substeps, 7 % short before, is the CPU tests' case: here the far positions, where it was worst)
  test.each([[300, 20], [-1000, 200]])('free fall at y = %d m with %d substeps: ½gt², as on the CPU (positions keep their residuals)', async (y, substeps) => {
    // before the residuals, float32 rounded g·h² away: 7 % short at 200 substeps near the origin, no fall at 300 m
    const sc = scene('custom', (s) => { s.colliders = []; s.cloth.resolution = 2; s.cloth.position = [0, y, 0]; s.solver.substeps = substeps; });
    const p = await pair(sc);
    const y0 = p.gpu.positions[1];
    await p.advance(30);
    const t = 30 * FRAME_DT, fell = y0 - p.gpu.positions[1];
    // read back to float32: a position's last bit (6·10⁻⁵ m at 1 km) of the 1.2 m fall is 5·10⁻⁵ of it
    expect(Math.abs(fell / (0.5 * 9.81 * t * t) - 1)).toBeLessThan(1e-4);
    expect(Math.abs(p.gpu.positions[1] - p.cpu.positions[1])).toBeLessThan(1e-4);
  });

  test('still air (the wind on at 0 m/s): a falling sheet meets its terminal speed √(2ρ_A·g/ρ_air), as on the CPU', async () => {
    // as physics.test.ts: the mean speed over 0.3–0.45 s against v_t·tanh(g·t/v_t) integrated, within 1 %
    const sc = scene('custom', (s) => {
      s.colliders = []; s.cloth.resolution = 8;
      s.wind = { ...s.wind, enabled: true, strength: 0, gusts: { ...s.wind.gusts, enabled: false } };
    });
    const p = await pair(sc);
    await p.advance(18);
    const y0 = centroid(p.gpu)[1];
    await p.advance(9);
    const speed = (y0 - centroid(p.gpu)[1]) / (9 * FRAME_DT);
    const vt = Math.sqrt((2 * sc.material.arealDensity! * 9.81) / sc.wind.airDensity);
    const drop = (t: number) => ((vt * vt) / 9.81) * Math.log(Math.cosh((9.81 * t) / vt));
    expect(Math.abs(speed / ((drop(0.45) - drop(0.3)) / 0.15) - 1)).toBeLessThan(0.01);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-4);
  });

  // as physics.test.ts: a step must not add energy to a cloth in fast motion (a 1 m sheet of 16 faces hung by one
  // corner, let go 60° out of the vertical). Read every 10 frames over its first half second, the fastest part of the
  // swing (where a step that adds energy showed it: 11 J of a start of 1.8 J by 0.4 s), its kinetic + gravitational
  // energy stays below its start, for each way the GPU solves springs and stencils (one at a time, together, both
  // together; the CPU's test holds every setting for 2 s)
  test.each([
    ['gauss-seidel', 'springs', 'gauss-seidel'], ['global', 'springs', 'gauss-seidel'], ['gauss-seidel', 'hinges', 'global'], ['global', 'hinges', 'global'],
  ])('a cloth swinging from one corner, stretch %s, bending %s solved %s: kinetic + gravitational energy never above its start', async (stretch, bending, bendingSolve) => {
    const sc = validateScene({
      cloth: { orientation: 'hanging', resolution: 16, position: [0, 1.5, 0], rotation: [60, 0, 0] },
      material: { fabric: 'cotton' }, solver: { stretch, bending, bendingSolve }, colliders: [], pins: ['top-left'],
    });
    const p = await pair(sc);
    const mechanical = () => { const e = energy(p.model, p.gpu, p.params); return e.kinetic + e.gravitational; };
    const e0 = mechanical();
    for (let f = 0; f < 30; f += 10) {
      await p.advance(10);
      expect(mechanical() - e0).toBeLessThanOrEqual(0);
    }
  });

  test('pinned particles do not move', async () => {
    const p = await pair(scene('pins'));
    const x0 = p.gpu.positions.slice();
    await p.advance(40);
    let pins = 0;
    for (let i = 0; i < p.model.particleCount; i++) {
      if (!p.gpu.pinned[i]) continue;
      pins++;
      for (let k = 0; k < 3; k++) expect(p.gpu.positions[3 * i + k]).toBe(x0[3 * i + k]);
    }
    expect(pins).toBe(4);
    expect(centroid(p.gpu)[1]).toBeLessThan(1.5 - 0.01); // the rest sags (a little: it cannot stretch)
  });

  test('cloth stays outside the sphere (penetration ≤ 1 mm) and rests on it', async () => {
    const sc = scene('cotton-basic', (s) => { s.cloth.resolution = 16; });
    const p = await pair(sc);
    let worst = 0;
    for (let k = 0; k < 4; k++) {
      await p.advance(15);
      worst = Math.max(worst, maxPenetration(p.model, p.gpu, p.params));
    }
    expect(worst).toBeLessThanOrEqual(1e-3);
    const mid = (16 / 2) * 17 + 16 / 2; // centre particle, above the sphere's top (y = 0.8)
    expect(p.gpu.positions[3 * mid + 1]).toBeGreaterThan(0.8);
  });

  test('wind pushes the cloth along the wind', async () => {
    // the flag hangs in the xy plane from its left edge; blow across it (+z) and obliquely (+x +z)
    const setup = (s: Scene) => { s.cloth.resolution = 8; s.wind.gusts.enabled = false; };
    // without wind the direction is nothing to the cloth: one calm flag for both
    const calm = await pair(scene('wind', (s) => { setup(s); s.wind.enabled = false; }));
    await calm.advance(15);
    for (const dir of [[0, 0, 1], [1, 0, 1]] as const) {
      const windy = await pair(scene('wind', (s) => { setup(s); s.wind.direction = [...dir]; }));
      await windy.advance(15);
      const a = centroid(calm.gpu), b = centroid(windy.gpu);
      expect(b[2] - a[2]).toBeGreaterThan(0.05); // pushed downwind
      expect(maxDistance(windy.gpu.positions, windy.cpu.positions)).toBeLessThan(1e-3);
    }
  });

  test('the wind scene with the wind off: the flag buckles out of its plane and droops from its pole, as on the CPU', async () => {
    // exactly flat it could not leave the plane of gravity and stayed up on its in-plane shear stiffness (1.6 cm
    // for the shear beam); with the scene's 1 mm bulge the CPU flag drops 0.38 m in 2 s at 12² (physics.test.ts)
    const p = await pair(scene('wind', (s) => { s.wind.enabled = false; }));
    const y0 = centroid(p.gpu)[1];
    await p.advance(120);
    expect(isFinite3(p.gpu)).toBe(true);
    expect(y0 - centroid(p.gpu)[1]).toBeGreaterThan(0.3);
    expect(y0 - centroid(p.cpu)[1]).toBeGreaterThan(0.3);
  });

  test('finite under extreme parameters', async () => {
    const sc = scene('wind', (s) => {
      s.cloth.resolution = 10;
      s.material = { ...s.material, structuralStiffness: 1e6, shearStiffness: 1e6, bendingRigidity: 1, damping: 10, mass: 1e-5, stretchFactor: 2, friction: 2, staticFriction: 2 };
      delete s.material.arealDensity;
      s.solver = { ...s.solver, substeps: 1, iterations: 20 };
      s.gravity = [0, -50, 0];
      s.wind = { ...s.wind, strength: 30, airDensity: 10, gusts: { enabled: true, amplitude: 1, frequency: 10, seed: 3 } };
      s.colliders = [{ type: 'sphere', center: [0, 1.2, 0], radius: 0.4 }, { type: 'floor', height: 0 }];
      s.cloth.thickness = 0.1;
    });
    const p = await pair(sc);
    await p.advance(40);
    expect(isFinite3(p.gpu)).toBe(true);
    for (const v of p.gpu.positions) expect(Math.abs(v)).toBeLessThan(100);
    expect(p.gpu.velocities.every(Number.isFinite)).toBe(true);
  });

  test('params refused for self-contact past what the device binds change nothing: the old ones step on', async () => {
    const device = gpu!.device;
    const plain = scene('pins', (s) => { s.cloth.resolution = 6; });
    const model = modelFor(plain);
    const solver = await GpuClothSolver.create(device, model);
    const state = createState(model);
    solver.upload(state);
    const before = resolveParams(model, plain);
    solver.setParams(before);
    // the same cloth with self-contact and two more colliders, on a device that binds 1 kB
    const more = scene('pins', (s) => {
      s.cloth.resolution = 6; s.solver.selfContact = true;
      s.colliders = [...s.colliders, { type: 'sphere', center: [0, 0.3, 0], radius: 0.1 }, { type: 'floor', height: 0 }];
    });
    const limits = device.limits;
    const spy = vi.spyOn(device, 'limits', 'get').mockReturnValue({ ...limits, maxStorageBufferBindingSize: 1024 } as GPUSupportedLimits);
    try {
      expect(() => solver.setParams(resolveParams(model, more))).toThrow(/^GPU solver: self-contact needs .* this device binds at most 0 MiB$/);
    } finally {
      spy.mockRestore();
    }
    // (the same params object: nothing is set again)
    for (let f = 0; f < 3; f++) solver.step(state, before, FRAME_DT);
    await solver.read(state);
    expect(isFinite3(state)).toBe(true);
    solver.destroy();
  });

  test('vertex normals of a cloth uploaded before any params (GpuBackend): computed, not zero', async () => {
    const model = modelFor(scene('cotton-basic'));
    const solver = await GpuClothSolver.create(gpu!.device, model);
    solver.upload(createState(model));
    const n = await readBuffer(solver.normalBuffer, model.particleCount * 16);
    for (let i = 0; i < model.particleCount; i++) expect(n[4 * i + 1]).toBeGreaterThan(0.999);
    solver.destroy();
  });

  test('vertex normals: unit length, +y for a flat horizontal cloth', async () => {
    const p = await pair(scene('cotton-basic'));
    await p.advance(1);
    const n = await readBuffer(p.solver.normalBuffer, p.model.particleCount * 16);
    for (let i = 0; i < p.model.particleCount; i++) {
      expect(Math.hypot(n[4 * i], n[4 * i + 1], n[4 * i + 2])).toBeCloseTo(1, 5);
      expect(n[4 * i + 1]).toBeGreaterThan(0.999);
    }
  });

  test('kernels are compiled once per device: another model on it compiles nothing', async () => {
    const device = gpu!.device;
    solvers.push(await GpuClothSolver.create(device, modelFor(scene('cotton-basic'))));
    const spy = vi.spyOn(device, 'createShaderModule');
    try {
      const other = await GpuClothSolver.create(device, modelFor(scene('pins', (s) => { s.cloth.resolution = 20; })));
      solvers.push(other);
      expect(spy).not.toHaveBeenCalled();
      const g = createState(other.model);
      other.upload(g);
      other.step(g, resolveParams(other.model, scene('pins', (s) => { s.cloth.resolution = 20; })), FRAME_DT);
      await other.read(g);
      expect(isFinite3(g)).toBe(true);
    } finally {
      spy.mockRestore();
    }
  });

  test('two solvers made at once each get their own errors: the one with an invalid buffer is refused, the other made', async () => {
    const device = gpu!.device;
    const model = modelFor(scene('pins', (s) => { s.cloth.resolution = 6; }));
    await GpuClothSolver.create(device, model).then((s) => s.destroy()); // the kernels compiled
    const create = device.createBuffer.bind(device);
    let broken = false;
    // the first buffer made after this is invalid (usage 0): a validation error on the device, the first solver's
    const spy = vi.spyOn(device, 'createBuffer').mockImplementation((d: GPUBufferDescriptor) => {
      if (!broken) { broken = true; return create({ ...d, usage: 0 }); }
      return create(d);
    });
    try {
      const [a, b] = await Promise.allSettled([GpuClothSolver.create(device, model), GpuClothSolver.create(device, model)]);
      expect(a.status).toBe('rejected');
      expect(String((a as PromiseRejectedResult).reason)).toMatch(/^Error: GPU solver: /);
      expect(b.status).toBe('fulfilled');
      (b as PromiseFulfilledResult<GpuClothSolver>).value.destroy();
    } finally {
      spy.mockRestore();
    }
  });

  test('a buffer that new parameters need and the device cannot make: the next step says so, not a cloth standing still', async () => {
    const device = gpu!.device;
    const sc = scene('pins', (s) => { s.cloth.resolution = 6; s.solver.selfContact = true; });
    const model = modelFor(sc);
    const solver = await GpuClothSolver.create(device, model);
    const state = createState(model);
    solver.upload(state);
    const create = device.createBuffer.bind(device);
    // self-contact's buffers, made by the first params that have it, come out invalid (as out of memory would)
    const spy = vi.spyOn(device, 'createBuffer').mockImplementation((d: GPUBufferDescriptor) => create({ ...d, usage: 0 }));
    try {
      solver.setParams(resolveParams(model, sc));
    } finally {
      spy.mockRestore();
    }
    // (the device says so a moment later: the error scopes resolve asynchronously)
    const params = resolveParams(model, sc);
    await vi.waitFor(() => expect(() => solver.step(state, params, FRAME_DT)).toThrow(), { timeout: 60_000, interval: 20 });
    expect(() => solver.step(state, params, FRAME_DT))
      .toThrow(/^GPU solver: the device refused a buffer or a write for the new parameters \(self-contact's lists, the bending stencils, mesh colliders\) \(49 particles\): /);
    expect(() => solver.read(state)).toThrow(/^GPU solver: the device refused a buffer or a write/);
    solver.destroy();
  });

  test('rejects what it cannot run, with a message', async () => {
    const sc = scene('cotton-basic', (s) => { s.solver.type = 'mass-spring'; });
    const p = await pair(scene('cotton-basic'));
    expect(() => p.solver.setParams(resolveParams(p.model, sc))).toThrow(/only the xpbd solver/);
  });
});

describe.skipIf(!gpu)('GPU benchmark hook', () => {
  test('benchGpu runs at small sizes and reports consistent numbers', async () => {
    const [r] = await benchGpu(gpu!.device, [6], 4, 3);
    expect(r.particles).toBe(36);
    expect(r.msPerFrame).toBeGreaterThan(0);
    expect(r.bytesPerSubstep).toBeGreaterThan(36 * 100);
    expect(r.copyBandwidthGBs).toBeGreaterThan(0);
    expect(r.fractionOfBandwidthFloor).toBeGreaterThan(0);
    expect(r.particleSubstepsPerSecond).toBeCloseTo((36 * 4) / (r.msPerFrame / 1000), 0);
  });
});
