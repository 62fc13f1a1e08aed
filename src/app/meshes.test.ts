import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { SceneError, Simulation, builtinScene, setScenePath } from '../core/index.js';
import { PageMeshStore, baseName, meshNames, missingMesh, missingMeshes, namesFile, readColliderFile, readMeshFile, clothMesh, sceneMeshes } from './meshes.js';

const bytes = (path: string) => new Uint8Array(readFileSync(new URL(`../../${path}`, import.meta.url)));
const obj = (text: string) => new TextEncoder().encode(text);
/** a closed box 0.8 × 0.4 × 0.8 m standing on y = 0, as OBJ */
const BOX_OBJ = 'v -0.4 0 -0.4\nv 0.4 0 -0.4\nv -0.4 0.4 -0.4\nv 0.4 0.4 -0.4\nv -0.4 0 0.4\nv 0.4 0 0.4\nv -0.4 0.4 0.4\nv 0.4 0.4 0.4\n' +
  'f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n';
/** the cotton scene with the box as colliders[1] under the cloth, between the sphere and a floor */
const withBox = (path: string) => setScenePath(builtinScene('cotton-basic'), 'colliders', [
  { type: 'floor', height: 0 }, { type: 'mesh', mesh: path, position: [0, 0, 0] },
]);

describe('the page\'s imported meshes', () => {
  it('reads the example T-shirt from OBJ and glTF, counting the particles its cloth has', () => {
    const a = readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj');
    const b = readMeshFile(bytes('examples/tshirt.gltf'), 'tshirt.gltf');
    expect(a.name).toBe('tshirt.obj');
    expect(a.particles).toBe(1258);
    expect(b.particles).toBe(1258);
  });

  it('refuses a file that is not a manifold mesh, or of another kind, naming the file', () => {
    // three triangles on one edge
    const fin = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n';
    expect(() => readMeshFile(obj(fin), 'fin.obj')).toThrow(SceneError);
    expect(() => readMeshFile(obj(fin), 'fin.obj')).toThrow(/^fin\.obj: /);
    expect(() => readMeshFile(obj('v 0 0 0\n'), 'notes.txt')).toThrow(/notes\.txt: not a mesh file/);
    expect(() => readMeshFile(obj('{"asset": {"version": "2.0"}, "buffers": [{"uri": "x.bin", "byteLength": 4}]}'), 'ext.gltf'))
      .toThrow(/ext\.gltf: /);
  });

  it('resolves a scene\'s cloth.mesh by the file\'s name, or by the last part of its path', () => {
    const store = new PageMeshStore();
    const e = readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj');
    expect(store.add(e)).toBeUndefined();
    expect(store.resolve('tshirt.obj')).toBe(e.mesh);
    expect(store.resolve('garments/tshirt.obj')).toBe(e.mesh);
    expect(store.resolve('C:\\garments\\tshirt.obj')).toBe(e.mesh);
    expect(store.particles('tshirt.obj')).toBe(1258);
    expect(baseName('a/b\\c.obj')).toBe('c.obj');
  });

  it('asks for a file that is not imported, and puts back what a refused import replaced', () => {
    const store = new PageMeshStore();
    expect(() => store.resolve('dress.glb')).toThrow(SceneError);
    expect(() => store.resolve('dress.glb')).toThrow('import the mesh file dress.glb too');
    expect(() => store.particles('garments/dress.glb')).toThrow(missingMesh('garments/dress.glb'));
    const first = readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj');
    const second = { ...first, particles: 7 };
    store.add(first);
    const before = store.add(second);
    expect(before).toBe(first);
    store.restore('tshirt.obj', before);
    expect(store.find('tshirt.obj')).toBe(first);
    store.restore('new.obj', undefined);
    expect(store.has('new.obj')).toBe(false);
    expect(store.size).toBe(1);
  });

  it('is the resolver a Simulation of a mesh scene takes', () => {
    const store = new PageMeshStore();
    store.add(readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj'));
    const scene = setScenePath(builtinScene('cotton-basic'), 'cloth.mesh', 'tshirt.obj');
    expect(clothMesh(scene.cloth)).toBe('tshirt.obj');
    expect(clothMesh(builtinScene('cotton-basic').cloth)).toBeNull();
    const sim = new Simulation(scene, { kernel: 'ts', meshes: store.resolve });
    expect(sim.model.particleCount).toBe(1258);
    expect(() => new Simulation(setScenePath(scene, 'cloth.mesh', 'other.obj'), { kernel: 'ts', meshes: store.resolve }))
      .toThrow('import the mesh file other.obj too');
  });

  it('lists the mesh files a scene names, the cloth\'s first, and which of them the page lacks', () => {
    const scene = setScenePath(withBox('props/box.obj'), 'cloth.mesh', 'tshirt.obj');
    expect(sceneMeshes(scene)).toEqual([
      { field: 'cloth.mesh', path: 'tshirt.obj', cloth: 0 },
      { field: 'colliders[1].mesh', path: 'props/box.obj', collider: 1 },
    ]);
    // each cloth of a list by its own field
    const layers = setScenePath(builtinScene('layers'), 'cloths[2].cloth.mesh', 'garments/tshirt.obj');
    expect(sceneMeshes(layers)).toEqual([{ field: 'cloths[2].cloth.mesh', path: 'garments/tshirt.obj', cloth: 2 }]);
    expect(meshNames(setScenePath(scene, 'colliders', [...scene.colliders, { type: 'mesh', mesh: 'tshirt.obj' }]))).toEqual(['tshirt.obj', 'props/box.obj']);
    expect(sceneMeshes(builtinScene('cotton-basic'))).toEqual([]);
    expect(namesFile('props/box.obj', 'box.obj')).toBe(true);
    expect(namesFile('props/box.obj', 'props')).toBe(false);
    const store = new PageMeshStore();
    store.add(readColliderFile(obj(BOX_OBJ), 'box.obj'));
    expect(missingMeshes(scene, (p) => store.has(p))).toEqual([{ field: 'cloth.mesh', path: 'tshirt.obj', cloth: 0 }]);
    expect(missingMesh('props/box.obj', 'colliders[1].mesh')).toBe(
      "colliders[1].mesh: 'props/box.obj' is a mesh file that is not imported in this page: import the mesh file box.obj too (Scene & export → import mesh…)");
  });

  it('a mesh collider\'s file: read without the cloth\'s checks, found by the Simulation, asked for naming its field', () => {
    const store = new PageMeshStore();
    const scene = withBox('box.obj');
    // the core names the field, then the file to import (the resolver's words carry no field of their own)
    expect(() => new Simulation(scene, { kernel: 'ts', meshes: store.resolve }))
      .toThrow(new SceneError(missingMesh('box.obj', 'colliders[1].mesh')));
    // three faces on one edge are no cloth (not a manifold) but a collider (an open shell)
    const fin = obj('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n');
    expect(() => readMeshFile(fin, 'fin.obj')).toThrow(/^fin\.obj: /);
    store.add(readColliderFile(fin, 'fin.obj'));
    expect(new Simulation(withBox('fin.obj'), { kernel: 'ts', meshes: store.resolve }).params.colliders[1].type).toBe('mesh');
    const entry = readColliderFile(obj(BOX_OBJ), 'box.obj');
    expect(entry.particles).toBeUndefined();
    store.add(entry);
    const sim = new Simulation(scene, { kernel: 'ts', meshes: store.resolve });
    expect(sim.params.colliders.map((c) => c.type)).toEqual(['floor', 'mesh']);
    // made a cloth, it is checked as one then, and refused naming the file
    expect(() => store.particles('fin.obj')).toThrow(/^fin\.obj: /);
    expect(() => readColliderFile(obj('v 0 0 0\n'), 'box.txt')).toThrow(/box\.txt: not a mesh file/);
    // a file imported for a collider that is a cloth too is counted once, when a scene makes it one
    store.add(readColliderFile(bytes('examples/tshirt.obj'), 'tshirt.obj'));
    expect(store.find('tshirt.obj')?.particles).toBeUndefined();
    expect(store.particles('tshirt.obj')).toBe(1258);
    expect(store.find('tshirt.obj')?.particles).toBe(1258);
  });
});
