/**
 * `drape run` with the collider shapes, the analytic ones and a mesh from a file: runs on the CPU and on the GPU, which
 * agree; bad fields name themselves.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { main } from './main.js';

async function run(...argv: string[]) {
  const out: string[] = [], err: string[] = [];
  const code = await main(argv, (s) => out.push(s), (s) => err.push(s));
  return { code, out: out.join('\n'), err: err.join('\n') };
}

function sceneFile(colliders: object[]): string {
  const dir = mkdtempSync(join(tmpdir(), 'drape-colliders-'));
  const path = join(dir, 'scene.json');
  writeFileSync(path, JSON.stringify({ name: 'shapes', cloth: { resolution: 8, position: [0, 0.9, 0] }, colliders }));
  return path;
}

const box = { type: 'box', center: [0, 0.35, 0], halfExtents: [0.3, 0.35, 0.3], rotation: [0, 20, 0] };

describe('drape run with the new collider shapes', () => {
  it('a box scene runs on the CPU: the cloth lies on the box', async () => {
    const r = await run('run', sceneFile([box, { type: 'floor', height: 0 }]), '--frames', '90', '--json');
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    expect(j).toMatchObject({ backend: 'cpu', finite: true, particles: 81 });
    expect(j.maxPenetration).toBeLessThanOrEqual(0.005);
    // on the table top (0.7 m), its edges hanging, not on the floor
    expect(j.bounds.max[1]).toBeGreaterThan(0.7);
    expect(j.bounds.max[1]).toBeLessThan(0.8);
    expect(j.centroid[1]).toBeGreaterThan(0.55);
  });

  it('the built-in tablecloth runs, and plane, capsule and cylinder scenes too', async () => {
    expect((await run('run', 'tablecloth', '--frames', '10', '--set', 'cloth.resolution=8', '--json')).code).toBe(0);
    for (const c of [{ type: 'plane', normal: [0.2, 1, 0] }, { type: 'capsule' }, { type: 'cylinder' }]) {
      const r = await run('run', sceneFile([c]), '--frames', '30', '--json');
      expect(r.code, JSON.stringify(c)).toBe(0);
      expect(JSON.parse(r.out).finite).toBe(true);
    }
  });

  // 20 frames: the cloth (dropped from 0.9 m) has landed on each shape; GPU–CPU centroid seen ≤ 1.1e-4 m → 1 mm
  // (the parity tolerance of src/gpu/moving-colliders.test.ts)
  it.each([
    [{ type: 'box' }, 0], [{ type: 'capsule' }, 1], [{ type: 'cylinder' }, 1], [{ type: 'plane', point: [0, 0.6, 0], normal: [0.2, 1, 0] }, 1],
  ])('--backend gpu runs %j (colliders[%i]) as the CPU does', async (shape, k) => {
    const colliders = k === 0 ? [shape] : [{ type: 'sphere', center: [0.8, 0.3, 0.8], radius: 0.2 }, shape];
    const args = ['run', sceneFile(colliders), '--frames', '20', '--json'];
    const r = await run(...args, '--backend', 'gpu');
    expect(r.code, r.err).toBe(0);
    const gpu = JSON.parse(r.out), cpu = JSON.parse((await run(...args)).out);
    expect(gpu).toMatchObject({ backend: 'gpu', finite: true, particles: 81 });
    expect(gpu.maxPenetration).toBeLessThanOrEqual(1e-3);
    gpu.centroid.forEach((c: number, j: number) => expect(Math.abs(c - cpu.centroid[j])).toBeLessThan(1e-3));
  });

  it('--backend gpu runs a moving box that carries pins', async () => {
    const moving = { ...box, pins: ['top-left'], motion: { keyframes: [{ time: 0 }, { time: 0.5, translation: [0, 0.1, 0], rotation: [0, 30, 0] }] } };
    const r = await run('run', sceneFile([moving]), '--frames', '20', '--backend', 'gpu', '--json');
    expect(r.code, r.err).toBe(0);
    expect(JSON.parse(r.out)).toMatchObject({ backend: 'gpu', finite: true });
  });

  it.each([
    [{ type: 'box', halfExtents: [0.3, -1, 0.3] }, 'colliders[0].halfExtents[1]: must be >= 0.001'],
    [{ type: 'box', rotation: [0, 400, 0] }, 'colliders[0].rotation[1]: must be <= 360'],
    [{ type: 'capsule', a: [0, 0] }, 'colliders[0].a: must NOT have fewer than 3 items'],
    [{ type: 'cylinder', axis: [0, 0, 0] }, 'colliders[0].axis: must not be zero'],
    [{ type: 'cylinder', radius: 'wide' }, 'colliders[0].radius: must be number'],
    [{ type: 'plane', up: [0, 1, 0] }, 'colliders[0].up: unknown key'],
    [{ type: 'torus' }, 'colliders[0].type: must be one of "sphere", "floor", "plane", "box", "capsule", "cylinder", "mesh"'],
  ])('%j: exit 2, one line naming the field', async (c, message) => {
    const r = await run('run', sceneFile([c]), '--frames', '1');
    expect(r.code).toBe(2);
    expect(r.err.split('\n')).toHaveLength(1);
    expect(r.err).toContain(message);
  });

  it('--set reaches the new fields, with the same errors', async () => {
    const path = sceneFile([box]);
    expect((await run('run', path, '--frames', '5', '--set', 'colliders[0].halfExtents=[0.2,0.2,0.2]', '--json')).code).toBe(0);
    const r = await run('run', path, '--frames', '5', '--set', 'colliders[0].halfExtents=[0.2,0,0.2]');
    expect(r.code).toBe(2);
    expect(r.err).toContain('colliders[0].halfExtents[1]: must be >= 0.001');
  });
});

/** A folder with scene.json and a unit cube OBJ (standing on y = 0 in the file's own coordinates). */
function meshSceneFile(collider: object, objText?: string): string {
  const dir = mkdtempSync(join(tmpdir(), 'drape-mesh-collider-'));
  writeFileSync(join(dir, 'cube.obj'), objText ?? [
    'v -0.3 0 -0.3', 'v 0.3 0 -0.3', 'v 0.3 0 0.3', 'v -0.3 0 0.3', 'v -0.3 0.6 -0.3', 'v 0.3 0.6 -0.3', 'v 0.3 0.6 0.3', 'v -0.3 0.6 0.3',
    'f 1 2 3 4', 'f 5 8 7 6', 'f 1 5 6 2', 'f 2 6 7 3', 'f 3 7 8 4', 'f 4 8 5 1',
  ].join('\n'));
  const path = join(dir, 'scene.json');
  writeFileSync(path, JSON.stringify({ name: 'mesh', cloth: { resolution: 8, position: [0, 0.9, 0] }, colliders: [collider, { type: 'floor', height: 0 }] }));
  return path;
}

describe('drape run with a mesh collider', () => {
  it('a cube OBJ next to the scene file: the cloth lies on it, in the file\'s own coordinates', async () => {
    const r = await run('run', meshSceneFile({ type: 'mesh', mesh: 'cube.obj' }), '--frames', '90', '--json');
    expect(r.code, r.err).toBe(0);
    const j = JSON.parse(r.out);
    expect(j).toMatchObject({ backend: 'cpu', finite: true, particles: 81 });
    expect(j.maxPenetration).toBeLessThanOrEqual(0.005);
    expect(j.bounds.max[1]).toBeGreaterThan(0.6);
    expect(j.bounds.max[1]).toBeLessThan(0.7);
  });

  it('scale, position and rotation place it', async () => {
    const r = await run('run', meshSceneFile({ type: 'mesh', mesh: 'cube.obj', scale: 0.5, position: [0, 0.2, 0], rotation: [0, 45, 0] }), '--frames', '90', '--json');
    expect(r.code, r.err).toBe(0);
    const top = JSON.parse(r.out).bounds.max[1];
    expect(top).toBeGreaterThan(0.5); // 0.2 + 0.3
    expect(top).toBeLessThan(0.6);
  });

  it.each([
    [{ type: 'mesh' }, undefined, 'colliders[0].mesh: required'],
    [{ type: 'mesh', mesh: 'missing.obj' }, undefined, 'colliders[0].mesh: '],
    [{ type: 'mesh', mesh: 'cube.stl' }, undefined, 'colliders[0].mesh: cube.stl: not a mesh file'],
    [{ type: 'mesh', mesh: 'cube.obj' }, 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3', 'colliders[0].mesh: cube.obj: no triangle has any area'],
    [{ type: 'mesh', mesh: 'cube.obj', scale: 0 }, undefined, 'colliders[0].scale: must be >= 0.000001'],
  ])('%j: exit 2, one line naming the field', async (c, obj, message) => {
    const r = await run('run', meshSceneFile(c, obj), '--frames', '1');
    expect(r.code).toBe(2);
    expect(r.err.split('\n')).toHaveLength(1);
    expect(r.err).toContain(message);
  });

  // 20 frames of 10 substeps: the cloth (dropped from 0.9 m) has landed on the cube; GPU–CPU centroid as for the
  // analytic shapes above → 1 mm
  it('--backend gpu runs it from its file as the CPU does', async () => {
    const scene = meshSceneFile({ type: 'mesh', mesh: 'cube.obj', rotation: [0, 20, 0] });
    const args = ['run', scene, '--frames', '20', '--set', 'solver.substeps=10', '--json'];
    const r = await run(...args, '--backend', 'gpu');
    expect(r.code, r.err).toBe(0);
    const gpu = JSON.parse(r.out), cpu = JSON.parse((await run(...args)).out);
    expect(gpu).toMatchObject({ backend: 'gpu', finite: true, particles: 81 });
    expect(gpu.maxPenetration).toBeLessThanOrEqual(1e-3);
    gpu.centroid.forEach((c: number, j: number) => expect(Math.abs(c - cpu.centroid[j])).toBeLessThan(1e-3));
  });
});
