/**
 * Physics tests, run for every CPU solver and, for XPBD, both CPU kernels (TypeScript, WebAssembly). Each asserts a physical law or an invariant of the model, with a
 * tolerance that comes from the numbers (float32 round-off, discretisation), not from what the code happens to do.
 */
import { describe, expect, it } from 'vitest';
import { buildModel, type ClothModel } from '../model.js';
import { modelFor } from '../cloth-shape.js';
import { FRAME_DT, resolveParams, type SimParams } from '../params.js';
import { SceneError, validateScene, type Scene, type SolverType } from '../scene.js';
import { builtinScene, SCENE_NAMES } from '../scenes.js';
import { Simulation, type CpuKernel } from '../simulation.js';
import { copyState, createState, grab, release, setPinned, type ClothState } from '../state.js';
import { TsBackend, WasmBackend } from '../backend.js';
import { bounds, energy, maxStructuralStrain } from '../metrics.js';
import { sceneSchema } from '../scene-schema.js';

/** the scene schema's fields, read as a tree (its declared type is any JSON Schema document) */
type SchemaTree = { properties: Record<string, any> };

/**
 * The built-in scenes the random fuzz tests start from: all but fold and layers (made to pile cloth on cloth), which
 * self-contact.test.ts and cloths.test.ts hold to their own tests (in TypeScript, they cost many times the others).
 * The fuzz switches self-contact on or off at random.
 */
const FUZZ_SCENES = SCENE_NAMES.filter((name) => name !== 'fold' && name !== 'layers');

const SOLVER_TYPES: SolverType[] = ['xpbd', 'mass-spring'];
/** every solver with every CPU kernel that runs it (the WebAssembly kernel runs XPBD) */
const CASES: [SolverType, CpuKernel][] = [['xpbd', 'ts'], ['xpbd', 'wasm'], ['mass-spring', 'ts']];

function scene(name: string, edit: (s: Scene) => void = () => {}): Scene {
  const s = builtinScene(name)!;
  edit(s);
  return s;
}

describe.each(CASES)('%s solver, %s kernel', (solver, kernel) => {
  const newSim = (sc: Scene) => new Simulation(sc, { kernel });
  it('free fall matches y0 − ½gt² (Verlet with a Taylor start is exact for constant acceleration)', () => {
    // one substep per frame keeps float32 round-off (~ε·N^1.5) near 1e-4 m, while a wrong start would be off by
    // ½·g·h·t = 8 cm after 1 s
    const sim = newSim(scene('custom', (s) => { s.colliders = []; s.solver = { ...s.solver, type: solver, substeps: 1, iterations: 1 }; s.cloth.resolution = 2; }));
    const y0 = sim.state.positions[1];
    sim.advance(60);
    const exact = y0 - 0.5 * 9.81 * 1 * 1;
    for (let i = 0; i < sim.model.particleCount; i++) expect(Math.abs(sim.state.positions[3 * i + 1] - exact)).toBeLessThan(2e-4);
  });

  it.each([
    [1.2, 1], [1.2, 20], [1.2, 200], [100, 20], [300, 200], [-1000, 200], [1000, 1],
  ])('free fall at y = %d m with %d substeps matches ½gt² (float32 positions keep their residuals)', (y, substeps) => {
    // before the residuals: 7 % short at 200 substeps near the origin, 12 % long at 100 m, nothing fell at 300 m
    const sim = newSim(scene('custom', (s) => {
      s.colliders = []; s.solver = { ...s.solver, type: solver, substeps }; s.cloth.resolution = 2; s.cloth.position = [0, y, 0];
    }));
    const x = sim.state.positions, r = sim.state.residuals;
    const y0 = x[1] + r[1];
    for (const frames of [15, 45]) {
      sim.advance(frames);
      const t = sim.state.time, fell = y0 - (x[1] + r[1]);
      // what is left is the residual's own float32 rounding, 2⁻²⁴ of up to half a position's last bit per step
      // (2·10⁻¹² m at 1 km), integrated twice over up to 9000 steps: ≤ 10⁻⁵ of the fall (measured 1.8·10⁻⁶ at −1 km,
      // 200 substeps; 0 to 10⁻⁷ elsewhere). The issue asked for 0.5 %.
      expect(Math.abs(fell / (0.5 * 9.81 * t * t) - 1)).toBeLessThan(1e-5);
    }
  });

  it.each([[100, 1], [2000, 0.2], [50, 4]])('a mass on a spring (k=%d N/m, M=%d kg) keeps its period 2π√(m/k) within 1%%', (k, M) => {
    // two particles joined by one structural spring; particle 0 pinned, so the free one has m = M/2
    const model = buildModel({
      restPositions: new Float32Array([0, 0, 0, 1, 0, 0]),
      triangles: new Uint32Array(0),
      springs: [new Uint32Array([0, 1]), new Uint32Array(0), new Uint32Array(0)],
    });
    // step one substep of h = 1/1200 s at a time so zero crossings are sampled finely
    const h = FRAME_DT / 20;
    const sc = validateScene({ solver: { type: solver, substeps: 1 }, gravity: [0, 0, 0], colliders: [], material: { structuralStiffness: k, mass: M, damping: 0, stretchFactor: 2 } });
    const params = resolveParams(model, sc, h);
    expect(params.clamps).toEqual([]);
    const backend = kernel === 'wasm' ? WasmBackend.create(model)! : new TsBackend(model);
    expect(backend.kind).toBe(kernel);
    const state = backend.state;
    setPinned(state, 0, true);
    state.positions[3] = state.previousPositions[3] = 1.05;
    // XPBD is implicit-Euler-like and damps a stiff oscillator within a few periods, so time the first four
    const expected = 2 * Math.PI * Math.sqrt(M / 2 / k);
    const crossings: number[] = [];
    let prev = 0.05, t = 0;
    while (crossings.length < 9) {
      backend.frame(model, params, h);
      t += h;
      const d = state.positions[3] - 1;
      if ((prev > 0 && d <= 0) || (prev < 0 && d >= 0)) crossings.push(t - (h * d) / (d - prev));
      prev = d;
      expect(t).toBeLessThan(10 * expected); // it does oscillate
    }
    const period = (2 * (crossings[crossings.length - 1] - crossings[0])) / (crossings.length - 1);
    expect(Math.abs(period / expected - 1)).toBeLessThan(0.01);
  });

  it('pinned particles never move', () => {
    const sim = newSim(scene('pins', (s) => { s.solver.type = solver; s.cloth.resolution = 16; s.wind.enabled = true; }));
    const pinned = [...sim.state.pinned.keys()].filter((i) => sim.state.pinned[i]);
    expect(pinned.length).toBe(4);
    const before = pinned.map((i) => [...sim.state.positions.subarray(3 * i, 3 * i + 3)]);
    sim.advance(120);
    pinned.forEach((i, k) => expect([...sim.state.positions.subarray(3 * i, 3 * i + 3)]).toEqual(before[k]));
  });

  it("a hanging cotton cloth's structural strain stays under its stretch factor", () => {
    const sim = newSim(scene('cotton-basic', (s) => {
      s.solver.type = solver;
      s.cloth = { ...s.cloth, orientation: 'hanging', position: [0, 1.5, 0], resolution: 24 };
      s.colliders = [];
      s.pins = ['top-left', 'top-right'];
      // a sheet hanging from two corners never meets itself
      s.solver.selfContact = false;
    }));
    let worst = 0;
    for (let f = 0; f < 180; f++) {
      sim.advance(1);
      // (report().maxStrain, without the rest of the report each frame)
      if (f > 30) worst = Math.max(worst, maxStructuralStrain(sim.model, sim.state));
    }
    expect(sim.report().finite).toBe(true);
    // the limit is enforced by Gauss–Seidel projection: allow 0.1 percentage point of residual
    expect(worst).toBeLessThan(sim.scene.material.stretchFactor - 1 + 1e-3);
  });

  it('the wind scene with the wind off: the flag buckles out of its plane and droops from its pole', () => {
    // A flat flag in the plane of gravity can only shear in it: a cantilever shear beam, whose centroid drops
    // ρ_A·g·L²/(3G) = 1.6 cm for cotton (G = 56 N/m). A real one buckles (its lower half is in compression, and cotton
    // buckles under a few hundredths of a N/m) and hangs from the pole: measured 0.41–0.44 m in 2 s with the scene's
    // 1 mm bulge (scripts/flag-droop.mjs); exactly flat, XPBD kept it within 2.0 cm (4.2 cm after 10 s).
    const sim = newSim(scene('wind', (s) => { s.solver.type = solver; s.wind = { ...s.wind, enabled: false }; }));
    const y0 = sim.report().centroid[1];
    sim.advance(120);
    const r = sim.report();
    expect(r.finite).toBe(true);
    expect(y0 - r.centroid[1]).toBeGreaterThan(0.3);
  });

  /** cotton-basic at 20² faces on the sphere: the drop below, and the resting cloth the colliders further down move into */
  const dropOnSphere = () => newSim(scene('cotton-basic', (s) => { s.solver.type = solver; s.cloth.resolution = 20; }));
  /** the drop's state at frame 90 (draped), kept by the drop test or made here, for the collider tests to start from */
  let draped: ClothState | undefined;
  const DRAPED_AT = 90;
  const keepDraped = (sim: Simulation) => {
    if (draped) return;
    draped = createState(sim.model);
    copyState(sim.state, draped);
  };
  /**
   * A drop started from `draped`, as if it had run its first 90 frames itself: the same cloth bit for bit as one that
   * did (a CPU backend's state is its arrays; measured on all three kernels), without stepping them again for each test.
   */
  const drapedSim = () => {
    if (!draped) {
      const sim = dropOnSphere();
      sim.advance(DRAPED_AT);
      keepDraped(sim);
    }
    const sim = dropOnSphere();
    copyState(draped!, sim.state);
    sim.backend.stateChanged('all');
    sim.frame = DRAPED_AT;
    return sim;
  };

  it('a cloth dropped on the sphere comes to rest on it: penetration ≤ 1 mm, kinetic energy decaying', () => {
    const sim = dropOnSphere();
    const ke: number[] = [];
    for (let second = 0; second < 4; second++) {
      sim.advance(30);
      if (sim.frame === DRAPED_AT) keepDraped(sim);
      sim.advance(30);
      ke.push(sim.report().energy.kinetic);
    }
    const r = sim.report();
    expect(r.maxPenetration).toBeLessThanOrEqual(1e-3);
    expect(ke[3]).toBeLessThan(ke[1]);
    expect(ke[3]).toBeLessThan(1e-3 * 0.12 * 9.81); // < 0.1% of m·g·(1 m)
    expect(r.centroid[1]).toBeGreaterThan(0.4); // on the sphere (top at 0.8 m), not on the floor
  });

  it('a 1-face cloth dropped centred on the sphere rests on it (triangle contact, not only particles)', () => {
    const sim = newSim(scene('resolution', (s) => { s.solver.type = solver; s.cloth.resolution = 1; }));
    sim.advance(180);
    const r = sim.report();
    expect(r.maxPenetration).toBeLessThanOrEqual(1e-3);
    expect(r.centroid[1]).toBeGreaterThan(0.75); // sphere top at 0.8 m; falling through would end near the floor
  });

  it('wind pushes the cloth along the wind', () => {
    for (const dir of [1, -1]) {
      const sim = newSim(scene('wind', (s) => {
        s.solver.type = solver;
        s.cloth.resolution = 12;
        s.pins = ['top-edge'];
        s.wind = { ...s.wind, direction: [0, 0, dir], gusts: { ...s.wind.gusts, enabled: false } };
      }));
      const z0 = sim.report().centroid[2];
      sim.advance(90);
      expect(dir * (sim.report().centroid[2] - z0)).toBeGreaterThan(0.1);
    }
  });

  it('still air (the wind on at 0 m/s) drags a falling sheet to its terminal speed √(2ρ_A·g/ρ_air); with the air off it falls freely', () => {
    // a flat cotton sheet, no colliders: the air's drag on its 1 m², ½ρ_air·v²·A, meets its weight at v_t = 1.39 m/s,
    // and from rest v = v_t·tanh(g·t/v_t). Measured over 0.3–0.45 s, while the sheet is still nearly flat (a falling
    // sheet is unstable: its corners, which carry less of the drag, lag and it cups, 0.1–0.2 m deep by 1 s); in a
    // vacuum it would be falling at g·t = 3.7 m/s
    const fall = (air: boolean) => {
      const sim = newSim(scene('custom', (s) => {
        s.solver.type = solver; s.colliders = []; s.cloth.resolution = 8;
        s.wind = { ...s.wind, enabled: air, strength: 0, gusts: { ...s.wind.gusts, enabled: false } };
      }));
      sim.advance(18);
      const y0 = sim.report().centroid[1];
      sim.advance(9);
      return { sim, speed: (y0 - sim.report().centroid[1]) / (9 * FRAME_DT) };
    };
    const still = fall(true), vt = Math.sqrt((2 * still.sim.scene.material.arealDensity! * 9.81) / still.sim.scene.wind.airDensity);
    // the exact mean speed over the window: (v_t²/g)·ln(cosh(g·t/v_t)) between its ends, over 0.15 s
    const drop = (t: number) => ((vt * vt) / 9.81) * Math.log(Math.cosh((9.81 * t) / vt));
    // within 1 %: what is left is the sheet beginning to cup (XPBD 0.3 % fast; mass-spring, its springs held to what an
    // explicit step carries, 0.6 %)
    expect(Math.abs(still.speed / ((drop(0.45) - drop(0.3)) / 0.15) - 1)).toBeLessThan(0.01);
    expect(fall(false).speed / (9.81 * 0.375)).toBeCloseTo(1, 3);
  });

  // the elastic energy is the cloth's shape, from its positions (metrics.ts): where a solver converges, total
  // energy never grows; XPBD's sweep alone does not converge, and its unresolved stretch shows as energy
  // (docs/physics.md, "Energy"), which the coarse correction (the default) mostly removes
  it('total energy never grows without wind or grabbing (mass-spring); XPBD\'s unconverged stretch shows in it, less with the coarse correction', () => {
    /** the largest rise of the total energy from one frame to the next, over the cloth's first energy, and the last over it */
    const rises = (stretch?: 'gauss-seidel') => {
      const sim = newSim(scene('cotton-basic', (s) => { s.solver.type = solver; s.cloth.resolution = 16; if (stretch) s.solver.stretch = stretch; }));
      // (report().energy, without the rest of the report each frame)
      const total = () => { const e = energy(sim.model, sim.state, sim.params); return e.kinetic + e.gravitational + e.elastic; };
      const e0 = total();
      let prev = e0, rise = 0;
      for (let f = 0; f < 240; f++) {
        sim.advance(1);
        const e = total();
        rise = Math.max(rise, e - prev);
        prev = e;
      }
      sim.dispose();
      return { rise: rise / Math.abs(e0), last: prev / e0 };
    };
    const { rise, last } = rises();
    expect(last).toBeLessThan(1);
    // slack: contact push-out can lift a particle by what it sank within one substep (measured ≤ 1e-5·E0)
    if (solver === 'mass-spring') expect(rise).toBeLessThanOrEqual(1e-4);
    else {
      // measured in the frame the cloth lands, the stretch XPBD leaves, shown rather than hidden: 0.53·E0 with the
      // sweep alone, 0.095·E0 with the coarse correction
      const sweep = rises('gauss-seidel');
      expect(sweep.rise).toBeGreaterThan(0.3);
      expect(rise).toBeLessThan(0.3 * sweep.rise);
    }
  });

  it('a grabbed particle follows its target, and the cloth keeps its momentum when released', () => {
    // weightless free cloth: grab the middle particle and carry it up 2 cm per frame for 10 frames
    const sim = newSim(scene('custom', (s) => { s.solver.type = solver; s.cloth.resolution = 8; s.gravity = [0, 0, 0]; s.colliders = []; }));
    const p = 40; // the middle particle of the 9×9 grid
    const target: [number, number, number] = [...sim.state.positions.subarray(3 * p, 3 * p + 3)] as [number, number, number];
    for (let f = 0; f < 10; f++) {
      target[1] += 0.02;
      grab(sim.state, p, target);
      sim.advance(1);
      [0, 1, 2].forEach((k) => expect(sim.state.positions[3 * p + k]).toBeCloseTo(target[k], 5));
    }
    expect(sim.state.velocities[3 * p + 1]).toBeCloseTo(0.02 / FRAME_DT, 1); // carried at 1.2 m/s
    release(sim.state);
    const y0 = sim.report().centroid[1];
    sim.advance(10);
    expect(sim.report().centroid[1] - y0).toBeGreaterThan(0.05); // still moving up after release
    expect(sim.state.pinned[p]).toBe(0);
  });

  it('random parameter sets from the documented ranges stay finite and bounded: every scene with self-contact off, then on', () => {
    let seed = 12345;
    const rnd = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
    const range = (lo: number, hi: number, log = false) => (log ? Math.exp(Math.log(lo) + rnd() * (Math.log(hi) - Math.log(lo))) : lo + rnd() * (hi - lo));
    const mat = (sceneSchema as SchemaTree).properties.material.properties;
    // the material, solver and forces are what is random here: the mannequin's scenes (sixteen moving shapes, the
    // slowest contact there is) are left to their own tests
    const names = FUZZ_SCENES.filter((name) => name !== 'cape' && name !== 'skirt');
    // each scene twice, self-contact off and then on: every scene meets both, where 40 trials with self-contact drawn
    // at random left some pairs out (silk-drape never ran without it)
    for (let trial = 0; trial < 2 * names.length; trial++) {
      const sc = builtinScene(names[trial % names.length]);
      const substeps = Math.round(range(1, 40)), iterations = Math.round(range(1, 3));
      // (the draw that chose self-contact is still made, so that every other value is the one these trials drew then)
      rnd();
      sc.solver = { ...sc.solver, type: solver, substeps, iterations, selfContact: trial >= names.length };
      // a scene that pins particles by index (the skirt's waist) keeps its resolution: another would refuse its pins
      const resolution = Math.round(range(1, 12));
      const byIndex = [sc.pins, ...sc.colliders.map((c) => c.pins ?? [])].some((list) => list.some((p) => typeof p === 'number'));
      if (!byIndex) sc.cloth.resolution = resolution;
      sc.material = {
        structuralStiffness: range(mat.structuralStiffness.minimum, mat.structuralStiffness.maximum, true),
        shearStiffness: range(0.01, mat.shearStiffness.maximum, true),
        bendingRigidity: range(1e-8, mat.bendingRigidity.maximum, true),
        damping: range(0, mat.damping.maximum),
        mass: range(mat.mass.minimum, mat.mass.maximum, true),
        stretchFactor: range(1, 2),
        friction: range(0, 2),
        staticFriction: range(0, 2),
        scaleWithResolution: rnd() < 0.5,
      };
      sc.gravity = [range(-50, 50) * 0.2, range(-50, 50), range(-50, 50) * 0.2];
      sc.wind = { ...sc.wind, enabled: rnd() < 0.5, strength: range(0, 30), direction: [range(-1, 1), range(-1, 1), range(-1, 1)] };
      const sim = newSim(sc);
      const start = sim.report().centroid;
      const label = JSON.stringify({ trial, solver: sc.solver, res: sc.cloth.resolution, material: sc.material });
      sim.advance(30);
      const r = sim.report();
      expect(r.finite, label).toBe(true);
      const size = sim.model.size;
      for (const b of [r.bounds.min, r.bounds.max]) for (let k = 0; k < 3; k++) expect(Math.abs(b[k] - start[k]), label).toBeLessThan(50 * size);
    }
  });

  it('colliders of every shape placed at random inside, across and around the cloth: refused by name, or after 2 s a cloth near where it fell and in one piece (at rest among spheres and floors)', () => {
    let seed = 4242;
    const rnd = () => ((seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0) / 2 ** 32);
    const range = (lo: number, hi: number) => lo + rnd() * (hi - lo);
    let ran = 0, refused = 0;
    for (let trial = 0; trial < 60; trial++) {
      const sc = builtinScene(FUZZ_SCENES[trial % FUZZ_SCENES.length]);
      sc.resolutionSweep = undefined;
      sc.solver.type = solver;
      sc.solver.selfContact = rnd() < 0.5;
      sc.wind.enabled = false;
      sc.cloth.resolution = Math.round(range(2, 12));
      const c = sc.cloth.position, size = Math.max(sc.cloth.width, sc.cloth.height);
      // a floor to rest on, then every shape anywhere from inside the cloth to around it
      sc.colliders = [{ type: 'floor', height: c[1] - range(0.3, 1.5) * size }];
      const near = (): [number, number, number] => [c[0] + range(-1, 1) * size, c[1] + range(-1, 1) * size, c[2] + range(-1, 1) * size];
      const dir = (): [number, number, number] => [range(-1, 1), range(-1, 1), range(-1, 1)];
      for (let k = Math.floor(rnd() * 3); k >= 0; k--) {
        const pick = rnd();
        sc.colliders.push(pick < 0.3 ? { type: 'sphere', center: near(), radius: range(0.02, 2) * size }
          : pick < 0.4 ? { type: 'floor', height: c[1] + range(-1, 1) * size }
          // a plane tilted at most 5.7°, under every fabric's friction angle: the cloth may rest on it
          : pick < 0.5 ? { type: 'plane', point: near(), normal: [range(-0.07, 0.07), 1, range(-0.07, 0.07)] }
          : pick < 0.7 ? { type: 'box', center: near(), halfExtents: [range(0.02, 1), range(0.02, 1), range(0.02, 1)].map((v) => v * size) as [number, number, number], rotation: [range(-90, 90), range(-90, 90), range(-90, 90)] }
          : pick < 0.85 ? { type: 'capsule', a: near(), b: near(), radius: range(0.02, 0.5) * size }
          : { type: 'cylinder', center: near(), axis: dir(), radius: range(0.02, 1) * size, height: range(0.05, 2) * size });
      }
      const label = JSON.stringify({ trial, scene: sc.name, res: sc.cloth.resolution, colliders: sc.colliders });
      let sim: Simulation;
      try {
        sim = newSim(sc);
      } catch (e) {
        expect(e, label).toBeInstanceOf(SceneError);
        expect((e as Error).message, label).toMatch(/^scene '[a-z-]+': colliders\[\d\] \((sphere|floor|plane|box|capsule|cylinder)\)/);
        refused++;
        continue;
      }
      ran++;
      const start = sim.report().centroid;
      sim.advance(120);
      const r = sim.report();
      const m = sim.params.mass, g = Math.hypot(...sc.gravity);
      expect(r.finite, label).toBe(true);
      // not thrown: it stays near where it fell (sliding off a large sphere may carry it a few sizes sideways)
      expect(Math.hypot(r.centroid[0] - start[0], r.centroid[1] - start[1], r.centroid[2] - start[2]), label).toBeLessThan(5 * size);
      // nearly at rest among spheres and floors; a turned box, a tilted cap or a plane is a ramp the cloth may still
      // slide down after 2 s (seen: rubber off a cylinder's 45° cap), so there only not thrown and in one piece
      if (sc.colliders.every((k) => k.type === 'sphere' || k.type === 'floor')) expect(r.energy.kinetic, label).toBeLessThan(0.05 * m * g * size);
      expect(r.maxStrain, label).toBeLessThanOrEqual(sc.material.stretchFactor - 1 + 0.02); // in one piece
    }
    expect(ran).toBeGreaterThan(20);
    expect(refused).toBeGreaterThan(20);
  });

  it('a cloth that starts under a floor is lifted onto it at the depenetration speed, not thrown', () => {
    const sim = newSim(scene('custom', (s) => { s.solver.type = solver; s.cloth.resolution = 8; s.colliders = [{ type: 'floor', height: 1.25 }]; }));
    // 5 cm under the floor: lifted solver.depenetrationSpeed (0.25 m/s) × 1/60 s in the first frame, less gravity's pull
    const lift = sim.scene.solver.depenetrationSpeed / 60;
    sim.advance(1);
    expect(sim.report().centroid[1]).toBeGreaterThan(1.2 + lift - 0.002);
    expect(sim.report().centroid[1]).toBeLessThan(1.2 + lift + 1e-4);
    sim.advance(29);
    const r = sim.report();
    expect(r.centroid[1]).toBeCloseTo(1.25 + sim.scene.cloth.thickness, 4); // resting on it
    expect(r.energy.kinetic).toBeLessThan(1e-6);
  });

  it.each([
    ['the floor raised into the draped cloth', 'colliders[1].height', 0.6],
    ['the sphere moved sideways into it', 'colliders[0].center', [0.25, 0.5, 0.1]],
    ['the sphere moved up through it', 'colliders[0].center', [0, 0.9, 0]],
    ['the sphere grown around it', 'colliders[0].radius', 0.6],
  ])('a collider moved into a resting cloth (%s) pushes it out without throwing it', (_label, path, value) => {
    // the drop on the sphere after 90 frames (its state kept by the test above)
    const sim = drapedSim();
    sim.set(path, value);
    // pushed out (at 0.25 m/s: 27 cm sideways take 1 s), the cloth may slide off the sphere onto the floor before it
    // rests: at rest again at some 10th frame from 3.5 s to 5 s after the push (measured: by 3.2 s; since edge pairs
    // are kept h/2 apart at rest, docs/physics.md, the TypeScript kernel's cloth pushed sideways rests 2.5 s after the
    // push, slides 3 mm further down the sphere 1 s later, 2.3 mJ at its peak, and rests again 0.2 s after that)
    const rest = 1e-3 * 0.12 * 9.81;
    sim.advance(210);
    let r = sim.report();
    for (let f = 210; f < 300 && !(r.energy.kinetic < rest); f += 10) {
      sim.advance(10);
      r = sim.report();
    }
    expect(r.finite).toBe(true);
    for (let k = 0; k < 3; k++) {
      expect(r.bounds.min[k]).toBeGreaterThan(-1.5); // measured: within ±0.8 m; thrown cloths went kilometres
      expect(r.bounds.max[k]).toBeLessThan(1.5);
    }
    expect(r.energy.kinetic).toBeLessThan(rest); // at rest again
    expect(r.maxStrain).toBeLessThanOrEqual(sim.scene.material.stretchFactor - 1 + 2e-3); // in one piece
  });

  it('a sphere grown at once under draped rubber lifts it onto its new top without a slingshot', () => {
    // the overlap is undone at solver.depenetrationSpeed; counted as pressure, it gave the rubber static friction
    // that held it while the sphere stretched it, released as a throw when the overlap closed (measured above the
    // new top: 34–39 cm at the old default 1 m/s; now 1.5 mm on XPBD, 12 mm mass-spring)
    const sim = newSim(scene('rubber-stretch', (s) => { s.solver.type = solver; s.solver.selfContact = false; s.cloth.resolution = 24; }));
    sim.advance(120);
    const radius = 0.36;
    sim.set('colliders[0].radius', radius);
    const top = sim.scene.colliders[0].type === 'sphere' ? sim.scene.colliders[0].center[1] + radius + sim.scene.cloth.thickness : NaN;
    let highest = -Infinity;
    for (let f = 0; f < 60; f++) {
      sim.advance(1);
      highest = Math.max(highest, bounds(sim.state).max[1]); // (report().bounds, without the rest of the report each frame)
    }
    expect(highest).toBeGreaterThan(top - 2e-3); // lifted onto the new top
    expect(highest - top).toBeLessThan(0.025);
    expect(sim.report().energy.kinetic).toBeLessThan(1e-3 * 0.12 * 9.81);
  });
});

describe.each(['ts', 'wasm'] as const)('XPBD with several passes per substep, %s kernel', (kernel) => {
  // a 30 cm cotton square clamped over its middle 18 cm, bending at the hinges (solved together), its springs swept:
  // with 40 substeps of 16 passes, λ that left the damping's share out of each pass blew it up within half a
  // second (elastic energy 4.6 J, the skirt 2 cm above the clamp, threads 7 % long: docs/physics.md "Three
  // specimens"); with the whole Δλ in λ it hangs, its springs nearer their rest length than one pass leaves them
  const clamped = (iterations: number) => new Simulation(validateScene({
    name: 'clamped square', cloth: { width: 0.3, height: 0.3, resolution: 32, position: [0, 0.506, 0] },
    material: { fabric: 'cotton' }, pins: [{ min: [-0.09, 0.4, -0.09], max: [0.09, 0.6, 0.09] }], colliders: [],
    solver: { bending: 'hinges', bendingSolve: 'global', stretch: 'gauss-seidel', substeps: 40, iterations },
    wind: { enabled: true, strength: 0 },
  }), { kernel });
  it('a damped cloth clamped over its middle hangs below its clamp, less strained than with one pass', () => {
    const one = clamped(1), many = clamped(16);
    one.advance(30); many.advance(30);
    const a = one.report(), b = many.report();
    expect(b.finite).toBe(true);
    expect(b.bounds.max[1]).toBeLessThanOrEqual(0.506 + 1e-5);
    expect(b.energy.elastic).toBeLessThan(a.energy.elastic);
    expect(b.maxStrain).toBeLessThan(a.maxStrain);
    one.dispose(); many.dispose();
  });
});

describe('scene behaviour shared by both solvers', () => {
  it('every built-in scene runs finite with both solvers and both kernels', () => {
    for (const name of SCENE_NAMES) for (const [solver, kernel] of CASES) {
      const sim = new Simulation(scene(name, (s) => {
        s.solver.type = solver;
        // every cloth of the scene (the first is s.cloth itself)
        for (const c of [s.cloth, ...(s.cloths ?? []).map((e) => e.cloth)]) c.resolution = Math.min(c.resolution, 12);
      }), { kernel });
      expect(sim.kernel).toBe(kernel);
      sim.advance(30);
      expect(sim.report().finite, `${name}/${solver}/${kernel}`).toBe(true);
    }
  });
});

describe('the mass-spring stability limit is local (params.ts limitPerSpring)', () => {
  const hanging = (material: object, substeps = 20) => validateScene({
    solver: { type: 'mass-spring', substeps }, colliders: [], cloth: { resolution: 16, orientation: 'hanging' }, material,
  });
  /** the stiffness each spring would have without a limit: the same scene solved with xpbd, which has none */
  const unlimited = (model: ClothModel, sc: Scene) => resolveParams(model, { ...sc, solver: { ...sc.solver, type: 'xpbd', bending: 'springs' } }).stiffness;
  const touches = (model: ClothModel, s: number, set: (i: number) => boolean) => set(model.springs[2 * s]) || set(model.springs[2 * s + 1]);
  /** largest eigenvalue of M⁻¹K at rest, by power iteration (the matrix is similar to a symmetric one, so it converges) */
  const largestEigenvalue = (model: ClothModel, invMass: Float32Array, k: Float32Array) => {
    const n = model.particleCount, x0 = model.restPositions;
    let v = new Float64Array(3 * n).map((_, i) => Math.sin(1.7 * i + 0.3)), lambda = 0;
    for (let it = 0; it < 2000; it++) {
      const y = new Float64Array(3 * n);
      for (let s = 0; s < k.length; s++) {
        const a = model.springs[2 * s], b = model.springs[2 * s + 1];
        const d = [0, 1, 2].map((c) => x0[3 * a + c] - x0[3 * b + c]), len = Math.hypot(...d);
        const dot = [0, 1, 2].reduce((t, c) => t + (d[c] / len) * (v[3 * a + c] - v[3 * b + c]), 0);
        for (let c = 0; c < 3; c++) { y[3 * a + c] += k[s] * dot * d[c] / len; y[3 * b + c] -= k[s] * dot * d[c] / len; }
      }
      for (let i = 0; i < n; i++) for (let c = 0; c < 3; c++) y[3 * i + c] *= invMass[i];
      const norm = Math.hypot(...y);
      lambda = norm / Math.hypot(...v);
      v = y.map((e) => e / norm);
    }
    return lambda;
  };
  /** hang the cloth from its top corners for 4 s and return the fastest speed of the given particles at the end */
  const hangAndMeasure = (model: ClothModel, params: SimParams, watch: number[]) => {
    const backend = new TsBackend(model);
    setPinned(backend.state, 0, true);
    setPinned(backend.state, 16, true);
    for (let f = 0; f < 240; f++) backend.frame(model, params, FRAME_DT);
    const v = backend.state.velocities;
    expect(v.every(Number.isFinite)).toBe(true);
    return Math.max(...watch.map((i) => Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2])));
  };

  it('one light particle limits only its own springs, and the cloth stays stable; at full stiffness it would not', () => {
    const sc = hanging({ arealDensity: 0.2, structuralStiffness: 50, shearStiffness: 5, bendingRigidity: 1e-6, damping: 0.01 });
    const base = modelFor(sc);
    const light = 8 * 17 + 8; // the middle particle, at 1/100 of its mass
    const w = Float32Array.from(base.massWeights);
    w[light] /= 100;
    const model: ClothModel = { ...base, massWeights: w };
    const params = resolveParams(model, sc), full = unlimited(model, sc);
    const atLight = (i: number) => i === light;
    let limited = 0;
    for (let s = 0; s < full.length; s++) {
      if (touches(model, s, atLight)) { expect(params.stiffness[s]).toBeLessThan(0.1 * full[s]); limited++; }
      else expect(params.stiffness[s], `spring ${s}`).toBe(full[s]); // every other spring at full stiffness
    }
    expect(limited).toBe(12); // 4 structural, 4 shear, 4 bend
    expect(params.clamps[0]).toMatch(/^mass-spring at 20 substeps: 12 of 1566 springs are too stiff for so long a time step and were softened, the most to \d\.?\d* % of their stiffness \(structural [\d.]+ of 45\.5 N\/m; shear \d\.?\d* %; bend [\d.e-]+ %\) — at full stiffness these explicit springs would overshoot and blow up\. For the full stiffness: more substeps \(solver\.substeps\), or the xpbd solver$/);
    // the step's bound: h²·λ_max(M⁻¹K) ≤ 2 (Gershgorin), Verlet's limit being 4 (measured 0.50)
    const h = FRAME_DT / 20;
    expect(h * h * largestEigenvalue(model, params.particleInvMass, params.stiffness)).toBeLessThanOrEqual(2);
    // hanging, the light particle comes to rest (measured 5 mm/s after 4 s) ...
    expect(hangAndMeasure(model, params, [light])).toBeLessThan(0.05);
    // ... where its springs at full stiffness (h²·λ_max = 9.8) shake it at metres per second (measured 10.7 m/s)
    expect(h * h * largestEigenvalue(model, params.particleInvMass, full)).toBeGreaterThan(4);
    expect(hangAndMeasure(model, { ...params, stiffness: full }, [light])).toBeGreaterThan(1);
  });

  it('a cloth at few substeps limits its edge springs only, the interior keeps its full stiffness, and it hangs still', () => {
    // rubber at 16² and 25 substeps: the interior's w·Σk is just under 1/h², the lighter-loaded edges are over it
    const sc = hanging({ fabric: 'rubber' }, 25);
    const model = modelFor(sc), params = resolveParams(model, sc), full = unlimited(model, sc);
    const edge = (i: number) => i % 17 === 0 || i % 17 === 16 || i < 17 || i >= 16 * 17;
    let limited = 0, kept = 0;
    for (let s = 0; s < full.length; s++) {
      if (params.stiffness[s] < full[s]) { limited++; expect(touches(model, s, edge), `spring ${s}`).toBe(true); }
      if (!touches(model, s, edge)) { expect(params.stiffness[s]).toBe(full[s]); kept++; }
    }
    expect(limited).toBeGreaterThan(0);
    expect(kept).toBeGreaterThan(0.7 * full.length);
    expect(params.clamps[0]).toContain(`mass-spring at 25 substeps: ${limited} of ${full.length} springs are too stiff`);
    const h = FRAME_DT / 25; // measured h²·λ_max = 1.18
    expect(h * h * largestEigenvalue(model, params.particleInvMass, params.stiffness)).toBeLessThanOrEqual(2);
    // still swinging slowly on its corners after 4 s (measured 0.068 m/s at most), not shaking apart
    const all = [...Array(model.particleCount).keys()];
    expect(hangAndMeasure(model, params, all)).toBeLessThan(0.2);
  });

  it('the damping limit is local too: a light particle lowers its own springs\' damping only', () => {
    // 0.02 N·s/m: h·w_i·Σc = 0.34 at an edge particle, 0.43 at a corner, 25 at the light one
    const sc = hanging({ arealDensity: 0.2, structuralStiffness: 50, shearStiffness: 5, bendingRigidity: 1e-6, damping: 0.02 });
    const base = modelFor(sc);
    const light = 8 * 17 + 8;
    const w = Float32Array.from(base.massWeights);
    w[light] /= 100;
    const model: ClothModel = { ...base, massWeights: w };
    const params = resolveParams(model, sc);
    const h = FRAME_DT / 20;
    for (let s = 0; s < model.restLengths.length; s++) {
      if (touches(model, s, (i) => i === light)) expect(params.springDamping[s]).toBeLessThan(0.002);
      else expect(params.springDamping[s]).toBe(0.02);
    }
    // at every particle h·w_i·Σc ≤ ½
    const sum = new Float64Array(model.particleCount);
    for (let s = 0; s < model.restLengths.length; s++) { sum[model.springs[2 * s]] += params.springDamping[s]; sum[model.springs[2 * s + 1]] += params.springDamping[s]; }
    for (let i = 0; i < model.particleCount; i++) expect(h * params.particleInvMass[i] * sum[i]).toBeLessThanOrEqual(0.5 * (1 + 1e-9));
    expect(params.clamps.some((c) => c.startsWith('mass-spring at 20 substeps: the damping is too strong for so long a time step on 12 of 1566 springs'))).toBe(true);
  });
});

/**
 * A step must not add energy to a cloth in fast motion. A 1 m sheet (16 faces) hung by one corner and let go 60° out
 * of the vertical swings through a large, fast turn; with no wind and no grab nothing feeds it, so its kinetic plus
 * gravitational energy can only fall below where it started (the elastic energy, ≥ 0, takes the rest). Every solver
 * setting, on both CPU kernels. A prototype that took the springs' directions from a sweep and then held them with a
 * pass in one matrix reached 11 J here from a start of 1.8 J (docs/physics.md, "The sweep, the bending, then one pass
 * of both in one matrix"); static and slow checks (the cantilever, a hanging sheet, free fall) did not show it. Nor did
 * they for a coarse Gauss–Newton correction of the positions, which reached 10 J within a fifth of a second ("A coarse
 * correction of the multipliers").
 */
describe('no solver setting adds energy to a cloth swinging from one corner', () => {
  const SETTINGS: [SolverType, string, string, string][] = [
    ['xpbd', 'gauss-seidel', 'springs', 'gauss-seidel'], ['xpbd', 'global', 'springs', 'gauss-seidel'],
    ['xpbd', 'gauss-seidel', 'hinges', 'gauss-seidel'], ['xpbd', 'gauss-seidel', 'hinges', 'global'],
    ['xpbd', 'global', 'hinges', 'global'], ['xpbd', 'gauss-seidel', 'laplacian', 'global'],
    ['xpbd', 'two-level', 'springs', 'gauss-seidel'], ['xpbd', 'two-level', 'hinges', 'global'], ['mass-spring', 'gauss-seidel', 'springs', 'gauss-seidel'],
  ];
  const CASES = SETTINGS.flatMap((s) => (s[0] === 'xpbd' ? (['ts', 'wasm'] as CpuKernel[]) : (['ts'] as CpuKernel[])).map((k) => [...s, k] as const));
  it.each(CASES)('%s, stretch %s, bending %s solved %s, %s kernel: kinetic + gravitational energy never above its start', (type, stretch, bending, bendingSolve, kernel) => {
    const sim = new Simulation(validateScene({
      cloth: { orientation: 'hanging', resolution: 16, position: [0, 1.5, 0], rotation: [60, 0, 0] },
      material: { fabric: 'cotton' }, solver: { type, stretch, bending, bendingSolve }, colliders: [], pins: ['top-left'],
    }), { kernel });
    const mechanical = () => { const e = energy(sim.model, sim.state, sim.params); return e.kinetic + e.gravitational; };
    const e0 = mechanical();
    let most = -Infinity;
    for (let f = 0; f < 120; f++) {
      sim.advance(1);
      most = Math.max(most, mechanical() - e0);
    }
    // measured: at most −1.0·10⁻⁴ J (xpbd) and −8.4·10⁻⁵ J (mass-spring) from the start of 1.77 J, from the first frame on
    expect(most).toBeLessThanOrEqual(0);
    sim.dispose();
  });
});
