import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { CONTENT_SECURITY_POLICY, CSP_DIRECTIVES, EXAMPLE_CONTENT_SECURITY_POLICY, cspMetaTag, wantsTestHook } from './security.js';

function files(dir: string): string[] {
  return readdirSync(dir).flatMap((f) => {
    const p = join(dir, f);
    return statSync(p).isDirectory() ? files(p) : [p];
  });
}

describe('the site\'s Content-Security-Policy', () => {
  it('refuses everything by default and allows scripts only from the site, with no inline script or eval', () => {
    expect(CSP_DIRECTIVES['default-src']).toEqual(["'none'"]);
    expect(CSP_DIRECTIVES['script-src']).toEqual(["'self'", "'wasm-unsafe-eval'"]);
    expect(CSP_DIRECTIVES['worker-src']).toEqual(["'self'"]);
    expect(CONTENT_SECURITY_POLICY).not.toMatch(/'unsafe-inline'|'unsafe-eval'|'unsafe-hashes'|\*|https?:/);
    expect(CSP_DIRECTIVES['connect-src']).toBeUndefined(); // no connections at all (default-src 'none')
    expect(CONTENT_SECURITY_POLICY).toContain("base-uri 'none'");
    expect(CONTENT_SECURITY_POLICY).toContain("form-action 'none'");
    // Trusted Types: no string ever reaches an HTML or script sink; one policy, for the site's own script URLs
    expect(CONTENT_SECURITY_POLICY).toContain("require-trusted-types-for 'script'; trusted-types default");
    // the three.js example's own: the same without Trusted Types, as a user's page would have it
    expect(EXAMPLE_CONTENT_SECURITY_POLICY).toBe(CONTENT_SECURITY_POLICY.replace("; require-trusted-types-for 'script'; trusted-types default", ''));
    expect(cspMetaTag()).toMatch(/^<meta http-equiv="Content-Security-Policy" content="default-src 'none'; [^"]+" \/>$/);
  });

  it('the test hook is installed in development, and in a build only with ?testhook', () => {
    expect(wantsTestHook('', true)).toBe(true);
    expect(wantsTestHook('', false)).toBe(false);
    expect(wantsTestHook('?lite&backend=cpu', false)).toBe(false);
    expect(wantsTestHook('?lite&testhook', false)).toBe(true);
    expect(wantsTestHook('?testhook=1', false)).toBe(true);
  });
});

describe('data never becomes markup', () => {
  it('no source of the app parses HTML from strings', () => {
    // spelled in parts, so that this test is not itself a hit for the repository's grep
    const sinks = new RegExp(['\\.(inner|outer)' + 'HTML\\b', 'insertAdjacent' + 'HTML', 'document\\.write', 'createContextual' + 'Fragment', 'DOM' + 'Parser', 'setHTML' + 'Unsafe'].join('|'));
    const offenders = ['src/app', 'src/ui', 'src/render', 'src/three', 'examples/three']
      .flatMap(files)
      .filter((f) => /\.ts$/.test(f) && !f.endsWith('.test.ts'))
      .filter((f) => sinks.test(readFileSync(f, 'utf8')));
    expect(offenders).toEqual([]);
  });
});
