/** Page helpers for the browser tests: open the app, drive the panel by its test ids, read window.drape. */
import { mkdirSync, writeFileSync } from 'node:fs';
import type { BrowserContext, Page } from 'playwright-core';
import { inject } from 'vitest';
import { collectErrors } from './browser.js';
import { decodePng, imageStats } from './png.js';

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
 * no `window.drape` without it.
 */
export async function openApp(context: BrowserContext, hash = '', query = '?lite'): Promise<Opened> {
  const page = await context.newPage();
  const errors = collectErrors(page);
  await page.goto(`${inject('baseURL')}${withHook(query)}${hash}`);
  await page.waitForFunction(() => (window as any).drape?.ready === true, null, { timeout: 30_000 });
  const readyMs = await page.evaluate(() => (window as any).drape.firstFrameMs as number);
  // open every panel folder so that all controls can be reached
  await page.evaluate(() => document.querySelectorAll<HTMLElement>('.lil-gui.lil-closed > .lil-title').forEach((t) => t.click()));
  return { page, errors, readyMs };
}

export const byId = (page: Page, id: string) => page.locator(`[data-testid="${id}"]`);

/** Pauses the loop so that only explicit steps advance the cloth (results independent of the machine's speed). */
/** Pauses the loop and waits until a frame it had already asked for has arrived, so the frame count stays put. */
export async function pause(page: Page): Promise<void> {
  if (!(await page.evaluate(() => (window as any).drape.paused()))) await byId(page, 'play').locator('button').click();
  await page.waitForFunction(() => (window as any).drape.paused());
  // a round trip of no frames: the worker answers in order, so it comes back after any request still in flight
  await step(page, 0);
}

export async function step(page: Page, frames: number): Promise<void> {
  await page.evaluate((n) => (window as any).drape.step(n), frames);
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

export async function setChecked(page: Page, id: string, on: boolean): Promise<void> {
  const box = byId(page, id).locator('input[type=checkbox]');
  if ((await box.isChecked()) !== on) await box.click();
}

export async function press(page: Page, id: string): Promise<void> {
  await byId(page, id).locator('button').click();
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
  if (resolution) await choose(page, 'cloth.resolution', `${resolution} × ${resolution}  (${resolution * resolution} faces)`);
  await page.waitForFunction(() => (window as any).drape.frame() === 0);
}

/** Saves a screenshot under test-results/ and checks it is not blank. */
export async function shoot(page: Page, name: string): Promise<{ colours: number; lumaStd: number }> {
  mkdirSync(RESULTS, { recursive: true });
  // two frames so the latest positions are on screen
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const png = await page.screenshot();
  writeFileSync(`${RESULTS}/${name}.png`, png);
  return imageStats(decodePng(png));
}

/** Stats of the 3D view only (left of the panel, below nothing): for "not blank" checks. */
export async function viewStats(page: Page): Promise<{ colours: number; lumaStd: number }> {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const png = await page.screenshot({ clip: { x: 300, y: 320, width: 340, height: 260 } });
  return imageStats(decodePng(png));
}

export function writeJson(name: string, data: unknown): void {
  mkdirSync(RESULTS, { recursive: true });
  writeFileSync(`${RESULTS}/${name}.json`, JSON.stringify(data, null, 2));
}
