import { defineConfig } from 'vitest/config';

// Unit and physics tests, beside the code. Browser tests live in e2e/ with their own config.
export default defineConfig({
  test: {
    include: ['src/**/*.test.ts'],
    // no test may fail because the machine is busy: the limits only stop a test that hangs (a sweep of nine cloths
    // takes 2 s on an idle machine here and can take many times that on a loaded one)
    testTimeout: 600_000,
    hookTimeout: 600_000,
  },
});
