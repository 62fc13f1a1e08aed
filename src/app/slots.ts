/**
 * The current scene turned into the cloths on screen ("slots"): replacing the scene, loading its slots into the
 * simulation, one view per slot, framing the camera, and putting things back after a refused change.
 */
import { Box3, Vector3 } from 'three/webgpu';
import { SceneError, plainText, sceneMannequin, type Scene } from '../core/index.js';
import { ClothView } from '../render/cloth-view.js';
import { fabricFor, fabricLook } from '../render/textures.js';
import type { App } from './app.js';
import { emptyBounds, frameBounds } from './framing.js';

/** The cloths on screen, made from the app's scene. */
export class Slots {
  constructor(private readonly app: App) {}

  /**
   * Replaces the scene: new cloths from their start, camera framed, panel and link updated. A scene the simulation
   * refuses (the core's SceneError: a collider cutting through the cloth where it starts, a pin inside one) throws,
   * and the page keeps what it had.
   */
  apply(scene: Scene, key: string): void {
    if (scene.cloths && scene.cloths.length > 1) {
      throw new SceneError(`scene '${plainText(scene.name, 100)}' has ${scene.cloths.length} cloths (cloths): the app shows one cloth for now; run it with drape run or the library`);
    }
    const app = this.app;
    app.interaction?.cancel();
    const before = { scene: app.scene as Scene | undefined, sceneKey: app.sceneKey, sweepIndex: app.sweep.index, capNote: app.capNote };
    app.scene = scene;
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
      this.restore();
      throw e;
    }
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
    const look = fabricLook(fabricFor(app.scene.name));
    const gpu = app.sim.kind === 'gpu';
    app.views = app.sim.mirrors.map((m) => {
      const v = new ClothView(m.sim.model, look, gpu);
      v.setView(app.view);
      app.stage.content.add(v.group);
      return v;
    });
    app.labels.make();
    app.dirty = true;
  }

  /** Rebuilds the views of slots whose cloth was rebuilt. */
  syncViews(): void {
    const app = this.app;
    let changed = false;
    app.sim.mirrors.forEach((m, k) => {
      if (app.views[k]?.model === m.sim.model) return;
      changed = true;
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

  /** which cloth, in words: 'the cloth', or 'cloth 3 (16 × 16)' when there are several */
  clothName(slot: number): string {
    const { sim } = this.app;
    const r = sim.mirrors[slot]?.sim.scene.cloth.resolution;
    return sim.mirrors.length > 1 ? `cloth ${slot + 1} (${r} × ${r})` : 'the cloth';
  }
}
