import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { Simulation, builtinScene, clothEntries, clothScene, editCloth, modelFor, setScenePath, type Scene } from '../core/index.js';
import { PageMeshStore, readMeshFile } from './meshes.js';
import { restBottom, withMesh, withShape, withoutMesh } from './shape-change.js';

const store = new PageMeshStore();
store.add(readMeshFile(new Uint8Array(readFileSync(new URL('../../examples/tshirt.obj', import.meta.url))), 'tshirt.obj'));
const meshes = store.resolve;
/** the lowest point of a scene's cloth as the model is built */
const lowest = (scene: Scene) => {
  const p = modelFor(scene, meshes).restPositions;
  let lo = Infinity;
  for (let k = 1; k < p.length; k += 3) lo = Math.min(lo, p[k]);
  return lo;
};
/** the lowest point and particles of a scene's cloth as the simulation (which refuses what it cannot start) builds it */
const built = (scene: Scene) => {
  const sim = new Simulation(scene, { kernel: 'ts', meshes });
  let lo = Infinity;
  for (let k = 1; k < sim.model.restPositions.length; k += 3) lo = Math.min(lo, sim.model.restPositions[k]);
  return { lo, n: sim.model.particleCount };
};

describe('changing the cloth\'s shape', () => {
  it('measures where a cloth starts as the model builds it', () => {
    for (const scene of [
      builtinScene('cotton-basic'), builtinScene('wind'),
      setScenePath(builtinScene('cotton-basic'), 'cloth.rotation', [30, 0, 10]),
      setScenePath(builtinScene('wind'), 'cloth.shape', 'disc'),
      setScenePath(builtinScene('pins'), 'cloth.shape', 'tube'),
      setScenePath(builtinScene('cotton-basic'), 'cloth.mesh', 'tshirt.obj'),
    ]) {
      expect(Math.abs(restBottom(scene, meshes) - lowest(scene))).toBeLessThan(1e-3);
    }
  });

  it('a disc or tube from the panel starts with its lowest point where the rectangle\'s was, and the simulation takes it', () => {
    const cotton = builtinScene('cotton-basic');
    const disc = withShape(cotton, 'disc', meshes);
    expect(disc.scene.cloth.shape).toBe('disc');
    expect(disc.scene.cloth.position).toEqual([0, 1.2, 0]);
    expect(disc.note).toBe('');
    expect(built(disc.scene).n).toBe(817); // 1 + 3K(K + 1), K = 16 at resolution 32
    // a horizontal tube is a cylinder on its side: at the rectangle's height it would cut through the sphere
    const tube = withShape(cotton, 'tube', meshes);
    expect(tube.scene.cloth.shape).toBe('tube');
    expect(built(tube.scene).lo).toBeCloseTo(1.2, 3);
    expect(tube.scene.cloth.position[1]).toBeCloseTo(1.7, 3);
    // and back: the rectangle is where it was
    expect(withShape(tube.scene, 'rectangle', meshes).scene.cloth.position[1]).toBeCloseTo(1.2, 3);
    // a hanging cloth keeps its lowest point too
    const wind = withShape(builtinScene('wind'), 'tube', meshes);
    expect(built(wind.scene).lo).toBeCloseTo(built(builtinScene('wind')).lo, 3);
  });

  it('drops the pins another shape cannot take, and says which', () => {
    const pins = setScenePath(builtinScene('pins'), 'pins', ['top-left', 'center', 'right-edge', 7]);
    const disc = withShape(pins, 'disc', meshes);
    expect(disc.scene.pins).toEqual(['center']);
    expect(disc.note).toBe('dropped pin presets top-left, right-edge (a disc has no corners or edges) and 1 particle pin (their numbers belong to the old cloth)');
    const rect = withShape(disc.scene, 'rectangle', meshes);
    expect(rect.scene.pins).toEqual(['center']);
    expect(rect.note).toBe('');
    expect(() => withShape(pins, 'mesh' as never, meshes)).toThrow(/not one of rectangle, disc, tube/);
  });

  it('an imported mesh becomes the cloth: pins cleared, a sweep dropped, the rest of the scene kept', () => {
    const sweep = setScenePath(builtinScene('resolution'), 'material.damping', 0.3);
    const s = withMesh({ ...sweep, pins: ['center'] }, 'tshirt.obj', meshes);
    expect(s.cloth.shape).toBe('mesh');
    expect(s.cloth.mesh).toBe('tshirt.obj');
    expect(s.pins).toEqual([]);
    expect(s.resolutionSweep).toBeUndefined();
    expect(s.material.damping).toBe(0.3);
    expect(built(s).lo).toBeCloseTo(restBottom(sweep, meshes), 3);
    expect(built(s).n).toBe(1258);
  });

  it('a link\'s mesh that is not here becomes the default rectangle, keeping the rest', () => {
    const s = setScenePath(setScenePath(builtinScene('silk-drape'), 'cloth.mesh', 'tshirt.obj'), 'pins', ['center', 12]);
    const r = withoutMesh(s);
    expect(r.cloth.shape).toBe('rectangle');
    expect(r.cloth.mesh).toBeUndefined();
    expect(r.pins).toEqual(['center']);
    expect(r.material).toEqual(s.material);
    expect(built(r).n).toBe(33 * 33);
  });

  it('one cloth of a scene of several, as that cloth alone: the others stay, and the scene still starts', () => {
    const layers = setScenePath(builtinScene('layers'), 'cloths[1].pins', ['top-left', 'center']);
    const before = restBottom(clothScene(layers, 1), meshes);
    let note = '';
    const disc = editCloth(layers, 1, (one) => { const r = withShape(one, 'disc', meshes); note = r.note; return r.scene; });
    const entries = clothEntries(disc);
    expect(entries.map((e) => e.cloth.shape)).toEqual(['rectangle', 'disc', 'rectangle']);
    expect(entries[1].pins).toEqual(['center']);
    expect(note).toBe('dropped pin preset top-left (a disc has no corners or edges)');
    expect(restBottom(clothScene(disc, 1), meshes)).toBeCloseTo(before, 4);
    expect(entries[0]).toEqual(clothEntries(layers)[0]);
    expect(entries[2]).toEqual(clothEntries(layers)[2]);
    new Simulation(disc, { kernel: 'ts' });
    // a mesh file as that cloth
    const shirt = editCloth(layers, 2, (one) => withMesh(one, 'tshirt.obj', meshes));
    expect(clothEntries(shirt).map((e) => e.cloth.mesh)).toEqual([undefined, undefined, 'tshirt.obj']);
    expect(new Simulation(shirt, { kernel: 'ts', meshes }).model.clothStarts[3] - 2 * 441).toBe(1258);
  });
});
