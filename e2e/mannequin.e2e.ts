/**
 * The mannequin in the app: the `cape` scene loads from the scene menu, draws the mannequin's 15 parts, the cape
 * runs on the CPU worker, the drawn mannequin turns with the simulated time (its meshes posed from the same
 * keyframes the physics uses), and the panel's Mannequin controls pose it anew, the cloth starting again (and the link
 * says so). No errors, no CSP violations. Explicit steps: nothing depends on the machine's speed.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launch, type Browser } from './browser.js';
import { byId, choose, hook, loadScene, openApp, pause, shoot, step } from './helpers.js';

let browser: Browser;

beforeAll(async () => {
  browser = await launch('webgl');
});

afterAll(async () => {
  await browser?.close();
});

type Pose = { position: number[]; quaternion: number[] };

/** The angle [degrees] a drawn mesh turned about the vertical between two poses (quaternions x, y, z, w). */
function turnedAboutY(a: Pose, b: Pose): number {
  // b·a⁻¹ for unit quaternions; its y part and w give the turn about y (the mannequin's turn is about y only)
  const [ax, ay, az, aw] = a.quaternion, [bx, by, bz, bw] = b.quaternion;
  const w = bw * aw + bx * ax + by * ay + bz * az;
  const y = by * aw - bw * ay - bz * ax + bx * az;
  return (2 * Math.atan2(y, w) * 180) / Math.PI;
}

/** The drawn collider meshes once the page has drawn what the last step brought (two animation frames later). */
async function drawnPoses(page: import('playwright-core').Page): Promise<Pose[]> {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return hook<Pose[]>(page, 'colliderPoses');
}

describe('the mannequin in the app', () => {
  it('cape: the mannequin is drawn, turns as the cloth runs, and its animation is a control', async () => {
    const { page, errors } = await openApp(browser.context);
    await pause(page);
    await loadScene(page, 'Cape');
    await expect.poll(() => hook(page, 'sceneName')).toBe('cape');
    await pause(page);
    expect(await hook(page, 'colliders')).toEqual(['sphere', ...Array(14).fill('capsule')]);
    expect(await hook(page, 'mannequin')).toEqual({ pose: 'stand', animation: 'turn' });
    expect(await byId(page, 'mannequin.animation').isVisible()).toBe(true);
    expect(await hook(page, 'simBackend')).toBe('cpu');

    const chest = 2;
    const start = (await drawnPoses(page))[chest];
    const frame0 = await hook<number>(page, 'frame');
    // at frame f the turn is at 70°·sin(2π·f/240) (TURN_ANGLE, TURN_PERIOD 4 s): at frame 60, its 70° to the left
    await step(page, 60 - frame0);
    expect(await hook(page, 'frame')).toBe(60);
    const turned = (await drawnPoses(page))[chest];
    expect(turnedAboutY(start, turned)).toBeCloseTo(70 - 70 * Math.sin((2 * Math.PI * frame0) / 240), 0);
    const x = await hook<number[][]>(page, 'positions');
    expect(x.flat().every(Number.isFinite)).toBe(true);
    await shoot(page, 'mannequin-cape-turning');

    // the animation control: 'none' holds the pose, so the mannequin is drawn back where it stands, and the cloth
    // starts again with it (its carried pins would otherwise jump 70° round in one substep)
    await choose(page, 'mannequin.animation', 'none');
    await expect.poll(() => hook(page, 'mannequin')).toEqual({ pose: 'stand', animation: 'none' });
    // the link says so in one key
    await expect.poll(() => page.evaluate(() => location.hash)).toBe('#scene=cape&mannequin=stand,none');
    expect(await hook(page, 'frame')).toBeLessThan(60);
    await step(page, 1);
    const held = (await drawnPoses(page))[chest];
    expect(Math.abs(turnedAboutY(start, held) + 70 * Math.sin((2 * Math.PI * frame0) / 240))).toBeLessThan(0.5);
    expect(held.position.map((v, k) => Math.abs(v - start.position[k])).every((d) => d < 1e-3)).toBe(true);

    // walking: the cape starts clear of the legs (it was once refused: a shin started inside it)
    await choose(page, 'mannequin.animation', 'walk');
    await expect.poll(() => hook(page, 'mannequin')).toEqual({ pose: 'stand', animation: 'walk' });
    await expect.poll(() => page.evaluate(() => location.hash)).toBe('#scene=cape&mannequin=stand,walk');
    await step(page, 30);
    expect((await hook<number[][]>(page, 'positions')).flat().every(Number.isFinite)).toBe(true);
    // the garment's shape is the scene's: the Shape control is off, and says why
    const shape = byId(page, 'cloth.shape');
    expect(await shape.locator('select').isDisabled()).toBe(true);
    expect(await shape.getAttribute('title')).toMatch(/garment fitted to the mannequin/);
    expect(errors).toEqual([]);
    await page.close();
  });
});
