import { describe, expect, it } from 'vitest';
import { SCENE_NAMES, builtinMannequin, builtinScene, defaultScene, clothEntries, sceneDocument, setScenePath, validateScene, withMannequin } from '../core/index.js';
import { decodeHash, encodeHash, linkScene } from './url-state.js';

describe('URL hash state', () => {
  it('is empty for an unchanged default and names the base scene otherwise', () => {
    const scene = builtinScene('silk-drape')!;
    expect(encodeHash({ scene, base: 'silk-drape', view: {} })).toBe('#scene=silk-drape');
    // the schema's defaults as they are: a hash of their own, which reads back as them (an empty hash is no link)
    expect(encodeHash({ scene: defaultScene(), base: '', view: {} })).toBe('#scene=');
    expect(decodeHash('#scene=')!.scene).toEqual(defaultScene());
  });

  it('round-trips changed fields, arrays and view keys', () => {
    let scene = builtinScene('cotton-basic')!;
    scene = setScenePath(scene, 'material.damping', 0.3);
    scene = setScenePath(scene, 'wind.enabled', true);
    scene = setScenePath(scene, 'pins', ['top-left', 5]);
    scene = setScenePath(scene, 'wind.direction', [0, 0, 1]);
    scene = setScenePath(scene, 'name', 'my "odd" name & more');
    const hash = encodeHash({ scene, base: 'cotton-basic', view: { view: 'strain', sweep: 'side-by-side' } });
    expect(hash).toContain('material.damping=0.3');
    expect(hash).toContain('pins=["top-left",5]');
    const back = decodeHash(hash)!;
    expect(back.scene).toEqual(scene);
    expect(back.base).toBe('cotton-basic');
    expect(back.view).toEqual({ view: 'strain', sweep: 'side-by-side' });
  });

  it('another named fabric is one key, and the fields changed after it', () => {
    const silk = setScenePath(builtinScene('cotton-basic'), 'material.fabric', 'silk');
    expect(encodeHash({ scene: silk, base: 'cotton-basic', view: {} })).toBe('#scene=cotton-basic&material.fabric=silk');
    const softer = setScenePath(silk, 'material.damping', 0.3);
    const hash = encodeHash({ scene: softer, base: 'cotton-basic', view: {} });
    expect(hash).toBe('#scene=cotton-basic&material.fabric=silk&material.damping=0.3');
    expect(decodeHash(hash)!.scene).toEqual(softer);
    // a base that gives the older mass path: the fabric drops it, so the link need not
    const mass = setScenePath(builtinScene('cotton-basic'), 'material.mass', 0.2);
    const leather = setScenePath(mass, 'material.fabric', 'leather');
    expect(decodeHash(encodeHash({ scene: leather, base: '', view: {} }))!.scene).toEqual(leather);
  });

  it('a mannequin posed anew is one key, not its colliders\' keys, and reads back as the same scene', () => {
    const scene = setScenePath(withMannequin(builtinScene('cape'), builtinMannequin('cape')!, { pose: 't-pose', animation: 'walk' }), 'material.damping', 0.3);
    const hash = encodeHash({ scene, base: 'cape', view: {} });
    expect(hash).toBe('#scene=cape&mannequin=t-pose,walk&material.damping=0.3');
    expect(decodeHash(hash)!.scene).toEqual(scene);
    // unchanged: no key; a bad value or a scene without a mannequin: one line naming the key
    expect(encodeHash({ scene: builtinScene('cape'), base: 'cape', view: {} })).toBe('#scene=cape');
    expect(() => decodeHash('#scene=cape&mannequin=sit,walk')).toThrow(/^link: mannequin: must be pose,animation with pose one of stand, t-pose/);
    expect(() => decodeHash('#scene=pins&mannequin=stand,walk')).toThrow("link: mannequin: scene 'pins' has no mannequin");
  });

  it('round-trips a mesh cloth (the link names the file; it cannot carry it)', () => {
    for (const base of ['cotton-basic', '']) {
      const scene = setScenePath(setScenePath(builtinScene('cotton-basic')!, 'cloth.mesh', 'tshirt.obj'), 'cloth.rotation', [-90, 0, 0]);
      const hash = encodeHash({ scene, base, view: {} });
      expect(hash).toContain('cloth.mesh=tshirt.obj');
      expect(decodeHash(hash)!.scene).toEqual(scene);
      // and a disc
      const disc = setScenePath(builtinScene('cotton-basic')!, 'cloth.shape', 'disc');
      expect(decodeHash(encodeHash({ scene: disc, base, view: {} }))!.scene).toEqual(disc);
    }
  });

  it('carries the names of mesh colliders\' files; a link\'s scene is shown without the mesh files the page lacks, saying which', () => {
    const colliders = [{ type: 'floor', height: 0 }, { type: 'mesh', mesh: 'props/chair.obj', scale: 0.01, position: [0, 0, 0.2] }];
    const scene = setScenePath(builtinScene('cotton-basic'), 'colliders', colliders);
    const hash = encodeHash({ scene, base: 'cotton-basic', view: {} });
    expect(decodeURIComponent(hash)).toContain('"mesh":"props/chair.obj"');
    expect(decodeHash(hash)!.scene).toEqual(scene);

    // every file here: as it is
    expect(linkScene(scene, () => true)).toEqual({ scene, missing: [], note: '' });
    // the collider's file missing: the rest of the scene, and the file asked for
    const without = linkScene(scene, () => false);
    expect(without.scene.colliders).toEqual([scene.colliders[0]]);
    expect(without.scene.cloth).toEqual(scene.cloth);
    expect(without.missing).toEqual([{ field: 'colliders[1].mesh', path: 'props/chair.obj', collider: 1 }]);
    expect(without.note).toBe('link: colliders[1] is the mesh file chair.obj, which a link cannot carry: import the mesh file chair.obj ' +
      '(Scene & export → import mesh…) to see it; showing the scene without colliders[1] meanwhile');
    // and the cloth's too: a rectangle meanwhile, both files asked for; only the cloth's: as before
    const both = linkScene(setScenePath(scene, 'cloth.mesh', 'tshirt.obj'), (p) => p === 'nothing');
    expect(both.scene.cloth.shape).toBe('rectangle');
    expect(both.scene.colliders).toHaveLength(1);
    expect(both.note).toBe('link: the cloth is the mesh file tshirt.obj and colliders[1] is the mesh file chair.obj, which a link cannot carry: ' +
      'import the mesh files tshirt.obj, chair.obj (Scene & export → import mesh…) to see them; showing a rectangle cloth and the scene without colliders[1] meanwhile');
    const cloth = linkScene(setScenePath(scene, 'cloth.mesh', 'tshirt.obj'), (p) => p !== 'tshirt.obj');
    expect(cloth.scene.colliders).toEqual(scene.colliders);
    expect(cloth.note).toBe('link: the cloth is the mesh file tshirt.obj, which a link cannot carry: import the mesh file tshirt.obj ' +
      '(Scene & export → import mesh…) to see it; showing a rectangle cloth meanwhile');
  });

  it('a scene of several cloths: cloth by cloth against its built-in, and back (its document: no top-level cloth)', () => {
    const layers = builtinScene('layers');
    expect(encodeHash({ scene: layers, base: 'layers', view: {} })).toBe('#scene=layers');
    let scene = setScenePath(layers, 'cloths[1].material.fabric', 'silk');
    scene = setScenePath(scene, 'cloths[2].cloth.resolution', 8);
    scene = setScenePath(scene, 'cloths[0].pins', ['top-left', 3]);
    const hash = encodeHash({ scene, base: 'layers', view: {} });
    // the fabric's own fields follow the fabric: one key
    expect(hash).toBe('#scene=layers&cloths[0].pins=["top-left",3]&cloths[1].material.fabric=silk&cloths[2].cloth.resolution=8');
    const back = decodeHash(hash)!.scene;
    expect(sceneDocument(back)).toEqual(sceneDocument(scene));
    expect(clothEntries(back).map((e) => e.material.fabric)).toEqual(['leather', 'silk', 'silk']);
    expect(back.cloths![1].material).toEqual(scene.cloths![1].material);
    // a mesh file for one of them: its shape goes with it
    const mesh = setScenePath(layers, 'cloths[1].cloth.mesh', 'tshirt.obj');
    const meshHash = encodeHash({ scene: mesh, base: 'layers', view: {} });
    expect(meshHash).not.toContain('cloth.shape');
    expect(sceneDocument(decodeHash(meshHash)!.scene)).toEqual(sceneDocument(mesh));
  });

  it('a list of cloths against a base of another number of cloths: the whole list, first', () => {
    const doc = { name: 'two', description: 'two cloths', solver: { substeps: 12 }, cloths: [
      { name: 'a', cloth: { resolution: 4, position: [0, 1, 0] }, material: { fabric: 'denim' } },
      { name: 'b', cloth: { resolution: 6, position: [0, 1.4, 0] }, pins: ['top-left'] },
    ] };
    const scene = validateScene(doc);
    for (const base of ['', 'cotton-basic', 'layers']) {
      const hash = encodeHash({ scene, base, view: {} });
      expect(decodeURIComponent(hash), base).toMatch(base ? new RegExp(`^#scene=${base}&cloths=\\[`) : /^#cloths=\[/);
      expect(sceneDocument(decodeHash(hash)!.scene), base).toEqual(sceneDocument(scene));
    }
    // a one-cloth scene against a base of several: a list of one, the same cloth
    const one = setScenePath(builtinScene('cotton-basic'), 'name', 'layers');
    const back = decodeHash(encodeHash({ scene: one, base: 'layers', view: {} }))!.scene;
    expect(clothEntries(back)).toHaveLength(1);
    expect(back.cloth).toEqual(one.cloth);
    expect(back.material).toEqual(one.material);
    // a bad list says so in one line
    expect(() => decodeHash('#cloths=[{"cloth":{"resolution":0}}]')).toThrow(/^link: cloths\[0\]\.cloth\.resolution: must be >= 1/);
  });

  it("a link's scene of several cloths without a cloth's mesh file: a rectangle in its place, saying which", () => {
    const scene = setScenePath(builtinScene('layers'), 'cloths[1].cloth.mesh', 'tshirt.obj');
    const shown = linkScene(scene, () => false);
    expect(clothEntries(shown.scene).map((e) => e.cloth.shape)).toEqual(['rectangle', 'rectangle', 'rectangle']);
    expect(clothEntries(shown.scene).map((e) => e.name)).toEqual(['leather', 'cotton', 'silk']);
    expect(shown.missing).toEqual([{ field: 'cloths[1].cloth.mesh', path: 'tshirt.obj', cloth: 1 }]);
    expect(shown.note).toBe('link: cloths[1] is the mesh file tshirt.obj, which a link cannot carry: import the mesh file tshirt.obj ' +
      '(Scene & export → import mesh…) to see it; showing a rectangle as cloths[1] meanwhile');
  });

  it('names the field of a bad value, and refuses unknown scenes and keys', () => {
    expect(() => decodeHash('#scene=nope')).toThrow(/unknown scene 'nope'/);
    expect(() => decodeHash('#scene=wind&material.damping=99')).toThrow(/link: material\.damping: must be <= 10/);
    expect(() => decodeHash('#material.nope=1')).toThrow(/material\.nope/);
    expect(() => decodeHash('#garbage')).toThrow(/not key=value/);
    expect(decodeHash('')).toBeNull();
  });

  it('a string that looks like JSON stays a string', () => {
    const scene = setScenePath(builtinScene('custom')!, 'name', 'true');
    const back = decodeHash(encodeHash({ scene, base: 'custom', view: {} }))!;
    expect(back.scene.name).toBe('true');
  });

  it('refuses a list index far past the end in one line, without building a huge list', () => {
    expect(() => decodeHash('#cloth.position[100000000]=2')).toThrow(/^link: cloth\.position\[100000000\]: cloth\.position has 3 items, no item 100000000/);
    expect(() => decodeHash('#colliders[5].radius=1')).toThrow(/colliders has \d+ items?, no item 5/);
    expect(() => decodeHash('#pins[99999999]=3')).toThrow(/pins has 0 items, no item 99999999 \(0 appends one\)/);
    // one past the end appends, as the CLI's --set does
    expect(decodeHash('#pins[0]=3')!.scene.pins).toEqual([3]);
  });

  it('keeps a hostile scene name as plain data (the page shows it as text)', () => {
    const name = '<img src=x onerror="window.__pwned=1">';
    const back = decodeHash(`#scene=custom&name=${encodeURIComponent(name)}`)!;
    expect(back.scene.name).toBe(name);
    expect(decodeHash(encodeHash(back))!.scene.name).toBe(name);
  });
});

describe('every built-in scene, renamed (an imported file of it), goes through a link and back', () => {
  it.each(SCENE_NAMES)('%s', (name) => {
    const scene = { ...builtinScene(name), name: `my-${name}` };
    const hash = encodeHash({ scene, base: '', view: {} });
    const back = decodeHash(hash)!;
    // (through JSON: a mannequin's keyframes hold −0, which a link writes as 0)
    const json = (s: unknown) => JSON.parse(JSON.stringify(s));
    expect(json(back.scene)).toEqual(json(scene));
  });
});

describe('a link of a scene that dropped a list of its built-in', () => {
  it('writes the list empty: the Mesh Resolution scene without its sweep (a mesh imported into it) stays without one', () => {
    const scene = { ...builtinScene('resolution') };
    delete scene.resolutionSweep;
    const hash = encodeHash({ scene, base: 'resolution', view: {} });
    expect(hash).toBe('#scene=resolution&resolutionSweep=[]');
    expect(decodeHash(hash)!.scene.resolutionSweep).toEqual([]);
  });
});
