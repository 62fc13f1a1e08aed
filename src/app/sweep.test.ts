import { describe, expect, it } from 'vitest';
import { builtinScene, setScenePath, type ColliderSpec } from '../core/index.js';
import type { App } from './app.js';
import { Sweep, sweepIgnored, sweeps } from './sweep.js';

describe('the resolution sweep side by side', () => {
  it('moves every collider with its cloth, a mesh collider by its position; a floor stays', () => {
    const colliders: ColliderSpec[] = [
      { type: 'floor', height: 0 },
      { type: 'mesh', mesh: 'box.obj', scale: 1, position: [0.1, 0, -0.2], rotation: [0, 30, 0] },
      { type: 'sphere', center: [0, 0.5, 0], radius: 0.3 },
    ];
    const scene = setScenePath(setScenePath(builtinScene('resolution'), 'colliders', colliders), 'resolutionSweep', [2, 4, 8]);
    const sweep = new Sweep({ scene, sim: { kind: 'cpu' } } as unknown as App);
    sweep.layout = 'side-by-side';
    const slots = sweep.scenes();
    expect(slots).toHaveLength(3);
    for (const s of slots) {
      const dx = s.cloth.position[0] - scene.cloth.position[0];
      // (the validated scene's colliders: with their defaults, e.g. no pins)
      const [floor, mesh, sphere] = s.colliders;
      expect(floor).toEqual(scene.colliders[0]);
      expect(mesh).toEqual({ ...scene.colliders[1], position: [0.1 + dx, 0, -0.2] });
      expect(sphere).toEqual({ ...scene.colliders[2], center: [dx, 0.5, 0] });
    }
    expect(slots.map((s) => s.cloth.position[0] - scene.cloth.position[0])).toEqual([-1.6, 0, 1.6]);
  });

  it('a scene of several cloths with a sweep runs as it is, one slot, saying so', () => {
    const scene = setScenePath(builtinScene('layers'), 'resolutionSweep', [2, 4]);
    expect(sweeps(scene)).toBe(false);
    expect(sweepIgnored(scene)).toBe("the resolution sweep is of one rectangle's resolutions: this scene's 3 cloths run as they are");
    const sweep = new Sweep({ scene, sim: { kind: 'cpu' } } as unknown as App);
    sweep.layout = 'side-by-side';
    expect(sweep.scenes()).toEqual([scene]);
  });

  it('keeps the pins that hold at every resolution: presets and regions (the cantilever\'s clamp), not particle indices', () => {
    const cantilever = builtinScene('cantilever');
    const scene = setScenePath(setScenePath(cantilever, 'pins', [...cantilever.pins, 'top-left', 7]), 'resolutionSweep', [8, 16]);
    const sweep = new Sweep({ scene, sim: { kind: 'cpu' } } as unknown as App);
    for (const s of sweep.scenes()) expect(s.pins).toEqual([...cantilever.pins, 'top-left']);
    expect(cantilever.pins.some((p) => typeof p === 'object')).toBe(true);
  });

  it('side by side, a pin region moves with its cloth, as the colliders do', () => {
    const cantilever = builtinScene('cantilever');
    const scene = setScenePath(cantilever, 'resolutionSweep', [8, 16]);
    const sweep = new Sweep({ scene, sim: { kind: 'cpu' } } as unknown as App);
    sweep.layout = 'side-by-side';
    const region = cantilever.pins.find((p) => typeof p === 'object') as { min: number[]; max: number[] };
    for (const s of sweep.scenes()) {
      const dx = s.cloth.position[0] - scene.cloth.position[0];
      expect(dx).not.toBe(0);
      expect(s.pins.find((p) => typeof p === 'object')).toEqual({ min: [region.min[0] + dx, region.min[1], region.min[2]], max: [region.max[0] + dx, region.max[1], region.max[2]] });
    }
  });
});
