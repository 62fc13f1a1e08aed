/**
 * Several cloths in one scene (`cloths`): the document form, the merged model, each cloth's material, pins and
 * contact values, and cloth–cloth contact through self-contact, on both CPU kernels.
 */
import { describe, expect, it } from 'vitest';
import {
  FABRICS, PHASE, PhaseLog, SceneError, Simulation, builtinScene, clothEntries, countIntersections, perClothRefusal,
  sceneDocument, setScenePath, validateScene, type Scene, type WasmBackend,
} from './index.js';

/** Two square cloths stacked over a sphere of radius 0.5 at the origin (the top one smaller and turned). */
function stacked(selfContact: boolean, resolution = 12): Scene {
  return validateScene({
    name: 'stacked',
    solver: { selfContact },
    colliders: [{ type: 'sphere', center: [0, 0, 0], radius: 0.5 }],
    cloths: [
      { name: 'under', cloth: { resolution, position: [0, 0.6, 0] }, material: { fabric: 'leather' } },
      { name: 'over', cloth: { resolution, width: 0.6, height: 0.6, position: [0, 0.75, 0], rotation: [0, 30, 0] }, material: { fabric: 'silk' } },
    ],
  });
}

/** The highest point of cloth c now [m]. */
function top(sim: Simulation, c: number): number {
  const x = sim.state.positions, s = sim.model.clothStarts;
  let y = -Infinity;
  for (let i = s[c]; i < s[c + 1]; i++) y = Math.max(y, x[3 * i + 1]);
  return y;
}

describe('a scene of several cloths: the document', () => {
  it('validates each cloth with its own defaults and fabric, and keeps the first as cloth, material and pins', () => {
    const s = stacked(true);
    expect(s.cloths).toHaveLength(2);
    expect(s.cloth).toBe(s.cloths![0].cloth);
    expect(s.material.bendingRigidity).toBe(FABRICS.leather.bendingRigidity);
    expect(s.cloths![1].material.bendingRigidity).toBe(FABRICS.silk.bendingRigidity);
    expect(s.cloths![1].cloth.thickness).toBe(0.005);
    expect(s.cloths![1].pins).toEqual([]);
  });

  it('is written back as a list (no top-level cloth) and validates to itself; a one-cloth scene keeps its form', () => {
    const s = stacked(true);
    const doc = sceneDocument(s);
    expect(Object.keys(doc)).not.toContain('cloth');
    expect(Object.keys(doc)).not.toContain('material');
    expect(Object.keys(doc)).not.toContain('pins');
    const again = validateScene(JSON.parse(JSON.stringify(doc)));
    expect(sceneDocument(again)).toEqual(doc);
    const one = builtinScene('cotton-basic');
    expect(sceneDocument(one)).toEqual({ ...one });
    expect(clothEntries(one)).toHaveLength(1);
  });

  it('refuses both forms at once, and names a field inside a cloth by its place in the list', () => {
    expect(() => validateScene({ cloth: { resolution: 8 }, cloths: [{}] })).toThrow(/scene: cloth: give the cloths either as cloth, material and pins or as a list cloths, not both/);
    expect(() => validateScene({ cloths: [{}, { cloth: { resolution: 5000 } }] })).toThrow(/cloths\[1\]\.cloth\.resolution: must be <= 1024/);
    expect(() => validateScene({ cloths: [{}, { material: { mass: 1, arealDensity: 0.2 } }] })).toThrow(/cloths\[1\]\.material\.arealDensity: give either cloths\[1\]\.material\.mass or/);
    expect(() => validateScene({ cloths: [{}, { pins: ['nowhere'] }] })).toThrow(/cloths\[1\]\.pins\[0\]: must be one of/);
    expect(() => validateScene({ cloths: [{}, { pins: [5000] }] })).toThrow(/cloths\[1\]\.pins\[0\]: particle 5000 does not exist/);
    expect(() => validateScene({ cloths: Array.from({ length: 9 }, () => ({})) })).toThrow(/cloths: must NOT have more than 8 items/);
    expect(() => validateScene({ cloths: [{}, {}], colliders: [{ type: 'floor', height: 0, pins: ['top-left'] }] })).toThrow(/colliders\[0\]\.pins\[0\]: in a scene of several cloths, pin a collider's particles by region or by index/);
  });

  it('--set paths name a cloth of the list; a named fabric puts that cloth\'s fields back; the one-cloth paths say where to look', () => {
    const s = stacked(true);
    const t = setScenePath(s, 'cloths[1].material.fabric', 'leather');
    expect(t.cloths![1].material.bendingRigidity).toBe(FABRICS.leather.bendingRigidity);
    expect(t.material.bendingRigidity).toBe(FABRICS.leather.bendingRigidity);
    const u = setScenePath(s, 'cloths[0].cloth.resolution', 7);
    expect(u.cloth.resolution).toBe(7);
    expect(u.cloths![1].cloth.resolution).toBe(12);
    expect(() => setScenePath(s, 'material.friction', 0.1, '--set material.friction')).toThrow('--set material.friction: this scene has a list of cloths; name one: cloths[0].material.friction');
    expect(() => setScenePath(s, 'cloths[2].material.friction', 0.1, '--set x')).toThrow(/cloths has 2 items, no item 2/);
    // and a one-cloth scene's paths are the cloth's own
    expect(() => setScenePath(validateScene({}), 'cloths[0].material.mass', 1, '--set cloths.0.material.mass')).toThrow('--set cloths.0.material.mass: this scene has one cloth, not a list of cloths: material.mass');
    expect(() => setScenePath(validateScene({}), 'cloths[1]', {}, '--set cloths.1')).toThrow('--set cloths.1: this scene has one cloth, not a list of cloths: cloth.…, material.… and pins');
  });
});

describe('a scene of several cloths: the model and its params', () => {
  it('numbers the particles through the cloths in order, each with its own mass, stiffness and pins', () => {
    const s = setScenePath(setScenePath(stacked(false), 'cloths[1].pins', ['top-left']), 'cloths[0].pins', ['bottom-right']);
    const sim = new Simulation(s, { kernel: 'ts' });
    const { model, params } = sim;
    expect(Array.from(model.clothStarts)).toEqual([0, 169, 338]);
    expect(model.triangles.length / 3).toBe(2 * 288);
    // each cloth weighs its areal density × its area
    const mass = (c: number) => params.particleMass.slice(model.clothStarts[c], model.clothStarts[c + 1]).reduce((a, b) => a + b, 0);
    expect(mass(0)).toBeCloseTo(FABRICS.leather.arealDensity * 1, 6);
    expect(mass(1)).toBeCloseTo(FABRICS.silk.arealDensity * 0.36, 6);
    expect(params.mass).toBeCloseTo(mass(0) + mass(1), 6);
    // a structural spring of each cloth has its fabric's stiffness (the axis springs: a share of it)
    const k = (c: number) => {
      for (let s2 = 0; s2 < model.restLengths.length; s2++) {
        const a = model.springs[2 * s2];
        if (model.springKinds[s2] === 0 && a >= model.clothStarts[c] && a < model.clothStarts[c + 1]) return params.stiffness[s2];
      }
      return NaN;
    };
    expect(k(0)).toBeGreaterThan(0.9 * FABRICS.leather.structuralStiffness * 0.5);
    expect(k(1)).toBeLessThan(FABRICS.silk.structuralStiffness);
    // each cloth's pins count from its own first particle: leather's bottom-right is 168, silk's top-left 169 + 0
    expect(Array.from(sim.state.pinned.keys()).filter((i) => sim.state.pinned[i])).toEqual([168, 169]);
    // contact values by cloth
    expect(Array.from(params.perCloth.friction)).toEqual([FABRICS.leather.friction, FABRICS.silk.friction]);
    expect(params.owner[168]).toBe(0);
    expect(params.owner[169]).toBe(1);
  });

  it('a kernel that reads one value for the model leaves the phases the cloths differ in to the reference', () => {
    const differ = new Simulation(stacked(false), { kernel: 'ts' }).params;
    expect(perClothRefusal(PHASE.contact, differ)).toBe("the scene's cloths differ in material.friction");
    expect(perClothRefusal(PHASE.distance, differ)).toBe("the scene's cloths differ in material.damping");
    expect(perClothRefusal(PHASE.integrate, differ)).toBeNull();
    const same = new Simulation(setScenePath(stacked(false), 'cloths[1].material.fabric', 'leather'), { kernel: 'ts' }).params;
    expect(perClothRefusal(PHASE.contact, same)).toBeNull();
    // the kernel runs contact itself where the cloths agree, and leaves it to TypeScript where they do not
    for (const [scene, who] of [[stacked(false), 'reference'], [setScenePath(stacked(false), 'cloths[1].material.fabric', 'leather'), 'kernel']] as const) {
      const sim = new Simulation(scene, { kernel: 'wasm' });
      const backend = sim.backend as WasmBackend, log = new PhaseLog();
      backend.kernel.frame(sim.model, sim.state, sim.params, 1 / 60, log);
      const k = Array.from(log.ids.subarray(0, log.length)).indexOf(PHASE.contact);
      expect(k).toBeGreaterThanOrEqual(0);
      expect(log.byReference[k] ? 'reference' : 'kernel').toBe(who);
      sim.dispose();
    }
  });
});

describe.each(['ts', 'wasm'] as const)('several cloths in one scene (%s kernel)', (kernel) => {
  it('with self-contact the upper cloth lands on the lower one and stays on it: no crossing at any 10th frame of 1.5 s', () => {
    const sim = new Simulation(stacked(true), { kernel });
    for (let f = 1; f <= 90; f++) {
      sim.advance(1);
      if (f % 10 === 0) expect(countIntersections(sim.model.triangles, sim.state.positions), `frame ${f}`).toBe(0);
    }
    expect(sim.report().finite).toBe(true);
    // stacked on the sphere's top: leather within two thicknesses of it (a stiff sheet tents), silk a thickness (the
    // mean of 5 mm and 5 mm) above it
    const under = top(sim, 0), over = top(sim, 1);
    expect(under).toBeGreaterThan(0.5);
    expect(under).toBeLessThan(0.5 + 2 * 0.005);
    expect(over - under).toBeGreaterThan(0.8 * 0.005);
    expect(over - under).toBeLessThan(2 * 0.005);
    sim.dispose();
  });

  it('without it the upper cloth falls through the lower one (what the test above would catch)', () => {
    const sim = new Simulation(stacked(false), { kernel });
    sim.advance(90);
    expect(top(sim, 1) - top(sim, 0)).toBeLessThan(0.002);
    sim.dispose();
  });

  it('each cloth has its own friction: on a 26.6° ramp (tan θ = 0.5) rubber (μs 1.0) stays and silk (μs 0.25) slides', () => {
    const scene = validateScene({
      name: 'ramp',
      // the ramp falls towards +z; the two cloths lie side by side on it, 5 mm above its surface
      colliders: [{ type: 'plane', point: [0, 0, 0], normal: [0, 1, 0.5] }],
      cloths: [
        { name: 'rubber', cloth: { resolution: 6, width: 0.3, height: 0.3, position: [-0.3, 0.0045 * Math.sqrt(5) / 2 + 0.001, 0], rotation: [26.565, 0, 0] }, material: { fabric: 'rubber' } },
        { name: 'silk', cloth: { resolution: 6, width: 0.3, height: 0.3, position: [0.3, 0.0045 * Math.sqrt(5) / 2 + 0.001, 0], rotation: [26.565, 0, 0] }, material: { fabric: 'silk' } },
      ],
    });
    const sim = new Simulation(scene, { kernel });
    const start = sim.report().cloths!.map((c) => c.centroid[2]);
    sim.advance(60);
    const moved = sim.report().cloths!.map((c, k) => c.centroid[2] - start[k]);
    expect(moved[0]).toBeLessThan(0.005);
    expect(moved[1]).toBeGreaterThan(0.1);
    sim.dispose();
  });
});

describe('the built-in scenes of several cloths', () => {
  it('layers: three fabrics stacked on the sphere, each on the one below, no crossing at any 10th frame of 2 s', () => {
    const scene = builtinScene('layers');
    expect(clothEntries(scene).map((e) => e.material.fabric)).toEqual(['leather', 'cotton', 'silk']);
    const sim = new Simulation(scene, { kernel: 'wasm' });
    for (let f = 10; f <= 120; f += 10) {
      sim.advance(10);
      expect(countIntersections(sim.model.triangles, sim.state.positions), `frame ${f}`).toBe(0);
    }
    const r = sim.report();
    expect(r.finite).toBe(true);
    expect(r.cloths!.map((c) => c.name)).toEqual(['leather', 'cotton', 'silk']);
    const tops = [0, 1, 2].map((c) => top(sim, c));
    expect(tops[1]).toBeGreaterThan(tops[0]);
    expect(tops[2]).toBeGreaterThan(tops[1]);
    sim.dispose();
  });

  it('a one-entry list is the same cloth as the one-cloth form', () => {
    const one = builtinScene('cotton-basic');
    const { cloth: _c, material: _m, pins: _p, ...rest } = sceneDocument(one);
    const listed = validateScene({ ...rest, cloths: [{ cloth: one.cloth, material: { fabric: 'cotton' }, pins: one.pins }] });
    const a = new Simulation(one, { kernel: 'ts' }), b = new Simulation(listed, { kernel: 'ts' });
    a.advance(30); b.advance(30);
    expect(Array.from(b.state.positions)).toEqual(Array.from(a.state.positions));
  });

  it('a scene error inside a cloth of the list is a SceneError', () => {
    expect(() => validateScene({ cloths: [{ cloth: { shape: 'mesh' } }] })).toThrow(SceneError);
  });
});

describe.each(['ts', 'wasm'] as const)('a cloth added or taken out of a running scene (setScene with carry), %s kernel', (kernel) => {
  it('the cloths kept go on where they were, as they were moving, the clock with them; the new one from its start pose', async () => {
    const sim = new Simulation(stacked(true, 6), { kernel });
    await sim.whenReady();
    sim.advance(20);
    const doc = sceneDocument(sim.scene) as { cloths: object[] };
    const before = { x: sim.state.positions.slice(), v: sim.state.velocities.slice(), time: sim.state.time, frame: sim.frame };
    const n = sim.model.particleCount;
    // a third cloth added after the two: they keep their particle numbers
    const third = { name: 'third', cloth: { resolution: 4, width: 0.3, height: 0.3, position: [0, 1.5, 0] } };
    expect(sim.setScene({ ...doc, cloths: [...doc.cloths, third] }, [{ from: 0, to: 0, count: n }])).toBe(true);
    expect(Array.from(sim.state.positions.subarray(0, 3 * n))).toEqual(Array.from(before.x));
    expect(Array.from(sim.state.velocities.subarray(0, 3 * n))).toEqual(Array.from(before.v));
    expect([sim.state.time, sim.frame]).toEqual([before.time, before.frame]);
    expect(Math.min(...sim.state.positions.subarray(3 * n).filter((_, k) => k % 3 === 1))).toBeCloseTo(1.5, 6);
    // and going on from there: the first cloth as a simulation that never had the third (which falls far above it)
    const alone = new Simulation(stacked(true, 6), { kernel });
    await alone.whenReady();
    alone.advance(21);
    sim.advance(1);
    const under = sim.model.clothStarts[1];
    for (let i = 0; i < 3 * under; i++) expect(Math.abs(sim.state.positions[i] - alone.state.positions[i])).toBeLessThan(1e-6);

    // the first cloth taken out: the others move down to start at particle 0
    const over = sim.model.clothStarts[2] - under;
    const kept = sim.state.positions.slice(3 * under);
    expect(sim.setScene({ ...doc, cloths: [doc.cloths[1], third] }, [{ from: under, to: 0, count: sim.model.particleCount - under }])).toBe(true);
    expect(sim.model.particleCount).toBe(over + 25);
    expect(Array.from(sim.state.positions)).toEqual(Array.from(kept));
    // a range outside either cloth is refused, naming it, and nothing changes
    expect(() => sim.setScene(doc, [{ from: 0, to: 0, count: 10_000 }])).toThrow(/^Simulation\.setScene: carry \{"from":0,"to":0,"count":10000\} is outside the old cloth/);
    expect(sim.model.particleCount).toBe(over + 25);
    expect(sim.scene.cloths!.map((c) => c.name)).toEqual(['over', 'third']);
    sim.dispose();
    alone.dispose();
  });
});
