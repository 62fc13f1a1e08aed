/**
 * The WebAssembly XPBD kernel on several threads (Node worker threads over a shared memory): every spring is solved
 * by exactly the same arithmetic whichever thread takes it, so the cloth is bit-for-bit the 1-thread cloth.
 */
import { availableParallelism } from 'node:os';
import { describe, expect, it } from 'vitest';
import { builtinScene, grab, release, Simulation, validateScene, WasmBackend, type HelperSpawner, type Scene } from '../core/index.js';
import { spawnNodeHelper } from './threads.js';

function scene(): Scene {
  // wind (TypeScript phase), pins (tethers), sphere + floor (kernel contact) and a grab of a particle in the
  // second thread's run (particles 1024… of 41² = 1681), 41² particles
  const sc = builtinScene('wind')!;
  sc.cloth.resolution = 40;
  // the flag blows onto this sphere, 2 cm behind it at the start (thousands of particle contacts in 40 frames, in
  // the kernel: a sphere this large needs no triangle contact at this mesh size)
  sc.colliders = [{ type: 'sphere', center: [0.2, 1.6, 0.62], radius: 0.6 }, { type: 'floor', height: 0 }];
  return sc;
}

/**
 * Steps `sc` for `frames` frames on one thread and on two (every frame with the helper), then `compare`s the two
 * cloths; the two-thread one never ran a frame alone and stays finite.
 */
async function sideBySide(sc: Scene, frames: number, compare: (one: Simulation, many: Simulation) => void): Promise<void> {
  const one = new Simulation(sc, { kernel: 'wasm', threads: 1 });
  const many = new Simulation(sc, { kernel: 'wasm', threads: 2, spawnHelper: spawnNodeHelper });
  try {
    await many.whenReady();
    (many.backend as WasmBackend).kernel.mode.hold(true);
    for (let f = 0; f < frames; f++) { one.advance(1); many.advance(1); }
    expect((many.backend as WasmBackend).kernel.mode.framesAlone).toBe(0);
    compare(one, many);
    expect(many.report().finite).toBe(true);
  } finally {
    many.dispose();
  }
}

// threads need a second core to mean anything (CI machines have 2)
describe.skipIf(availableParallelism() < 2)('kernel threads', () => {
  it.each([['spinning briefly before they sleep', 32768], ['sleeping at every wait (the path of a busy machine)', 0]])('2 threads give the same cloth as 1, bit for bit, %s', async (_label, spins) => {
    const threads = 2;
    const one = new Simulation(scene(), { kernel: 'wasm', threads: 1 });
    const many = new Simulation(scene(), { kernel: 'wasm', threads, spawnHelper: spawnNodeHelper });
    try {
      await many.whenReady();
      expect(many.threads).toBe(threads);
      (many.backend as WasmBackend).kernel.spinLimit = spins;
      (many.backend as WasmBackend).kernel.mode.hold(true); // every frame with the helper, however slow sleeping makes it
      expect(many.state.positions.buffer).toBeInstanceOf(SharedArrayBuffer);
      for (let f = 0; f < 40; f++) {
        // a drag of 15 cm in a frame (9 m/s, a quick hand): a teleport across the flag would tangle it, and a
        // tangled cloth's self-contact costs ~40× a frame (1 s at 41²) without testing the threads any better
        if (f === 10) {
          const x = one.state.positions, p = 3 * 1500, to: [number, number, number] = [x[p], x[p + 1] + 0.15, x[p + 2]];
          for (const s of [one, many]) grab(s.state, 1500, to);
        }
        if (f === 20) for (const s of [one, many]) release(s.state);
        one.advance(1);
        many.advance(1);
      }
      expect((many.backend as WasmBackend).kernel.mode.framesAlone).toBe(0);
      expect([...many.state.positions]).toEqual([...one.state.positions]);
      expect([...many.state.velocities]).toEqual([...one.state.velocities]);
      expect(many.report().finite).toBe(true);
    } finally {
      many.dispose();
    }
  });

  it('every analytic shape, moving, under one cloth: 2 threads give the same cloth as 1, bit for bit', async () => {
    // 41² particles (two chunks of the contact phase) 2 mm above six shapes whose tops are at 0.8 m, each moving
    // into the cloth and turning from the start (the kernel's records written per substep, read by both threads)
    const motion = { keyframes: [{ time: 0 }, { time: 1, translation: [0.3, 0.3, 0.1], rotation: [0, 40, 10] }] };
    const sc = validateScene({
      name: 'shapes',
      cloth: { resolution: 40, width: 2, height: 2, position: [0, 0.802, 0] },
      solver: { type: 'xpbd' },
      colliders: [
        { type: 'sphere', center: [-0.6, 0.6, -0.5], radius: 0.2 },
        { type: 'plane', point: [0, 0.3, 0], normal: [0.02, 1, 0.01] },
        { type: 'box', center: [0, 0.6, -0.5], halfExtents: [0.2, 0.2, 0.2], rotation: [0, 30, 0] },
        { type: 'capsule', a: [0.4, 0.7, -0.5], b: [0.8, 0.7, -0.45], radius: 0.1 },
        { type: 'cylinder', center: [-0.4, 0.6, 0.5], axis: [1, 0, 0.1], radius: 0.2, height: 0.5 },
        { type: 'floor', height: 0.2 },
      ].map((c) => ({ ...c, motion })),
    });
    await sideBySide(sc, 15, (one, many) => {
      expect([...many.state.positions]).toEqual([...one.state.positions]);
      expect([...many.state.velocities]).toEqual([...one.state.velocities]);
    });
  });

  it.each(['hinges', 'laplacian'] as const)('bending on the %s stencils (chunks of a colour batch on both threads): 2 threads give the same cloth as 1, bit for bit', async (bending) => {
    // 41² particles on the sphere: each colour batch of the stencils is 2–4 chunks of the bending phase
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 40;
    sc.solver = { ...sc.solver, bending, selfContact: false };
    sc.material.bendingRigidity = 1e-4;
    await sideBySide(sc, 30, (one, many) => {
      expect([...many.state.positions]).toEqual([...one.state.positions]);
      expect([...many.state.bendingLambdas]).toEqual([...one.state.bendingLambdas]);
    });
  });

  it('the springs and the hinges solved together (the global steps on the calling thread between two substeps of both threads): 2 threads give the same cloth as 1, bit for bit', async () => {
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 40;
    sc.solver = { ...sc.solver, stretch: 'global', bending: 'hinges', bendingSolve: 'global', selfContact: false };
    await sideBySide(sc, 20, (one, many) => {
      expect([...many.state.positions]).toEqual([...one.state.positions]);
      expect([...many.state.velocities]).toEqual([...one.state.velocities]);
    });
  });

  it('triangle contact with the sphere (one chunk: one thread takes it, in order): 2 threads give the same cloth as 1, bit for bit', async () => {
    // 33² particles on the sphere, whose surface pokes between them: the kernel's triangle pass every substep
    const sc = builtinScene('cotton-basic')!;
    sc.cloth.resolution = 32;
    sc.solver = { ...sc.solver, selfContact: false };
    await sideBySide(sc, 40, (one, many) => {
      expect([...many.state.positions]).toEqual([...one.state.positions]);
    });
  });

  it('triangle contact with the mannequin\'s capsules (the skirt, self-contact on): 2 threads give the same cloth as 1, bit for bit', async () => {
    await sideBySide(builtinScene('skirt')!, 60, (one, many) => {
      expect([...many.state.positions]).toEqual([...one.state.positions]);
    });
  });

  it('a rebuild stops the old helpers and starts new ones; after dispose it steps on one thread', async () => {
    const sim = new Simulation(scene(), { kernel: 'wasm', threads: 2, spawnHelper: spawnNodeHelper });
    await sim.whenReady();
    const oldKernel = (sim.backend as WasmBackend).kernel;
    expect(sim.set('cloth.resolution', 20)).toBe(true);
    expect(oldKernel.activeThreads).toBe(1);
    await sim.whenReady();
    expect(sim.threads).toBe(2);
    sim.advance(5);
    sim.dispose();
    expect(sim.threads).toBe(1);
    sim.advance(5);
    expect(sim.report().finite).toBe(true);
  });

  it('after dispose: no helpers again (not by a rebuild either), and nothing waits for them', async () => {
    const sim = new Simulation(scene(), { kernel: 'wasm', threads: 2, spawnHelper: spawnNodeHelper });
    await sim.whenReady();
    const kernel = (sim.backend as WasmBackend).kernel;
    sim.dispose();
    expect(() => kernel.startHelpers(spawnNodeHelper)).toThrow(/disposed/);
    await sim.whenReady(); // at once
    sim.set('cloth.resolution', 12);
    expect((sim.backend as WasmBackend).kernel.threads).toBe(1);
    sim.advance(2);
    expect(sim.report().finite).toBe(true);
  });

  it('a helper that fails to start makes whenReady reject with its error, and stepping stays on one thread', async () => {
    const failing: HelperSpawner = Object.assign((_init: unknown, onError: (e: Error) => void) => {
      setTimeout(() => onError(new Error('no worker for you')), 1);
      return { terminate() {} };
    }, { cores: 2 });
    const sim = new Simulation(scene(), { kernel: 'wasm', threads: 2, spawnHelper: failing });
    await expect(sim.whenReady()).rejects.toThrow(/no worker for you/);
    sim.advance(2);
    expect(sim.threads).toBe(1);
  });

  it('without a helper spawner the kernel runs on the calling thread', () => {
    const sim = new Simulation(scene(), { kernel: 'wasm', threads: 2 });
    expect(sim.threads).toBe(1);
    expect((sim.backend as WasmBackend).kernel.threads).toBe(1);
  });
});
