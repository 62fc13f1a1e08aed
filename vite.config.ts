import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig, type Plugin } from 'vite';
import { precompiledAjvModule } from './src/app/precompiled-ajv.js';
import { EXAMPLE_CONTENT_SECURITY_POLICY, cspMetaTag } from './src/app/security.js';
import { sceneSchema } from './src/core/scene-schema.js';

const PRECOMPILED_AJV = '\0drape:precompiled-ajv';

/**
 * The site build ships no JavaScript code generator: `ajv` (used by the core to validate scenes) resolves to Ajv's
 * standalone validator of the scene schema, compiled here at build time (src/app/precompiled-ajv.ts), so the
 * Content-Security-Policy needs no 'unsafe-eval'. In the page and in the worker.
 */
function precompiledAjv(): Plugin {
  return {
    name: 'drape:precompiled-ajv',
    apply: 'build',
    enforce: 'pre',
    resolveId(id) {
      return id === 'ajv' ? PRECOMPILED_AJV : null;
    },
    load(id) {
      return id === PRECOMPILED_AJV ? precompiledAjvModule(sceneSchema) : null;
    },
  };
}

/**
 * The Content-Security-Policy of src/app/security.ts as a meta tag, first in each built page's <head>: the app's,
 * and the three.js example's own (the same without Trusted Types, as a user's page would have it).
 */
function contentSecurityPolicy(): Plugin {
  return {
    name: 'drape:csp',
    apply: 'build',
    transformIndexHtml: {
      order: 'post',
      handler(html, ctx) {
        if (!/<head>/.test(html)) throw new Error(`${ctx.path}: no <head> for the Content-Security-Policy`);
        const tag = ctx.path.startsWith('/examples/') ? cspMetaTag(EXAMPLE_CONTENT_SECURITY_POLICY) : cspMetaTag();
        // right after <meta charset>, before anything that loads
        return html.replace(/(<head>\s*<meta charset="utf-8" \/>|<head>)/, (m) => `${m}\n    ${tag}`);
      },
    },
  };
}

/** lil-gui's stylesheet file (its package exports only the script); the panel imports it instead of injecting it */
const LIL_GUI_CSS = join(dirname(createRequire(import.meta.url).resolve('lil-gui')), 'lil-gui.css');

// The browser app: index.html at the repository root, and the three.js addon's example page
// (examples/three/index.html, importing `drape/three` from the source); static build in dist/web (tsc writes
// dist/core, dist/cli, dist/gpu, dist/three).
export default defineConfig({
  root: '.',
  base: './',
  publicDir: 'public',
  plugins: [precompiledAjv(), contentSecurityPolicy()],
  resolve: {
    alias: [
      { find: /^lil-gui\/dist\/lil-gui\.css$/, replacement: LIL_GUI_CSS },
      { find: /^drape\/three$/, replacement: fileURLToPath(new URL('./src/three/index.ts', import.meta.url)) },
    ],
  },
  build: {
    outDir: 'dist/web',
    rolldownOptions: { input: { main: 'index.html', three: 'examples/three/index.html' } },
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
  },
  worker: { format: 'es', plugins: () => [precompiledAjv()] },
  server: { open: false },
});
