import { defineConfig } from 'vitest/config';

// Browser tests: build the site, serve it, drive Debian's Chromium through playwright-core (see e2e/).
// Run: node e2e/ensure-chromium.mjs && npx vitest run --config vitest.e2e.config.ts
export default defineConfig({
  test: {
    include: ['e2e/**/*.e2e.ts'],
    environment: 'node',
    globalSetup: ['e2e/global-setup.ts'],
    testTimeout: 90_000,
    hookTimeout: 90_000,
    // one browser at a time: SwiftShader already uses both cores
    fileParallelism: false,
    reporters: ['default'],
  },
});
