import { defineConfig } from 'vitest/config';

// Browser tests: build the site, serve it, drive Debian's Chromium through playwright-core (see e2e/).
// Run: node e2e/ensure-chromium.mjs && npx vitest run --config vitest.e2e.config.ts
export default defineConfig({
  test: {
    include: ['e2e/**/*.e2e.ts'],
    environment: 'node',
    globalSetup: ['e2e/global-setup.ts'],
    // generous limits, so that a busy machine makes the suite slower, never red: they only stop a test that hangs
    testTimeout: 300_000,
    hookTimeout: 300_000,
    expect: { poll: { timeout: 30_000 } },
    // one browser at a time: SwiftShader already uses both cores
    fileParallelism: false,
    reporters: ['default'],
  },
});
