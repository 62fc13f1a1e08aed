/**
 * The GPU's stencil bending (solver.bending 'hinges' or 'laplacian', the `bending` kernel) against the TypeScript
 * reference (solveBending), on whatever adapter `createNodeDevice` finds. Same adapter rule as gpu.test.ts: no adapter, the
 * file fails in CI and is skipped (saying why) elsewhere.
 */
import { afterAll, describe, expect, test } from 'vitest';
import type {} from 'webgpu';
import { BEND_SPRING_PER_RIGIDITY, FRAME_DT, builtinScene, centroid, resolveParams, step, validateScene, type Scene, type StencilModel } from '../core/index.js';
import { bentness, gpuPair, maxDistance, testDevice, type Pair } from './test-device.js';
import { GpuClothSolver } from './solver.js';

const gpu = await testDevice('src/gpu/bending.test.ts');

const solvers: GpuClothSolver[] = [];
afterAll(() => {
  for (const s of solvers) s.destroy();
});

/** the stiff cloth's bending rigidity: a bend spring of 1000 N/m at 1/32 m [N·m] */
const STIFF = 1000 / BEND_SPRING_PER_RIGIDITY;

/**
 * The hammock scene as a 16² cloth hung from two corners of one edge (it swings down and folds), bending with the
 * stencil model `kind` with bending rigidity B [N·m], `iterations` passes per substep, its springs swept alone
 * (solver.stretch 'gauss-seidel', as when these tolerances were measured: the coarse correction's own tests,
 * coarse-stretch.test.ts, run it with the hinges, and its ten more dispatches a substep cost a third of this file's
 * time on SwiftShader).
 */
function hinged(B: number, iterations: number, kind: StencilModel = 'hinges'): Scene {
  const s = builtinScene('pins');
  s.cloth.resolution = 16;
  s.pins = ['top-left', 'top-right'];
  s.material.bendingRigidity = B;
  s.solver = { ...s.solver, bending: kind, iterations, selfContact: false, stretch: 'gauss-seidel' };
  return validateScene(s);
}

/** `frames` frames of one scene on the CPU and on the GPU from the same start (test-device.ts gpuPair). */
async function run(sc: Scene, frames: number): Promise<Pair> {
  const p = await gpuPair(gpu!.device, sc, solvers);
  await p.advance(frames);
  return p;
}

describe.skipIf(!gpu)('stencil bending on the GPU', () => {
  // Tolerances as docs/gpu.md "Parity" sets them: a few times the larger of the GPU–CPU difference seen on
  // SwiftShader and the CPU's own spread with its start nudged by 1e-7 (relative). At frame 30, with 1 and 2
  // iterations. Hinges: seen ≤ 1.9e-4 m (spread ≤ 1.5e-4 m) → 1e-3 m, the pins scene's; centroid seen ≤ 9.4e-6 m
  // (spread ≤ 1.3e-5 m) → 1e-4 m. Laplacian (the stiff sheet is more sensitive to its start): seen ≤ 8.0e-4 m
  // (spread ≤ 9.6e-4 m) → 3e-3 m; centroid seen ≤ 6.9e-5 m (spread ≤ 2.9e-5 m) → 3e-4 m. The bentness seen ≤ 1.4e-3
  // apart (relative) → 1e-2.
  test.each<[number, StencilModel]>([[1, 'hinges'], [2, 'hinges'], [1, 'laplacian'], [2, 'laplacian']])(
    '%i iteration(s) with %s: as on the CPU, and a stiff cloth stays flatter by as much as there', async (iterations, kind) => {
    // B = 0.0106 N·m (a bend spring of 1000 N/m): stiff enough to keep a 1 m cotton sheet flat through its swing; 0: no stencil is solved
    const stiff = await run(hinged(STIFF, iterations, kind), 30);
    const soft = await run(hinged(0, iterations, kind), 30);
    const [far, centre] = kind === 'hinges' ? [1e-3, 1e-4] : [3e-3, 3e-4];
    for (const r of [stiff, soft]) {
      expect(maxDistance(r.gpu.positions, r.cpu.positions)).toBeLessThan(far);
      const a = centroid(r.cpu), b = centroid(r.gpu);
      expect(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2])).toBeLessThan(centre);
    }
    // the kernel at work: the stiff cloth is bent far less (seen 0.38 against 13 with hinges, 0.34 against 18 with
    // the Laplacian, at frame 30, on both)
    const bent = (r: typeof stiff, on: 'cpu' | 'gpu') => bentness(r.model, r[on].positions, kind);
    expect(bent(stiff, 'cpu')).toBeLessThan(0.1 * bent(soft, 'cpu'));
    expect(bent(stiff, 'gpu')).toBeLessThan(0.1 * bent(soft, 'gpu'));
    for (const r of [stiff, soft]) expect(Math.abs(bent(r, 'gpu') - bent(r, 'cpu'))).toBeLessThan(1e-2 * bent(r, 'cpu'));
  });

  // The stencil buffers are made on the first params with a stencil model: here after 10 frames of bend springs,
  // then made anew for the Laplacian after 10 frames of hinges. Seen 2.1e-5 m at frame 20 (hinges) → 1e-3 m (0.5 m
  // without the bending kernel's bind group made anew).
  test('switched on mid-run (a live parameter change), then to the other model: as on the CPU', async () => {
    const sc = hinged(STIFF, 1);
    sc.solver.bending = 'springs';
    const r = await run(sc, 10);
    for (const kind of ['hinges', 'laplacian'] as const) {
      sc.solver.bending = kind;
      const params = resolveParams(r.model, sc); // step() sees a new params object and calls setParams
      for (let f = 0; f < 10; f++) {
        step(r.model, r.cpu, params, FRAME_DT);
        r.solver.step(r.gpu, params, FRAME_DT);
      }
      await r.solver.read(r.gpu);
      expect(maxDistance(r.gpu.positions, r.cpu.positions)).toBeLessThan(1e-3);
    }
  });

  test.each(['hinges', 'laplacian'] as const)('its traffic and dispatches are counted, and only for a stencil model (%s)', async (kind) => {
    const sc = hinged(STIFF, 2, kind);
    const r = await run(sc, 1);
    const st = r.model.stencils[kind], count = st.areas.length, entries = st.vertices.length;
    const bending = r.solver.substepTraffic().byKernel.bending;
    // per stencil: offsets, compliance, λ written; per entry: particle, K, w, x to make C, then particle, K, w, x in
    // and out; ×2 passes, λ read once
    expect(bending).toBe((count * (8 + 4 + 12) + entries * (28 + 44)) * 2 + count * 12);
    if (kind === 'hinges') expect(entries).toBe(4 * count);
    const dispatches = r.solver.dispatchesPerFrame(r.params);
    sc.solver.bending = 'springs';
    const springs = resolveParams(r.model, sc);
    r.solver.setParams(springs);
    expect(r.solver.substepTraffic().byKernel.bending).toBeUndefined();
    expect(dispatches - r.solver.dispatchesPerFrame(springs)).toBe(sc.solver.substeps * 2 * st.batches.length);
  });
});
