import { defineConfig } from 'vitest/config';

// Unit and physics tests, beside the code. Browser tests live in e2e/ with their own config.
//
// Three groups, one after the other. The files that drive WebGPU (SwiftShader, which already keeps both cores busy, in
// Node and in the CLI's processes) run first, one at a time: beside another file each ran 4–5× slower. The src/gpu
// files share one module graph (not isolated), so one device and its compiled kernels serve them all
// (src/gpu/test-device.ts): each file compiled them again otherwise, 2.6 s on SwiftShader here (measured: those files
// took 99 s shared against 139 s isolated). The rest are single-threaded TypeScript and WebAssembly and run two at a
// time, one per core, each worker keeping its modules from file to file (not isolated: 146 s against 170 s isolated,
// 2026-12-06, the import of the core and its kernels then made once per worker, not once per file). No test depends on
// how fast it runs, so a busy machine makes the run slower, never red.
const GPU_SHARED = ['src/gpu/**/*.test.ts'];
const GPU_FILES = [
  // these run `drape … --backend gpu` or the GPU backend beside the CPU's
  'src/cli/main.test.ts',
  'src/cli/colliders.test.ts',
  'src/cli/garment.test.ts',
  // the page's GPU driver on the test device
  'src/three/sim/gpu-sim.test.ts',
];

// the limits only stop a test that hangs (a sweep of nine cloths takes 2 s on an idle machine here and can take
// many times that on a loaded one)
const limits = { testTimeout: 600_000, hookTimeout: 600_000 };

export default defineConfig({
  test: {
    projects: [
      { test: { name: 'gpu', include: GPU_SHARED, maxWorkers: 1, isolate: false, sequence: { groupOrder: 0 }, ...limits } },
      { test: { name: 'gpu-cli', include: GPU_FILES, maxWorkers: 1, sequence: { groupOrder: 1 }, ...limits } },
      { test: { name: 'cpu', include: ['src/**/*.test.ts'], exclude: [...GPU_SHARED, ...GPU_FILES], maxWorkers: 2, isolate: false, sequence: { groupOrder: 2 }, ...limits } },
    ],
  },
});
