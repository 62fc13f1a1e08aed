/**
 * What the panel, the keyboard shortcuts and the pointer ask the app to do: scene changes (built-in scenes, one
 * parameter at a time, pins), play, pause, step, reset, view and camera, and the file and link buttons, which it
 * hands to their jobs. It is the panel's host and the pointer's; it reads the app's state and sends commands.
 */
import {
  SceneError, builtinScene, clothCount, clothEntries, clothModelOf, clothName, clothParticle, clothPath, editCloth, isBuiltinScene,
  pathCloth, plainText, resolvePins, setScenePath, withMannequin, type MannequinOptions, type PinEntry, type PinPreset, type Scene,
} from '../core/index.js';
import { VIEWS, VIEW_LABELS, type ViewName } from '../render/cloth-view.js';
import type { CameraPreset } from '../render/stage.js';
import type { PanelHost, SweepLayout } from '../ui/panel.js';
import type { App } from './app.js';
import type { BackendChoice } from './backend.js';
import type { InteractionHost } from './interaction.js';
import { MAX_RESOLUTION, resolutionPins } from './limits.js';
import { refusal } from './refusal.js';
import { withShape, type PanelShape } from './shape-change.js';
import { sweeps } from './sweep.js';

/** The app's commands: the panel's host (PanelHost) and the pointer's (InteractionHost). */
export class Commands implements PanelHost, InteractionHost {
  constructor(private readonly app: App) {}

  get scene() { return this.app.scene; }
  get sceneKey() { return this.app.sceneKey; }
  get paused() { return this.app.sim.paused; }
  get view() { return this.app.view; }
  get pinTool() { return this.app.pinTool; }
  get sweepLayout() { return this.app.sweep.layout; }
  get sweeping() { return sweeps(this.app.scene); }
  get backendChoice() { return this.app.backend.choice; }

  /** the cloth the panel's Cloth & material and Pins folders edit (a scene of several cloths; else 0) */
  get cloth() { return this.app.cloth; }

  /** The panel's cloth control: which cloth of the scene its Cloth & material and Pins folders edit. */
  selectCloth(k: number): void {
    const app = this.app;
    if (!Number.isInteger(k) || k < 0 || k >= clothCount(app.scene)) return;
    app.cloth = k;
    app.panel.sync();
  }

  /** the resolution of the cloth on screen: the sweep's current one when it runs one after another, else the edited cloth's */
  get shownResolution(): number {
    const { sweep, scene } = this.app;
    const list = sweep.list();
    return list.length && sweep.layout === 'sequence' ? list[sweep.index % list.length] : clothEntries(scene)[this.app.cloth].cloth.resolution;
  }
  get sim() { return this.app.sim; }
  get camera() { return this.app.stage.camera; }

  /** the scene's mannequin's pose and animation, or null when it has none */
  get mannequin(): MannequinOptions | null {
    return this.app.mannequin?.options ?? null;
  }

  /**
   * The Mannequin controls: the mannequin posed or moved anew (its colliders made again by mannequinColliders), the
   * cloth going on as it is. A pose that cuts through the cloth is refused with a message, and nothing changes.
   */
  setMannequin(change: MannequinOptions): void {
    const app = this.app, m = app.mannequin;
    if (!m) return;
    let next: Scene;
    try {
      next = withMannequin(app.scene, m, change);
    } catch (e) {
      app.overlay.message(refusal(e));
      return;
    }
    if (this.setPath('colliders', next.colliders)) {
      app.mannequin = { ...m, options: { ...m.options, ...change } };
      // the new motion has the body somewhere else now: the pins it carries would jump there in one substep and
      // fling the cloth, so the cloth starts again with the body
      this.reset();
    }
    app.panel.sync();
  }

  /** largest resolution the panel offers now */
  get maxResolution(): number {
    return MAX_RESOLUTION[this.app.sim?.kind ?? 'cpu'];
  }

  /** The panel's backend choice. */
  setBackend(choice: BackendChoice): void {
    this.app.backend.set(choice);
  }

  /** The scene dropdown: a built-in scene by name; one the simulation refuses says why and changes nothing. */
  loadBuiltin(name: string): void {
    const app = this.app;
    if (!isBuiltinScene(name)) { app.overlay.message(`unknown scene '${name}'`); return; }
    try {
      app.slots.apply(builtinScene(name), name);
    } catch (e) {
      app.overlay.message(refusal(e));
    }
  }

  /**
   * A live change of one scene path (a panel control); false, with a message, when refused, and nothing changes.
   * A cloth's field is its own path in a scene of several (`cloths[1].material.damping`). Its `cloth.shape` (the
   * Shape control) changes that cloth as shape-change.ts says (pins it cannot take dropped, with a notice; its
   * lowest point where the old cloth's was).
   */
  setPath(path: string, value: unknown): boolean {
    const app = this.app;
    const at = pathCloth(path);
    let next: Scene;
    let note = '';
    try {
      let base = app.scene;
      // particle-index pins belong to one resolution: a new resolution keeps the presets and regions
      if (at?.field === 'cloth.resolution') base = editCloth(base, at.cloth, (one) => ({ ...one, pins: resolutionPins(one.pins) }));
      if (at?.field === 'cloth.shape') {
        next = editCloth(base, at.cloth, (one) => {
          const change = withShape(one, value as PanelShape, app.meshes.resolve);
          note = change.note;
          return change.scene;
        });
      } else {
        next = setScenePath(base, path, value);
      }
    } catch (e) {
      app.overlay.message(e instanceof SceneError ? e.message.replace(/^--set /, '') : String(e));
      app.panel.sync();
      return false;
    }
    const before = { scene: app.scene, capNote: app.capNote, slots: app.sim.mirrors.map((m) => m.sim.scene) };
    try {
      this.applyPath(path, next);
    } catch (e) {
      // refused by the simulation (a collider cutting through the cloth, a pin inside one): as it was
      const why = refusal(e);
      app.scene = before.scene;
      app.capNote = before.capNote;
      if (app.sim.mirrors.length === before.slots.length) {
        before.slots.forEach((s, k) => { if (app.sim.mirrors[k].sim.scene !== s) app.sim.setScene(k, s); });
        app.slots.syncViews();
      } else {
        app.sim.mirrors.length = 0;
      }
      app.slots.restore();
      app.overlay.message(why);
      return false;
    }
    if (note && at) {
      const e = clothEntries(app.scene)[at.cloth];
      app.overlay.message(`${clothCount(app.scene) > 1 ? `${plainText(clothName(e, at.cloth), 60)}: ` : ''}${e.cloth.shape}: ${note}`, 'notice');
    }
    // self-contact set by hand stays as set: the frame budget no longer switches it (contact-budget.ts)
    if (path === 'solver.selfContact') app.contactBudget.chosen = true;
    app.dirty = true;
    app.link.schedule();
    return true;
  }

  /** setPath's change, once the new scene is valid; throws SceneError when the simulation refuses it */
  private applyPath(path: string, next: Scene): void {
    const app = this.app;
    // the path within its cloth ('cloth.resolution' of cloths[1].cloth.resolution); '' outside the cloths
    const field = pathCloth(path)?.field ?? '';
    app.scene = next;
    if (field === 'cloth.resolution' || field === 'cloth.shape' || path === 'resolutionSweep') app.capNote = '';
    const capBefore = app.capNote;
    if (app.backend.wanted().kind !== app.sim.kind) {
      app.backend.place(true);
      const capped = app.capNote !== capBefore ? app.capNote : '';
      if (app.backend.note || capped) app.overlay.message([app.backend.note, capped].filter(Boolean).join('. '), 'notice');
    } else {
      app.backend.note = app.backend.wanted().note;
      app.backend.capTo(app.sim.kind);
    }
    const scenes = app.sweep.scenes();
    if (scenes.length !== app.sim.mirrors.length) {
      app.slots.load();
    } else {
      scenes.forEach((s, k) => {
        // keep slot-local pins (pin tool on a sweep cloth) when only parameters change
        const keep = sweeps(app.scene) ? { ...s, pins: app.sim.mirrors[k].sim.scene.pins } : s;
        const derived = field.startsWith('cloth.') || field === 'material.scaleWithResolution' || field === 'pins';
        const rebuilt = app.sim.setScene(k, derived ? s : keep);
        if (rebuilt) app.interaction.cancel();
      });
      app.slots.syncViews();
      if (field === 'material.scaleWithResolution') app.labels.make();
    }
    if (field.startsWith('cloth.')) app.slots.frameCamera(false);
  }

  /** Every cloth back to its start (a sweep sequence back to its first resolution). */
  reset(): void {
    const app = this.app;
    app.interaction.cancel();
    app.recorder.interrupt('the simulation was reset');
    app.sweep.halted = false;
    if (sweeps(app.scene) && app.sweep.layout === 'sequence' && app.sweep.index !== 0) {
      app.sweep.index = 0;
      app.slots.load();
    } else {
      app.sim.reset();
    }
    app.hud.clearPlot();
    // the unstable-cloth message (and its Reset button) has done its job
    if (app.overlay.lastMessage.startsWith('The simulation became unstable')) app.overlay.clearMessage();
    app.dirty = true;
  }

  /** Play or pause. */
  togglePause(): void {
    this.app.sim.paused = !this.app.sim.paused;
    this.app.panel.updatePlay();
  }

  /** Hides or shows the HUD and the panel (H). */
  toggleLayout(): void {
    this.app.layout.toggle();
  }

  /** Shows or hides what the scene demonstrates (E, the panel's "explain this scene"). */
  toggleExplain(): void {
    this.app.layout.toggleExplain();
  }

  /** One frame forward, pausing first. */
  stepOnce(): void {
    if (!this.app.sim.paused) this.togglePause();
    void this.app.sim.step(1);
  }

  /** How the cloths are drawn (shaded, wireframe, …). */
  setView(view: ViewName): void {
    const app = this.app;
    app.view = view;
    for (const v of app.views) v.setView(view);
    app.overlay.toast(VIEW_LABELS[view]);
    app.panel.sync();
    app.dirty = true;
    app.link.schedule();
  }

  /** The next view in the list (V). */
  cycleView(): void {
    this.setView(VIEWS[(VIEWS.indexOf(this.app.view) + 1) % VIEWS.length]);
  }

  /** A camera preset (front, side, top, reset). */
  setCamera(preset: CameraPreset): void {
    this.app.stage.setCamera(preset);
  }

  /** Turns one pin preset of the edited cloth on or off. */
  setPreset(preset: PinPreset, on: boolean): void {
    const { scene, cloth } = this.app;
    const pins = clothEntries(scene)[cloth].pins.filter((p) => p !== preset);
    if (on) pins.push(preset);
    this.setPath(clothPath(scene, cloth, 'pins'), pins);
    this.app.panel.sync();
  }

  /** Unpins the edited cloth (every cloth of a sweep too). */
  clearPins(): void {
    const app = this.app;
    this.setPath(clothPath(app.scene, app.cloth, 'pins'), []);
    if (sweeps(app.scene)) app.sim.mirrors.forEach((m, k) => app.sim.setScene(k, { ...m.sim.scene, pins: [] }));
    app.panel.sync();
  }

  /** The pin tool on or off (a click on the cloth pins instead of grabbing). */
  setPinTool(on: boolean): void {
    this.app.pinTool = on;
    this.app.stage.container.classList.toggle('pin-tool', on);
    this.app.panel.sync();
  }

  /**
   * Pin tool: pins or unpins one particle (of the slot's model: in a scene of several cloths, a particle of the
   * cloth it is in, numbered from that cloth's first, in that cloth's pins); presets and regions it breaks up become
   * particle lists.
   */
  togglePin(slot: number, particle: number): void {
    const app = this.app;
    const m = app.sim.mirrors[slot];
    const scene = m.sim.scene;
    const { cloth, index } = clothParticle(m.sim.model, particle);
    const own = clothModelOf(m.sim.model, cloth), entry = clothEntries(scene)[cloth];
    const pinned = new Set(resolvePins(own, entry.pins));
    const on = !pinned.has(index);
    let pins: PinEntry[];
    if (on) {
      pins = [...entry.pins, index];
    } else {
      pins = [];
      for (const p of entry.pins) {
        if (p === index) continue;
        if (typeof p !== 'number') {
          const members = resolvePins(own, [p]);
          if (members.includes(index)) { pins.push(...members.filter((i) => i !== index)); continue; }
        }
        pins.push(p);
      }
    }
    if (sweeps(app.scene)) {
      try {
        app.sim.setScene(slot, { ...scene, pins });
      } catch (e) {
        app.overlay.message(refusal(e));
        return;
      }
    } else {
      if (!this.setPath(clothPath(scene, cloth, 'pins'), pins)) return;
      app.panel.sync();
    }
    const of = clothCount(scene) > 1 ? ` of ${plainText(clothName(entry, cloth), 60)}` : '';
    app.overlay.toast(`${on ? 'Pinned' : 'Unpinned'} particle ${index}${of}`);
    app.dirty = true;
  }

  /** The panel's sweep layout (sequence or side by side). */
  setSweepLayout(layout: SweepLayout): void {
    this.app.sweep.setLayout(layout);
  }

  /** A grab started or ended: the cursor shows it. */
  grabChanged(active: boolean): void {
    this.app.stage.container.classList.toggle('grabbing', active);
  }

  /** The `?` sheet. */
  showHelp(): void {
    this.app.overlay.help();
  }

  /** Downloads the scene as a JSON document. */
  exportJson(): void {
    this.app.fileExport.exportJson();
  }

  /** Opens the file picker for a scene document. */
  importJson(): void {
    this.app.fileImport.open();
  }

  /** Opens the file picker for a mesh file (OBJ, glTF) to make the cloth. */
  importMesh(): void {
    this.app.meshImport.open();
  }

  /** Copies the link to this scene. */
  copyLink(): void {
    this.app.link.copy();
  }

  /** Downloads a PNG of the view. */
  screenshot(size: string): void {
    this.app.fileExport.screenshot(size);
  }

  /** Downloads the cloths as OBJ. */
  exportObj(): void {
    this.app.fileExport.exportObj();
  }

  /** Downloads the cloths as binary glTF. */
  exportGltf(): void {
    this.app.fileExport.exportGltf();
  }

  /** Starts recording, or stops and downloads the recording as an animated .glb. */
  toggleRecording(): void {
    this.app.recorder.toggle();
  }

  get recording() {
    const r = this.app.recorder, cap = r.effectiveCap;
    return { active: r.active, frames: r.frames, bytes: r.bytes(), cap, capBytes: r.bytes(cap) };
  }

  setRecordCap(frames: number): void {
    this.app.recorder.cap = frames;
    this.app.panel.syncRecording();
  }
}
