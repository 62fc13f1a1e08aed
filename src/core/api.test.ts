/**
 * The library's public entry points refuse bad arguments with one clear error in the library's own words (never a
 * NaN cloth, a hang, or "Cannot read properties of undefined").
 */
import { describe, expect, it } from 'vitest';
import { SceneError, type SceneInput } from './scene.js';
import { builtinScene } from './scenes.js';
import { Simulation, type SimulationOptions } from './simulation.js';
import { WasmBackend } from './backend.js';
import { grab, release, setPinned } from './state.js';

const small = () => { const s = builtinScene('custom'); s.cloth.resolution = 8; return s; };

describe('library arguments', () => {
  it('builtinScene names the built-in scenes for an unknown name', () => {
    expect(() => builtinScene('nope')).toThrow(SceneError);
    expect(() => builtinScene('nope')).toThrow(/^unknown scene 'nope' \(built-in scenes: .*silk-drape/);
  });

  it.each([
    [{ kernel: 'bogus' }, /^Simulation: options\.kernel must be 'auto', 'wasm' or 'ts', got "bogus"$/],
    [{ threads: NaN }, /^Simulation: options\.threads must be 'auto' or an integer ≥ 1, got NaN$/],
    [{ threads: 0 }, /got 0$/],
    [{ threads: 1.5 }, /got 1\.5$/],
    [{ threads: 'many' }, /got many$/],
    [{ spawnHelper: 'yes' }, /options\.spawnHelper must be a function/],
    [{ spawnHelper: () => ({ terminate() {} }) }, /options\.spawnHelper\.cores must be the number of cores its threads can use/],
  ])('new Simulation(scene, %j) throws at once', (options, message) => {
    expect(() => new Simulation(small(), options as unknown as SimulationOptions)).toThrow(message);
  });

  it('threads are capped at the cores the spawner reports', async () => {
    const started: number[] = [];
    const spawner = Object.assign((init: { thread: number }) => { started.push(init.thread); return { terminate() {} }; }, { cores: 2 });
    const s = builtinScene('custom'); s.cloth.resolution = 64;
    const sim = new Simulation(s, { kernel: 'wasm', threads: 1000, spawnHelper: spawner });
    expect((sim.backend as WasmBackend).kernel.threads).toBe(2);
    expect(started).toEqual([1]); // one helper, not 999
    sim.dispose();
  });

  it('a spawner that returns no { terminate() } is refused in one line, and the helpers it did start are stopped', () => {
    let stopped = 0, calls = 0;
    const spawner = Object.assign(() => (++calls === 1 ? { terminate() { stopped++; } } : {}), { cores: 4 });
    const s = builtinScene('custom'); s.cloth.resolution = 64;
    expect(() => new Simulation(s, { kernel: 'wasm', threads: 3, spawnHelper: spawner as never })).toThrow(
      /^the helper spawner \(options\.spawnHelper\) must return \{ terminate\(\) \} for each thread it starts, got \[object Object\]$/);
    expect(stopped).toBe(1);
  });

  it('set() speaks of itself, not of --set, and advance() wants a frame count', () => {
    const sim = new Simulation(small());
    expect(() => sim.set('material.nope', 1)).toThrow(/^Simulation\.set\('material\.nope'\): unknown key$/);
    expect(() => sim.set('cloth.position[9]', 1)).toThrow(/^Simulation\.set\('cloth\.position\[9\]'\): cloth\.position has 3 items/);
    expect(() => sim.set('material.damping', NaN)).toThrow(/^Simulation\.set\('material\.damping'\): must be a finite number, got NaN$/);
    expect(() => sim.advance(-1)).toThrow(/^Simulation\.advance: frames must be an integer ≥ 0, got -1$/);
    expect(() => sim.advance(NaN)).toThrow(RangeError);
    expect(() => sim.advance('2' as unknown as number)).toThrow('Simulation.advance: frames must be an integer ≥ 0, got "2"');
    expect(() => sim.setScene(sim.scene, null as never)).toThrow(/^Simulation\.setScene: carry must be an array of \{ from, to, count \}, got null$/);
    expect(() => new Simulation({ cloth: { resolution: 'x' } } as never)).toThrow(/^scene: cloth\.resolution: must be integer$/);
  });

  it.each([
    [1.5, [0, 1, 0], /^grab: particle must be an integer in 0…80, got 1\.5$/],
    [81, [0, 1, 0], /got 81$/],
    [-1, [0, 1, 0], /got -1$/],
    [NaN, [0, 1, 0], /got NaN$/],
    [3, [NaN, 1, 0], /^grab: target must be \[x, y, z\] of finite numbers within ±10000 m, got \[NaN, 1, 0\]$/],
    [3, [0, Infinity, 0], /got \[0, Infinity, 0\]$/],
    [3, [1e30, 0, 0], /got \[1e\+30, 0, 0\]$/],
    [3, [0, 1], /got \[0, 1\]$/],
    [3, null, /got null$/],
  ])('grab(state, %s, %j) throws and leaves the cloth as it was', (particle, target, message) => {
    const sim = new Simulation(small());
    expect(() => grab(sim.state, particle as number, target as never)).toThrow(message);
    expect(sim.state.grabbed).toBe(-1);
    sim.advance(5);
    expect(sim.report().finite).toBe(true);
  });

  it('a grab to the farthest allowed target and back keeps the cloth finite', () => {
    const sim = new Simulation(small());
    grab(sim.state, 40, [10_000, -10_000, 10_000]);
    expect(sim.advance(10)).toBe(true);
    release(sim.state);
    expect(sim.advance(60)).toBe(true);
    expect(sim.unstableFrame).toBeNull();
  });

  it('setPinned refuses what is not a particle, or not a boolean', () => {
    const sim = new Simulation(small());
    expect(() => setPinned(sim.state, 1.5, true)).toThrow(/^setPinned: particle must be an integer in 0…80, got 1\.5$/);
    expect(() => setPinned(sim.state, 81, true)).toThrow(RangeError);
    expect(() => setPinned(sim.state, 3, 1 as never)).toThrow(/^setPinned: pinned must be true or false, got 1$/);
    expect([...sim.state.pinned].every((p) => p === 0)).toBe(true);
  });

  it('a cloth that turns non-finite stops stepping and says at which frame; reset clears it', () => {
    const sim = new Simulation(small());
    expect(sim.advance(3)).toBe(true);
    sim.state.positions[7] = NaN;
    expect(sim.advance(10)).toBe(false);
    expect(sim.unstableFrame).toBe(4);
    expect(sim.frame).toBe(4);
    sim.reset();
    expect(sim.unstableFrame).toBeNull();
    expect(sim.advance(3)).toBe(true);
  });
});

describe('scene input', () => {
  it('takes a partial scene, typed as one: what is missing takes its default', () => {
    // these lines are also a type test: npm run typecheck fails if SceneInput stops being deep-partial
    const input: SceneInput = { cloth: { resolution: 6 }, material: { fabric: 'silk' }, colliders: [{ type: 'floor' }] };
    const sim = new Simulation(input, { kernel: 'ts' });
    expect(sim.state.positions.length).toBe(7 * 7 * 3);
    expect(sim.scene.cloth.width).toBe(1);
    expect(sim.scene.colliders).toEqual([{ type: 'floor', height: 0, pins: [] }]);
    expect(sim.setScene({ cloth: { resolution: 4 } })).toBe(true);
    expect(sim.state.positions.length).toBe(5 * 5 * 3);
  });
});
