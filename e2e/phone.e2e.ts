/**
 * The app on a phone (390 × 844 CSS px, a touch screen; issue 14): the panel starts collapsed and the HUD compact,
 * so that most of the screen shows the 3D view; both hide and show with H or the corner button, and the choice
 * survives a reload. The Mesh Resolution title stays on screen. Paused, explicit steps: nothing depends on the
 * machine's speed.
 */
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launch, type Browser } from './browser.js';
import { byId, hook, loadScene, openApp, shoot, writeJson } from './helpers.js';

const PHONE = { width: 390, height: 844 };
let browser: Browser;
let page: Page;
let errors: string[];

beforeAll(async () => {
  browser = await launch('webgpu', { viewport: PHONE, touch: true });
  // openApp opens every collapsed folder, the panel too: what the page shows at start is measured before that
  ({ page, errors } = await openApp(browser.context, '', '?lite&backend=cpu', { openFolders: false }));
});

afterAll(async () => {
  await browser?.close();
});

/** The share of the viewport no overlay covers (HUD, panel, buttons, labels, messages), on a 2 px grid. */
function freeShare(p: Page): Promise<number> {
  return p.evaluate(() => {
    const sel = '.drape-hud, .lil-gui.drape-panel, .drape-layout-toggle, .drape-label, .drape-message.show, .drape-caption';
    const rects = [...document.querySelectorAll<HTMLElement>(sel)]
      .filter((e) => e.offsetParent !== null || getComputedStyle(e).position === 'fixed')
      .filter((e) => getComputedStyle(e).display !== 'none' && !e.hidden)
      .map((e) => e.getBoundingClientRect());
    const w = window.innerWidth, h = window.innerHeight;
    let free = 0, all = 0;
    for (let y = 1; y < h; y += 2) {
      for (let x = 1; x < w; x += 2) {
        all++;
        if (!rects.some((r) => x >= r.left && x < r.right && y >= r.top && y < r.bottom)) free++;
      }
    }
    return free / all;
  });
}

const rectOf = (p: Page, selector: string) => p.locator(selector).first().evaluate((e) => {
  const r = e.getBoundingClientRect();
  return { left: r.left, top: r.top, right: r.right, bottom: r.bottom };
});

describe('phone layout (390 × 844)', () => {
  it('at start the 3D view has at least 60 % of the screen: the panel collapsed, the HUD compact', async () => {
    const share = await freeShare(page);
    writeJson('phone-layout', { viewport: PHONE, freeShareAtStart: share });
    console.log(`phone: ${(100 * share).toFixed(1)} % of the screen shows the 3D view at start`);
    expect(share).toBeGreaterThanOrEqual(0.6);
    expect(await page.locator('.lil-gui.drape-panel').first().getAttribute('class')).toContain('lil-closed');
    expect(await byId(page, 'hud').getAttribute('class')).toContain('compact');
    expect(await page.locator('.drape-hud-plot').isVisible()).toBe(false);
    // the scene's explanation starts off on a phone (E shows it)
    expect(await byId(page, 'caption').isVisible()).toBe(false);
    const hud = await rectOf(page, '.drape-hud');
    expect(hud.right).toBeLessThanOrEqual(PHONE.width * 0.62);
    await shoot(page, 'phone-start');
    expect(errors).toEqual([]);
  });

  it('H hides the HUD and the panel, the choice survives a reload, and the corner button shows them again', async () => {
    await page.keyboard.press('h');
    expect(await byId(page, 'hud').isVisible()).toBe(false);
    expect(await page.locator('.lil-gui.drape-panel').first().isVisible()).toBe(false);
    expect(await byId(page, 'layout-toggle').innerText()).toBe('show panels (H)');
    expect(await freeShare(page)).toBeGreaterThan(0.95);

    await page.reload();
    await page.waitForFunction(() => (window as any).drape?.ready === true, null, { timeout: 60_000, polling: 50 });
    expect(await byId(page, 'hud').isVisible()).toBe(false);
    expect(await page.locator('.lil-gui.drape-panel').first().isVisible()).toBe(false);

    await byId(page, 'layout-toggle').click();
    expect(await byId(page, 'hud').isVisible()).toBe(true);
    expect(await page.locator('.lil-gui.drape-panel').first().isVisible()).toBe(true);
    expect(await byId(page, 'layout-toggle').innerText()).toBe('hide panels (H)');
    expect(errors).toEqual([]);
  });

  it('the panel, once opened, stays open after a reload; the Mesh Resolution title is on screen, clear of the HUD', async () => {
    await page.locator('.lil-gui.drape-panel > .lil-title').first().click();
    // lil-gui opens with an animation, a frame later
    await expect.poll(() => page.locator('.lil-gui.drape-panel').first().getAttribute('class')).not.toContain('lil-closed');
    await page.reload();
    await page.waitForFunction(() => (window as any).drape?.ready === true, null, { timeout: 60_000, polling: 50 });
    expect(await page.locator('.lil-gui.drape-panel').first().getAttribute('class')).not.toContain('lil-closed');

    await loadScene(page, 'Mesh Resolution');
    expect((await hook<string[]>(page, 'labels'))[0]).toContain('1 face');
    // the label is placed by the frame loop: wait for a drawn frame
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    const label = await rectOf(page, '.drape-label');
    expect(label.left).toBeGreaterThanOrEqual(0);
    expect(label.right).toBeLessThanOrEqual(PHONE.width);
    expect(label.top).toBeGreaterThanOrEqual(0);
    expect(label.bottom).toBeLessThanOrEqual(PHONE.height);
    const hud = await rectOf(page, '.drape-hud');
    expect(label.top >= hud.bottom || label.left >= hud.right).toBe(true);
    // with the scene's explanation shown (E), the title sits above it
    await page.keyboard.press('e');
    expect(await byId(page, 'caption').isVisible()).toBe(true);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    const caption = await rectOf(page, '.drape-caption');
    expect((await rectOf(page, '.drape-label')).bottom).toBeLessThanOrEqual(caption.top);
    await shoot(page, 'phone-resolution');
    expect(errors).toEqual([]);
  });
});
