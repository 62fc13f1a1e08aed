import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { Simulation, bakeBytes, validateScene } from '../core/index.js';
import type { App } from './app.js';
import { MAX_TAKE_BYTES, Recorder, type Take } from './recorder.js';

// (the recorder asks before the page is left during a take: a window to listen on)
const listeners: ((e: { preventDefault(): void }) => void)[] = [];
beforeAll(() => { (globalThis as { window?: unknown }).window = { addEventListener: (_: string, f: (e: { preventDefault(): void }) => void) => listeners.push(f) }; });
afterAll(() => { delete (globalThis as { window?: unknown }).window; });

/** The parts of the page a Recorder uses: the driver's mirrors, the file export, the overlay and the panel. */
function page(resolution = 2) {
  const sim = new Simulation(validateScene({ name: 'take', cloth: { resolution } }), { kernel: 'ts' });
  const mirror = { sim, frame: 0, unstableAt: -1 };
  const messages: string[] = [], downloads: Take[] = [];
  let problem = '';
  const app = {
    scene: sim.scene,
    sim: { mirrors: [mirror] },
    fileExport: {
      exportProblem: () => problem,
      downloadTake: async (t: Take) => { downloads.push(t); },
      // (file-export.ts says it with a Reset button)
      refuse: (what: string, why: string) => messages.push(`${what} refused: ${why}.`),
    },
    overlay: { message: (m: string) => messages.push(m) },
    panel: { syncRecording: () => {} },
  };
  /** the driver steps `n` frames and hands the recorder the positions */
  const step = (recorder: Recorder, n = 1) => {
    sim.advance(n);
    mirror.frame += n;
    recorder.capture([mirror.frame]);
  };
  return { app: app as unknown as App, sim, mirror, messages, downloads, step, refuse: (why: string) => { problem = why; } };
}

describe('the Record button (a take of the simulation, downloaded as an animated .glb)', () => {
  it('records each new frame from the press, ignores a frame it has, and downloads what it has when stopped', () => {
    const p = page();
    const r = new Recorder(p.app);
    p.step(r, 3); // before the press: nothing
    r.toggle();
    expect(r.active).toBe(true);
    // leaving the page now asks first
    let asked = false;
    listeners.at(-1)!({ preventDefault: () => { asked = true; } });
    expect(asked).toBe(true);
    p.step(r);
    r.capture([p.mirror.frame]); // the same frame again (a second readback of it)
    p.step(r, 2);
    expect(r.frames).toBe(2);
    r.toggle();
    expect(r.active).toBe(false);
    expect(p.downloads).toHaveLength(1);
    const take = p.downloads[0];
    expect([take.name, take.start, take.frames]).toEqual(['take', 3, [4, 6]]);
    expect(take.shapes[1][0]).toEqual(p.sim.state.positions);
    // the start is the press's pose, not the cloth's start
    expect(take.first[0][1]).toBeLessThan(p.sim.model.restPositions[1]);
    expect(p.messages.at(-1)).toBe('Recording ended (stopped): 3 frames, downloading the .glb.');
  });

  it('ends, downloading what it has, when the simulation is reset, the cloth rebuilt or unstable, or the cap is reached', () => {
    const ended = (change: (p: ReturnType<typeof page>, r: Recorder) => void, why: string) => {
      const p = page();
      const r = new Recorder(p.app);
      r.toggle();
      p.step(r);
      change(p, r);
      expect(r.active).toBe(false);
      expect(p.downloads).toHaveLength(1);
      expect(p.messages.at(-1)).toMatch(new RegExp(`^Recording ended \\(${why}\\): 2 frames`));
    };
    ended((p, r) => { p.mirror.frame = 0; r.capture([0]); }, 'the simulation was reset');
    ended((p, r) => { p.sim.set('cloth.resolution', 3); p.step(r); }, 'the cloth was rebuilt');
    ended((p, r) => { p.mirror.unstableAt = 1; p.step(r); }, 'the simulation became unstable');
    ended((_, r) => r.interrupt('another backend'), 'another backend');
    const p = page();
    const r = new Recorder(p.app);
    r.cap = 3;
    r.toggle();
    for (let k = 0; k < 5; k++) p.step(r);
    expect(p.downloads[0].frames).toEqual([1, 2, 3]);
    expect(p.messages.at(-1)).toMatch(/^Recording ended \(the frame cap was reached\): 4 frames/);
  });

  it('stopped before the simulation moved, downloads nothing and says why; refused where exports are', () => {
    const p = page();
    const r = new Recorder(p.app);
    r.toggle();
    r.toggle();
    expect(p.downloads).toEqual([]);
    expect(p.messages.at(-1)).toMatch(/before the simulation moved: nothing to download/);
    p.refuse('the cloth is not finite');
    r.toggle();
    expect(r.active).toBe(false);
    expect(p.messages.at(-1)).toBe('Recording refused: the cloth is not finite.');
  });

  it('lowers the frame cap so that a take of a large cloth stays within MAX_TAKE_BYTES', () => {
    const small = new Recorder(page(2).app);
    expect(small.effectiveCap).toBe(600);
    const big = new Recorder(page(256).app);
    const n = 257 * 257;
    expect(bakeBytes(n, big.effectiveCap)).toBeLessThanOrEqual(MAX_TAKE_BYTES);
    expect(bakeBytes(n, big.effectiveCap + 1)).toBeGreaterThan(MAX_TAKE_BYTES);
    expect(big.effectiveCap).toBe(338);
  });
});
