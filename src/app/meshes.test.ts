import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { SceneError, Simulation, builtinScene, setScenePath } from '../core/index.js';
import { MeshStore, baseName, missingMesh, readMeshFile, sceneMesh } from './meshes.js';

const bytes = (path: string) => new Uint8Array(readFileSync(new URL(`../../${path}`, import.meta.url)));
const obj = (text: string) => new TextEncoder().encode(text);

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
    const store = new MeshStore();
    const e = readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj');
    expect(store.add(e)).toBeUndefined();
    expect(store.resolve('tshirt.obj')).toBe(e.mesh);
    expect(store.resolve('garments/tshirt.obj')).toBe(e.mesh);
    expect(store.resolve('C:\\garments\\tshirt.obj')).toBe(e.mesh);
    expect(store.particles('tshirt.obj')).toBe(1258);
    expect(baseName('a/b\\c.obj')).toBe('c.obj');
  });

  it('asks for a file that is not imported, and puts back what a refused import replaced', () => {
    const store = new MeshStore();
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
    const store = new MeshStore();
    store.add(readMeshFile(bytes('examples/tshirt.obj'), 'tshirt.obj'));
    const scene = setScenePath(builtinScene('cotton-basic'), 'cloth.mesh', 'tshirt.obj');
    expect(sceneMesh(scene)).toBe('tshirt.obj');
    expect(sceneMesh(builtinScene('cotton-basic'))).toBeNull();
    const sim = new Simulation(scene, { kernel: 'ts', meshes: store.resolve });
    expect(sim.model.particleCount).toBe(1258);
    expect(() => new Simulation(setScenePath(scene, 'cloth.mesh', 'other.obj'), { kernel: 'ts', meshes: store.resolve }))
      .toThrow('import the mesh file other.obj too');
  });
});
