import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { Ajv } from 'ajv';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { builtinScene, sceneSchema, SCENE_NAMES } from '../core/index.js';
import { CORE_AJV_OPTIONS, precompiledAjvModule } from './precompiled-ajv.js';

type Validate = ((data: unknown) => boolean) & { errors?: unknown[] | null };
interface Precompiled { validate: Validate; Ajv: new (options?: object) => { compile(schema: object): Validate } }

let pre: Precompiled;
let file = '';
const live = new Ajv(CORE_AJV_OPTIONS).compile(sceneSchema) as Validate;

beforeAll(async () => {
  // inside the repository, so that the module's imports of ajv's run-time helpers resolve
  const dir = join('node_modules', '.cache', 'drape-test');
  mkdirSync(dir, { recursive: true });
  file = join(dir, `precompiled-ajv-${process.pid}.mjs`);
  writeFileSync(file, precompiledAjvModule(sceneSchema));
  pre = await import(/* @vite-ignore */ pathToFileURL(file).href) as Precompiled;
});

afterAll(() => { if (file) rmSync(file, { force: true }); });

const DOCS: unknown[] = [
  {},
  { name: 'x'.repeat(100) },
  { name: '😀'.repeat(100) }, // 100 characters by ucs2length, 200 UTF-16 units
  { name: 'x'.repeat(101) },
  { name: '<img src=x onerror=alert(1)>' },
  { cloth: { resolution: 2048 } },
  { cloth: { resolution: 1.5, position: [0, 1] } },
  { material: { damping: 99, mass: -1 }, solver: { type: 'verlet' } },
  { colliders: [{ type: 'sphere', center: [0, 0.5, 0], radius: 0.3 }, { type: 'floor', height: 0 }, { type: 'box' }] },
  { pins: ['top-left', 'top-left', 5, 'nowhere'] },
  { resolutionSweep: [1, 2, 4, 2048] },
  { wind: { enabled: true, gusts: { enabled: true, seed: 3 } }, extra: 1 },
  [],
  'scene',
  null,
  ...SCENE_NAMES.map((n) => builtinScene(n)),
];

describe('the site\'s precompiled scene validator (no code generated in the page)', () => {
  it('accepts, refuses, reports and fills in defaults exactly like Ajv at run time', () => {
    for (const doc of DOCS) {
      const a = structuredClone(doc), b = structuredClone(doc);
      const okLive = live(a), okPre = pre.validate(b);
      expect(okPre, JSON.stringify(doc)).toBe(okLive);
      expect(pre.validate.errors ?? null).toEqual(live.errors ?? null);
      expect(b).toEqual(a); // defaults filled in the same way
    }
  });

  it('its Ajv hands out the validator only for the core\'s options and schema', () => {
    expect(new pre.Ajv(CORE_AJV_OPTIONS).compile(structuredClone(sceneSchema))).toBe(pre.validate);
    expect(() => new pre.Ajv({ ...CORE_AJV_OPTIONS, allErrors: false })).toThrow(/built for the options/);
    expect(() => new pre.Ajv(CORE_AJV_OPTIONS).compile({ type: 'object' })).toThrow(/not built for/);
  });
});
