/** Page helpers for the browser tests: open the app, drive the panel by its test ids, read window.drape. */
import { mkdirSync, writeFileSync } from 'node:fs';
import type { BrowserContext, Locator, Page } from 'playwright-core';
import { expect, inject } from 'vitest';
import { collectErrors } from './browser.js';
import { crop, decodePng, imageStats } from './png.js';

export const RESULTS = 'test-results';

export interface Opened {
  page: Page;
  errors: string[];
  /** ms from navigation start to the first drawn frame */
  readyMs: number;
}

/** `query` with the parameter that installs the test hook `window.drape` in the built site */
export function withHook(query: string): string {
  return `${query}${query.length > 1 ? '&' : query ? '' : '?'}testhook`;
}

/**
 * Opens the built app. `hash` is the URL hash (scene link); `query` defaults to `?lite` (cheaper rendering on
 * SwiftShader: no MSAA, pixel ratio 1; the same code paths otherwise). `?testhook` is added: the built site has
 * no `window.drape` without it. `options.openFolders: false` leaves the panel's folders as the page opened them.
 * The page is paused from the start (see pause): a running page steps and redraws
 * every frame, which on SwiftShader takes the CPU from everything else a test does; tests step it explicitly.
 */
export async function openApp(context: BrowserContext, hash = '', query = '?lite', options: { openFolders?: boolean } = {}): Promise<Opened> {
  const page = await context.newPage();
  const errors = collectErrors(page);
  await page.goto(`${inject('baseURL')}${withHook(query)}${hash}`);
  // the hook comes with the app, before its first frame
  await page.waitForFunction(() => (window as any).drape !== undefined, null, { timeout: 30_000, polling: POLL_MS });
  await pause(page);
  await page.waitForFunction(() => (window as any).drape.ready === true, null, { timeout: 30_000, polling: POLL_MS });
  const readyMs = await page.evaluate(() => (window as any).drape.firstFrameMs as number);
  // open every panel folder so that all controls can be reached (unless the test looks at the page as it opens)
  if (options.openFolders !== false) {
    await page.evaluate(() => document.querySelectorAll<HTMLElement>('.lil-gui.lil-closed > .lil-title').forEach((t) => t.click()));
  }
  return { page, errors, readyMs };
}

/** how often page conditions are polled [ms]: on a timer, not on animation frames, which SwiftShader makes slow */
export const POLL_MS = 50;

export const byId = (page: Page, id: string) => page.locator(`[data-testid="${id}"]`);

/**
 * Pauses the loop (the panel's Play/Pause button, clicked in the page: no wait for animation frames) so that only
 * explicit steps advance the cloth, and waits until a frame it had already asked for has arrived, so the frame
 * count stays put: results independent of the machine's speed.
 */
export async function pause(page: Page): Promise<void> {
  const paused = await byId(page, 'play').locator('button').evaluate((b: HTMLButtonElement) => {
    if (!(window as any).drape.paused()) b.click();
    return (window as any).drape.paused() as boolean;
  });
  if (!paused) throw new Error('the Play/Pause button did not pause');
  // a round trip of no frames: the worker answers in order, so it comes back after any request still in flight
  await step(page, 0);
}

export async function step(page: Page, frames: number): Promise<void> {
  await page.evaluate((n) => (window as any).drape.step(n), frames);
}

/**
 * Waits until the cloth is simulated on the GPU and drawn from its buffers: its pipelines compiled, which on
 * SwiftShader takes seconds, and many more on a busy machine (a generous limit; it only stops a hang).
 */
export async function gpuReady(page: Page): Promise<void> {
  try {
    await page.waitForFunction(() => (window as any).drape.simBackend() === 'gpu' && (window as any).drape.gpuDrawing(), null, { timeout: 120_000, polling: POLL_MS });
  } catch (e) {
    const state = await page.evaluate(() => {
      const d = (window as any).drape;
      return { simBackend: d.simBackend(), gpuDrawing: d.gpuDrawing(), backend: d.backend(), scene: d.sceneName(), lastMessage: d.lastMessage().text };
    });
    throw new Error(`${(e as Error).message}; the page: ${JSON.stringify(state)}`);
  }
}

/**
 * Presses a panel button that downloads a file, and returns the file's name and bytes (read as a stream: that
 * works whether the browser was launched here or is the suite's shared one, see browser.ts).
 */
export async function download(page: Page, id: string): Promise<{ name: string; data: Buffer }> {
  const [dl] = await Promise.all([page.waitForEvent('download'), press(page, id)]);
  const chunks: Buffer[] = [];
  for await (const chunk of await dl.createReadStream()) chunks.push(chunk as Buffer);
  return { name: dl.suggestedFilename(), data: Buffer.concat(chunks) };
}

/** Picks an option of a dropdown control by its label. */
export async function choose(page: Page, id: string, label: string): Promise<void> {
  await byId(page, id).locator('select').selectOption({ label });
}

/** Types a value into a number control and commits it. */
export async function setNumber(page: Page, id: string, value: number): Promise<void> {
  const input = byId(page, id).locator('input').first();
  await input.fill(String(value));
  await input.press('Enter');
}

/**
 * Clicks a panel control once it is visible, in the page (element.click(): the click event lil-gui listens to).
 * A mouse click first waits for two steady animation frames, and on SwiftShader a frame drawing the change just
 * made takes about a second; a mouse click without that wait can land on another control while a folder of the
 * panel opens or a control appears.
 */
async function clickControl(control: Locator): Promise<void> {
  await expect.poll(() => control.isVisible(), { interval: POLL_MS }).toBe(true);
  await control.evaluate((e: HTMLElement) => e.click());
}

export async function setChecked(page: Page, id: string, on: boolean): Promise<void> {
  const box = byId(page, id).locator('input[type=checkbox]');
  if ((await box.isChecked()) !== on) await clickControl(box);
}

export async function press(page: Page, id: string): Promise<void> {
  await clickControl(byId(page, id).locator('button'));
}

export const hook = <T>(page: Page, fn: string, ...args: unknown[]): Promise<T> =>
  page.evaluate(([f, a]) => (window as any).drape[f as string](...(a as unknown[])), [fn, args] as const) as Promise<T>;

export const centroid = (page: Page, slot = 0) => hook<number[]>(page, 'centroid', slot);

/** Loads a built-in scene through the dropdown at a given resolution, paused. */
export async function loadScene(page: Page, label: string, resolution?: number): Promise<void> {
  await pause(page);
  const select = byId(page, 'scene').locator('select');
  const current = await select.evaluate((s: HTMLSelectElement) => s.selectedOptions[0]?.textContent ?? '');
  // choosing the option already shown fires no change: go through another scene to start afresh
  if (current === label) await choose(page, 'scene', label === 'Cotton Basic' ? 'Silk Drape' : 'Cotton Basic');
  await choose(page, 'scene', label);
  if (resolution) await choose(page, 'cloth.resolution', `${resolution} × ${resolution}  (${(resolution * resolution).toLocaleString('en')} face${resolution === 1 ? '' : 's'})`);
  await page.waitForFunction(() => (window as any).drape.frame() === 0, null, { polling: POLL_MS });
}

/** the 3D view only (left of the panel, below the HUD): where "not blank" is judged */
const VIEW_CLIP = { x: 300, y: 320, width: 340, height: 260 };

/** Waits for two animation frames, so that the latest positions are on screen. */
async function drawn(page: Page): Promise<void> {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}

/**
 * Saves a screenshot of the page under test-results/ and returns the stats of its 3D view (see viewStats), taken
 * from the same picture: for "not blank" checks.
 */
export async function shoot(page: Page, name: string): Promise<{ colours: number; lumaStd: number }> {
  mkdirSync(RESULTS, { recursive: true });
  await drawn(page);
  const png = await page.screenshot();
  writeFileSync(`${RESULTS}/${name}.png`, png);
  return imageStats(crop(decodePng(png), VIEW_CLIP));
}

/** Stats of the 3D view only (left of the panel, below the HUD): for "not blank" checks. */
export async function viewStats(page: Page): Promise<{ colours: number; lumaStd: number }> {
  await drawn(page);
  return imageStats(decodePng(await page.screenshot({ clip: VIEW_CLIP })));
}

export function writeJson(name: string, data: unknown): void {
  mkdirSync(RESULTS, { recursive: true });
  writeFileSync(`${RESULTS}/${name}.json`, JSON.stringify(data, null, 2));
}
