/**
 * Recording a span of the simulation as an animated .glb (the panel's Record button): from the press, every frame
 * whose positions reach the page (each worker answer; on the GPU each readback, every frame while recording) is
 * copied, until Record is pressed again, the frame cap is reached, or the cloths change under it (a reset, a rebuilt
 * cloth, a cloth that blew up, another backend). A take that ends is always downloaded, whatever ended it, and
 * leaving the page while one is going asks first: nothing recorded is lost.
 * The file is the core's writer's (mesh/glb.ts) through FileExport.
 */
import { bakeBytes, type ClothModel, type Scene } from '../core/index.js';
import type { App } from './app.js';

/**
 * Most bytes a take's animation may have (bakeBytes: its part of the file, written at the end beside the take's own
 * copies, half as big): the cap is lowered to fit (a 257² cloth: 338 frames).
 */
export const MAX_TAKE_BYTES = 512 * 2 ** 20;

/** What a take holds: each slot's cloths as they were at the start, and a copy of every frame recorded. */
export interface Take {
  /** the scene's name at the press (the file's) */
  readonly name: string;
  readonly scenes: readonly Scene[];
  readonly models: readonly ClothModel[];
  /** each slot's positions at the press */
  readonly first: readonly Float32Array[];
  /** the simulation frame of `first` */
  readonly start: number;
  /** per frame recorded after the first, each slot's positions */
  readonly shapes: Float32Array[][];
  /** the simulation frame of each */
  readonly frames: number[];
}

export class Recorder {
  /** the most frames a take records after its first (the panel's frame cap) */
  cap = 600;
  private take: Take | null = null;

  constructor(private readonly app: App) {
    // leaving the page while recording asks first (the take is downloaded only when it ends)
    window.addEventListener('beforeunload', (e) => { if (this.take) e.preventDefault(); });
  }

  get active(): boolean {
    return this.take !== null;
  }

  /** frames recorded after the first */
  get frames(): number {
    return this.take?.frames.length ?? 0;
  }

  /** particles of the cloths on screen (or of the take) */
  private particles(): number {
    const models = this.take?.models ?? this.app.sim.mirrors.map((m) => m.sim.model);
    return models.reduce((n, m) => n + m.particleCount, 0);
  }

  /** the cap, lowered so that a take of the cloths on screen stays within MAX_TAKE_BYTES */
  get effectiveCap(): number {
    const n = this.particles();
    if (bakeBytes(n, this.cap) <= MAX_TAKE_BYTES) return this.cap;
    // the most frames that fit (bakeBytes grows with the frames)
    let lo = 1, hi = this.cap;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (bakeBytes(n, mid) <= MAX_TAKE_BYTES) lo = mid; else hi = mid;
    }
    return lo;
  }

  /** the animation's bytes for `frames` frames of the cloths on screen (or the take's) */
  bytes(frames = this.frames): number {
    return bakeBytes(this.particles(), frames);
  }

  /** Starts a take, or ends the one going (and downloads it). */
  toggle(): void {
    if (this.take) this.finish('stopped');
    else this.start();
  }

  private start(): void {
    const app = this.app;
    const problem = app.fileExport.exportProblem();
    if (problem) { app.fileExport.refuse('Recording', problem); return; }
    const mirrors = app.sim.mirrors;
    this.take = {
      name: app.scene.name, scenes: mirrors.map((m) => m.sim.scene), models: mirrors.map((m) => m.sim.model),
      first: mirrors.map((m) => m.sim.state.positions.slice()), start: mirrors[0]?.frame ?? 0, shapes: [], frames: [],
    };
    app.overlay.message(`Recording: up to ${this.effectiveCap} frames (${(this.bytes(this.effectiveCap) / 1e6).toFixed(1)} MB); press Record again to stop and download.`, 'notice');
    app.panel.syncRecording();
  }

  /** Ends the take going, if any, and downloads it: the cloths are about to change (`why`: what changes them). */
  interrupt(why: string): void {
    if (this.take) this.finish(why);
  }

  /** New positions in the mirrors (SimDriver.onPositions): `frames[k]` is the frame mirror k's are of. */
  capture(frames: readonly number[]): void {
    const take = this.take;
    if (!take) return;
    const mirrors = this.app.sim.mirrors;
    if (mirrors.length !== take.models.length || mirrors.some((m, k) => m.sim.model !== take.models[k])) { this.finish('the cloth was rebuilt'); return; }
    if (mirrors.some((m) => m.unstableAt >= 0)) { this.finish('the simulation became unstable'); return; }
    const last = take.frames.length ? take.frames[take.frames.length - 1] : take.start;
    const frame = frames[0];
    if (frames.some((f) => f !== frame) || frame < last) { this.finish('the simulation was reset'); return; }
    if (frame === last) return;
    take.shapes.push(mirrors.map((m) => m.sim.state.positions.slice()));
    take.frames.push(frame);
    if (take.frames.length >= this.effectiveCap) this.finish('the frame cap was reached');
    else this.app.panel.syncRecording();
  }

  private finish(why: string): void {
    const take = this.take!;
    this.take = null;
    this.app.panel.syncRecording();
    if (!take.frames.length) {
      this.app.overlay.message(`Recording ended (${why}) before the simulation moved: nothing to download. Press Play while recording.`, 'notice');
      return;
    }
    this.app.overlay.message(`Recording ended (${why}): ${take.frames.length + 1} frames, downloading the .glb.`, 'notice');
    void this.app.fileExport.downloadTake(take);
  }
}
