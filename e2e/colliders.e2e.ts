/**
 * The analytic collider shapes in the app (issue 11, first step): a scene file with a box and a capsule, imported
 * through the panel, draws both; the cloth drapes on them on the CPU worker; the automatic backend choice, from the
 * start and with this scene, stays on the CPU on this software WebGPU adapter and says why (the adapter: the GPU
 * solver has every collider shape). Explicit steps on a small cloth: nothing depends on the machine's speed.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launch, type Browser } from './browser.js';
import { byId, hook, openApp, pause, shoot, step } from './helpers.js';

let browser: Browser;

beforeAll(async () => {
  browser = await launch('webgpu');
});

afterAll(async () => {
  await browser?.close();
});

const BOX = { type: 'box', center: [-0.25, 0.3, 0], halfExtents: [0.2, 0.3, 0.3], rotation: [0, 15, 0] };
const CAPSULE = { type: 'capsule', a: [0.25, 0.25, -0.4], b: [0.25, 0.25, 0.4], radius: 0.12 };
const SCENE = {
  name: '<i>shapes</i>',
  cloth: { resolution: 12, position: [0, 0.9, 0] },
  colliders: [BOX, CAPSULE, { type: 'floor', height: 0 }],
};

/** exact signed distances, from the shapes' definitions */
function boxDistance(p: number[]): number {
  const t = (BOX.rotation[1] * Math.PI) / 180;
  // the box's axes: x and z turned about y
  const axes = [[Math.cos(t), 0, -Math.sin(t)], [0, 1, 0], [Math.sin(t), 0, Math.cos(t)]];
  const d = p.map((v, k) => v - BOX.center[k]);
  const e = axes.map((a, k) => Math.abs(a[0] * d[0] + a[1] * d[1] + a[2] * d[2]) - BOX.halfExtents[k]);
  const o = Math.hypot(...e.map((v) => Math.max(v, 0)));
  return o > 0 ? o : Math.max(...e);
}
function capsuleDistance(p: number[]): number {
  const ab = CAPSULE.b.map((v, k) => v - CAPSULE.a[k]);
  const ap = p.map((v, k) => v - CAPSULE.a[k]);
  const t = Math.min(Math.max((ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2]) / (ab[0] ** 2 + ab[1] ** 2 + ab[2] ** 2), 0), 1);
  return Math.hypot(...ap.map((v, k) => v - t * ab[k])) - CAPSULE.radius;
}

describe('collider shapes in the app', () => {
  it('an imported scene with a box and a capsule draws them, drapes on them on the CPU, and auto says why not the GPU (the adapter, not the shapes)', async () => {
    const { page, errors } = await openApp(browser.context); // SwiftShader here: a fallback adapter
    await page.waitForFunction(() => (window as any).drape.backend() === 'webgpu');
    // auto, from the start (the default scene): WebGPU draws, the cloth runs on the CPU worker, the HUD says why
    expect(await hook(page, 'simBackend')).toBe('cpu');
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('software fallback');
    await byId(page, 'import-file').setInputFiles({ name: 'shapes.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(SCENE)) });
    await expect.poll(() => hook(page, 'sceneName')).toBe('<i>shapes</i>');
    // the scene's name reaches the page as text only
    expect(await page.locator('i', { hasText: 'shapes' }).count()).toBe(0);
    expect(await hook(page, 'colliders')).toEqual(['box', 'capsule']);
    expect(await hook(page, 'particleCount')).toBe(169);

    // auto keeps the CPU worker on this software adapter, and the HUD says so: the GPU has boxes and capsules
    expect(await hook(page, 'simBackend')).toBe('cpu');
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('software fallback');
    expect(await byId(page, 'hud').innerText()).not.toContain('CPU only');

    await pause(page);
    await step(page, 150);
    const all = Array.from({ length: 169 }, (_, i) => i);
    const x = await hook<number[][]>(page, 'positions', all);
    expect(x.flat().every(Number.isFinite)).toBe(true);
    // no particle inside either shape (the contact thickness is 5 mm; particles are kept at it)
    const deepest = Math.min(...x.map(boxDistance), ...x.map(capsuleDistance));
    expect(deepest).toBeGreaterThan(-0.005);
    // it lies on them: over the box top (0.6 m) and the capsule (0.37 m), not fallen to the floor
    expect(Math.max(...x.map((p) => p[1]))).toBeGreaterThan(0.6);
    expect(Math.min(...x.map(boxDistance))).toBeLessThan(0.01);
    expect(Math.min(...x.map(capsuleDistance))).toBeLessThan(0.01);

    const s = await shoot(page, 'colliders-box-capsule');
    expect(s.colours).toBeGreaterThan(20);
    expect(s.lumaStd).toBeGreaterThan(4);
    expect(errors).toEqual([]);
    await page.close();
  });
  it('a floor that moves is drawn where it is: the ground rises with its collider, and the cloth on it', async () => {
    const { page, errors } = await openApp(browser.context, '', '?lite&backend=cpu');
    const rising = {
      name: 'rising floor',
      cloth: { resolution: 8, position: [0, 0.3, 0] },
      colliders: [{ type: 'floor', height: 0, motion: { keyframes: [{ time: 0 }, { time: 1, translation: [0, 0.2, 0] }] } }],
    };
    await hook(page, 'import', JSON.stringify(rising));
    await expect.poll(() => hook(page, 'sceneName')).toBe('rising floor');
    expect(await hook<number>(page, 'groundHeight')).toBeCloseTo(0, 6);
    await step(page, 60); // 1 s: the floor 0.2 m up
    await expect.poll(() => hook<number>(page, 'groundHeight')).toBeCloseTo(0.2, 3);
    const ys = (await hook<number[][]>(page, 'positions')).map((p) => p[1]);
    expect(Math.min(...ys)).toBeGreaterThan(0.2);
    expect(errors).toEqual([]);
    await page.close();
  });
});
