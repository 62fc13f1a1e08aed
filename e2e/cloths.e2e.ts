/**
 * Several cloths in one scene in the app: the built-in `layers` (leather, cotton and silk dropped on the sphere,
 * self-contact on) from a link, each cloth drawn with its own fabric's look; the panel's cloth control choosing
 * which cloth Cloth & material and Pins edit (cloth 1's fabric, its pins through the pin tool); the link and the
 * exports in the document form (`cloths`); and, with the three made GPU-fit by the link, the same drawing from the
 * GPU solver's buffers. Small cloths (8 faces a side) and explicit steps: SwiftShader is slow.
 */
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launch, type Browser } from './browser.js';
import { POLL_MS, byId, choose, download, gpuReady, hook, openApp, setChecked, shoot, step } from './helpers.js';
import { decodePng } from './png.js';

let browser: Browser;

beforeAll(async () => {
  browser = await launch('webgpu');
});

afterAll(async () => {
  await browser?.close();
});

/** `layers` at 8 faces a side per cloth (81 particles each) */
const SMALL = [0, 1, 2].map((k) => `cloths[${k}].cloth.resolution=8`).join('&');

type Drawn = { name: string; first: number; particles: number; look: string; triangles: number };
const drawn = (page: Page) => hook<Drawn[]>(page, 'cloths');

/** each view once, drawn without an error (the errors list is checked by the caller) */
async function everyView(page: Page, name: string): Promise<void> {
  for (const view of ['Wireframe mesh', 'Particles', 'Springs by kind', 'Strain heat map', 'Shaded']) {
    await choose(page, 'view', view);
    await step(page, 1);
    const stats = await shoot(page, `${name}-${view.split(' ')[0].toLowerCase()}`);
    expect(stats.colours, view).toBeGreaterThan(20);
  }
}

describe('several cloths in the app', () => {
  it('layers: three cloths drawn in their fabrics, the panel editing one at a time, the link and the exports in the list form', async () => {
    const { page, errors } = await openApp(browser.context, `#scene=layers&${SMALL}`);
    expect(await hook(page, 'sceneName')).toBe('layers');
    // the scene menu has it
    expect(await byId(page, 'scene').locator('select').evaluate((s: HTMLSelectElement) => s.selectedOptions[0]?.textContent)).toBe('Layers (three cloths)');
    // one slot of three cloths, each drawn with its own look, its own triangles
    expect(await hook(page, 'slots')).toBe(1);
    expect(await drawn(page)).toEqual([
      { name: 'leather', first: 0, particles: 81, look: 'leather', triangles: 128 },
      { name: 'cotton', first: 81, particles: 81, look: 'cotton', triangles: 128 },
      { name: 'silk', first: 162, particles: 81, look: 'silk', triangles: 128 },
    ]);
    // on the CPU worker, and the HUD says why not the GPU (the scene, before the software adapter), and each cloth
    expect(await hook(page, 'simBackend')).toBe('cpu');
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('cloths that differ in their contact or spring values run on the CPU only (cloths[1].material.damping)');
    expect(await byId(page, 'hud-cloths').innerText()).toBe('3 cloths: leather 81 · cotton 81 · silk 81 particles');
    // a resolution sweep in a scene of several cloths does not run: the panel keeps each cloth's resolution its own
    const swept = await openApp(browser.context, `#scene=layers&${SMALL}&resolutionSweep=[8,16]`);
    await expect.poll(() => byId(swept.page, 'hud').innerText()).toContain("this scene's 3 cloths run as they are");
    expect(await byId(swept.page, 'cloth.resolution').locator('select').isDisabled()).toBe(false);
    expect(await byId(swept.page, 'cloth.resolution').innerText()).not.toContain('sweep');
    expect(await byId(swept.page, 'sweep').isVisible()).toBe(false);
    expect(swept.errors).toEqual([]);
    await swept.page.close();

    // the panel's cloth control: cloth 1 (cotton), its fabric made silk; the others keep theirs
    const which = byId(page, 'cloth.which');
    expect(await which.isVisible()).toBe(true);
    expect(await which.locator('option').allTextContents()).toEqual(['leather', 'cotton', 'silk']);
    await choose(page, 'cloth.which', 'cotton');
    expect(await hook(page, 'editedCloth')).toBe(1);
    expect(await byId(page, 'material.fabric').locator('select').inputValue()).toBe('cotton');
    await choose(page, 'material.fabric', 'silk');
    const scene = await hook<any>(page, 'scene');
    expect(scene.cloth).toBeUndefined();
    expect(scene.cloths.map((c: any) => c.material.fabric)).toEqual(['leather', 'silk', 'silk']);
    expect(scene.cloths[1].material.damping).toBe(0.05);
    // the other controls show the new fabric's values at once
    expect(await byId(page, 'material.damping').locator('input').first().inputValue()).toBe('0.05');
    expect((await drawn(page)).map((c) => c.look)).toEqual(['leather', 'silk', 'silk']);
    // Pins follows the cloth control: a preset of cotton's, its first particle pinned; then off again
    expect(await byId(page, 'pin.top-left').locator('input').isChecked()).toBe(false);
    await setChecked(page, 'pin.top-left', true);
    expect((await hook<any>(page, 'scene')).cloths.map((c: any) => c.pins)).toEqual([[], ['top-left'], []]);
    expect(await hook(page, 'pinned')).toEqual([81]);
    await setChecked(page, 'pin.top-left', false);
    expect(await hook(page, 'pinned')).toEqual([]);
    // the pin tool pins a particle of the cloth it clicks (silk, on top), in that cloth's pins, counted from its first
    await setChecked(page, 'pinTool', true);
    const at = await hook<{ x: number; y: number }>(page, 'screenOf', 162 + 40);
    await page.mouse.click(at.x, at.y);
    await expect.poll(() => hook<any>(page, 'scene').then((s) => s.cloths[2].pins)).toHaveLength(1);
    expect((await hook<any>(page, 'scene')).cloths[2].pins).toEqual([40]);
    expect(await hook(page, 'pinned')).toEqual([162 + 40]);
    await setChecked(page, 'pinTool', false);
    // the cloths fall in every view
    await step(page, 20);
    await everyView(page, 'layers');
    expect((await hook<number[][]>(page, 'positions', [0]))[0][1]).toBeLessThan(0.69);

    // landed on each other: the contact view marks the particles lying on another cloth in red, and the HUD counts
    // them (on the same positions while paused: the same number)
    await step(page, 100);
    await choose(page, 'view', 'Self-contacts');
    await step(page, 1);
    // (drawn at the next display frame)
    await expect.poll(() => hook<number>(page, 'contacts')).toBeGreaterThan(10);
    const marked = await hook<number>(page, 'contacts');
    expect(marked).toBeLessThan(162);
    await expect.poll(() => byId(page, 'hud-contacts').innerText()).toBe(`self-contact on · ${marked} particles in contact`);
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('within 7.5 mm of another part of the cloth');
    await shoot(page, 'layers-contacts');
    const shot = decodePng(await page.screenshot());
    let red = 0;
    for (let i = 0; i < shot.rgba.length; i += 4) if (shot.rgba[i] > 180 && shot.rgba[i + 1] < 110 && shot.rgba[i + 2] < 100) red++;
    expect(red).toBeGreaterThan(50);
    await choose(page, 'view', 'Shaded');

    // the link: the document form, cloth by cloth; a fresh page from it shows the same scene
    await page.waitForFunction(() => location.hash.includes('cloths[1].material.fabric=silk'), null, { polling: POLL_MS });
    const hash = await page.evaluate(() => location.hash);
    expect(hash).not.toMatch(/[#&]cloth\./);
    const other = await openApp(browser.context, hash);
    expect(await hook(other.page, 'scene')).toEqual(await hook(page, 'scene'));
    expect((await drawn(other.page)).map((c) => c.look)).toEqual(['leather', 'silk', 'silk']);
    expect(other.errors).toEqual([]);
    await other.page.close();

    // the scene JSON: the list form, which imports back; the OBJ: an object per cloth over the scene's particles
    const json = JSON.parse((await download(page, 'exportJson')).data.toString('utf8'));
    expect(Object.keys(json)).not.toContain('cloth');
    expect(json.cloths.map((c: any) => c.name)).toEqual(['leather', 'cotton', 'silk']);
    expect(await hook(page, 'import', JSON.stringify(json))).toBe(true);
    expect((await drawn(page)).map((c) => c.look)).toEqual(['leather', 'silk', 'silk']);
    const obj = (await download(page, 'exportObj')).data.toString('utf8');
    expect(obj.match(/^o .*/gm)).toEqual(['o leather', 'o cotton', 'o silk']);
    expect(obj.match(/^v /gm)).toHaveLength(243);
    // the silk's first face indexes its own particles (the file's numbering is the scene's)
    const silkFace = obj.slice(obj.indexOf('o silk')).match(/^f (\d+)/m)!;
    expect(Number(silkFace[1])).toBeGreaterThan(162);

    // cloth names from a file reach the page as text only: the cloth control, the Pins title, the HUD
    const hostile = '<img src=x onerror="window.__pwned=1">';
    const two = { name: 'two', cloths: [
      { name: hostile, cloth: { resolution: 4, position: [0, 1, 0] } },
      { name: 'b', cloth: { resolution: 4, position: [0, 1.4, 0] } },
    ] };
    expect(await hook(page, 'import', JSON.stringify(two))).toBe(true);
    expect(await hook(page, 'editedCloth')).toBe(1);
    expect(await which.locator('option').allTextContents()).toEqual([hostile, 'b']);
    await expect.poll(() => byId(page, 'hud-cloths').innerText()).toBe(`2 cloths: ${hostile} 25 · b 25 particles`);
    expect(await page.locator('img').count()).toBe(0);
    expect(await page.evaluate(() => (window as any).__pwned)).toBeUndefined();
    expect(errors).toEqual([]);
    await page.close();
  });

  it('the same three cloths on the GPU backend, drawn from its buffers in their looks, in every view', async () => {
    // the GPU takes cloths that agree in their contact and spring values (here without self-contact, which it runs
    // too, to keep the page quick on a software adapter)
    const same = [0, 2].flatMap((k) => [['damping', 0.1], ['stretchFactor', 1.05], ['friction', 0.3], ['staticFriction', 0.4]]
      .map(([f, v]) => `cloths[${k}].material.${f}=${v}`)).join('&');
    const { page, errors } = await openApp(browser.context, `#scene=layers&${SMALL}&solver.selfContact=false&${same}`, '?lite&backend=gpu');
    await gpuReady(page);
    expect((await drawn(page)).map((c) => [c.look, c.triangles])).toEqual([['leather', 128], ['cotton', 128], ['silk', 128]]);
    await step(page, 10);
    await everyView(page, 'layers-gpu');
    expect(errors).toEqual([]);
    await page.close();
  });
});
