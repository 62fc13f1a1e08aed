/**
 * The GPU as a core Backend: a Simulation steps on it like on the CPU, and what the CPU changes (pins, a reset, a
 * cloth moved over) reaches the GPU without bringing back an older cloth. Same adapter rule as gpu.test.ts.
 */
import { describe, expect, it, vi } from 'vitest';
import type {} from 'webgpu';
import { Simulation, TsBackend, validateScene } from '../core/index.js';
import { GpuBackend } from './backend.js';
import { testDevice } from './test-device.js';

const device = (await testDevice('src/gpu/backend.test.ts'))?.device;

const scene = () => validateScene({ cloth: { resolution: 8 }, colliders: [] });

describe.skipIf(!device)('GpuBackend', () => {
  it('runs a Simulation like the CPU, and pins set after 30 frames hold the cloth where it has fallen to', async () => {
    const cpu = new Simulation(scene(), { kernel: 'ts' });
    const gpu = new Simulation(scene(), { kernel: 'ts' });
    gpu.useBackend(await GpuBackend.create(device!, gpu.model));
    expect(gpu.backend.kind).toBe('gpu');
    for (const sim of [cpu, gpu]) {
      sim.advance(30);
      sim.set('pins', [0]);
      sim.advance(10);
    }
    await gpu.sync();
    const a = cpu.report().centroid, b = gpu.report().centroid;
    // falling freely for half a second, then hanging from one corner: well below the start (1.2 m), as on the CPU
    expect(b[1]).toBeLessThan(0);
    for (let k = 0; k < 3; k++) expect(Math.abs(a[k] - b[k])).toBeLessThan(5e-3);
    gpu.dispose();
  });

  it('refuses to move a cloth off the GPU before its frames are read back, and moves it after', async () => {
    const sim = new Simulation(scene(), { kernel: 'ts' });
    sim.useBackend(await GpuBackend.create(device!, sim.model));
    sim.advance(20);
    expect(() => sim.useBackend(new TsBackend(sim.model))).toThrow(/await sync\(\) first/);
    await sim.sync();
    const y = sim.report().centroid[1];
    expect(y).toBeLessThan(1.2);
    sim.useBackend(new TsBackend(sim.model));
    expect(sim.report().centroid[1]).toBe(y);
    sim.reset();
    expect(sim.report().centroid[1]).toBeCloseTo(1.2, 6);
  });

  it('a read on its way when the cloth is reset brings back the reset cloth, not the one before', async () => {
    const sim = new Simulation(scene(), { kernel: 'ts' });
    sim.useBackend(await GpuBackend.create(device!, sim.model));
    sim.advance(20);
    // the reset comes once the read's copy of frame 20 is submitted (its mapping waits for the device)
    const queue = device!.queue, submit = queue.submit.bind(queue);
    let copied!: () => void;
    const submitted = new Promise<void>((r) => { copied = r; });
    const spy = vi.spyOn(queue, 'submit').mockImplementation((buffers: Iterable<GPUCommandBuffer>) => { submit(buffers); copied(); });
    const reading = sim.sync();
    await submitted;
    spy.mockRestore();
    sim.reset();
    await reading;
    expect(sim.frame).toBe(0);
    expect(sim.report().centroid[1]).toBeCloseTo(1.2, 6);
    sim.advance(5);
    await sim.sync();
    expect(sim.report().centroid[1]).toBeLessThan(1.2);
    sim.dispose();
  });

  it('a read asked for before the cloth is let go, and run after it, touches no freed buffer: it rejects, and the device reports nothing', async () => {
    // (as in the app: a load lets the solvers go while a readback is queued behind one in flight; a copy from freed
    // buffers would be a validation error that a new solver's error scope, open while it is made, takes for its own)
    const sim = new Simulation(scene(), { kernel: 'ts' });
    const backend = await GpuBackend.create(device!, sim.model);
    sim.useBackend(backend);
    sim.advance(2);
    device!.pushErrorScope('validation');
    const first = backend.solver.read(sim.state), second = backend.solver.read(sim.state);
    backend.dispose();
    const results = await Promise.allSettled([first, second]);
    expect(results.map((r) => r.status)).toEqual(['rejected', 'rejected']);
    expect(await device!.popErrorScope()).toBeNull();
  });
});
