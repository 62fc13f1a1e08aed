/**
 * A mesh collider in the app: a scene file naming a mesh collider's file that is not imported is refused, asking
 * for the file, and waits for it; a bad file is refused naming the field, the page unchanged; the good file loads
 * the scene, the collider drawn, the cloth coming to rest on it on the CPU worker, and the automatic backend saying
 * why it is not the GPU. A link naming the file shows the scene without it meanwhile, and the file then brings the
 * whole scene back, the collider drawn where its keyframes put it. Small cloth, explicit steps, waits on conditions.
 */
import type { Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { validateScene } from '../src/core/scene.js';
import { sceneRefusal } from '../src/gpu/encoder.js';
import { launch, type Browser } from './browser.js';
import { byId, hook, openApp, pause, shoot, step } from './helpers.js';

let browser: Browser;

beforeAll(async () => {
  browser = await launch('webgpu');
});

afterAll(async () => {
  await browser?.close();
});

/** half width and height of the pedestal [m]; the file is in centimetres, its origin at the middle of its base */
const HALF = 0.25, TOP = 0.4;
const PEDESTAL_OBJ = Buffer.from([
  ...[[-25, 0, -25], [25, 0, -25], [-25, 40, -25], [25, 40, -25], [-25, 0, 25], [25, 0, 25], [-25, 40, 25], [25, 40, 25]]
    .map((v) => `v ${v.join(' ')}`),
  'f 1 5 7 3', 'f 2 4 8 6', 'f 1 2 6 5', 'f 3 7 8 4', 'f 1 3 4 2', 'f 5 6 8 7',
].join('\n') + '\n');
/** three points on a line: no face with area, which the core refuses for a collider */
const FLAT_OBJ = Buffer.from('v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n');

/** a 0.8 m cloth of 9 × 9 particles over the 0.5 m pedestal, which its edges overhang */
const SCENE = {
  name: 'on a pedestal',
  cloth: { resolution: 8, width: 0.8, height: 0.8, position: [0, 0.55, 0] },
  colliders: [{ type: 'mesh', mesh: 'pedestal.obj', scale: 0.01 }, { type: 'floor', height: 0 }],
};
const PARTICLES = 81;

const message = (page: Page) => hook<{ text: string; kind: string }>(page, 'lastMessage');
const importScene = (page: Page, name: string, scene: unknown) =>
  byId(page, 'import-file').setInputFiles({ name, mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scene)) });
const importMesh = (page: Page, name: string, buffer: Buffer) =>
  byId(page, 'import-mesh-file').setInputFiles({ name, mimeType: 'application/octet-stream', buffer });
const positions = (page: Page) => hook<number[][]>(page, 'positions');

/** the pedestal's exact signed distance [m] */
function pedestalDistance(p: number[]): number {
  const e = [Math.abs(p[0]) - HALF, Math.abs(p[1] - TOP / 2) - TOP / 2, Math.abs(p[2]) - HALF];
  const out = Math.hypot(...e.map((v) => Math.max(v, 0)));
  return out > 0 ? out : Math.max(...e);
}

/** Steps until no particle moves 1 mm over 10 frames (at most 600 frames). */
async function toRest(page: Page): Promise<void> {
  let before = await positions(page);
  for (let frames = 10; frames <= 600; frames += 10) {
    await step(page, 10);
    const now = await positions(page);
    const moved = Math.max(...now.map((p, i) => Math.hypot(p[0] - before[i][0], p[1] - before[i][1], p[2] - before[i][2])));
    if (moved < 1e-3) return;
    before = now;
  }
  throw new Error('the cloth did not come to rest in 600 frames');
}

describe('a mesh collider in the app', () => {
  it('a scene file waits for its collider\'s file; a bad one is refused naming the field; the good one drapes the cloth on it', async () => {
    const { page, errors } = await openApp(browser.context); // auto: the backend the scene and adapter allow
    const sceneBefore = await hook<string>(page, 'sceneName');
    const collidersBefore = await hook<string[]>(page, 'colliders');

    // the collider's file is not here: refused, asking for it, nothing changed
    await importScene(page, 'pedestal.json', SCENE);
    await expect.poll(async () => (await message(page)).text).toContain(
      "Import refused — pedestal.json: colliders[0].mesh: 'pedestal.obj' is a mesh file that is not imported in this page: import the mesh file pedestal.obj too");
    expect((await message(page)).text).toContain('pedestal.json loads once pedestal.obj is imported');
    expect(await hook(page, 'sceneName')).toBe(sceneBefore);
    expect(await hook(page, 'colliders')).toEqual(collidersBefore);

    // a file by that name that is no collider: refused naming the field and the file, nothing changed
    await importMesh(page, 'pedestal.obj', FLAT_OBJ);
    await expect.poll(async () => (await message(page)).text)
      .toBe('Mesh import refused — pedestal.json: colliders[0].mesh: pedestal.obj: no triangle has any area');
    expect(await hook(page, 'sceneName')).toBe(sceneBefore);
    expect(await hook(page, 'colliders')).toEqual(collidersBefore);

    // the pedestal: the waiting scene loads, the collider drawn (the floor is the stage's ground)
    await importMesh(page, 'pedestal.obj', PEDESTAL_OBJ);
    await expect.poll(() => hook(page, 'sceneName')).toBe('on a pedestal');
    expect((await message(page)).text).toContain('Imported mesh pedestal.obj: loaded pedestal.json');
    expect(await hook(page, 'colliders')).toEqual(['mesh']);
    expect(await hook(page, 'particleCount')).toBe(PARTICLES);
    expect((await hook<any>(page, 'scene')).colliders[0].mesh).toBe('pedestal.obj');

    // auto: the GPU only if the GPU solver takes the scene; here the worker, and the HUD says why
    const why = sceneRefusal(validateScene(SCENE)) ?? 'software fallback';
    expect(await hook(page, 'simBackend')).toBe('cpu');
    await expect.poll(() => byId(page, 'hud').innerText()).toContain(why);
    await expect.poll(() => byId(page, 'hud').innerText()).toContain('a link cannot carry an imported mesh (pedestal.obj)');

    await pause(page);
    await toRest(page);
    const x = await positions(page);
    expect(x.flat().every(Number.isFinite)).toBe(true);
    // outside the pedestal, on its top: the middle of the cloth at the top's height plus the contact thickness
    // (5 mm), the particles nearer its edges a little higher (the triangles over the edges keep off them), the
    // overhang below the top, nothing fallen to the floor
    expect(Math.min(...x.map(pedestalDistance))).toBeGreaterThan(-0.002);
    const over = (p: number[], r: number) => Math.abs(p[0]) < r && Math.abs(p[2]) < r;
    const middle = x.filter((p) => over(p, 0.15));
    expect(middle).toHaveLength(9);
    for (const p of middle) expect(p[1]).toBeCloseTo(TOP + 0.005, 2);
    for (const p of x.filter((q) => over(q, HALF))) {
      expect(p[1]).toBeGreaterThan(TOP);
      expect(p[1]).toBeLessThan(TOP + 0.03);
    }
    expect(Math.min(...x.map((p) => p[1]))).toBeLessThan(TOP - 0.05);
    expect(Math.min(...x.map((p) => p[1]))).toBeGreaterThan(0.05);
    const s = await shoot(page, 'mesh-collider-pedestal');
    expect(s.colours).toBeGreaterThan(20);

    // the link names the file (it cannot carry it)
    await expect.poll(() => page.evaluate(() => decodeURIComponent(location.hash))).toContain('"mesh":"pedestal.obj"');
    expect(errors).toEqual([]);
    await page.close();
  });

  it('a link naming a mesh collider\'s file shows the scene without it, then with it once imported, drawn where it moves', async () => {
    const moving = {
      ...SCENE,
      colliders: [
        { ...SCENE.colliders[0], motion: { keyframes: [{ time: 0 }, { time: 1, translation: [0, 0.1, 0], rotation: [0, 45, 0] }] } },
        SCENE.colliders[1],
      ],
    };
    const hash = `#name=${encodeURIComponent(moving.name)}&cloth.resolution=8&cloth.width=0.8&cloth.height=0.8&cloth.position=[0,0.55,0]` +
      `&colliders=${encodeURIComponent(JSON.stringify(moving.colliders))}`;
    const { page, errors } = await openApp(browser.context, hash, '?lite&backend=cpu');
    const msg = await message(page);
    expect(msg.text).toBe('link: colliders[0] is the mesh file pedestal.obj, which a link cannot carry: import the mesh file pedestal.obj ' +
      '(Scene & export → import mesh…) to see it; showing the scene without colliders[0] meanwhile');
    expect(msg.kind).toBe('error');
    expect(await hook(page, 'sceneName')).toBe('on a pedestal');
    expect(await hook(page, 'colliders')).toEqual([]);
    expect(await hook(page, 'particleCount')).toBe(PARTICLES);

    await importMesh(page, 'pedestal.obj', PEDESTAL_OBJ);
    await expect.poll(() => hook(page, 'colliders')).toEqual(['mesh']);
    expect((await message(page)).text).toContain('Imported mesh pedestal.obj: loaded the link');
    expect((await hook<any>(page, 'scene')).colliders[0].motion.keyframes).toHaveLength(2);
    await pause(page);
    expect(await hook(page, 'frame')).toBe(0);
    await step(page, 60);
    // 1 s: 0.1 m up and turned 45° about y, as its keyframes say
    await expect.poll(async () => (await hook<{ position: number[] }[]>(page, 'colliderPoses'))[0].position[1]).toBeCloseTo(0.1, 4);
    const [pose] = await hook<{ position: number[]; quaternion: number[] }[]>(page, 'colliderPoses');
    const half = (22.5 * Math.PI) / 180;
    [0, Math.sin(half), 0, Math.cos(half)].forEach((q, k) => expect(pose.quaternion[k]).toBeCloseTo(q, 4));
    expect(pose.position[0]).toBeCloseTo(0, 4);
    expect(pose.position[2]).toBeCloseTo(0, 4);
    expect(errors).toEqual([]);
    await page.close();
  });
});
