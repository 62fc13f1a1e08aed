/**
 * The current scene turned into the cloths on screen ("slots"): replacing the scene, loading its slots into the
 * simulation, one view per slot, framing the camera, and putting things back after a refused change.
 */
import { Box3, Vector3 } from 'three/webgpu';
import { SceneError, clothCount, clothEntries, clothName, fabricFor, sceneMannequin, type Scene } from '../core/index.js';
import { ClothView } from '../render/cloth-view.js';
import { fabricLook, type FabricLook } from '../render/textures.js';
import type { App } from './app.js';
import { contactDistance } from './contact-meter.js';
import { ContactBudget } from './contact-budget.js';
import { emptyBounds, frameBounds } from './framing.js';

/** The cloths on screen, made from the app's scene. */
export class Slots {
  /** the slot scene each view last took its cloths' looks from (syncViews runs every frame) */
  private lookedAt: Scene[] = [];

  constructor(private readonly app: App) {}

  /**
   * Replaces the scene: new cloths from their start, camera framed, panel and link updated. A scene the simulation
   * refuses (the core's SceneError: a collider cutting through the cloth where it starts, a pin inside one) throws,
   * and the page keeps what it had.
   */
  apply(scene: Scene, key: string): void {
    const app = this.app;
    app.interaction?.cancel();
    const before = { scene: app.scene as Scene | undefined, sceneKey: app.sceneKey, sweepIndex: app.sweep.index, capNote: app.capNote, cloth: app.cloth };
    app.scene = scene;
    // the panel goes on editing the same cloth where the new scene has it (a link or file of the same scene)
    if (app.cloth >= clothCount(scene)) app.cloth = 0;
    app.sceneKey = key;
    app.mannequin = sceneMannequin(scene, key) ?? null;
    app.sweep.index = 0;
    app.capNote = '';
    app.sweep.halted = false;
    try {
      this.load();
    } catch (e) {
      if (!(e instanceof SceneError) || !before.scene) throw e;
      app.scene = before.scene;
      app.sceneKey = before.sceneKey;
      app.mannequin = sceneMannequin(before.scene, before.sceneKey) ?? null;
      app.sweep.index = before.sweepIndex;
      app.capNote = before.capNote;
      app.cloth = before.cloth;
      this.restore();
      throw e;
    }
    // a scene loaded: its self-contact is the scene's again until chosen by hand (contact-budget.ts), and the
    // notice that the last scene's was switched off goes with that scene
    app.contactBudget.reset();
    if (ContactBudget.said(app.overlay.lastMessage)) app.overlay.clearMessage();
    // a scene loaded: whatever waited for mesh files is not what the page shows any more
    app.waiting = null;
    this.frameCamera(true);
    app.hud?.clearPlot();
    app.panel?.sync();
    app.link.schedule();
  }

  /**
   * After a refused change: the scene is the one before again. The cloths on screen still are too (loads are
   * all-or-nothing) unless the backend changed on the way, which left none: then they start again.
   */
  restore(): void {
    const app = this.app;
    if (!app.sim.mirrors.length) this.load();
    app.backend.note = app.backend.wanted().note;
    app.panel?.sync();
    app.link.schedule();
    app.dirty = true;
  }

  /** Loads the scene's slots from their start, on the backend the choice and scene ask for; throws SceneError when refused. */
  load(): void {
    const app = this.app;
    app.backend.place(false);
    app.sim.load(app.sweep.scenes());
    this.drawColliders();
    this.rebuildViews();
  }

  /** The colliders of every cloth on screen, drawn as the simulation built them (the mirrors' params). */
  drawColliders(): void {
    this.app.stage.setColliders(this.app.sim.mirrors.flatMap((m) => m.sim.params.colliders));
  }

  /** New views (and sweep labels) for the cloths the simulation has now. */
  rebuildViews(): void {
    const app = this.app;
    for (const v of app.views) { app.stage.content.remove(v.group); v.dispose(); }
    const gpu = app.sim.kind === 'gpu';
    this.lookedAt = app.sim.mirrors.map((m) => m.sim.scene);
    app.views = app.sim.mirrors.map((m) => {
      const looks = this.looks(m.sim.scene);
      const v = new ClothView(m.sim.model, clothEntries(m.sim.scene).map((entry, c) => ({ entry, name: clothName(entry, c), look: looks[c] })), gpu);
      v.setView(app.view);
      v.setContactDistance(contactDistance(m.sim));
      app.stage.content.add(v.group);
      return v;
    });
    app.labels.make();
    app.dirty = true;
  }

  /** Each cloth's look in a slot's scene: its fabric's (or the built-in scene's own: the flag, the hammock). */
  looks(scene: Scene): FabricLook[] {
    return clothEntries(scene).map((e) => fabricLook(fabricFor(this.app.scene.name, e.material.fabric)));
  }

  /** Rebuilds the views of slots whose cloth was rebuilt; the others take their cloths' looks (a fabric changed). */
  syncViews(): void {
    const app = this.app;
    let changed = false;
    app.sim.mirrors.forEach((m, k) => {
      if (app.views[k]?.model !== m.sim.model) { changed = true; return; }
      if (this.lookedAt[k] !== m.sim.scene) {
        app.views[k].setLooks(this.looks(m.sim.scene));
        app.views[k].setContactDistance(contactDistance(m.sim));
        this.lookedAt[k] = m.sim.scene;
      }
    });
    if (changed) this.rebuildViews();
  }

  /** Fits the camera's framing to the cloths and their colliders; `moveCamera`: also go to the default view. */
  frameCamera(moveCamera: boolean): void {
    const app = this.app;
    const bounds = emptyBounds();
    for (const m of app.sim.mirrors) frameBounds(m.sim.model.restPositions, m.sim.scene.colliders, m.sim.params.colliders, bounds);
    const box = new Box3(new Vector3(...bounds.min), new Vector3(...bounds.max));
    const size = box.getSize(new Vector3());
    const center = box.getCenter(new Vector3());
    center.y = Math.max(0.55, center.y - 0.1 * size.y);
    const row = app.sim.mirrors.length > 1;
    // a row of cloths is framed from the front, by its width; a single cloth from the front right
    app.stage.frame(row ? size.x * 0.72 : Math.max(size.x, size.y, size.z) * 0.75, center);
    app.stage.defaultView = row ? 'front' : 'reset';
    if (moveCamera) app.stage.setCamera(app.stage.defaultView);
  }

  /** which cloth, in words: 'the cloth', 'the cloths' (a scene of several), or 'cloth 3 (16 × 16)' of a sweep's row */
  clothName(slot: number): string {
    const { sim } = this.app;
    const scene = sim.mirrors[slot]?.sim.scene;
    if (sim.mirrors.length > 1) return `cloth ${slot + 1} (${scene?.cloth.resolution} × ${scene?.cloth.resolution})`;
    return scene && clothCount(scene) > 1 ? 'the cloths' : 'the cloth';
  }
}
