/** Builds the site once (as users get it from `npm run build`) and serves dist/web on a free localhost port. */
import type { Server } from 'node:http';
import type { BrowserServer } from 'playwright-core';
import { build } from 'vite';
import type { TestProject } from 'vitest/node';
import { launchServer, SHARED_KINDS, type BrowserKind } from './browser.js';
import { serve } from './server.js';

let server: Server | undefined;

export default async function setup(project: TestProject): Promise<() => Promise<void>> {
  const t0 = Date.now();
  if (!process.env.DRAPE_E2E_NO_BUILD) {
    // a production build, as `npm run build` makes it (under vitest NODE_ENV is 'test', which Vite would build as
    // a development bundle: import.meta.env.DEV true, and so the test hook always on)
    const env = process.env.NODE_ENV;
    process.env.NODE_ENV = 'production';
    try {
      await build({ configFile: 'vite.config.ts', mode: 'production', logLevel: 'warn' });
    } finally {
      process.env.NODE_ENV = env;
    }
  }
  const s = await serve('dist/web');
  server = s.server;
  project.provide('baseURL', s.url);
  // the browsers several files use, started once (browser.ts)
  const browsers = await Promise.all(SHARED_KINDS.map(launchServer));
  project.provide('browsers', Object.fromEntries(SHARED_KINDS.map((k, i) => [k, browsers[i].wsEndpoint()])));
  console.log(`e2e: built and serving dist/web at ${s.url}, browsers started (${Date.now() - t0} ms)`);
  return async () => {
    await Promise.all(browsers.map((b: BrowserServer) => b.close()));
    await new Promise<void>((r) => server?.close(() => r()));
  };
}

declare module 'vitest' {
  export interface ProvidedContext {
    baseURL: string;
    /** the WebSocket endpoint of each browser the suite shares (browser.ts) */
    browsers: Partial<Record<BrowserKind, string>>;
  }
}
