import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { COLLIDER_TYPES, defaultScene, parseScene, parseSetValue, SceneError, setScenePath, TEST_TYPES, validateScene } from './scene.js';
import { sceneSchema } from './scene-schema.js';
import { builtinScene, isBuiltinScene, SCENE_NAMES } from './scenes.js';

/** the scene schema's fields, read as a tree (its declared type is any JSON Schema document) */
type SchemaTree = { properties: Record<string, any> };

const rejects = (doc: unknown, field: RegExp) => {
  expect(() => validateScene(doc)).toThrow(SceneError);
  expect(() => validateScene(doc)).toThrow(field);
};

describe('scenes', () => {
  it('every built-in scene validates, with the seed presets among them', () => {
    for (const name of ['cotton-basic', 'silk-drape', 'leather-stiff', 'rubber-stretch', 'custom', 'wind', 'pins', 'resolution']) {
      expect(SCENE_NAMES).toContain(name);
      expect(builtinScene(name)!.name).toBe(name);
    }
    expect(() => builtinScene('nope')).toThrow(/^unknown scene 'nope' \(built-in scenes: cotton-basic, /);
    // prototype names are not scenes
    for (const name of ['__proto__', 'constructor', 'toString', 'hasOwnProperty']) {
      expect(isBuiltinScene(name), name).toBe(false);
      expect(() => builtinScene(name), name).toThrow(SceneError);
    }
  });

  it('list indices in paths are bounded: an existing item, or one past the end to append', () => {
    const s = defaultScene();
    expect(setScenePath(s, 'cloth.position[2]', 3).cloth.position).toEqual([0, 1.2, 3]);
    expect(setScenePath(s, 'pins[0]', 'center').pins).toEqual(['center']); // appends to []
    expect(() => setScenePath(s, 'cloth.position[100000000]', 2)).toThrow(/^--set cloth\.position\[100000000\]: cloth\.position has 3 items, no item 100000000 \(3 appends one\)$/);
    expect(() => setScenePath(s, 'pins[1]', 'center')).toThrow(/pins has 0 items, no item 1/);
    expect(() => setScenePath(s, 'colliders[5].radius', 1)).toThrow(/colliders has 2 items, no item 5$/);
    // '01' is not an index: it would name a property of the list and change nothing
    expect(() => setScenePath(s, 'cloth.position.01', 5)).toThrow(/cloth\.position is a list; use an index such as cloth\.position\[0\]/);
    expect(() => setScenePath(s, 'pins[00]', 'center')).toThrow(/pins is a list/);
    // only the scene's own keys are paths
    expect(() => setScenePath(s, 'cloth.constructor.name', 1)).toThrow(/not a scene path/);
    expect(() => setScenePath(s, 'material.toString.x', 1)).toThrow(/material\.toString is not an object in this scene/);
    // a list's item is named with its index in brackets, as the path is written
    expect(() => setScenePath(s, 'colliders[0].motion.keyframes[0].time', 1)).toThrow(/^--set colliders\[0\]\.motion\.keyframes\[0\]\.time: colliders\[0\]\.motion is not an object in this scene$/);
  });

  it('a scene file saved with a byte-order mark reads as without (it was refused as malformed JSON)', () => {
    const text = JSON.stringify({ cloth: { resolution: 6 } });
    expect(parseScene('\ufeff' + text, 'bom.json')).toEqual(parseScene(text, 'bom.json'));
    expect(() => parseScene('\ufeff\ufeff' + text, 'bom.json')).toThrow(/^bom\.json: malformed JSON/);
  });

  it('a path names every key: empty keys are not a path (they used to be dropped)', () => {
    const s = defaultScene();
    for (const path of ['cloth..resolution', '.cloth.resolution', 'cloth.resolution.', '', '.', 'pins[0].']) {
      expect(() => setScenePath(s, path, 6), path).toThrow(new RegExp(`^--set ${path.replace(/[.[\]]/g, '\\$&')}: not a scene path$`));
    }
    expect(setScenePath(s, 'cloth.resolution', 6).cloth.resolution).toBe(6);
  });

  it('the scene must be an object: a clear error, not a TypeError from inside', () => {
    for (const scene of [null, undefined, 3, 'cotton-basic', [1]]) {
      expect(() => setScenePath(scene as never, 'cloth.resolution', 6)).toThrow(/^setScenePath: the scene must be a scene object/);
    }
  });

  it('a document nested absurdly deep is refused by name, not with a stack overflow', () => {
    const deep = JSON.parse('{"cloth":' + '['.repeat(100_000) + ']'.repeat(100_000) + '}');
    expect(() => validateScene(deep, 'deep.json')).toThrow(/^deep\.json: nested more than 32 levels deep/);
    expect(() => parseScene('{"a":'.repeat(100_000) + '1' + '}'.repeat(100_000), 'deep.json')).toThrow(/^deep\.json: nested/);
  });

  it('an empty document is a full scene with every default from the schema', () => {
    const s = defaultScene();
    expect(s.cloth.resolution).toBe((sceneSchema as SchemaTree).properties.cloth.properties.resolution.default);
    expect(s.material.arealDensity).toBe((sceneSchema as SchemaTree).properties.material.properties.arealDensity.default);
    expect(s.material.mass).toBeUndefined();
    expect(s.solver.type).toBe('xpbd');
    expect(s.colliders.map((c) => c.type)).toEqual(['sphere', 'floor']);
    expect(s.wind.gusts.enabled).toBe(false);
  });

  it('the paths the CLI documents for --set all exist', () => {
    const s = defaultScene() as unknown as Record<string, Record<string, unknown>>;
    for (const path of ['cloth.resolution', 'cloth.width', 'cloth.height', 'material.structuralStiffness', 'material.shearStiffness',
      'material.bendingRigidity', 'material.damping', 'material.arealDensity', 'material.stretchFactor', 'material.friction', 'solver.type',
      'solver.substeps', 'wind.enabled', 'wind.strength', 'wind.direction', 'gravity', 'colliders', 'pins']) {
      const [a, b] = path.split('.');
      expect(b === undefined ? s[a] : s[a][b], path).not.toBeUndefined();
    }
  });

  it('bad scenes are rejected with the field named', () => {
    rejects({ material: { bendStifness: 1 } }, /material\.bendStifness: unknown key/);
    rejects({ cloth: { resolution: 2000 } }, /cloth\.resolution: must be <= 1024/);
    rejects({ cloth: { resolution: 2.5 } }, /cloth\.resolution: must be integer/);
    rejects({ material: { mass: 'heavy' } }, /material\.mass: must be number/);
    // not a JSON value, but a library caller's: named for what it is, not for the range test it fails
    rejects({ gravity: [0, NaN, 0] }, /^scene: gravity\[1\]: must be a finite number, got NaN$/);
    rejects({ material: { damping: Infinity } }, /^scene: material\.damping: must be a finite number, got Infinity$/);
    rejects({ solver: { type: 'euler' } }, /solver\.type: must be one of "xpbd", "mass-spring"/);
    rejects({ gravity: [0, -9.81] }, /gravity: must NOT have fewer than 3 items/);
    rejects({ colliders: [{ type: 'sphere', radius: -1 }] }, /colliders\[0\]\.radius: must be >= 0\.001/);
    rejects({ colliders: [{ type: 'cube' }] }, /colliders\[0\]\.type: must be one of "sphere", .*, "mesh", got "cube"$/);
    rejects({ colliders: [{ type: true }] }, /colliders\[0\]\.type: must be one of "sphere", .*, got true$/);
    // the fabric test's type lists the tests, not the colliders
    rejects({ test: { type: 'pendulum' } }, /^scene: test\.type: must be one of "cantilever", "cusick", got "pendulum"$/);
    rejects({ test: { type: 5 } }, /^scene: test\.type: must be one of "cantilever", "cusick", got 5$/);
    rejects({ pins: ['middle'] }, /pins\[0\]: must be one of top-left/);
    rejects({ pins: [5000] }, /pins\[0\]: particle 5000 does not exist/);
    rejects({ wat: 1 }, /wat: unknown key/);
    rejects([1, 2], /must be a JSON object/);
  });

  it('the types its errors list are the schema\'s: the colliders\' and the fabric tests\'', () => {
    const types = (node: unknown) => (node as { oneOf: { properties: { type: { const: string } } }[] }).oneOf.map((o) => o.properties.type.const);
    const props = (sceneSchema as unknown as { properties: { test: unknown; colliders: { items: unknown } } }).properties;
    expect(types(props.test)).toEqual([...TEST_TYPES]);
    expect(types(props.colliders.items)).toEqual([...COLLIDER_TYPES]);
  });

  it('what an error quotes of the input is safe to print, and a path or value that is no scene\'s is named', () => {
    // a key with a line break or a terminal escape: one line, the characters replaced
    rejects({ 'a\nb': 1 }, /^scene: a\ufffdb: unknown key$/);
    rejects({ '\u001b[2J': 1 }, /^scene: \ufffd\[2J: unknown key$/);
    expect(() => builtinScene('x\ny')).toThrow(/^unknown scene 'x\ufffdy'/);
    expect(() => setScenePath(defaultScene(), 5 as unknown as string, 1)).toThrow(/^setScenePath: the path must be a string such as 'cloth\.resolution', got 5$/);
    expect(() => setScenePath(defaultScene(), 'name', Symbol('x'))).toThrow(/^--set name: must be a JSON value .*, got a symbol$/);
    expect(() => setScenePath(defaultScene(), 'cloth', { f: () => 1 })).toThrow(SceneError);
    // a value nested absurdly deep is named for its depth, as a scene is (not as a value that is no JSON)
    let deep: unknown = 1;
    for (let d = 0; d < 20000; d++) deep = [deep];
    expect(() => setScenePath(defaultScene(), 'name', deep)).toThrow(/^--set name: nested more than \d+ levels deep/);
  });

  it('malformed JSON is a one-line error, not a stack trace', () => {
    expect(() => parseScene('{"cloth": {', 'my.json')).toThrow(/^my\.json: malformed JSON/);
    const e = (() => { try { parseScene('{ nope }'); } catch (err) { return err as Error; } })()!;
    expect(e.message.split('\n')).toHaveLength(1);
  });

  it('--set values are JSON when they parse and strings otherwise; paths are validated', () => {
    expect(parseSetValue('3')).toBe(3);
    expect(parseSetValue('[1,0,0]')).toEqual([1, 0, 0]);
    expect(parseSetValue('true')).toBe(true);
    expect(parseSetValue('mass-spring')).toBe('mass-spring');
    const s = defaultScene();
    expect(setScenePath(s, 'material.bendingRigidity', 2e-5).material.bendingRigidity).toBe(2e-5);
    expect(setScenePath(s, 'colliders[0].radius', 0.5).colliders[0]).toMatchObject({ radius: 0.5 });
    expect(setScenePath(s, 'colliders', []).colliders).toEqual([]);
    expect(s.material.bendingRigidity).not.toBe(2e-5); // the input is not changed
    expect(() => setScenePath(s, 'material.nope', 1)).toThrow(/^--set material\.nope: unknown key$/);
    expect(() => setScenePath(s, 'cloth.resolution', 'fine')).toThrow(/^--set cloth\.resolution: must be integer$/);
    expect(() => setScenePath(s, 'colliders.0.radius', 0)).toThrow(/^--set colliders\.0\.radius: must be >= 0\.001$/);
    // a change that breaks another field names both
    expect(() => setScenePath(setScenePath(s, 'pins', [1000]), 'cloth.resolution', 4)).toThrow(/^--set cloth\.resolution: pins\[0\]: particle 1000 does not exist/);
    expect(() => setScenePath(s, 'gravity.x', 1)).toThrow(SceneError);
    expect(() => setScenePath(s, '__proto__.x', 1)).toThrow(/not a scene path/);
  });

  it('scene.schema.json at the repository root is the schema in the code', () => {
    const file = JSON.parse(readFileSync(new URL('../../scene.schema.json', import.meta.url), 'utf8'));
    expect(file).toEqual(JSON.parse(JSON.stringify(sceneSchema)));
  });
});
