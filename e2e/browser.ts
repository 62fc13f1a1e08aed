/**
 * Launches Debian's Chromium through playwright-core with the flags of docs/testing (shared/testing.md):
 * - 'webgpu': WebGPU on SwiftShader, presenting to a canvas (Vulkan + ANGLE SwiftShader flags);
 * - 'webgl':  no --enable-unsafe-webgpu: no WebGPU adapter, so three.js falls back to WebGL2 by itself;
 * - 'lost':   --enable-unsafe-webgpu WITHOUT the presenting flags: the WebGPU device is lost at the first frame and
 *             Drape must notice and switch to WebGL2.
 * The kinds several files use ('webgpu', 'webgl') are launched once for the whole suite by the global setup
 * (SHARED_KINDS): each file gets a new browser context of its own in it (its own pages, storage and downloads),
 * which saves a Chromium start per file. Without the global setup (or for 'lost'), a file launches its own.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium, type BrowserContext, type BrowserServer, type Page } from 'playwright-core';
import { inject } from 'vitest';
import { findChromium } from './ensure-chromium.mjs';

export type BrowserKind = 'webgpu' | 'webgl' | 'lost';

/** the kinds the global setup launches once for all files */
export const SHARED_KINDS = ['webgpu', 'webgl'] as const;

const VIEWPORT = { width: 960, height: 600 };

function chromiumPath(): string {
  const executablePath = findChromium() as string | null;
  if (!executablePath) throw new Error('no Chromium: run `node e2e/ensure-chromium.mjs`');
  return executablePath;
}

/** Starts a browser of a kind that files connect to (global setup). */
export function launchServer(kind: BrowserKind): Promise<BrowserServer> {
  return chromium.launchServer({ executablePath: chromiumPath(), headless: true, args: argsFor(kind) });
}

const BASE_ARGS = ['--no-sandbox', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'];
const PRESENT_ARGS = ['--use-angle=swiftshader', '--use-vulkan=swiftshader', '--enable-features=Vulkan'];

export function argsFor(kind: BrowserKind): string[] {
  switch (kind) {
    case 'webgpu': return [...BASE_ARGS, '--enable-unsafe-webgpu', ...PRESENT_ARGS];
    case 'webgl': return [...BASE_ARGS, ...PRESENT_ARGS];
    case 'lost': return [...BASE_ARGS, '--enable-unsafe-webgpu'];
  }
}

export interface Browser {
  context: BrowserContext;
  close(): Promise<void>;
}

/** `viewport`: the page's size in CSS px (default 960 × 600); `touch`: a touch screen, as a phone's */
export async function launch(kind: BrowserKind, options: { viewport?: { width: number; height: number }; touch?: boolean } = {}): Promise<Browser> {
  const viewport = options.viewport ?? VIEWPORT;
  const hasTouch = options.touch ?? false;
  const endpoint = (inject('browsers') as Partial<Record<BrowserKind, string>> | undefined)?.[kind];
  if (endpoint) {
    const browser = await chromium.connect(endpoint);
    const context = await browser.newContext({ viewport, hasTouch, acceptDownloads: true });
    await context.addInitScript(CSP_REPORTER);
    return {
      context,
      async close() {
        await context.close();
        await browser.close(); // (disconnects: the shared browser goes on for the next file)
      },
    };
  }
  const dir = mkdtempSync(join(tmpdir(), 'drape-chrome-'));
  const context = await chromium.launchPersistentContext(dir, {
    executablePath: chromiumPath(),
    headless: true,
    args: argsFor(kind),
    viewport,
    hasTouch,
    acceptDownloads: true,
  });
  // every Content-Security-Policy violation of any page becomes a console error, which collectErrors records
  await context.addInitScript(CSP_REPORTER);
  return {
    context,
    async close() {
      await context.close();
      rmSync(dir, { recursive: true, force: true });
    },
  };
}

/** Reports `securitypolicyviolation` events as console errors (an init script: it runs before the page's own). */
export const CSP_REPORTER = `document.addEventListener('securitypolicyviolation', (e) => {
  console.error('CSP violation: ' + e.effectiveDirective + ' refused ' + (e.blockedURI || '(inline)') + ' at ' + e.sourceFile + ':' + e.lineNumber);
});`;

/** Console errors and uncaught exceptions of a page, collected from the start. */
export function collectErrors(page: Page): string[] {
  const errors: string[] = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
  return errors;
}
