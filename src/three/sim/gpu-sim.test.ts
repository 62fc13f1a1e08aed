/**
 * GpuSim, the page's GPU driver (on the test device of src/gpu/test-device.ts, skipped without one): a frame the GPU
 * refuses when it meets it says why through onError, once, and does not leave the driver stuck.
 */
import { describe, expect, it, vi } from 'vitest';
import type {} from 'webgpu';
import { validateScene } from '../../core/index.js';
import { testDevice } from '../../gpu/test-device.js';
import { GpuSim } from './gpu-sim.js';
import { MeshStore } from './meshes.js';

const device = (await testDevice('src/three/sim/gpu-sim.test.ts'))?.device;

describe.skipIf(!device)('GpuSim', () => {
  it('a frame the GPU solver refuses goes to onError with its message (the page then moves to the CPU)', async () => {
    const sim = new GpuSim(device!, new MeshStore());
    sim.load([validateScene({ cloth: { resolution: 6 }, colliders: [] })]);
    await sim.step(1); // made, and ready
    expect(sim.ready).toBe(true);
    const solver = sim.solverOf(0)!;
    const step = vi.spyOn(solver, 'step').mockImplementation(() => { throw new Error('GPU solver: refused here'); });
    const errors: string[] = [];
    sim.onError = (m) => errors.push(m);
    sim.tick(1000 / 60, performance.now());
    expect(errors).toEqual(['GPU solver: refused here']);
    // the same from a single step (the page's S key, paused)
    await sim.step(1);
    expect(errors).toEqual(['GPU solver: refused here', 'GPU solver: refused here']);
    step.mockRestore();
    sim.dispose();
  });
});
