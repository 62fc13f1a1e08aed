/**
 * Self-contact in the WebAssembly kernel (self-contact.as.ts, its host self-contact-wasm.ts) against the TypeScript
 * reference it ports (self-contact.ts): the same operations in the same order, so the same cloth bit for bit.
 */
import { describe, expect, it } from 'vitest';
import { countIntersections } from '../intersections.js';
import { FRAME_DT } from '../params.js';
import { REFERENCE } from '../reference.js';
import { builtinScene } from '../scenes.js';
import { PHASE, PhaseLog, framePhases } from '../schedule.js';
import { collideSelf, findSelfCandidates, lastSelfCandidates, selfContactBuilds, selfContactUpdates } from '../self-contact.js';
import { Simulation } from '../simulation.js';
import { copyState, createState } from '../state.js';
import type { Scene } from '../scene.js';
import { XpbdKernel } from './xpbd-wasm.js';
import { WasmBackend } from '../backend.js';

/** layers (three cloths of different friction) with the middle cloth thicker: the pairs' distances differ too */
function thickLayers(): Scene {
  const s = builtinScene('layers');
  s.cloths![1].cloth.thickness = 0.008;
  return s;
}

/**
 * Runs `sim` (TypeScript) to each of `frames`, then the next substep's phases before self-contact on a copy of its
 * state, and self-contact on that copy twice: the reference's collideSelf, and the kernel's (window: its pair
 * windows' size), each new to the cloth (a model of its own, with no searches before: how far ahead a search looks
 * follows how long the last held, searchAhead). Returns, per frame, whether the two gave the same positions bit for
 * bit, how many coordinates self-contact moved, whether the two searches listed the same pairs in the same order, and
 * who searched in the kernel.
 */
function phaseParity(scene: Scene, frames: number[], window?: number): { same: boolean; moved: number; sameList: boolean; foundBy: string }[] {
  // the springs swept alone, as when the frames were chosen (the cloths land there, the passes move them)
  scene.solver.stretch = 'gauss-seidel';
  const sim = new Simulation(scene, { kernel: 'ts' });
  const out: { same: boolean; moved: number; sameList: boolean; foundBy: string }[] = [];
  let at = 0;
  for (const f of frames) {
    sim.advance(f - at);
    at = f;
    const fresh = new Simulation(scene, { kernel: 'ts' });
    const { model, params } = fresh;
    const kernel = XpbdKernel.create(model, 1, window)!;
    const ts = createState(model);
    copyState(sim.state, ts);
    const frame = { h: FRAME_DT / params.substeps, substeps: params.substeps, sub: 0, forced: false, grabFrom: new Float64Array(3), grabTo: new Float64Array(3) };
    const phases = framePhases(model, ts, params);
    for (let id = 0; id < PHASE.selfContact; id++) if ((phases & (1 << id)) !== 0) REFERENCE[id](model, ts, params, frame);
    copyState(ts, kernel.state);
    kernel.state.invMass.set(ts.invMass);
    const before = ts.positions.slice();
    // the reference searches on this state too, as the new kernel does (its earlier pairs would hold as well)
    findSelfCandidates(model, ts, params, frame.h, frame.substeps);
    collideSelf(model, ts, params, frame.h, frame.substeps);
    kernel.run(1 << PHASE.selfContact, model, kernel.state, params, frame, undefined);
    let same = true, moved = 0;
    for (let i = 0; i < before.length; i++) {
      if (ts.positions[i] !== kernel.state.positions[i]) same = false;
      if (ts.positions[i] !== before[i]) moved++;
    }
    // each searched on the state before the passes (and again where the particle pass pushed one out of its box)
    const ref = lastSelfCandidates(model)!, listed = kernel.selfCandidates()!;
    const sameList = ref.pairCount > 0 && ref.edgePairCount > 0 &&
      String(listed.pairs) === String(ref.pairs.subarray(0, 2 * ref.pairCount)) &&
      String(listed.edgePairs) === String(ref.edgePairs.subarray(0, 2 * ref.edgePairCount));
    out.push({ same, moved, sameList, foundBy: listed.foundBy });
    kernel.dispose();
    fresh.dispose();
  }
  sim.dispose();
  return out;
}

describe('self-contact in the WebAssembly kernel', () => {
  it('is the kernel\'s own phase, also for cloths that differ in thickness and friction', () => {
    for (const scene of [builtinScene('fold'), thickLayers()]) {
      const sim = new Simulation(scene, { kernel: 'wasm', threads: 1 });
      const log = new PhaseLog();
      (sim.backend as WasmBackend).kernel.frame(sim.model, sim.state, sim.params, FRAME_DT, log);
      const names = log.names();
      expect(names.filter((n) => n === 'selfContact')).toHaveLength(sim.params.substeps);
      expect(names).not.toContain('selfContact (reference)');
      sim.dispose();
    }
  });

  // landing: the substeps where the passes move the most (fold lands corner first from frame ~10, layers' cloths
  // reach the sphere and each other from frame ~20)
  it.each([
    ['fold', () => builtinScene('fold'), [15, 30, 45]],
    ['layers, the middle cloth thicker', thickLayers, [30, 45, 60]],
  ] as const)('%s: one substep gives the reference\'s positions bit for bit, the kernel\'s own search its pairs in its order', (_name, scene, frames) => {
    const runs = phaseParity(scene(), [...frames]);
    expect(runs.map((r) => r.same)).toEqual(frames.map(() => true));
    expect(runs.every((r) => r.moved > 0)).toBe(true); // self-contact did move the cloth in each
    expect(runs.map((r) => [r.sameList, r.foundBy])).toEqual(frames.map(() => [true, 'kernel']));
  });

  it('pairs beyond the windows in the kernel memory are found in TypeScript and go through window by window, in order: the same positions', () => {
    // 64-pair windows: fold at 32² lists thousands of pairs
    const runs = phaseParity(builtinScene('fold'), [15, 30], 64);
    expect(runs.map((r) => r.same)).toEqual([true, true]);
    expect(runs.every((r) => r.moved > 0)).toBe(true);
    expect(runs.map((r) => [r.sameList, r.foundBy])).toEqual([[true, 'typescript'], [true, 'typescript']]);
  });

  it('a particle no longer finite: the kernel\'s search finds nothing, as the reference\'s, and the passes leave the cloth as the reference does', () => {
    const sim = new Simulation(builtinScene('fold'), { kernel: 'ts' });
    const { model, params } = sim;
    const kernel = XpbdKernel.create(model, 1)!;
    sim.advance(20);
    const ts = createState(model);
    const frame = { h: FRAME_DT / params.substeps, substeps: params.substeps, sub: 0, forced: false, grabFrom: new Float64Array(3), grabTo: new Float64Array(3) };
    // the kernel has found pairs before (the landing)
    copyState(sim.state, kernel.state);
    kernel.state.invMass.set(sim.state.invMass);
    kernel.run(1 << PHASE.selfContact, model, kernel.state, params, frame, undefined);
    expect(kernel.selfCandidates()?.foundBy).toBe('kernel');
    copyState(sim.state, ts);
    ts.positions[3 * (model.particleCount >> 1) + 1] = NaN;
    copyState(ts, kernel.state);
    expect(findSelfCandidates(model, ts, params, frame.h, frame.substeps)).toBeNull();
    collideSelf(model, ts, params, frame.h, frame.substeps);
    kernel.run(1 << PHASE.selfContact, model, kernel.state, params, frame, undefined);
    expect(lastSelfCandidates(model)).toBeNull();
    expect(kernel.selfCandidates()).toBeNull();
    // nothing kept apart on either side: every position as it was, the NaN included
    expect([...kernel.state.positions]).toEqual([...ts.positions]);
    expect(ts.positions.filter((v) => Number.isNaN(v))).toHaveLength(1);
    kernel.dispose();
    sim.dispose();
  });

  it('layers, 60 frames: the TypeScript kernel\'s cloth bit for bit, and its candidates (the kernel\'s other phases there are the reference\'s: the cloths differ in damping, friction and stretch limit)', () => {
    // substep after substep: the frames, the clock and the edge pairs' measured distances carried across substeps
    const ts = new Simulation(builtinScene('layers'), { kernel: 'ts' }), wasm = new Simulation(builtinScene('layers'), { kernel: 'wasm', threads: 1 });
    ts.advance(60); wasm.advance(60);
    expect([...wasm.state.positions]).toEqual([...ts.state.positions]);
    // both updated their candidates for a few particles at a time, as often, to the same lists
    expect(selfContactUpdates(ts.model)).toBeGreaterThan(10);
    expect(selfContactUpdates(wasm.model)).toBe(selfContactUpdates(ts.model));
    expect(selfContactBuilds(wasm.model)).toBe(selfContactBuilds(ts.model));
    const ref = lastSelfCandidates(ts.model)!, listed = (wasm.backend as WasmBackend).kernel.selfCandidates()!;
    expect(listed.foundBy).toBe('kernel');
    expect(String(listed.pairs)).toBe(String(ref.pairs.subarray(0, 2 * ref.pairCount)));
    expect(String(listed.edgePairs)).toBe(String(ref.edgePairs.subarray(0, 2 * ref.edgePairCount)));
    expect(countIntersections(wasm.model.triangles, wasm.state.positions)).toBe(0);
    ts.dispose();
    wasm.dispose();
  });

  it.each([
    ['layers', 60],
    ['fold', 90],
  ] as const)('%s, %i frames: updating the candidates for the particles out of their boxes gives the cloth of searching whole, bit for bit', (scene, frames) => {
    const updating = new Simulation(builtinScene(scene), { kernel: 'wasm', threads: 1 });
    const whole = new Simulation(builtinScene(scene), { kernel: 'wasm', threads: 1 });
    // this kernel never updates: wherever a particle leaves its box it searches whole
    const self = ((whole.backend as WasmBackend).kernel as unknown as { selfContact: { update: () => boolean } }).selfContact;
    self.update = () => false;
    updating.advance(frames); whole.advance(frames);
    expect(selfContactUpdates(whole.model)).toBe(0);
    expect(selfContactUpdates(updating.model)).toBeGreaterThan(10);
    expect(selfContactBuilds(updating.model)).toBeLessThan(selfContactBuilds(whole.model));
    expect([...updating.state.positions]).toEqual([...whole.state.positions]);
    updating.dispose();
    whole.dispose();
  });

  it('fold (32²) on the kernel crosses itself nowhere at frame 300, and every edge record the edge pass reads is current after each frame', () => {
    const sim = new Simulation(builtinScene('fold'), { kernel: 'wasm', threads: 1 });
    const kernel = (sim.backend as WasmBackend).kernel;
    // the edge pass's records carry their ends' travel and move (its first skip reads them) and their box: a
    // correction in the pass must bring its particles' edges' records up to date, and a record is made for the pass
    // that reads it; a pass with many pairs makes every record first, one with few only its pairs' edges' (both
    // happen in this run: the landing, the pile at rest)
    let stale = 0, every = 0, some = 0;
    const edges = sim.model.edges.length / 2;
    for (let f = 0; f < 300; f++) {
      sim.advance(1);
      const records = kernel.selfEdgeRecords()!;
      stale += records.stale;
      if (records.made === edges) every++;
      else if (records.made > 0) some++;
    }
    expect(stale).toBe(0);
    expect(every).toBeGreaterThan(10);
    expect(some).toBeGreaterThan(10);
    expect(countIntersections(sim.model.triangles, sim.state.positions)).toBe(0);
    expect(sim.report().finite).toBe(true);
    sim.dispose();
  });

  it('fold against the TypeScript kernel: 1 frame within f32 rounding, 30 frames the same cloth as a whole', () => {
    const ts = new Simulation(builtinScene('fold'), { kernel: 'ts' }), wasm = new Simulation(builtinScene('fold'), { kernel: 'wasm', threads: 1 });
    ts.advance(1); wasm.advance(1);
    let d = 0;
    for (let i = 0; i < ts.state.positions.length; i++) d = Math.max(d, Math.abs(ts.state.positions[i] - wasm.state.positions[i]));
    expect(d).toBeLessThan(1e-6);
    // the landing parts the runs at contact decisions (the constraint passes in f32 lanes there, f64 here)
    ts.advance(29); wasm.advance(29);
    const a = ts.report(), b = wasm.report();
    for (let k = 0; k < 3; k++) expect(Math.abs(a.centroid[k] - b.centroid[k])).toBeLessThan(2e-3);
    ts.dispose();
    wasm.dispose();
  });

  it('a scene with self-contact off gets a kernel without its memory; switched on, a kernel with it takes the cloth as it is and steps as one made with it', () => {
    const off = builtinScene('fold');
    off.solver.selfContact = false;
    const a = new Simulation(off, { kernel: 'wasm', threads: 1 });
    const b = new Simulation(builtinScene('fold'), { kernel: 'wasm', threads: 1 });
    const kernel = (sim: Simulation) => (sim.backend as WasmBackend).kernel;
    expect([kernel(a).hasSelfContact, kernel(b).hasSelfContact]).toEqual([false, true]);
    // 32²: 1089 particles; self-contact's memory is most of the kernel's (measured: 0.3 MB without it, 4.3 MB with)
    expect(kernel(a).bytes).toBeLessThan(0.2 * kernel(b).bytes);
    // b steps without it too (its kernel keeps the memory), then both switch it on
    b.set('solver.selfContact', false);
    expect(kernel(b).hasSelfContact).toBe(true);
    a.advance(10); b.advance(10);
    expect([...a.state.positions]).toEqual([...b.state.positions]);
    const before = a.state.positions.slice();
    a.set('solver.selfContact', true); b.set('solver.selfContact', true);
    expect(kernel(a).hasSelfContact).toBe(true);
    expect(a.state.positions).toEqual(before);
    a.advance(30); b.advance(30);
    expect([...a.state.positions]).toEqual([...b.state.positions]);
    expect(countIntersections(a.model.triangles, a.state.positions)).toBe(0);
    a.dispose(); b.dispose();
  });

  it('a kernel too big for one WebAssembly memory (4 GiB) with self-contact\'s is made without it (the reference then runs the phase)', () => {
    // (a window of 2²⁹ pairs stands for a cloth of about a million particles: its self-contact memory alone is over 4 GiB)
    const model = new Simulation(builtinScene('fold'), { kernel: 'ts' }).model;
    const big = XpbdKernel.create(model, 1, 2 ** 29)!;
    const fits = XpbdKernel.create(model, 1, 4096)!;
    expect([big.hasSelfContact, fits.hasSelfContact]).toEqual([false, true]);
    expect(big.bytes).toBeLessThan(fits.bytes);
    big.dispose(); fits.dispose();
  });

  it('a kernel made without self-contact\'s memory, asked for the phase, runs it in the reference: the same cloth bit for bit', () => {
    const sim = new Simulation(builtinScene('fold'), { kernel: 'ts' });
    sim.advance(20);
    const { model, params } = sim;
    const [bare, full] = [false, true].map((self) => WasmBackend.create(model, 1, undefined, self)!);
    const log = new PhaseLog();
    for (const k of [bare, full]) { copyState(sim.state, k.state); k.state.invMass.set(sim.state.invMass); }
    bare.kernel.frame(model, bare.state, params, FRAME_DT, log);
    full.frame(model, params, FRAME_DT);
    expect(log.names()).toContain('selfContact (reference)');
    expect([...bare.state.positions]).toEqual([...full.state.positions]);
    bare.dispose(); full.dispose(); sim.dispose();
  });
});
