/**
 * The two ways of not having WebGPU:
 * - no WebGPU adapter (Chromium without --enable-unsafe-webgpu): three.js falls back to WebGL2 by itself;
 * - a WebGPU adapter whose device is lost at the first frame (no presenting flags): Drape notices, switches to
 *   WebGL2 and says so in the page.
 * Both must draw, simulate and take input, without console errors.
 */
import { afterAll, describe, expect, it } from 'vitest';
import { launch, type Browser } from './browser.js';
import { byId, centroid, hook, loadScene, openApp, press, setChecked, shoot, step, viewStats, writeJson } from './helpers.js';

const browsers: Browser[] = [];
afterAll(async () => {
  for (const b of browsers) await b.close();
});

describe('without WebGPU (WebGL2 fallback)', () => {
  it('draws, drapes, drags (mouse and touch) and pins on WebGL2 with no console errors', async () => {
    const b = await launch('webgl');
    browsers.push(b);
    const { page, errors, readyMs } = await openApp(b.context);
    writeJson('ready-webgl', { readyMs });
    console.log(`page ready (first frame) with WebGL2: ${readyMs.toFixed(0)} ms`);
    expect(await hook(page, 'backend')).toBe('webgl2');
    const s = await viewStats(page);
    expect(s.colours).toBeGreaterThan(20);

    await loadScene(page, 'Silk Drape', 16);
    await step(page, 60); // on the sphere from about frame 30 (the CLI's centroid y: 0.596 then, 0.587 at rest)
    const c = await centroid(page);
    expect(c[1]).toBeGreaterThan(0.3);
    expect(c[1]).toBeLessThan(0.8);
    await shoot(page, 'webgl-silk');

    // drag
    await loadScene(page, 'Pins', 12);
    await step(page, 60);
    const at = await hook<{ x: number; y: number }>(page, 'screenOf', 6 * 13 + 6);
    await page.mouse.move(at.x, at.y);
    await page.mouse.down();
    const grabbed = await hook<number>(page, 'grabbed');
    expect(grabbed).toBeGreaterThanOrEqual(0);
    const y0 = (await hook<number[][]>(page, 'positions', [grabbed]))[0][1];
    await page.mouse.move(at.x, at.y - 70, { steps: 5 });
    await step(page, 30);
    expect((await hook<number[][]>(page, 'positions', [grabbed]))[0][1]).toBeGreaterThan(y0 + 0.08);
    await page.mouse.up();

    // touch: one finger on the cloth grabs it (pointer events from touch), and does not orbit
    const cam = await hook<number[]>(page, 'camera');
    const cdp = await page.context().newCDPSession(page);
    await cdp.send('Emulation.setTouchEmulationEnabled', { enabled: true, maxTouchPoints: 2 });
    const t0 = await hook<{ x: number; y: number }>(page, 'screenOf', 6 * 13 + 3);
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x: t0.x, y: t0.y }] });
    const touched = await hook<number>(page, 'grabbed');
    expect(touched).toBeGreaterThanOrEqual(0);
    const ty0 = (await hook<number[][]>(page, 'positions', [touched]))[0][1];
    for (let k = 1; k <= 5; k++) {
      await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x: t0.x, y: t0.y - 12 * k }] });
    }
    await step(page, 30);
    expect((await hook<number[][]>(page, 'positions', [touched]))[0][1]).toBeGreaterThan(ty0 + 0.05);
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
    expect(await hook(page, 'grabbed')).toBe(-1);
    expect(await hook<number[]>(page, 'camera')).toEqual(cam);

    // pins and views
    await setChecked(page, 'pin.center', true);
    expect((await hook<number[]>(page, 'pinned')).length).toBe(5);
    // once through the six views, back to shaded
    for (let k = 0; k < 6; k++) await page.keyboard.press('v');
    expect(await hook(page, 'view')).toBe('shaded');
    await press(page, 'reset');
    expect(await hook(page, 'frame')).toBe(0);
    expect(errors).toEqual([]);
  });
});

describe('WebGPU device lost (no presenting flags)', () => {
  it('notices the lost device, switches to WebGL2, says so, and keeps working', async () => {
    const b = await launch('lost');
    browsers.push(b);
    const { page, errors } = await openApp(b.context);
    await page.waitForFunction(() => (window as any).drape.backend() === 'webgl2', null, { timeout: 20_000 });
    const msg = await hook<{ text: string; kind: string }>(page, 'lastMessage');
    expect(msg.text).toContain('WebGPU device lost');
    expect(msg.text).toContain('WebGL2');
    // (the message itself fades after a few seconds, so whether it is still on screen depends on the machine's
    // speed; that it was shown is what the hook's lastMessage records)
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('WebGL2');

    await loadScene(page, 'Leather Stiff', 12);
    await step(page, 60); // on the sphere from about frame 30 (the CLI's centroid y: 0.589 then)
    const c = await centroid(page);
    expect(c[1]).toBeGreaterThan(0.3);
    expect(c[1]).toBeLessThan(0.85);
    const s = await shoot(page, 'lost-device-fallback');
    expect(s.colours).toBeGreaterThan(20);
    expect(errors).toEqual([]);
  });
});
