import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, symlinkSync, writeFileSync } from 'node:fs';
import { availableParallelism, tmpdir } from 'node:os';
import { join } from 'node:path';
import { validateBytes } from 'gltf-validator';
import { describe, expect, it, vi } from 'vitest';
import { Simulation, countIntersections } from '../core/index.js';
import { benchScene } from './bench.js';
import { main, type CliIo } from './main.js';

async function runWith(io: CliIo | undefined, argv: string[]) {
  const out: string[] = [], err: string[] = [];
  const code = await main(argv, (s) => out.push(s), (s) => err.push(s), io);
  return { code, out: out.join('\n'), err: err.join('\n') };
}
const run = (...argv: string[]) => runWith(undefined, argv);
const tmp = () => mkdtempSync(join(tmpdir(), 'drape-cli-'));

describe('drape CLI', () => {
  it('run --json prints exactly one JSON object with the documented fields', async () => {
    const r = await run('run', 'cotton-basic', '--frames', '30', '--set', 'cloth.resolution=8', '--json');
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    for (const k of ['scene', 'solver', 'backend', 'frames', 'particles', 'triangles', 'constraints', 'msPerFrame', 'finite',
      'maxStrain', 'maxPenetration', 'intersections', 'centroid', 'bounds', 'energy']) expect(j, k).toHaveProperty(k);
    expect(j).toMatchObject({ scene: 'cotton-basic', solver: 'xpbd', backend: 'cpu', frames: 30, particles: 81, triangles: 128, finite: true });
    expect(j.centroid).toHaveLength(3);
    expect(Object.keys(j.energy)).toEqual(['kinetic', 'gravitational', 'elastic', 'bending']);
  });

  it('a scene runs for its duration without --frames, and a fabric test scene reports test.* (JSON and text)', async () => {
    const plain = JSON.parse((await run('run', 'cotton-basic', '--set', 'cloth.resolution=4', '--json')).out);
    expect(plain.frames).toBe(180); // the default duration, 3 s
    expect(plain).not.toHaveProperty('test');
    const r = await run('run', 'cantilever', '--set', 'cloth.resolution=8', '--set', 'duration=0.25', '--set', 'material.fabric=silk', '--json');
    expect(r.code, r.err).toBe(0);
    const j = JSON.parse(r.out);
    expect(j.frames).toBe(15);
    expect(j.resolvedScene.material).toMatchObject({ fabric: 'silk', arealDensity: 0.061 });
    expect(j.test).toMatchObject({ type: 'cantilever' });
    expect(j.test.overhang).toBeCloseTo(0.04, 6);
    expect(j.test.bendingLength).toBeGreaterThan(0);
    const c = JSON.parse((await run('run', 'cusick', '--set', 'cloth.resolution=12', '--frames', '0', '--json')).out);
    expect(c.test.drapeCoefficient).toBeCloseTo(1, 1); // flat at the start
    const text = await run('run', 'cusick', '--set', 'cloth.resolution=12', '--frames', '2');
    expect(text.out).toMatch(/\n  test +type cusick, projectedArea [\d.]+, drapeCoefficient [\d.]+, folds \d+/);
    // a strip not bent yet: no bending length, alike in the text and the JSON (not "Infinity" beside null)
    const flat = await run('run', 'cantilever', '--set', 'cloth.resolution=8', '--frames', '0');
    expect(flat.out).toMatch(/\n  test +type cantilever, overhang 0\.0400, chordAngle 0, bendingLength — \(not yet\)(\n|$)/);
    expect(JSON.parse((await run('run', 'cantilever', '--set', 'cloth.resolution=8', '--frames', '0', '--json')).out).test.bendingLength).toBeNull();
  });

  it('--specimens N reads a test on N specimens (seeds s … s + N − 1) and their mean; refused where they would not differ', async () => {
    const r = await run('run', 'cusick', '--set', 'cloth.resolution=12', '--set', 'cloth.perturbation.seed=4', '--frames', '30', '--specimens', '3', '--json');
    expect(r.code, r.err).toBe(0);
    const j = JSON.parse(r.out);
    expect(j.specimens.map((s: { seed: number }) => s.seed)).toEqual([4, 5, 6]);
    expect(j.specimens[0].test).toEqual(j.test);
    const dc = j.specimens.map((s: { test: { drapeCoefficient: number } }) => s.test.drapeCoefficient);
    expect(new Set(dc).size).toBe(3);
    expect(j.testMean.drapeCoefficient).toBeCloseTo((dc[0] + dc[1] + dc[2]) / 3, 5);
    expect(j.testMean.type).toBe('cusick');
    const text = await run('run', 'cusick', '--set', 'cloth.resolution=12', '--frames', '2', '--specimens', '2');
    expect(text.out).toMatch(/\n  test +seed 1: type cusick, .*\n +seed 2: type cusick, .*\n  mean of 2 +type cusick, projectedArea [\d.]+, drapeCoefficient [\d.]+, folds [\d.]+/);
    for (const [args, said] of [
      [['cotton-basic'], /--specimens: reads a standard test's specimens .*'cotton-basic' has no test/],
      [['cusick', '--set', 'cloth.perturbation.amplitude=0'], /--specimens: the specimens differ only in cloth\.perturbation, whose amplitude is 0 here/],
      [['cusick', '--set', 'cloth.perturbation.seed=2147483647'], /--specimens: seeds 2147483647…2147483648 pass/],
    ] as const) {
      const bad = await run('run', ...args, '--specimens', '2', '--frames', '1');
      expect(bad.code).toBe(2);
      expect(bad.err).toMatch(said);
    }
    expect((await run('run', 'cusick', '--specimens', '0')).err).toMatch(/--specimens: must be an integer in 1…20, got '0'/);
  });

  it('--kernel and --threads choose how the CPU steps XPBD, and the JSON says what ran', async () => {
    const args = ['run', 'cotton-basic', '--frames', '10', '--set', 'cloth.resolution=8', '--json'];
    const ts = JSON.parse((await run(...args, '--kernel', 'ts')).out);
    const one = JSON.parse((await run(...args, '--kernel', 'wasm', '--threads', '1')).out);
    const auto = JSON.parse((await run(...args)).out);
    expect(ts).toMatchObject({ kernel: 'ts', threads: 1 });
    expect(one).toMatchObject({ kernel: 'wasm', threads: 1 });
    expect(auto).toMatchObject({ kernel: 'wasm', threads: 1 }); // a small cloth: threads would not pay
    const big = JSON.parse((await run('run', 'cotton-basic', '--frames', '1', '--set', 'cloth.resolution=64', '--json')).out);
    expect(big).toMatchObject({ kernel: 'wasm', threads: Math.min(8, availableParallelism()) });
    expect(auto.centroid).toEqual(one.centroid); // threads change nothing, bit for bit
    for (let k = 0; k < 3; k++) expect(Math.abs(one.centroid[k] - ts.centroid[k])).toBeLessThan(1e-4);
    // more threads than cores are clamped, with a note
    const many = await run(...args, '--threads', '999');
    expect(JSON.parse(many.out).threads).toBeLessThanOrEqual(availableParallelism());
    expect(many.err).toMatch(/--threads 999: using \d+, the cores available/);
    // mass-spring always steps in TypeScript, and says so
    expect(JSON.parse((await run(...args, '--solver', 'mass-spring')).out)).toMatchObject({ kernel: 'ts', threads: 1 });
  });

  it('bench --json times the wasm kernel on its threads, on 1 thread, in TypeScript, and mass-spring', async () => {
    const r = await run('bench', '--sizes', '9', '--frames', '2', '--warmup', '1', '--no-peer', '--no-contention', '--json');
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    const row = j.rows[0];
    expect(row.busy).toBeUndefined();
    expect(row).toMatchObject({ particlesPerSide: 9, particles: 81 });
    expect(row.xpbd).toMatchObject({ kernel: 'wasm', finite: true, stable: true });
    expect(j.threads).toBe('auto');
    expect(row.xpbd.threads).toBe(1); // 'auto' on a cloth this small
    expect(row.xpbd1).toMatchObject({ kernel: 'wasm', finite: true });
    for (const t of [row.xpbd, row.xpbd1, row.xpbdTs, row.massSpring]) expect(t.msPerFrame).toBeGreaterThan(0);
    // beside the like-for-like rows, the same cloth with the default fabric model: its bending and stretch at 20 substeps
    expect(row.model).toMatchObject({ bending: 'springs', bendingSolve: 'gauss-seidel', stretch: 'two-level', substeps: 20 });
    for (const t of [row.model.xpbd, row.model.xpbd1, row.model.xpbdTs]) expect(t).toMatchObject({ finite: true, stable: true });
    expect(row.model.ratio1).toBeCloseTo(row.model.xpbd1.msPerFrame / row.xpbd1.msPerFrame, 10);
  });

  // Jolt solves its distance constraints one at a time: the like-for-like cloth sweeps its springs alone, whatever the
  // default stretch solve (the coarse correction since 2026-12-06, which the fabric-model rows time)
  it('bench\'s like-for-like cloth is Jolt\'s: every spring a distance constraint, swept one at a time, no self-contact', () => {
    expect(benchScene(64, 10, 'xpbd').solver).toMatchObject({ type: 'xpbd', substeps: 10, iterations: 1, bending: 'springs', stretch: 'gauss-seidel', selfContact: false });
  });

  it('bench --set changes the fabric-model rows only: the hinges solved together beside the like-for-like rows', async () => {
    const r = await run('bench', '--sizes', '9', '--frames', '2', '--warmup', '1', '--no-peer', '--no-contention', '--json',
      '--set', 'solver.bending=hinges', '--set', 'solver.bendingSolve=global');
    expect(r.code).toBe(0);
    const row = JSON.parse(r.out).rows[0];
    expect(row.model).toMatchObject({ bending: 'hinges', bendingSolve: 'global', stretch: 'two-level', substeps: 20 });
    expect(row.model.xpbd).toMatchObject({ finite: true, stable: true });
    const table = await run('bench', '--sizes', '5', '--frames', '1', '--warmup', '0', '--no-peer', '--no-contention', '--set', 'solver.bending=laplacian');
    expect(table.out).toMatch(/with --set[^\n]*\n\n\| particles \| bending \| bending solve \|[^\n]*\n[^\n]*\n\| 5×5 \| laplacian \| gauss-seidel \| two-level \| 20 \|/);
  });

  it('bench --backend gpu --set: the GPU runs the changed scene (the hinges solved together: 4 dispatches a substep more)', async () => {
    const args = ['bench', '--backend', 'gpu', '--sizes', '9', '--frames', '2', '--substeps', '10', '--json'];
    const plain = await run(...args);
    const together = await run(...args, '--set', 'solver.bending=hinges', '--set', 'solver.bendingSolve=global');
    expect(together.code, together.err).toBe(0);
    const [p, t] = [JSON.parse(plain.out), JSON.parse(together.out)];
    expect(t.sets).toEqual(['solver.bending=hinges', 'solver.bendingSolve=global']);
    expect(t.rows[0].dispatchesPerFrame - p.rows[0].dispatchesPerFrame).toBe(4 * 10);
    expect(t.rows[0].cpuMsPerFrame).toBeGreaterThan(0);
    const table = await run('bench', '--backend', 'gpu', '--sizes', '5', '--frames', '1', '--set', 'solver.bending=laplacian');
    expect(table.out).toMatch(/^drape bench --backend gpu — cotton on sphere \+ floor, XPBD 10 substeps, with solver\.bending=laplacian, 1 timed frames;/);
  });

  it('run --backend gpu with the springs and the hinges solved together: the cantilever strip as on the CPU', async () => {
    const args = ['run', 'cantilever', '--frames', '30', '--set', 'cloth.resolution=8', '--set', 'solver.stretch=global', '--json'];
    const gpu = await run(...args, '--backend', 'gpu');
    expect(gpu.code, gpu.err).toBe(0);
    const [g, c] = [JSON.parse(gpu.out), JSON.parse((await run(...args)).out)];
    expect(g.backend).toBe('gpu');
    // seen 1.7e-6 apart (relative)
    expect(Math.abs(g.test.bendingLength / c.test.bendingLength - 1)).toBeLessThan(1e-3);
  });

  it('bench --scenes times built-in scenes as they are on each CPU solver and says what the GPU makes of them', async () => {
    const r = await run('bench', '--scenes', 'skirt,pins', '--frames', '2', '--warmup', '0', '--json');
    expect(r.code).toBe(0);
    const [skirt, pins] = JSON.parse(r.out).rows;
    expect(skirt).toMatchObject({ scene: 'skirt', colliders: 16, substeps: 10, xpbd: { kernel: 'wasm', finite: true }, xpbdTs: { finite: true }, massSpring: { finite: true } });
    // the GPU takes both (moving capsules and carried pins included)
    expect(skirt.gpuRefusal).toBeNull();
    expect(pins.gpuRefusal).toBeNull();
    const table = await run('bench', '--scenes', 'pins', '--frames', '1', '--warmup', '0');
    expect(table.out).toMatch(/^\| pins \| 1089 \| 1 \| 20 \| [\d.]+ \(wasm, 1 thread\) \| [\d.]+ \| [\d.]+ \| yes \/ yes \/ yes \| takes it/m);
  });

  it('bench --self-contact times a scene with self-contact off and on, and counts what crosses in each', async () => {
    const r = await run('bench', '--self-contact', '--scenes', 'layers', '--sizes', '8', '--frames', '40', '--no-peer', '--json');
    expect(r.code, r.err).toBe(0);
    const [row] = JSON.parse(r.out).rows;
    expect(row).toMatchObject({ scene: 'layers', resolution: 8, particles: 3 * 81, kernel: 'wasm', finite: true, onMaxIntersections: 0, onIntersections: 0, offSubsteps: 20, onSubsteps: 20 });
    // the three cloths have landed on each other: without self-contact they cross
    expect(row.offIntersections).toBeGreaterThan(100);
    expect(row.ratio).toBeCloseTo(row.onMsPerFrame / row.offMsPerFrame, 6);
    expect(JSON.parse(r.out).strip).toBeUndefined();
    // the table, and the Ten Minute Physics demo's strip by its method and by Drape's (peers/particle-hash.ts)
    const table = await run('bench', '--self-contact', '--sizes', '4', '--frames', '1');
    expect(table.out).toMatch(/^\| fold \| 4 \| 25 \| wasm, 1 thread \| 20 \/ 20 \| [\d.]+ \| [\d.]+ \| [\d.]+× \| \d+ \| 0 \| 0 \| yes \|$/m);
    expect(table.out).toMatch(/^\| Ten Minute Physics 15: particle hash.* \| 6000 \| [\d.]+ \| \d+ \| \d+ \| [\d.]+ \| yes \|$/m);
    expect(table.out).toMatch(/^\| Drape XPBD, cotton, self-contact on \(wasm, \d threads?\) \| 6000 \| [\d.]+ \| 0 \| 0 \| [\d.]+ \| yes \|$/m);
    expect(table.out).toMatch(/^\| Drape XPBD, cotton, self-contact off .* \| 6000 \|/m);
    expect((await run('bench', '--self-contact', '--backend', 'gpu')).err).toMatch(/^drape: --self-contact: times the CPU/);
  });

  it('bench --hanging says how long a hanging sheet takes to settle at its static elongation, for Drape and for Jolt', async () => {
    const r = await run('bench', '--hanging', '--sizes', '8', '--fabrics', 'rubber', '--seconds', '3', '--jolt-iterations', '40,1', '--json');
    expect(r.code, r.err).toBe(0);
    const j = JSON.parse(r.out);
    expect(j).toMatchObject({ faces: 8, seconds: 3, within: 0.25 });
    const [row] = j.rows;
    // rubber, 0.38 kg/m² and 600 N/m: a 1 m sheet lengthens by 0.38 · 9.81 / 1200 m
    expect(row.theory).toBeCloseTo((0.38 * 9.81) / 1200, 6);
    const by = (name: RegExp) => row.runs.find((x: { solver: string }) => name.test(x.solver));
    // the springs solved together settle within the band and stay there; the end of the run is inside it
    const global = by(/stretch global/);
    expect(global.settledAt).toBeGreaterThan(0);
    expect(global.settledAt).toBeLessThan(2);
    expect(Math.abs(global.ratio - 1)).toBeLessThanOrEqual(0.25);
    expect(by(/stretch gauss-seidel/)).toBeDefined();
    // so does the default, the sweep after the coarse correction
    const coarse = by(/^Drape default \(xpbd, 20 substeps × 1, two-level\)$/);
    expect(coarse.settledAt).toBeGreaterThan(0);
    expect(Math.abs(coarse.ratio - 1)).toBeLessThanOrEqual(0.25);
    // Jolt, its counts tried in ascending order: 1 iteration overstretches for good, so the next is tried; 40 settles
    expect(by(/^Jolt, 1 iterations$/)).toMatchObject({ settledAt: null, wallSeconds: null });
    expect(by(/^Jolt, 1 iterations$/).ratio).toBeGreaterThan(1.25);
    expect(by(/^Jolt, 40 iterations$/).settledAt).toBeGreaterThan(0);
    expect(row.runs).toHaveLength(5);
    const table = await run('bench', '--hanging', '--sizes', '4', '--fabrics', 'cotton', '--seconds', '3', '--no-peer');
    expect(table.out).toMatch(/^\| cotton \| 0\.068 \| Drape solver\.stretch global \| [\d.]+ \| [\d.]+ \| [\d.]+ \| [01]\.\d\d \|$/m);
    expect(table.out).toMatch(/^\| cotton \| 0\.068 \| Drape default \(xpbd, 20 substeps × 1, two-level\) \| (never \(3 s\)|[\d.]+) \|/m);
  });

  it('bench times the default threads against one thread on a machine it keeps busy', async () => {
    const r = await run('bench', '--sizes', '51', '--frames', '3', '--warmup', '1', '--no-peer');
    expect(r.code).toBe(0);
    expect(r.out).toMatch(/Busy machine: \d+ other processes keep every core busy/);
    expect(r.out).toMatch(/^\| 51×51 \| [\d.]+ \| \d \| \d+ % \| [\d.]+ \| [\d.]+ \|$/m);
    expect(r.out).toMatch(/^\| 51×51 \| springs \| gauss-seidel \| two-level \| 20 \| [\d.]+ \| \d \| [\d.]+ \| [\d.]+ \| [\d.]+ \| yes \|$/m);
  });

  it('--frames 0 reports the start state; --solver and --set change the scene', async () => {
    const j = JSON.parse((await run('run', 'pins', '--frames', '0', '--solver', 'mass-spring', '--set', 'cloth.position=[0,2,0]', '--json')).out);
    expect(j).toMatchObject({ frames: 0, solver: 'mass-spring', msPerFrame: 0, maxStrain: 0 });
    expect(j.centroid[1]).toBeCloseTo(2, 5);
  });

  it('says how many substeps it ran: more than asked where self-contact needs them, with the note why', async () => {
    // a 1 mm cloth: 6 m/s (solver.selfContactSpeed) moves 1 mm in 1/6000 s, so 100 substeps
    const thin = ['run', 'cotton-basic', '--frames', '1', '--set', 'cloth.resolution=4', '--set', 'cloth.thickness=0.001'];
    const j = JSON.parse((await run(...thin, '--json')).out);
    expect(j.substeps).toBe(100);
    expect(j.resolvedScene.solver).toMatchObject({ substeps: 20, selfContact: true, selfContactSpeed: 6 });
    expect(j.clamps).toEqual([expect.stringMatching(/^self-contact at 20 substeps: .* so it runs at 100 substeps/)]);
    const text = await run(...thin);
    expect(text.out).toMatch(/^scene cotton-basic: xpbd on cpu \(.*\), 100 substeps, 1 frames/m);
    expect(text.err).toMatch(/^drape: note: self-contact at 20 substeps: /m);
    expect(JSON.parse((await run(...thin, '--set', 'solver.selfContactSpeed=0', '--json')).out)).toMatchObject({ substeps: 20, clamps: [] });
  });

  it('the resolution scene runs its sweep from 1 to 4096 faces', async () => {
    // (without self-contact: single sheets dropped flat on the sphere, and the sweep is what is tested here)
    const j = JSON.parse((await run('run', 'resolution', '--frames', '60', '--set', 'solver.selfContact=false', '--json')).out);
    expect(j.sweep.map((s: { faces: number }) => s.faces)).toEqual([1, 4, 16, 64, 256, 1024, 4096]);
    expect(j.sweep[0].centroid[1]).toBeGreaterThan(0.6); // the 1-face cloth rests on the sphere
  });

  it('a flag the run does not use says so once: threads on the TypeScript kernel, the kernel on the mass-spring solver; a --set of the resolution in any spelling skips the sweep', async () => {
    const notes = async (...args: string[]) => (await run('run', 'custom', '--frames', '1', '--set', 'cloth.resolution=4', ...args)).err.split('\n').filter((l) => l.startsWith('drape: note: --'));
    expect(await notes('--kernel', 'ts', '--threads', '8')).toEqual(['drape: note: --threads 8: not used: the TypeScript kernel runs on one thread']);
    expect(await notes('--solver', 'mass-spring', '--kernel', 'wasm', '--threads', '1')).toEqual(['drape: note: --kernel wasm and --threads 1: not used: the mass-spring solver runs in TypeScript, on one thread']);
    expect(await notes('--kernel', 'wasm', '--threads', '1')).toEqual([]);
    // more threads than cores on a solver that takes none: one note, not a clamp to the cores beside it
    expect(await notes('--solver', 'mass-spring', '--threads', '64')).toEqual(['drape: note: --threads 64: not used: the mass-spring solver runs in TypeScript, on one thread']);
    const j = JSON.parse((await run('run', 'resolution', '--frames', '1', '--set', 'cloth={"resolution":2}', '--json')).out);
    expect([j.sweep, j.particles]).toEqual([undefined, 9]);
    // (an empty key is no spelling of it: refused, not read as cloth.resolution)
    expect((await run('run', 'resolution', '--frames', '1', '--set', 'cloth..resolution=2')).err.trim()).toBe('drape: --set cloth..resolution: not a scene path');
  });

  it('the sweep\'s runs report their own clamps: each run\'s in --json, and each new one once as a note', async () => {
    // (mass-spring softens more springs the finer the mesh; the first run, at 1 face, softens none)
    const args = ['run', 'resolution', '--frames', '1', '--solver', 'mass-spring', '--set', 'solver.selfContact=false'];
    const j = JSON.parse((await run(...args, '--json')).out);
    expect(j.clamps).toEqual([]);
    expect(j.sweep.map((s: { clamps: string[] }) => s.clamps.length)).toEqual([0, 1, 1, 2, 2, 2, 2]);
    const text = await run(...args);
    const notes = text.err.split('\n').filter((l) => l.startsWith('drape: note: '));
    expect(notes.length).toBe(new Set(j.sweep.flatMap((s: { clamps: string[] }) => s.clamps)).size);
    expect(notes[0]).toMatch(/^drape: note: at cloth\.resolution 2: mass-spring at 20 substeps: 26 of 26 springs are too stiff/);
  });

  it('reads scene files and exports OBJ', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'drape-cli-'));
    const file = join(dir, 'scene.json'), obj = join(dir, 'cloth.obj');
    writeFileSync(file, JSON.stringify({ name: 'mine', cloth: { resolution: 4 }, colliders: [] }));
    const r = await run('run', file, '--frames', '10', '--export', obj);
    expect(r.code).toBe(0);
    expect(r.out).toMatch(/scene mine: xpbd/);
    const text = readFileSync(obj, 'utf8');
    expect(text.match(/^v /gm)).toHaveLength(25);
    expect(text.match(/^vn /gm)).toHaveLength(25);
    expect(text.match(/^f /gm)).toHaveLength(32);
    expect(text.split('\n')[1]).toBe('mtllib cloth.mtl');
    expect(text).toMatch(/^o mine\nusemtl cotton_fabric$/m);
    expect(readFileSync(join(dir, 'cloth.mtl'), 'utf8')).toMatch(/^newmtl cotton_fabric\nKd 0\.5882 0\.6627 0\.7725\n/m);
    expect(r.out).toContain(`exported     ${obj} and ${join(dir, 'cloth.mtl')}`);
    // a name with a space: the MTL's name has none, so that the mtllib line (names end at white space) names it
    const spaced = join(dir, 'my cloth.obj');
    expect((await run('run', file, '--frames', '1', '--export', spaced)).code).toBe(0);
    expect(readFileSync(spaced, 'utf8').split('\n')[1]).toBe('mtllib my_cloth.mtl');
    expect(readFileSync(join(dir, 'my_cloth.mtl'), 'utf8')).toMatch(/^newmtl cotton_fabric$/m);
  });

  it('exports a .glb and bakes the run into one: its start and every stride-th frame, the last always', async () => {
    const dir = tmp(), glb = join(dir, 'end.glb'), bake = join(dir, 'run.glb');
    const r = await run('run', 'layers', '--set', 'cloths[0].cloth.resolution=4', '--frames', '7', '--export', glb, '--bake', bake, '--bake-stride', '3', '--json');
    expect(r.code, r.err).toBe(0);
    const j = JSON.parse(r.out);
    expect(j).toMatchObject({ exported: glb, baked: bake, bakedFrames: 4 });
    const chunk = (file: string) => {
      const bytes = readFileSync(file);
      return JSON.parse(bytes.subarray(20, 20 + bytes.readUInt32LE(12)).toString('utf8'));
    };
    expect(chunk(glb).meshes.map((m: { name: string }) => m.name)).toEqual(['leather', 'cotton', 'silk']);
    expect(chunk(glb).animations).toBeUndefined();
    const baked = chunk(bake);
    expect(baked.animations[0].extras.frames).toEqual([3, 6, 7]);
    expect(baked.meshes[0].primitives[0].targets).toHaveLength(3);
    // the files as the CLI wrote them pass the Khronos validator: no error, no warning
    for (const file of [glb, bake]) {
      const { issues } = await validateBytes(new Uint8Array(readFileSync(file)), { maxIssues: 100 });
      expect({ file, errors: issues.numErrors, warnings: issues.numWarnings }).toEqual({ file, errors: 0, warnings: 0 });
    }
  });

  it('a bake larger than 1 GiB is refused before the run, naming a stride that fits', async () => {
    const dir = tmp();
    const r = await run('run', 'custom', '--set', 'cloth.resolution=256', '--frames', '1000', '--bake', join(dir, 'big.glb'));
    expect(r.code).toBe(2);
    expect(r.err).toMatch(/^drape: --bake: 1000 frames of 66049 particles would be 1\.5 GiB, more than 1 GiB; give --bake-stride 2 or more, or fewer --frames$/);
    expect(existsSync(join(dir, 'big.glb'))).toBe(false);
  });

  it('reports the cloth\'s self-intersections: the pairs of triangles of the exported cloth that cross', async () => {
    // silk at 64² folds through itself on the sphere without self-contact, its springs swept alone: what the count is
    // for (after the coarse correction, the default since 2026-12-06, it lands without crossing itself by frame 180)
    const dir = tmp(), obj = join(dir, 'silk.obj');
    const r = await run('run', 'silk-drape', '--set', 'cloth.resolution=64', '--set', 'solver.selfContact=false', '--set', 'solver.stretch=gauss-seidel', '--frames', '180', '--json', '--export', obj);
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    const lines = readFileSync(obj, 'utf8').split('\n');
    const x = lines.filter((l) => l.startsWith('v ')).flatMap((l) => l.slice(2).trim().split(/\s+/).map(Number));
    const f = lines.filter((l) => l.startsWith('f ')).flatMap((l) => l.slice(2).trim().split(/\s+/).map((v) => parseInt(v, 10) - 1));
    expect(j.intersections).toBe(countIntersections(Uint32Array.from(f), x));
    expect(j.intersections).toBeGreaterThan(0);
    const text = await run('run', 'cotton-basic', '--set', 'cloth.resolution=8', '--frames', '10');
    expect(text.out).toContain('intersections 0 pairs of triangles crossing each other (sharing no vertex)');
  });

  it.each([
    [['run', 'nope'], /unknown scene 'nope'/],
    [['run', 'missing.json'], /missing\.json: no such file/],
    [['run', '--set', 'material.bendStifness=1'], /material\.bendStifness: unknown key/],
    [['run', '--set', 'cloth.resolution=abc'], /cloth\.resolution: must be integer/],
    [['run', '--set', 'nothing'], /expected PATH=VALUE/],
    [['run', '--frames', 'ten'], /--frames: must be an integer/],
    [['run', '--bogus'], /Unknown option '--bogus'$/],
    [['run', '--export', 'x.stl'], /^drape: --export: \.obj or \.glb files only, got 'x\.stl'$/],
    [['run', '--bake', 'x.gltf'], /^drape: --bake: writes a \.glb file, got 'x\.gltf'$/],
    [['run', '--bake', 'x.glb', '--frames', '0'], /^drape: --bake: --frames 0 runs no frame to bake/],
    [['run', '--bake', 'x.glb', '--bake-stride', '0'], /^drape: --bake-stride: must be an integer in 1…1000000, got '0'$/],
    [['run', '--bake-stride', '2'], /^drape: --bake-stride: bakes with --bake FILE\.glb; give --bake too$/],
    [['run', '--bake', 'x.glb', '--export', './x.glb'], /^drape: --bake: x\.glb is the --export file too; give two names$/],
    [['run', '--bake', '/no/such/folder/x.glb'], /^drape: --bake \/no\/such\/folder\/x\.glb: the folder \/no\/such\/folder does not exist$/],
    [['run', '--backend', 'quantum'], /--backend: must be cpu or gpu/],
    [['run', '--solver', 'foo', '--frames', '1'], /^drape: --solver: must be one of "xpbd", "mass-spring"$/],
    [['run', '--backend', 'gpu', '--solver', 'mass-spring', '--frames', '1'], /only the xpbd solver runs on the GPU/],
    [['bench', '--sizes', '64,x'], /--sizes: must be an integer/],
    [['bench', '--scenes', 'cape,nope'], /--scenes: unknown scene 'nope' \(built-in scenes: .*cape, skirt/],
    [['bench', '--scenes', 'cape', '--backend', 'gpu'], /--scenes: times the CPU solvers/],
    [['bench', '--hanging', '--fabrics', 'tweed'], /^drape: --fabrics: unknown fabric 'tweed' \(named fabrics: cotton, silk, leather, rubber, denim, wool\)$/],
    [['bench', '--hanging', '--sizes', '32,64'], /^drape: --hanging: one size/],
    [['bench', '--set', 'solver.bending=folds'], /^drape: .*solver\.bending/],
    [['bench', '--hanging', '--set', 'solver.bending=hinges'], /^drape: --set: changes the fabric-model rows of the CPU bench/],
    [['bench', '--hanging', '--self-contact'], /^drape: --hanging and --self-contact are two different benchmarks/],
    [['bench', '--hanging', '--seconds', '1'], /^drape: --seconds: must be an integer in 2…600, got '1'$/],
    [['bench', '--hanging', '--sizes', '1'], /^drape: --sizes: must be an integer in 2…256, got '1'$/],
    [['bench', '--hanging', '--scenes', 'cape'], /^drape: --hanging: runs each sheet until it settles or --seconds pass; --scenes is for the other benchmarks$/],
    [['bench', '--fabrics', 'silk'], /^drape: --fabrics: belongs to --hanging; give --hanging too$/],
    [['bench', '--scenes', 'cape', '--seconds', '5'], /^drape: --seconds: belongs to --hanging; give --hanging too$/],
    [['run', '--kernel', 'gpu'], /--kernel: must be wasm or ts/],
    [['run', '--threads', '0'], /--threads: must be an integer in 1…1024/],
    [['fly'], /unknown command 'fly'/],
  ])('bad input %j exits 2 with one line naming the problem', async (argv, message) => {
    const r = await run(...argv);
    expect(r.code).toBe(2);
    expect(r.out).toBe('');
    expect(r.err.split('\n')).toHaveLength(1);
    expect(r.err).toMatch(message);
  });

  it('malformed JSON in a scene file is exit 2, one line', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'drape-cli-'));
    writeFileSync(join(dir, 'bad.json'), '{"cloth": {');
    const r = await run('run', join(dir, 'bad.json'));
    expect(r.code).toBe(2);
    expect(r.err).toMatch(/bad\.json: malformed JSON/);
  });

  it('scenes lists the built-ins; --help works everywhere', async () => {
    expect((await run('scenes')).out).toMatch(/^cotton-basic .*sphere/m);
    for (const cmd of [[], ['--help'], ['run', '--help'], ['bench', '--help'], ['scenes', '--help'], ['schema', '--help']]) {
      const r = await run(...cmd);
      expect(r.code).toBe(0);
      expect(r.out).toMatch(/drape/);
    }
  });

  it('--backend gpu runs the same scene on WebGPU and agrees with the CPU', async () => {
    const args = ['run', 'cotton-basic', '--frames', '20', '--set', 'cloth.resolution=8', '--json'];
    // and bakes on the GPU as on the CPU: the same frames, read back on the way
    const dir = tmp(), bakes = [join(dir, 'gpu.glb'), join(dir, 'cpu.glb')];
    const gpu = JSON.parse((await run(...args, '--backend', 'gpu', '--bake', bakes[0], '--bake-stride', '8')).out);
    const cpu = JSON.parse((await run(...args, '--bake', bakes[1], '--bake-stride', '8')).out);
    expect(gpu).toMatchObject({ backend: 'gpu', finite: true, particles: 81, baked: bakes[0], bakedFrames: 4 });
    gpu.centroid.forEach((c: number, k: number) => expect(Math.abs(c - cpu.centroid[k])).toBeLessThan(1e-4)); // before contact: rounding only
    const morphs = (file: string) => {
      const bytes = readFileSync(file), json = JSON.parse(bytes.subarray(20, 20 + bytes.readUInt32LE(12)).toString('utf8'));
      const bin = bytes.subarray(28 + bytes.readUInt32LE(12));
      // each morph target's POSITION accessor: displacements from frame 0 [m]
      return { frames: json.animations[0].extras.frames, targets: json.meshes[0].primitives[0].targets.map((t: { POSITION: number }) => {
        const a = json.accessors[t.POSITION], v = json.bufferViews[a.bufferView];
        return new Float32Array(bin.buffer.slice(bin.byteOffset + v.byteOffset + (a.byteOffset ?? 0), bin.byteOffset + v.byteOffset + (a.byteOffset ?? 0) + 12 * a.count));
      }) };
    };
    const [g, c] = bakes.map(morphs);
    expect(g.frames).toEqual([8, 16, 20]);
    expect(c.frames).toEqual(g.frames);
    // the cloth falls 0.5·g·t² by the last: the same on both, to rounding
    g.targets.forEach((t: Float32Array, k: number) => t.forEach((v, i) => expect(Math.abs(v - c.targets[k][i])).toBeLessThan(1e-4)));
    expect(Math.min(...g.targets[2].filter((_: number, i: number) => i % 3 === 1))).toBeLessThan(-0.5);
  });

  it('the installed bin runs as a process: exit codes and stdout', () => {
    const bin = new URL('../../bin/drape.js', import.meta.url).pathname;
    const ok = execFileSync(process.execPath, [bin, 'run', 'cotton-basic', '--frames', '5', '--set', 'cloth.resolution=4', '--json'], { encoding: 'utf8' });
    expect(JSON.parse(ok).particles).toBe(25);
    const bad = spawnSync(process.execPath, [bin, 'run', 'nope'], { encoding: 'utf8' });
    expect(bad.status).toBe(2);
    expect(bad.stderr.trim().split('\n')).toHaveLength(1);
    expect(bad.stderr).not.toMatch(/at .*\.js:\d+/); // no stack trace
    // a reader that stops after one line (the sweep prints a line per run as it goes): quiet, exit 0, no stack trace
    const piped = spawnSync('bash', ['-c', `set -o pipefail; "${process.execPath}" "${bin}" run resolution --frames 1 | head -1`], { encoding: 'utf8' });
    expect([piped.status, piped.stderr, piped.stdout.split('\n').length]).toEqual([0, '', 2]);
    // output that cannot be written (a full disk): one line and exit 4, not a stack trace and 1
    for (const args of [['run', 'cotton-basic', '--frames', '2', '--set', 'cloth.resolution=4', '--json'], ['scenes']]) {
      const full = spawnSync('bash', ['-c', `"${process.execPath}" "${bin}" ${args.join(' ')} > /dev/full`], { encoding: 'utf8' });
      expect([full.status, full.stderr], args.join(' ')).toEqual([4, 'drape: could not write the output to standard output (ENOSPC)\n']);
    }
  });

  it.each([
    ['/dev/zero'], ['/dev/urandom'], ['/dev/null'],
  ])('refuses %s: scene files must be regular files', async (path) => {
    // refused before anything is read: before, /dev/zero and /dev/urandom were read until memory ran out
    const r = await run('run', path, '--frames', '1');
    expect(r.code).toBe(2);
    expect(r.err).toMatch(new RegExp(`^drape: ${path}: not a regular file`));
  });

  it('refuses a symlink to a device, a FIFO, a folder and an oversized file, without reading them', async () => {
    const dir = tmp();
    symlinkSync('/dev/zero', join(dir, 'zero.json'));
    execFileSync('mkfifo', [join(dir, 'pipe.json')]);
    mkdirSync(join(dir, 'folder.json'));
    writeFileSync(join(dir, 'big.json'), Buffer.alloc(32 * 2 ** 20 + 1, 32));
    const cases: [string, RegExp][] = [
      ['zero.json', /zero\.json: not a regular file/],
      ['pipe.json', /pipe\.json: not a regular file/],
      ['folder.json', /folder\.json: is a folder, not a scene file/],
      ['big.json', /big\.json: 32 MiB, more than the 32 MiB a scene file may have/],
    ];
    for (const [name, message] of cases) {
      const r = await run('run', join(dir, name), '--frames', '1'); // a FIFO with no writer used to hang here
      expect(r.code, name).toBe(2);
      expect(r.err, name).toMatch(message);
      expect(r.err.split('\n'), name).toHaveLength(1);
    }
  });

  it.each([
    [['--frames', ''], /--frames: must be an integer in 0…1000000, got ''/],
    [['--frames', '0x10'], /got '0x10'/],
    [['--frames', '1e3'], /got '1e3'/],
    [['--frames', ' 5'], /got ' 5'/],
    [['--frames=-1'], /got '-1'/],
    // a negative number as the next argument is the option's value, not an option (parseArgs: "ambiguous")
    [['--frames', '-1'], /^drape: --frames: must be an integer in 0…1000000, got '-1'$/],
    [['--threads', '-3'], /^drape: --threads: must be an integer in 1…\d+, got '-3'$/],
    [['--frames', '-x'], /^drape: --frames: its value starts with a dash, which reads as an option; write --frames=VALUE$/],
    [['--threads', '2.0'], /--threads: must be an integer/],
  ])('counts are decimal integers: %j exits 2', async (flags, message) => {
    const r = await run('run', 'pins', ...flags);
    expect(r.code).toBe(2);
    expect(r.err).toMatch(message);
  });

  it('bench: a negative size is the option\'s value, named by its range', async () => {
    const r = await run('bench', '--sizes', '-8');
    expect(r.code).toBe(2);
    expect(r.err).toBe("drape: --sizes: must be an integer in 2…1025, got '-8'");
  });

  it('built-in names are scenes only: prototype names are unknown scenes', async () => {
    for (const name of ['__proto__', 'constructor', 'toString']) {
      const r = await run('run', name, '--frames', '1');
      expect(r.code, name).toBe(2);
      expect(r.err, name).toMatch(new RegExp(`unknown scene '${name}'`));
    }
  });

  it('a huge list index in --set is refused; absurd nesting in a file names the file', async () => {
    const r = await run('run', 'pins', '--set', 'cloth.position[100000000]=2');
    expect(r.code).toBe(2);
    expect(r.err).toMatch(/cloth\.position has 3 items, no item 100000000/);
    const file = join(tmp(), 'deep.json');
    writeFileSync(file, '{"cloth":' + '['.repeat(100_000) + ']'.repeat(100_000) + '}');
    const deep = await run('run', file);
    expect(deep.code).toBe(2);
    expect(deep.err).toMatch(/deep\.json: nested more than 32 levels deep/);
  });

  it('a bad export destination is refused before simulating', async () => {
    const dir = tmp();
    writeFileSync(join(dir, 'file'), 'x');
    const cases: [string, RegExp][] = [
      [dir + '.obj', /the folder .* does not exist|is a folder/],
      [join(dir, 'missing', 'out.obj'), /the folder .*missing does not exist/],
      [join(dir, 'file', 'out.obj'), /a folder on the path is a file|is not a folder/],
    ];
    mkdirSync(dir + '.obj');
    for (const [path, message] of cases) {
      const spy = vi.spyOn(Simulation.prototype, 'advance');
      const r = await run('run', 'pins', '--frames', '600', '--export', path);
      expect(spy, path).not.toHaveBeenCalled(); // nothing simulated
      spy.mockRestore();
      expect(r.code, path).toBe(2);
      expect(r.err, path).toMatch(message);
    }
  });

  it('an export that fails after the run still prints the results, and exits 4', async () => {
    const failing: CliIo = { writeFile: () => { throw Object.assign(new Error('disk full'), { code: 'ENOSPC' }); } };
    const path = join(tmp(), 'out.obj');
    const text = await runWith(failing, ['run', 'pins', '--frames', '5', '--set', 'cloth.resolution=4', '--export', path]);
    expect(text.code).toBe(4);
    expect(text.out).toMatch(/^scene pins: /);
    expect(text.err).toMatch(/--export: could not write .*out\.obj \(ENOSPC\); the results above are complete/);
    const json = await runWith(failing, ['run', 'pins', '--frames', '5', '--set', 'cloth.resolution=4', '--export', path, '--json']);
    expect(json.code).toBe(4);
    const j = JSON.parse(json.out);
    expect(j.finite).toBe(true);
    expect(j.exportError).toMatch(/ENOSPC/);
    expect(j.exported).toBeUndefined();
    expect(existsSync(path)).toBe(false);
  });

  it('a run that becomes non-finite exits 3 naming the frame, and exports nothing', async () => {
    const advance = Simulation.prototype.advance;
    // a cloth that blows up at frame 7: no valid scene should, so the blow-up is made by hand
    const spy = vi.spyOn(Simulation.prototype, 'advance').mockImplementation(function (this: Simulation, frames = 1) {
      for (let f = 0; f < frames; f++) {
        if (this.frame === 6) this.state.positions[4] = NaN;
        if (!advance.call(this, 1)) return false;
      }
      return true;
    });
    try {
      const path = join(tmp(), 'out.obj');
      const line = 'pins: the simulation became unstable at frame 7 of 60 (positions are no longer finite); nothing was exported';
      const text = await run('run', 'pins', '--frames', '60', '--set', 'cloth.resolution=4', '--export', path);
      expect(text.code).toBe(3);
      expect(text.out).toBe('');
      expect(text.err).toBe(`drape: ${line}`);
      const json = await run('run', 'pins', '--frames', '60', '--set', 'cloth.resolution=4', '--export', path, '--json');
      expect(json.code).toBe(3);
      expect(JSON.parse(json.out)).toEqual({
        scene: 'pins', solver: 'xpbd', backend: 'cpu', frames: 60, substeps: 20, resolution: 4, finite: false, unstableFrame: 7, error: line,
      });
      expect(json.out).not.toMatch(/NaN|null/);
      expect(existsSync(path)).toBe(false);
    } finally {
      spy.mockRestore();
    }
  });

  it('strings from a scene reach the terminal and the OBJ without control characters', async () => {
    const dir = tmp();
    const file = join(dir, 'evil.json'), obj = join(dir, 'evil.obj');
    const name = 'x\nv 9 9 9\nmtllib evil.mtl\u001b[2J\u001b]0;pwned\u0007\u202e';
    writeFileSync(file, JSON.stringify({ name, cloth: { resolution: 2 }, colliders: [] }));
    const r = await run('run', file, '--frames', '1', '--export', obj);
    expect(r.code).toBe(0);
    expect(r.out).not.toMatch(/[\u0000-\u0009\u000b-\u001f\u007f-\u009f\u202e]/);
    expect(r.out).toMatch(/^scene x\ufffdv 9 9 9\ufffdmtllib evil\.mtl\ufffd\[2J/);
    expect(r.out.split('\n')[1]).toMatch(/^  cloth /); // the name added no line
    const text = readFileSync(obj, 'utf8');
    expect(text.match(/^v /gm)).toHaveLength(9); // the name added no vertex
    // only ours, naming the .mtl beside the file: the name's stays inside the comment line
    expect(text.match(/^mtllib .*$/gm)).toEqual(['mtllib evil.mtl']);
    expect(text).not.toMatch(/[\u001b\u0007\u202e]/);
    const j = await run('run', file, '--frames', '1', '--json');
    expect(j.out).not.toMatch(/[\u0000-\u001f\u007f-\u009f\u202e]/);
    expect(JSON.parse(j.out).scene).toBe(name); // the same name, escaped in JSON
    // an unknown key with an escape in it, in an error message
    writeFileSync(file, JSON.stringify({ '\u001b[31mkey': 1 }));
    const bad = await run('run', file);
    expect(bad.code).toBe(2);
    expect(bad.err).toBe('drape: ' + file + ': \ufffd[31mkey: unknown key');
    writeFileSync(file, JSON.stringify({ 'a\nb': 1 }));
    expect((await run('run', file)).err).toBe('drape: ' + file + ': a\ufffdb: unknown key');
  });
});
