import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { availableParallelism, tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { main } from './main.js';

async function run(...argv: string[]) {
  const out: string[] = [], err: string[] = [];
  const code = await main(argv, (s) => out.push(s), (s) => err.push(s));
  return { code, out: out.join('\n'), err: err.join('\n') };
}

describe('drape CLI', () => {
  it('run --json prints exactly one JSON object with the documented fields', async () => {
    const r = await run('run', 'cotton-basic', '--frames', '30', '--set', 'cloth.resolution=8', '--json');
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    for (const k of ['scene', 'solver', 'backend', 'frames', 'particles', 'triangles', 'constraints', 'msPerFrame', 'finite',
      'maxStrain', 'maxPenetration', 'centroid', 'bounds', 'energy']) expect(j, k).toHaveProperty(k);
    expect(j).toMatchObject({ scene: 'cotton-basic', solver: 'xpbd', backend: 'cpu', frames: 30, particles: 81, triangles: 128, finite: true });
    expect(j.centroid).toHaveLength(3);
    expect(Object.keys(j.energy)).toEqual(['kinetic', 'gravitational', 'elastic']);
  });

  it('--kernel and --threads choose how the CPU steps XPBD, and the JSON says what ran', async () => {
    const args = ['run', 'cotton-basic', '--frames', '10', '--set', 'cloth.resolution=8', '--json'];
    const ts = JSON.parse((await run(...args, '--kernel', 'ts')).out);
    const one = JSON.parse((await run(...args, '--kernel', 'wasm', '--threads', '1')).out);
    const auto = JSON.parse((await run(...args)).out);
    expect(ts).toMatchObject({ kernel: 'ts', threads: 1 });
    expect(one).toMatchObject({ kernel: 'wasm', threads: 1 });
    expect(auto).toMatchObject({ kernel: 'wasm', threads: Math.min(8, availableParallelism()) });
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
    const r = await run('bench', '--sizes', '9', '--frames', '2', '--warmup', '1', '--no-peer', '--json');
    expect(r.code).toBe(0);
    const j = JSON.parse(r.out);
    const row = j.rows[0];
    expect(row).toMatchObject({ particlesPerSide: 9, particles: 81 });
    expect(row.xpbd).toMatchObject({ kernel: 'wasm', finite: true, stable: true });
    expect(row.xpbd.threads).toBe(j.threads);
    expect(row.xpbd1).toMatchObject({ kernel: 'wasm', finite: true });
    for (const t of [row.xpbd, row.xpbd1, row.xpbdTs, row.massSpring]) expect(t.msPerFrame).toBeGreaterThan(0);
  });

  it('--frames 0 reports the start state; --solver and --set change the scene', async () => {
    const j = JSON.parse((await run('run', 'pins', '--frames', '0', '--solver', 'mass-spring', '--set', 'cloth.position=[0,2,0]', '--json')).out);
    expect(j).toMatchObject({ frames: 0, solver: 'mass-spring', msPerFrame: 0, maxStrain: 0 });
    expect(j.centroid[1]).toBeCloseTo(2, 5);
  });

  it('the resolution scene runs its sweep from 1 to 4096 faces', async () => {
    const j = JSON.parse((await run('run', 'resolution', '--frames', '60', '--json')).out);
    expect(j.sweep.map((s: { faces: number }) => s.faces)).toEqual([1, 4, 16, 64, 256, 1024, 4096]);
    expect(j.sweep[0].centroid[1]).toBeGreaterThan(0.6); // the 1-face cloth rests on the sphere
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
    expect(text.match(/^f /gm)).toHaveLength(32);
  });

  it.each([
    [['run', 'nope'], /unknown scene 'nope'/],
    [['run', 'missing.json'], /missing\.json: no such file/],
    [['run', '--set', 'material.bendStifness=1'], /material\.bendStifness: unknown key/],
    [['run', '--set', 'cloth.resolution=abc'], /cloth\.resolution: must be integer/],
    [['run', '--set', 'nothing'], /expected PATH=VALUE/],
    [['run', '--frames', 'ten'], /--frames: must be an integer/],
    [['run', '--bogus'], /Unknown option '--bogus'$/],
    [['run', '--export', 'x.stl'], /only \.obj/],
    [['run', '--backend', 'quantum'], /--backend: must be cpu or gpu/],
    [['run', '--backend', 'gpu', '--solver', 'mass-spring', '--frames', '1'], /only the xpbd solver runs on the GPU/],
    [['bench', '--sizes', '64,x'], /--sizes: must be an integer/],
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
    const gpu = JSON.parse((await run(...args, '--backend', 'gpu')).out);
    const cpu = JSON.parse((await run(...args)).out);
    expect(gpu).toMatchObject({ backend: 'gpu', finite: true, particles: 81 });
    gpu.centroid.forEach((c: number, k: number) => expect(Math.abs(c - cpu.centroid[k])).toBeLessThan(1e-4)); // before contact: rounding only
  });

  it('the installed bin runs as a process: exit codes and stdout', () => {
    const bin = new URL('../../bin/drape.js', import.meta.url).pathname;
    const ok = execFileSync(process.execPath, [bin, 'run', 'cotton-basic', '--frames', '5', '--set', 'cloth.resolution=4', '--json'], { encoding: 'utf8' });
    expect(JSON.parse(ok).particles).toBe(25);
    const bad = spawnSync(process.execPath, [bin, 'run', 'nope'], { encoding: 'utf8' });
    expect(bad.status).toBe(2);
    expect(bad.stderr.trim().split('\n')).toHaveLength(1);
    expect(bad.stderr).not.toMatch(/at .*\.js:\d+/); // no stack trace
  });
});
