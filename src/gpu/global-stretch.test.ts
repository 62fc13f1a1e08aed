/**
 * The global stretch step on the GPU (solver.stretch 'global': global-stretch.ts and its five kernels) against the
 * TypeScript reference (core solveGlobalStretch), on whatever adapter `createNodeDevice` finds (no adapter: the file's
 * tests fail in CI and are skipped, saying why, elsewhere). The factor's tables are global-bending.ts's FactorLayout,
 * tested there without a device.
 */
import { afterAll, describe, expect, test } from 'vitest';
import type {} from 'webgpu';
import { builtinScene, resolveParams, validateScene, type Scene } from '../core/index.js';
import { GpuClothSolver } from './solver.js';
import { centroidDistance, gpuPair, maxDistance, pinAndGrabChanges, testDevice, type Pair } from './test-device.js';

const gpu = await testDevice('src/gpu/global-stretch.test.ts');

const solvers: GpuClothSolver[] = [];
afterAll(() => {
  for (const s of solvers) s.destroy();
});

/** A 16² sheet of `fabric` hung from its top edge, its springs solved together (`iterations` passes a substep). */
function hanging(fabric: string, iterations = 1): Scene {
  const s = builtinScene('pins');
  s.cloth = { ...s.cloth, resolution: 16, orientation: 'hanging', position: [0, 1.5, 0] };
  s.pins = ['top-edge'];
  s.material = { fabric } as Scene['material'];
  s.solver = { ...s.solver, stretch: 'global', iterations, selfContact: false };
  s.colliders = [];
  return validateScene(s);
}

/** How far the sheet's bottom row hangs below its top row [m] (the particles of rows 0 and 16 of a 16² grid). */
function drop(x: Float32Array): number {
  let top = 0, bottom = 0;
  for (let i = 0; i < 17; i++) { top += x[3 * i + 1]; bottom += x[3 * (16 * 17 + i) + 1]; }
  return (top - bottom) / 17;
}

const pair = (sc: Scene): Promise<Pair> => gpuPair(gpu!.device, sc, solvers);

describe.skipIf(!gpu)('the springs solved together on the GPU', () => {
  // The GPU solves with the CPU's factor in float32, for the correction from the predicted positions: rubber and
  // cotton, one and three passes a substep; seen ≤ 3.9e-6 m apart at frame 30, the sheets' drops 3e-6 apart (relative).
  test.each([['rubber', 1], ['cotton', 3]] as const)('%s, %i pass(es) a substep: as on the CPU', async (fabric, iterations) => {
    const p = await pair(hanging(fabric, iterations));
    await p.advance(30);
    expect(maxDistance(p.gpu.positions, p.cpu.positions)).toBeLessThan(1e-4);
    expect(Math.abs(drop(p.gpu.positions) / drop(p.cpu.positions) - 1)).toBeLessThan(1e-4);
  });

  // The factor changes with the pins: a corner let go (refactored on the CPU, its values sent again), then the middle
  // grabbed and pulled 10 cm out of the sheet (z = A⁻¹·e_g sent, the particle held where the grab puts it), then
  // released; each change made to the CPU's cloth copied to the GPU, the two compared 5 frames later. Seen 1.1e-6,
  // 8.0e-6 and 1.3e-5 m.
  test('pins that change and a grab: as on the CPU', async () => {
    const p = await pair(hanging('rubber'));
    const { apart, grabbed } = await pinAndGrabChanges(p, [0, 0, 0.1]);
    for (const [what, d] of apart) expect(d, what).toBeLessThan(1e-4);
    expect(grabbed).toBeLessThan(1e-6);
    expect(centroidDistance(p.cpu, p.gpu)).toBeLessThan(1e-5);
  });

  test('its traffic and dispatches are counted: y kept and four dispatches a pass, in place of the batches, tethers and stretch limit', async () => {
    const sc = hanging('cotton', 2);
    const p = await pair(sc);
    await p.advance(1);
    const traffic = p.solver.substepTraffic().byKernel;
    expect(traffic.globalStretch).toBeGreaterThan(0);
    expect(traffic.solve).toBeUndefined();
    expect(traffic.limitStretch).toBeUndefined();
    const together = p.solver.dispatchesPerFrame(p.params);
    sc.solver.stretch = 'gauss-seidel';
    const oneByOne = resolveParams(p.model, sc);
    p.solver.setParams(oneByOne);
    expect(p.solver.substepTraffic().byKernel.globalStretch).toBeUndefined();
    // one by one: every colour batch each pass, the structural and shear batches again to cap the stretch, the tethers
    const batches = p.model.batches.length, stretchBatches = p.model.batches.filter((b) => b.kind < 2).length;
    expect(p.solver.dispatchesPerFrame(oneByOne) - together).toBe(sc.solver.substeps * (2 * batches + stretchBatches + 1 - (1 + 4 * 2)));
  });
});
