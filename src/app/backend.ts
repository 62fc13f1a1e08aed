/**
 * The simulation backend: which one the choice (panel, link, `?backend=`), the scene and the renderer allow; the
 * driver that runs it; moving the cloths from one backend to the other; and what happens when the WebGPU device is
 * lost or a cloth blows up.
 */
import { SCENE_NAMES, SceneError, builtinScene, plainText } from '../core/index.js';
import type { App } from './app.js';
import { GpuSim } from '../three/sim/gpu-sim.js';
import { capCloth } from './limits.js';
import { refusal } from './refusal.js';
import { SimClient, type SimDriver } from '../three/sim/sim-client.js';
import { carriable, carryState, chooseBackend, type BackendChoice } from '../three/sim/backend-choice.js';

export type { BackendChoice };
/** every backend choice, as the panel and the link name them */
export const BACKEND_CHOICES: readonly BackendChoice[] = ['auto', 'gpu', 'cpu'];

/** The simulation backend of the page: the choice, where it runs now and why, and the driver behind `app.sim`. */
export class Backend {
  /** simulation backend asked for (panel, link) */
  choice: BackendChoice = 'auto';
  /** why the simulation is not where it was asked to be ('' when it is) */
  note = '';
  /** the choice came from the link or the panel (so the link keeps it), not from `?backend=` */
  inLink = false;
  /** the WebGPU device was lost: the GPU backend is gone for this page */
  private gpuLost = false;
  /** why the GPU simulation failed (its solver could not be made, a readback failed), until the GPU is chosen again */
  private gpuFailure = '';

  constructor(private readonly app: App) {}

  /** `?backend=`: the choice when the link names none (not written into the link); anything else is ignored. */
  setDefault(choice: string | null | undefined): void {
    if (choice === null || choice === undefined) return;
    if ((BACKEND_CHOICES as readonly string[]).includes(choice)) this.choice = this.defaultChoice = choice as BackendChoice;
    // as a link's bad backend is answered (url-sync.ts): named, shown as text, and the page goes on with auto
    else this.app.overlay.message(`?backend: must be one of ${BACKEND_CHOICES.join(', ')}, got '${plainText(choice, 40)}' (ignored)`, 'error');
  }
  /** the choice when the link names none: `?backend=`'s, else auto */
  defaultChoice: BackendChoice = 'auto';

  /** The renderer lost its WebGPU device and went on with WebGL2: the GPU backend is gone for this page. */
  deviceLost(): void {
    const app = this.app;
    app.dirty = true;
    this.gpuLost = true;
    // the GPU simulation lived on the lost device: go on on the CPU from the last positions read back
    if (app.sim?.kind === 'gpu') {
      this.moveToCpu('WebGPU device lost; switched to WebGL2', '');
    } else {
      this.note = this.choice === 'gpu' ? 'GPU unavailable: the WebGPU device was lost' : '';
      app.panel?.sync();
    }
  }

  /**
   * The GPU simulation failed (GpuSim's onError: a solver that could not be made, a readback that failed): the
   * cloths go on on the CPU from the last positions read back, and the page says why. Choosing the GPU in the panel
   * tries it again.
   */
  private gpuFailed(message: string): void {
    this.app.dirty = true;
    this.gpuFailure = message;
    this.moveToCpu(message, '; choose GPU to try it again');
    this.app.panel?.sync();
  }

  /**
   * The GPU simulation cannot go on (`cause`, said first): the cloths go on on the CPU from the last positions read
   * back — a cloth the CPU's size cap clamps restarts smaller, one it cannot take at all gives way to the default
   * scene — and the page says which; `tail` ends the notice.
   */
  private moveToCpu(cause: string, tail: string): void {
    const app = this.app;
    const frame = app.sim.mirrors[0]?.frame ?? 0;
    const capBefore = app.capNote;
    try {
      this.place(true);
    } catch (e) {
      // a cloth the CPU cannot take and cannot clamp (a mesh file of more particles than its cap)
      if (!(e instanceof SceneError)) throw e;
      this.toDefault();
      app.overlay.message(`${cause}. The CPU cannot take this cloth (${e.message}): showing the default scene instead.`);
      return;
    }
    app.overlay.message(app.capNote !== capBefore
      ? `${cause}. The simulation moves to the CPU, which takes a smaller cloth (${app.capNote}): it restarts${tail}.`
      : `${cause}. The simulation continues on the CPU from the last positions read back from the GPU (frame ${frame})${tail}.`,
    'notice');
  }

  /** The backend the current scene and renderer allow for the choice, and why if it differs from the choice. */
  wanted(): { kind: 'cpu' | 'gpu'; note: string } {
    const { stage, scene } = this.app;
    const missing = this.gpuLost ? 'the WebGPU device was lost'
      : stage.backend !== 'webgpu' || !stage.device ? 'no WebGPU adapter (WebGL2)'
        : this.gpuFailure ? `the GPU simulation failed (${this.gpuFailure})` : null;
    return chooseBackend(this.choice, scene, { missing, software: stage.softwareAdapter }, { override: 'choose GPU to use it anyway', explainAuto: false });
  }

  private makeDriver(kind: 'cpu' | 'gpu'): SimDriver {
    const app = this.app;
    const d: SimDriver = kind === 'gpu' && app.stage.device ? new GpuSim(app.stage.device, app.meshes) : new SimClient(app.meshes);
    d.onFrame = () => { app.dirty = true; };
    d.onPositions = (frames) => app.recorder.capture(frames);
    // a GPU that fails goes on on the CPU, as a DrapeWorld does (world.ts fallBack); the worker's errors are said
    d.onError = (m) => {
      if (d.kind === 'gpu' && app.sim === d) this.gpuFailed(m);
      else app.overlay.message(m, 'error');
    };
    d.onUnstable = (slot, frame) => this.onUnstable(slot, frame);
    return d;
  }

  /**
   * A cloth's positions stopped being finite numbers (a blown-up solve): the driver has stopped stepping it and
   * keeps its last finite shape on screen. Say what happened and offer Reset.
   */
  private onUnstable(slot: number, frame: number): void {
    const app = this.app;
    app.dirty = true;
    app.overlay.message(
      `The simulation became unstable at frame ${frame} (${app.slots.clothName(slot)}: positions no longer finite numbers) and is ` +
      'stopped, showing the last finite shape. Reset to start again; more substeps or a softer material may help.',
      'error', { label: 'Reset', run: () => app.commands.reset() });
  }

  /** The default scene from its start, on the backend the choice asks for (after a scene that cannot go on). */
  private toDefault(): void {
    const app = this.app;
    app.scene = builtinScene(SCENE_NAMES[0]);
    app.sceneKey = SCENE_NAMES[0];
    app.capNote = '';
    app.sweep.index = 0;
    app.slots.load();
    app.slots.frameCamera(true);
    app.hud?.clearPlot();
    app.panel?.sync();
    app.link.schedule();
  }

  /**
   * Puts the simulation on the backend the choice and scene ask for. `keep`: the cloths go on from where they are
   * (positions, and velocities where the old backend has them) instead of restarting. Returns whether the driver
   * changed. A cloth the backend cannot take (a mesh file over its cap) throws SceneError before anything changes.
   */
  place(keep: boolean): boolean {
    const app = this.app;
    const { kind, note } = this.wanted();
    this.note = note;
    this.capTo(kind);
    const old = app.sim as SimDriver | undefined;
    if (old && old.kind === kind && !(old instanceof GpuSim && old.lost)) return false;
    app.interaction?.cancel();
    const paused = old?.paused ?? false;
    const oldMirrors = old ? old.mirrors.slice() : [];
    old?.dispose();
    app.sim = this.makeDriver(kind);
    app.sim.paused = paused;
    if (!keep || !old) return true;
    try {
      app.sim.load(app.sweep.scenes());
    } catch (e) {
      // accepted before, so only a clamp (a smaller cloth under the same colliders) can make it refused here
      app.overlay.message(`${refusal(e)} — showing the default scene instead`);
      app.scene = builtinScene(SCENE_NAMES[0]);
      app.sceneKey = SCENE_NAMES[0];
      app.capNote = '';
      app.sweep.index = 0;
      app.sim.load(app.sweep.scenes());
      oldMirrors.length = 0;
      app.slots.frameCamera(true);
      app.link.schedule();
    }
    app.sim.mirrors.forEach((m, k) => {
      const from = oldMirrors[k];
      if (carriable(from, m)) carryState(app.sim, k, from.sim.state, from.frame);
    });
    app.slots.drawColliders();
    app.slots.rebuildViews();
    app.hud?.clearPlot();
    app.panel?.sync();
    return true;
  }

  /**
   * Clamps the scene to what the backend takes (README: CPU 256 faces per side, GPU 1024; a disc or tube as many
   * particles) and says so: a link, a file or a backend switch never builds a cloth that would freeze the page.
   * Returns the note when it clamped. A mesh file over the cap (or not imported) throws SceneError, and nothing
   * changes.
   */
  capTo(kind: 'cpu' | 'gpu'): string {
    const app = this.app;
    const { scene, note } = capCloth(app.scene, kind, (path) => app.meshes.particles(path));
    if (!note) return '';
    app.scene = scene;
    app.capNote = note;
    app.overlay.message(note, 'notice');
    app.panel?.sync();
    app.link.schedule();
    return note;
  }

  /** The panel's backend choice: moves the cloths to that backend when it changes where they run. */
  set(choice: BackendChoice): void {
    const app = this.app;
    const before = { choice: this.choice, inLink: this.inLink, note: this.note, gpuFailure: this.gpuFailure };
    // the GPU chosen by hand is tried again after a failure
    if (choice === 'gpu') this.gpuFailure = '';
    this.choice = choice;
    this.inLink = true;
    const sweepBefore = app.sweep.list().length;
    const kindBefore = app.sim.kind;
    const capBefore = app.capNote;
    this.note = this.wanted().note;
    if (this.wanted().kind !== kindBefore) {
      try {
        this.place(true);
      } catch (e) {
        // the other backend cannot take this cloth (a mesh file over its cap): stay, and say why
        if (!(e instanceof SceneError)) throw e;
        Object.assign(this, before);
        app.panel.sync();
        app.overlay.message(`backend not changed: ${e.message}`);
        return;
      }
      if (app.sweep.list().length !== sweepBefore) { app.sweep.index = 0; app.slots.load(); app.slots.frameCamera(true); }
    }
    const capped = app.capNote !== capBefore ? app.capNote : '';
    if (this.note || capped) app.overlay.message([this.note, capped].filter(Boolean).join('. '), 'notice');
    app.panel.sync();
    app.link.schedule();
    app.dirty = true;
  }
}
