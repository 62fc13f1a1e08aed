/**
 * The site's Content-Security-Policy. `npm run build` writes it into the built index.html as a
 * `<meta http-equiv="Content-Security-Policy">` (vite.config.ts), so it holds on any static host, with no server
 * headers needed. The dev server (`npm start`) has none: Vite's dev client injects styles and opens a socket.
 *
 * Everything not listed is refused (`default-src 'none'`): no inline script, no eval, no plug-ins, no frames, no
 * outside connections, no forms. Each allowance is there because the page needs it:
 *
 * - `script-src 'self'`: the app's own modules (index, the exporters loaded on demand) — and nothing inline;
 * - `'wasm-unsafe-eval'`: compiling the XPBD WebAssembly kernel (WebAssembly only; JavaScript eval stays refused —
 *   which is why the build precompiles the scene validator: see precompiled-ajv.ts);
 * - `worker-src 'self'`: the simulation worker, a module file of the site;
 * - `style-src 'self'`: the built stylesheet (lil-gui's included: the panel does not inject its own `<style>`).
 *   Styles set from script through `element.style` (uPlot, lil-gui, labels) are not governed by CSP, so no
 *   'unsafe-inline' is needed;
 * - `img-src data:`: the page icon, an inline SVG in index.html; textures are painted on canvases;
 * - `font-src data:`: lil-gui's icon font, embedded in its stylesheet;
 * - `base-uri 'none'`, `form-action 'none'`: a `<base>` or a form could redirect the page's URLs or data
 *   (neither falls back to default-src);
 * - `require-trusted-types-for 'script'`, `trusted-types default`: Trusted Types — the browser itself refuses a
 *   string in any sink that parses HTML or runs script (eval-like calls included), so markup from data cannot
 *   come back even by a later mistake. The one policy, `default` (installTrustedTypesPolicy, before anything
 *   else runs), lets through only script URLs of the site itself: the worker's module.
 *
 * Downloads (scene JSON, PNG, OBJ, glTF) are `blob:` URLs opened by a link with `download`: a navigation, which
 * CSP does not restrict, so no `blob:` source is listed. `frame-ancestors` cannot be set from a meta tag (servers
 * that can should send `frame-ancestors 'none'` as a header).
 */
export const CSP_DIRECTIVES: Readonly<Record<string, readonly string[]>> = {
  'default-src': ["'none'"],
  'script-src': ["'self'", "'wasm-unsafe-eval'"],
  'worker-src': ["'self'"],
  'style-src': ["'self'"],
  'img-src': ['data:'],
  'font-src': ['data:'],
  'base-uri': ["'none'"],
  'form-action': ["'none'"],
  'require-trusted-types-for': ["'script'"],
  'trusted-types': ['default'],
};

/**
 * The page's Trusted Types policy (see the CSP above): the site's own script URLs pass (the simulation worker);
 * anything else, and every HTML or script string, is refused. Call once, first. No-op where the browser has no
 * Trusted Types (the CSP directive is then ignored too).
 */
export function installTrustedTypesPolicy(): void {
  const tt = (globalThis as { trustedTypes?: { createPolicy(name: string, rules: object): unknown } }).trustedTypes;
  if (!tt) return;
  tt.createPolicy('default', {
    createScriptURL(url: string): string {
      if (new URL(url, location.href).origin !== location.origin) throw new TypeError(`Drape: script URL from elsewhere refused: ${url}`);
      return url;
    },
  });
}

export const CONTENT_SECURITY_POLICY = Object.entries(CSP_DIRECTIVES).map(([k, v]) => `${k} ${v.join(' ')}`).join('; ');

/**
 * The three.js addon's example page's policy (examples/three): the site's without Trusted Types, as a user's page
 * that loads `drape/three` would have it (with Trusted Types, a page lets the worker's script URL through with a
 * default policy, as installTrustedTypesPolicy does: docs/three.md).
 */
export const EXAMPLE_CONTENT_SECURITY_POLICY = Object.entries(CSP_DIRECTIVES)
  .filter(([k]) => k !== 'require-trusted-types-for' && k !== 'trusted-types')
  .map(([k, v]) => `${k} ${v.join(' ')}`).join('; ');

/** The meta element for the built index.html (goes first in <head>, before any script or stylesheet). */
export function cspMetaTag(policy = CONTENT_SECURITY_POLICY): string {
  return `<meta http-equiv="Content-Security-Policy" content="${policy.replace(/"/g, '&quot;')}" />`;
}

/** Query parameter that installs the test hook (`window.drape`) in a production build. */
export const TEST_HOOK_PARAM = 'testhook';

/** Whether the page installs `window.drape`: always in development, else only when the query asks for it. */
export function wantsTestHook(search: string, dev: boolean): boolean {
  return dev || new URLSearchParams(search).has(TEST_HOOK_PARAM);
}
