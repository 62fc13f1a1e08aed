/**
 * The WebAssembly XPBD kernel against the TypeScript solver it mirrors: same phases, so the same cloth within f32
 * rounding of the constraint passes (the physics tests in solvers/physics.test.ts run on both kernels as well).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { FRAME_DT, builtinScene, createState, SCENE_NAMES, Simulation, step, validateScene, type ClothState, type ColliderSpec, type Scene, type Vec3 } from '../index.js';
import { PHASE, PHASES, PhaseLog } from '../schedule.js';
import { REFERENCE } from '../reference.js';
import { GENERATED_FILE, generateKernelModule } from './gen-wasm.mjs';
import { wasmKernelAvailable } from './xpbd-wasm.js';
import { XPBD_WASM_SINGLE, XPBD_WASM_THREADS } from './xpbd-kernel.generated.js';
import { WasmBackend } from '../backend.js';

function maxDiff(a: Float32Array, b: Float32Array): number {
  let d = 0;
  for (let i = 0; i < a.length; i++) d = Math.max(d, Math.abs(a[i] - b[i]));
  return d;
}

/**
 * One substep of phase `id` by `sim`'s kernel on its state and by the reference on a copy (positions, previous
 * positions, inverse masses, time), the kernel's run checked to be that phase alone: the state, the copy and the
 * positions before.
 */
function kernelAgainstReference(sim: Simulation, id: number): { st: ClothState; copy: ClothState; before: Float32Array } {
  const kernel = (sim.backend as WasmBackend).kernel, st = sim.state;
  const copy = createState(sim.model);
  copy.positions.set(st.positions);
  copy.previousPositions.set(st.previousPositions);
  copy.invMass.set(st.invMass);
  copy.time = st.time;
  const frame = { h: FRAME_DT / sim.params.substeps, substeps: sim.params.substeps, sub: 0, forced: false, grabFrom: new Float64Array(3), grabTo: new Float64Array(3) };
  const before = Float32Array.from(st.positions);
  const log = new PhaseLog();
  kernel.run(1 << id, sim.model, st, sim.params, frame, log);
  REFERENCE[id](sim.model, copy, sim.params, frame);
  expect(log.names()).toEqual([PHASES[id].name]);
  return { st, copy, before };
}

/**
 * `sim` after `frames` more frames: one substep of triangle contact by its kernel and by the reference on a copy,
 * the same positions and previous positions bit for bit, the phase having moved the cloth by more than `moved` [m].
 */
function triangleContactAsReference(sim: Simulation, frames: number, moved = 1e-7): void {
  sim.advance(frames);
  const { st, copy, before } = kernelAgainstReference(sim, PHASE.contactTriangles);
  expect(maxDiff(before, st.positions)).toBeGreaterThan(moved);
  expect([...st.positions]).toEqual([...copy.positions]);
  expect([...st.previousPositions]).toEqual([...copy.previousPositions]);
}

function pair(sc: Scene): [Simulation, Simulation] {
  return [new Simulation(sc, { kernel: 'ts' }), new Simulation(sc, { kernel: 'wasm' })];
}

describe('xpbd wasm kernel', () => {
  it('xpbd-kernel.generated.ts matches xpbd.as.ts (else run: node src/core/wasm/gen-wasm.mjs)', async () => {
    expect(readFileSync(GENERATED_FILE, 'utf8')).toBe(await generateKernelModule());
  }, 60_000);

  it('runs in Node, single-threaded and over a shared memory', () => {
    expect(wasmKernelAvailable()).toBe(true);
    expect(wasmKernelAvailable(true)).toBe(true);
    const sim = new Simulation(builtinScene('cotton-basic')!);
    expect(sim.kernel).toBe('wasm');
    expect(sim.state.positions.buffer).not.toBeInstanceOf(SharedArrayBuffer);
  });

  // 1 frame: the constraint passes in f32 lanes here, f64 there, measured ≤ 1.1e-6 m (the cape swinging back from
  // its start at up to 1.42 m, where an f32 step is 1.2e-7 m; the other scenes ≤ 4.8e-7); a wrong constraint or
  // contact is off by millimetres. 24 frames is after the impact on the sphere (from frame 18), where contact turns
  // rounding into millimetres, and growing: at 30 frames seen ≤ 5.9e-3 m and elastic energy ≤ 2.3 % (cotton;
  // docs/physics.md, "Two CPU kernels") with the springs swept alone; with the coarse correction (the default since
  // 2026-12-06, its phase the reference's bit for bit in both) rubber-stretch's 1.7e-3 m and 0.18 m/s apart at frame
  // 24, 1.2e-2 m and 1.08 m/s at 30 (the sweep alone 1.0e-4 and 3.8e-4 m)
  it.each(SCENE_NAMES)('%s: the same cloth as the TypeScript solver (1 frame: 2 µm; 24 frames: 1 cm, elastic energy 5 %%)', (name) => {
    const sc = builtinScene(name)!;
    sc.cloth.resolution = Math.min(sc.cloth.resolution, 12);
    const [ts, wasm] = pair(sc);
    ts.advance(1); wasm.advance(1);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(2e-6);
    ts.advance(23); wasm.advance(23);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-2);
    expect(maxDiff(ts.state.velocities, wasm.state.velocities)).toBeLessThan(1);
    const e = ts.report().energy, ew = wasm.report().energy;
    expect(Math.abs(ew.elastic - e.elastic)).toBeLessThanOrEqual(0.05 * e.elastic + 1e-9);
    const motion = e.kinetic + e.gravitational;
    expect(Math.abs(ew.kinetic + ew.gravitational - motion)).toBeLessThanOrEqual(1e-3 * Math.abs(motion) + 1e-9);
  });

  it('particle contact runs in the kernel at fine meshes and agrees (64² particles on sphere and floor)', () => {
    // start the cloth touching the sphere top (0.8 m) and the floor's plane raised into it, so that the very
    // first frame makes hundreds of particle contacts with friction on both colliders
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 63;
    sc.cloth.position = [0, 0.802, 0];
    sc.colliders = [{ type: 'sphere', center: [0, 0.5, 0], radius: 0.3 }, { type: 'floor', height: 0.799 }];
    sc.solver.substeps = 10;
    const [ts, wasm] = pair(sc);
    ts.advance(1); wasm.advance(1);
    // contact in f32 lanes: about ten f32 steps at 0.8 m (6e-7); a wrong push or friction is off by millimetres
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(5e-6);
    // later the runs part at stick/slip decisions of friction (a threshold amplifies f32 rounding): compare the
    // cloth as a whole
    ts.advance(44); wasm.advance(44);
    const a = ts.report(), b = wasm.report();
    for (let k = 0; k < 3; k++) expect(Math.abs(a.centroid[k] - b.centroid[k])).toBeLessThan(1e-3);
    expect(b.maxPenetration).toBeLessThanOrEqual(1e-3);
  });

  // every analytic shape with its top at 0.8 m under a cloth 2 mm above it (within the 5 mm contact thickness), so
  // that the first frame has contact; each shape turned so that its own frame is not the world's
  const SHAPES = {
    sphere: { type: 'sphere', center: [0, 0.5, 0], radius: 0.3 },
    floor: { type: 'floor', height: 0.799 },
    plane: { type: 'plane', point: [0, 0.799, 0], normal: [0.02, 1, 0.01] },
    box: { type: 'box', center: [0, 0.6, 0], halfExtents: [0.2, 0.2, 0.2], rotation: [0, 30, 0] },
    capsule: { type: 'capsule', a: [-0.3, 0.7, 0], b: [0.3, 0.7, 0.05], radius: 0.1 },
    cylinder: { type: 'cylinder', center: [0, 0.6, 0], axis: [1, 0, 0.1], radius: 0.2, height: 0.6 },
  };
  // moving: from the start, 0.7 m/s up and sideways into the cloth while turning 40° about y and 10° about z in 1 s
  const MOTION = { keyframes: [{ time: 0 }, { time: 1, translation: [0.6, 0.3, 0.2], rotation: [0, 40, 10] }] };
  it.each(Object.keys(SHAPES).flatMap((name) => [[name, 'still'], [name, 'moving']]))('%s, %s: particle contact runs in the kernel and agrees with TypeScript', (name, how) => {
    const collider = { ...SHAPES[name as keyof typeof SHAPES], ...(how === 'moving' ? { motion: MOTION } : {}) };
    // 17² particles: 72 groups of four lanes and one particle in the f64 tail (every particle in f64 for a collider
    // that also has triangle contact: the box, the cylinder, here the capsule)
    const sc = validateScene({ name: 'shape', cloth: { resolution: 16, width: 0.5, height: 0.5, position: [0, 0.802, 0] }, solver: { type: 'xpbd' }, colliders: [collider] });
    const [ts, wasm] = pair(sc);
    const log = new PhaseLog();
    ts.advance(1);
    (wasm.backend as WasmBackend).kernel.frame(wasm.model, wasm.state, wasm.params, FRAME_DT, log);
    const names = log.names();
    expect(names).toContain('contact');
    expect(names).not.toContain('contact (reference)');
    // triangle contact, where the shape needs it at this mesh size, is its own phase, in the kernel for every
    // analytic shape (triangle-contact.as.ts)
    expect(names).not.toContain('contactTriangles (reference)');
    expect(names.includes('contactTriangles')).toBe(['sphere', 'box', 'capsule', 'cylinder'].includes(name));
    // measured ≤ 3.2e-5 m (the cylinder moving; still shapes ≤ 2e-6): f32 constraint passes and lanes against
    // f64, where a contact's inside/outside or stick/slip decision amplifies rounding; a wrong normal, frame or
    // surface motion is off by the collider's motion over a frame (≥ 5 mm moving) or the push-out (mm)
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-4);
    ts.advance(29); wasm.advance(29);
    // later the runs part at such decisions (measured ≤ 8.4e-3 m, the moving sphere): the cloth as a whole agrees
    // (centroids measured ≤ 2.2e-5 m apart), and stays out of the shape
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(2e-2);
    const a = ts.report(), b = wasm.report();
    for (let k = 0; k < 3; k++) expect(Math.abs(a.centroid[k] - b.centroid[k])).toBeLessThan(1e-3);
    expect(b.maxPenetration).toBeLessThanOrEqual(1e-3);
  });

  it.each(['box', 'capsule', 'cylinder'])('%s on a cloth finer than its thickness (no triangle contact): the kernel has the shape, not a plane through it', (name) => {
    // 3.1 cm edges under a 5 cm thickness: the shape's sharp edges cannot poke between vertices, so only particle
    // contact runs; 4.5 cm above the shape's top, every particle touches it in the first frame
    const sc = validateScene({
      name: 'fine', cloth: { resolution: 16, width: 0.5, height: 0.5, position: [0, 0.845, 0], thickness: 0.05 },
      solver: { type: 'xpbd' }, colliders: [SHAPES[name as keyof typeof SHAPES]],
    });
    const [ts, wasm] = pair(sc);
    const log = new PhaseLog();
    ts.advance(1);
    (wasm.backend as WasmBackend).kernel.frame(wasm.model, wasm.state, wasm.params, FRAME_DT, log);
    expect(log.names()).toContain('contact');
    expect(log.names().some((n) => n.startsWith('contactTriangles'))).toBe(false);
    // the push-out is 5 mm: a kernel that missed the shape would be that far off
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-4);
  });

  it('several iterations per substep accumulate λ as in TypeScript', () => {
    const sc = builtinScene('pins')!;
    sc.cloth.resolution = 10;
    sc.solver = { ...sc.solver, type: 'xpbd', substeps: 5, iterations: 3 };
    const [ts, wasm] = pair(sc);
    ts.advance(1); wasm.advance(1);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-6);
    // λ comes from rest − length, a cancellation: f32 leaves it a few % of the largest λ
    expect(maxDiff(ts.state.lambdas, wasm.state.lambdas)).toBeLessThan(0.05 * Math.max(...ts.state.lambdas.map(Math.abs)));
  });

  it('a stiffness change applies on the next step (compliances are uploaded again)', () => {
    const sc = builtinScene('pins')!;
    sc.cloth.resolution = 10;
    const [ts, wasm] = pair(sc);
    const stale = new Simulation(sc, { kernel: 'wasm' }); // a kernel that keeps the old stiffness
    for (const sim of [ts, wasm, stale]) sim.advance(20);
    const before = maxDiff(ts.state.positions, wasm.state.positions);
    for (const sim of [ts, wasm]) sim.set('material.structuralStiffness', 5);
    for (const sim of [ts, wasm, stale]) sim.advance(1);
    // seen: 4.1e-5 m apart before, 5.3e-5 after (the springs swept alone: 4.2e-5, 4.8e-5); the kernel that kept the
    // old stiffness 1.9e-3 m from the reference (2.7e-3)
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(before + 2e-5);
    expect(maxDiff(ts.state.positions, stale.state.positions)).toBeGreaterThan(1e-3);
  });

  it('the mass-spring solver steps a kernel state exactly as a plain one', () => {
    const sc = builtinScene('wind')!;
    sc.cloth.resolution = 8;
    sc.solver.type = 'mass-spring';
    const a = new Simulation(sc, { kernel: 'ts' });
    const backend = WasmBackend.create(a.model)!;
    const state = backend.state;
    state.pinned.set(a.state.pinned);
    for (let f = 0; f < 20; f++) { a.advance(1); backend.frame(a.model, a.params, FRAME_DT); }
    expect(maxDiff(a.state.positions, state.positions)).toBe(0);
  });

  it('mass-spring steps in plain arrays; switching solver moves the cloth over as it is', () => {
    const sc = builtinScene('pins')!;
    sc.cloth.resolution = 8;
    const sim = new Simulation(sc);
    expect(sim.kernel).toBe('wasm');
    sim.advance(10);
    const before = { x: [...sim.state.positions], v: [...sim.state.velocities], pinned: [...sim.state.pinned], t: sim.state.time };
    sim.set('solver.type', 'mass-spring');
    expect(sim.kernel).toBe('ts');
    expect(sim.backend.kind).toBe('ts');
    expect([...sim.state.positions]).toEqual(before.x);
    expect([...sim.state.velocities]).toEqual(before.v);
    expect([...sim.state.pinned]).toEqual(before.pinned);
    expect(sim.state.time).toBe(before.t);
    sim.advance(5);
    sim.set('solver.type', 'xpbd');
    expect(sim.kernel).toBe('wasm');
    sim.advance(5);
    expect(sim.report().finite).toBe(true);
    expect(new Simulation({ ...sc, solver: { ...sc.solver, type: 'mass-spring' } }).kernel).toBe('ts');
  });

  // the kernel's bending phase is the reference's arithmetic (f64 on f32 data, the same order): the same cloth to the bit
  it.each([['hinges', 1], ['laplacian', 1], ['hinges', 3], ['laplacian', 3]] as const)('the %s stencils, %i pass(es) a substep: the kernel\'s bending phase moves every particle as the reference does, bit for bit', (bending, iterations) => {
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 16;
    sc.solver = { ...sc.solver, bending, iterations, selfContact: false };
    const sim = new Simulation(sc, { kernel: 'wasm' });
    // a draped, bent cloth (40 frames: on the sphere), then the kernel's phase against the reference on a copy
    sim.advance(40);
    const { st, copy, before } = kernelAgainstReference(sim, PHASE.bending);
    // the phase did act (it moved particles), and as the reference
    expect(maxDiff(before, st.positions)).toBeGreaterThan(1e-7);
    expect([...st.positions]).toEqual([...copy.positions]);
    expect([...st.bendingLambdas]).toEqual([...copy.bendingLambdas]);
  });

  // the flag in gusty wind, and in a gale (30 m/s, the schema's most) where the drag's cap holds it back (its pinned edge: the cap reads the free
  // inverse masses), and the cantilever's strip swinging in still air (the drag alone): the kernel's wind against
  // the reference's on a copy, one substep
  it.each([['wind', 0, 30], ['wind', 30, 30], ['cantilever', 0, 10]] as const)('the air on the %s scene\'s cloth (wind %i m/s, or the scene\'s): the kernel\'s wind phase gives every particle the reference\'s force, bit for bit', (name, strength, frames) => {
    const sc = builtinScene(name)!;
    sc.solver = { ...sc.solver, selfContact: false };
    // the gale on a light sheet in long substeps: the drag's cap, m̄·|v·n|/(2h), is below the drag there
    if (strength > 0) {
      sc.wind = { ...sc.wind, strength };
      sc.material = { ...sc.material, arealDensity: 0.03 };
      sc.solver = { ...sc.solver, substeps: 5 };
    }
    const sim = new Simulation(validateScene(sc), { kernel: 'wasm' });
    sim.advance(frames);
    const { st, copy } = kernelAgainstReference(sim, PHASE.wind);
    expect(Math.max(...st.forces.map(Math.abs))).toBeGreaterThan(1e-9);
    expect([...st.forces]).toEqual([...copy.forces]);
    sim.dispose();
  });

  // the default scene's cloth draped on its sphere (and the sphere moving: its surface's motion in the friction):
  // the kernel's triangle contact against the reference's on a copy, one substep
  it.each(['still', 'moving'] as const)('triangle contact with a sphere, %s: the kernel\'s phase moves every particle as the reference does, bit for bit', (how) => {
    const sc = builtinScene('cotton-basic')!;
    sc.solver = { ...sc.solver, selfContact: false };
    const motion = { keyframes: [{ time: 0, translation: [0, 0, 0] as Vec3, rotation: [0, 0, 0] as Vec3 }, { time: 2, translation: [0.3, 0.1, 0] as Vec3, rotation: [0, 30, 10] as Vec3 }], loop: false };
    if (how === 'moving') sc.colliders = sc.colliders.map((c) => c.type === 'sphere' ? { ...c, motion } : c);
    // the phase did act (the sag between vertices pushed out), and as the reference, x_prev too
    triangleContactAsReference(new Simulation(validateScene(sc), { kernel: 'wasm' }), 40);
  });

  // a cloth lying across two capsules (one turned, one moving, one through the cloth where its axis crosses
  // triangles): the kernel's triangle contact against the reference's on a copy, one substep
  it.each(['still', 'moving', 'through'] as const)('triangle contact with capsules, %s: the kernel\'s phase moves every particle as the reference does, bit for bit', (how) => {
    const motion = { keyframes: [{ time: 0, translation: [0, 0, 0] as Vec3, rotation: [0, 0, 0] as Vec3 }, { time: 2, translation: [0.2, 0.1, 0] as Vec3, rotation: [0, 30, 10] as Vec3 }], loop: false };
    const colliders = [
      { type: 'capsule' as const, a: [-0.4, 0.5, -0.1] as Vec3, b: [0.4, 0.5, 0.1] as Vec3, radius: 0.015, ...(how === 'moving' ? { motion } : {}) },
      { type: 'capsule' as const, a: [-0.1, 0.45, -0.4] as Vec3, b: [0.15, 0.4, 0.4] as Vec3, radius: 0.04 },
      ...(how === 'through' ? [{ type: 'capsule' as const, a: [0.2, 0.2, 0.2] as Vec3, b: [0.2, 0.9, 0.22] as Vec3, radius: 0.03 }] : []),
    ];
    const sc = validateScene({
      name: 'capsules', cloth: { resolution: 12, width: 1, height: 1, position: [0, 0.62, 0] }, solver: { type: 'xpbd', selfContact: false },
      colliders: [...colliders, { type: 'floor', height: 0 }],
    });
    triangleContactAsReference(new Simulation(sc, { kernel: 'wasm' }), how === 'through' ? 1 : 20);
  });

  // a 4 mm ball poking up 3 mm through a one-face sheet 2 cm from a pinned corner, on the edge to the free corner: the
  // deepest point's share of the free corner is 2 %, and the push-out (5 mm: the sheet moving down at 5 mm a
  // substep) would throw it by 0.25 m; no corner moves more than TRIANGLE_SPREAD_MOST (2) × the point's push
  it('triangle contact beside a pinned corner: the free corner moves at most twice the push, in the reference and the kernel alike', () => {
    const sc = validateScene({
      name: 'pinned corner', cloth: { resolution: 1, width: 1, height: 1, position: [0, 1, 0] }, solver: { type: 'xpbd', selfContact: false },
      pins: ['top-left', 'bottom-left', 'bottom-right'], colliders: [{ type: 'sphere', center: [-0.48, 0.999, -0.5], radius: 0.004 }],
    });
    const sim = new Simulation(sc, { kernel: 'wasm' });
    // a frame first (the inverse masses), then the sheet back where it started, moving down 5 mm a substep:
    // corner 0 at (−0.5, 1, −0.5) pinned, corner 1 at (0.5, 1, −0.5) free
    sim.advance(1);
    const x = sim.state.positions, xp = sim.state.previousPositions;
    x.set(sim.model.restPositions);
    expect([...x.subarray(0, 6)]).toEqual([-0.5, 1, -0.5, 0.5, 1, -0.5]);
    expect([...sim.state.invMass].map((w) => w > 0)).toEqual([false, true, false, false]);
    for (let i = 0; i < x.length; i++) xp[i] = x[i] + (i % 3 === 1 ? 0.005 : 0);
    const { st, copy, before } = kernelAgainstReference(sim, PHASE.contactTriangles);
    const moved = Math.hypot(st.positions[3] - before[3], st.positions[4] - before[4], st.positions[5] - before[5]);
    // the push: 5 mm moved in, plus the recovery allowance (a fraction of a millimetre)
    expect(moved).toBeGreaterThan(2 * 0.005);
    expect(moved).toBeLessThanOrEqual(2 * 0.0052);
    expect([...st.positions]).toEqual([...copy.positions]);
    expect([...st.previousPositions]).toEqual([...copy.previousPositions]);
  });

  // the cylinder and the box: the Cusick pedestal under the disc as it drapes (its cap, rim and side) and the
  // tablecloth's table (its top, edges and corners), each turned and moving under a sheet, and each just through a
  // sheet at its start (triangles across a rim or an edge: the golden-section search)
  const CONVEX = {
    cylinder: { type: 'cylinder', center: [0, 0.4, 0], axis: [1, 0.2, 0.1], radius: 0.15, height: 0.6 },
    box: { type: 'box', center: [0.02, 0.4, 0.01], halfExtents: [0.2, 0.15, 0.25], rotation: [10, 30, 5] },
  } as const;
  const THROUGH = {
    cylinder: { center: [0.03, 0.415, 0.02], axis: [0, 1, 0], radius: 0.23, height: 0.42 },
    box: { center: [0.03, 0.415, 0.02], halfExtents: [0.23, 0.21, 0.19], rotation: [0, 0, 0] },
  } as const;
  it.each([
    ['cylinder', 'the Cusick pedestal', 40], ['cylinder', 'the Cusick pedestal, later', 150], ['cylinder', 'turned, moving', 20], ['cylinder', 'just through a sheet', 1],
    ['box', 'the tablecloth\'s table', 30], ['box', 'the tablecloth\'s table, later', 120], ['box', 'turned, moving', 20], ['box', 'just through a sheet', 1],
  ] as const)('triangle contact with a %s, %s (frame %i): the kernel\'s phase moves every particle as the reference does, bit for bit', (shape, what, frames) => {
    const sheet = (c: object) => validateScene({
      name: shape, cloth: { resolution: 12, width: 1, height: 1, position: [0, 0.62, 0] }, solver: { type: 'xpbd', selfContact: false },
      colliders: [{ ...CONVEX[shape], ...c } as ColliderSpec, { type: 'floor', height: 0 }],
    });
    const sc = what.startsWith('turned') ? sheet({ motion: { keyframes: [{ time: 0 }, { time: 2, translation: [0.2, 0.1, 0], rotation: [0, 30, 10] }] } })
      // the Cusick disc unclamped, so that it rests on the pedestal's top (the scene clamps it there)
      : what.startsWith('just') ? sheet(THROUGH[shape]) : shape === 'cylinder' ? { ...builtinScene('cusick'), pins: [] } : builtinScene('tablecloth');
    triangleContactAsReference(new Simulation(sc, { kernel: 'wasm' }), frames);
  });

  it('triangle contact with the mannequin in the skirt (capsules and a sphere, turning): the kernel\'s phase moves every particle as the reference does, bit for bit', () => {
    triangleContactAsReference(new Simulation(builtinScene('skirt'), { kernel: 'wasm' }), 50, 1e-6);
  });

  it('the kernel keeps nothing of its own in memory (no data segment, no start function): the control block starts at 0', () => {
    // static data (a StaticArray, a string) would be laid out from address 1024 on, inside the control block's
    // collider records, and a start function would rewrite it whenever a helper thread instantiates the module
    for (const base64 of [XPBD_WASM_SINGLE, XPBD_WASM_THREADS]) {
      const b = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
      const sections: number[] = [];
      let p = 8;
      const leb = () => { let r = 0, shift = 0, x: number; do { x = b[p++]; r |= (x & 0x7f) << shift; shift += 7; } while (x & 0x80); return r >>> 0; };
      while (p < b.length) { const id = b[p++]; const len = leb(); sections.push(id); p += len; }
      expect(sections).not.toContain(8); // start
      expect(sections).not.toContain(11); // data
    }
  });

  it('the bending stencils beside six colliders (their records fill the control block): as the reference', () => {
    const sc = validateScene({
      cloth: { resolution: 12, position: [0, 1.2, 0] }, material: { fabric: 'cotton' }, solver: { bending: 'laplacian', selfContact: false },
      colliders: [
        { type: 'sphere', center: [0, 0.5, 0], radius: 0.3 }, { type: 'sphere', center: [0.6, 0.3, 0], radius: 0.1 },
        { type: 'box', center: [-0.6, 0.2, 0], halfExtents: [0.1, 0.1, 0.1] }, { type: 'capsule', a: [0, 0.1, 0.6], b: [0.3, 0.1, 0.6], radius: 0.05 },
        { type: 'cylinder', center: [0, 0.2, -0.6], axis: [0, 1, 0], radius: 0.1, height: 0.2 }, { type: 'floor', height: 0 },
      ],
    });
    expect(sc.colliders).toHaveLength(6);
    const [ts, wasm] = pair(sc);
    ts.advance(1); wasm.advance(1);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-6);
    ts.advance(20); wasm.advance(20);
    expect(wasm.report().finite).toBe(true);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-3);
  });

  it('the bending model switched between frames: the kernel takes the other stencils and their compliances', () => {
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 12;
    sc.solver = { ...sc.solver, bending: 'hinges', selfContact: false };
    const [ts, wasm] = pair(sc);
    ts.advance(10); wasm.advance(10);
    for (const sim of [ts, wasm]) { sim.set('solver.bending', 'laplacian'); sim.set('material.bendingRigidity', 1e-4); }
    ts.advance(1); wasm.advance(1);
    const log = new PhaseLog();
    (wasm.backend as WasmBackend).kernel.frame(wasm.model, wasm.state, wasm.params, FRAME_DT, log);
    expect(log.names()).toContain('bending');
    expect(log.names().some((n) => n.startsWith('bending ('))).toBe(false);
    ts.advance(1);
    expect(maxDiff(ts.state.positions, wasm.state.positions)).toBeLessThan(1e-5);
  });

  it('createState still makes plain arrays; kernel states keep theirs in the kernel memory', () => {
    const sim = new Simulation(builtinScene('custom')!, { kernel: 'ts' });
    expect(createState(sim.model).positions.buffer).not.toBe(WasmBackend.create(sim.model)!.state.positions.buffer);
    const st = WasmBackend.create(sim.model)!.state;
    expect(st.positions.buffer).toBe(st.previousPositions.buffer);
    expect([...st.positions]).toEqual([...sim.model.restPositions]);
    expect([...st.tetherAnchors].every((a) => a === -1)).toBe(true);
  });
});
