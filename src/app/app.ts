/**
 * The app: owns the current scene (what a link or an exported file reproduces), turns it into the cloths on screen
 * ("slots"), and connects the panel, the keyboard, the pointer, the HUD and the renderer to the simulation worker.
 * It holds no physics: everything it knows about the cloth comes from the core's model and the worker's frames.
 */
import { Box3, Group, Mesh, MeshStandardMaterial, BufferGeometry, BufferAttribute, DoubleSide, Vector3 } from 'three/webgpu';
import {
  SCENE_NAMES, SceneError, builtinScene, isBuiltinScene, parseScene, plainText, resolvePins, setScenePath, type PinPreset,
  type Scene,
} from '../core/index.js';
import { ClothView, VIEWS, VIEW_LABELS, type ViewName } from '../render/cloth-view.js';
import { Stage, type CameraPreset } from '../render/stage.js';
import { fabricFor, fabricLook } from '../render/textures.js';
import { append, h } from '../ui/dom.js';
import { Hud } from '../ui/hud.js';
import { Overlay } from '../ui/overlay.js';
import { CORNER_PINS, Panel, SCENE_LABELS, type PanelHost, type SweepLayout } from '../ui/panel.js';
import { GpuSim } from './gpu-sim.js';
import { Interaction, type InteractionHost } from './interaction.js';
import { MAX_RESOLUTION, capResolution, fitSideBySide, importSizeProblem } from './limits.js';
import { SimClient, type SimDriver } from './sim-client.js';
import { decodeHash, encodeHash } from './url-state.js';

/** frames each resolution runs for in the Mesh Resolution sequence (3 s) */
export const SWEEP_STAGE_FRAMES = 180;
/** spacing of cloths laid side by side [m] */
const SIDE_BY_SIDE_SPACING = 1.6;
/** the Mesh Resolution scene on the GPU goes on past the CPU's 64 faces per side */
export const GPU_SWEEP_EXTRA = [128, 256, 512, 1024];

/** the panel's and the link's backend choice; auto = the GPU when there is a hardware WebGPU device and the scene allows */
export type BackendChoice = 'auto' | 'gpu' | 'cpu';
export const BACKEND_CHOICES: readonly BackendChoice[] = ['auto', 'gpu', 'cpu'];

export interface AppOptions {
  forceWebGL?: boolean;
  lite?: boolean;
  /** `?backend=`: the backend choice when the link does not name one (not written into the link) */
  backend?: string | null;
}

/** The core's one-line refusal of a scene (SceneError); anything else is a bug, thrown on. */
function refusal(e: unknown): string {
  if (e instanceof SceneError) return e.message.replace(/^--set /, '');
  throw e;
}

export class App implements PanelHost, InteractionHost {
  scene!: Scene;
  sceneKey = 'cotton-basic';
  view: ViewName = 'shaded';
  pinTool = false;
  sweepLayout: SweepLayout = 'sequence';
  /** which resolution of the sweep is showing (sequence layout) */
  sweepIndex = 0;
  sim!: SimDriver;
  /** simulation backend asked for (panel, link) */
  backendChoice: BackendChoice = 'auto';
  /** why the simulation is not where it was asked to be ('' when it is) */
  backendNote = '';
  /** the Mesh Resolution sequence met a resolution the simulation refuses: it stays where it is until a reset */
  private sweepHalted = false;
  /** what the backend's size cap changed in the scene ('' when nothing): shown in the HUD until the next scene */
  capNote = '';
  /** the choice came from the link or the panel (so the link keeps it), not from `?backend=` */
  private backendInLink = false;
  /** the WebGPU device was lost: the GPU backend is gone for this page */
  private gpuLost = false;
  readonly stage: Stage;
  readonly overlay: Overlay;
  readonly hud: Hud;
  readonly panel: Panel;
  readonly interaction: Interaction;
  views: ClothView[] = [];
  private labels: HTMLElement[] = [];
  private fileInput: HTMLInputElement;
  private lastTime = 0;
  private fpsFrames = 0;
  private fpsTime = 0;
  fps = 0;
  /** nothing was drawn in the last half second (paused and untouched) */
  idle = false;
  private hudTime = 0;
  private plotTime = 0;
  private dirty = true;
  private hashTimer = 0;
  /** performance.now() when the first frame was drawn */
  firstFrameAt = 0;
  private firstFrameResolve!: () => void;
  readonly firstFrame = new Promise<void>((r) => { this.firstFrameResolve = r; });

  get camera() { return this.stage.camera; }
  get paused() { return this.sim.paused; }

  private constructor(readonly root: HTMLElement, stage: Stage, options: AppOptions = {}) {
    this.stage = stage;
    this.overlay = new Overlay(root);
    this.hud = new Hud(root);
    this.interaction = new Interaction(stage.container, this);

    // start from the link, or the first built-in scene; a bad link says why and falls back
    let start: { scene: Scene; base: string; view: Record<string, string | undefined> } | null = null;
    try {
      start = decodeHash(location.hash);
    } catch (e) {
      this.overlay.message(`${(e as Error).message} — showing the default scene instead`, 'error');
    }
    if (options.backend && (BACKEND_CHOICES as readonly string[]).includes(options.backend)) {
      this.backendChoice = options.backend as BackendChoice;
    }
    if (start?.view.backend && (BACKEND_CHOICES as readonly string[]).includes(start.view.backend)) {
      this.backendChoice = start.view.backend as BackendChoice;
      this.backendInLink = true;
    }
    if (start) {
      if (start.view.sweep === 'side-by-side' || start.view.sweep === 'sequence') this.sweepLayout = start.view.sweep;
      if (start.view.view && (VIEWS as readonly string[]).includes(start.view.view)) this.view = start.view.view as ViewName;
      try {
        this.applyScene(start.scene, start.base && start.base === start.scene.name ? start.base : SCENE_NAMES.includes(start.base) ? start.base : '');
      } catch (e) {
        // a scene the simulation refuses (a collider cutting through the cloth, …)
        this.overlay.message(`link: ${refusal(e)} — showing the default scene instead`, 'error');
        start = null;
      }
    }
    if (!start) this.applyScene(builtinScene(SCENE_NAMES[0]), SCENE_NAMES[0]);
    this.panel = new Panel(this);

    this.fileInput = document.createElement('input');
    this.fileInput.type = 'file';
    this.fileInput.accept = '.json,application/json';
    this.fileInput.hidden = true;
    this.fileInput.dataset.testid = 'import-file';
    this.fileInput.addEventListener('change', () => void this.readImport());
    root.append(this.fileInput);

    // capture phase: lil-gui stops key events from its controls, and shortcuts should work while one has focus
    window.addEventListener('keydown', this.onKey, { capture: true });
    const fit = () => {
      this.stage.insetRight = this.panel.gui.domElement.getBoundingClientRect().width;
      this.stage.resize();
    };
    fit();
    window.addEventListener('resize', fit);
    window.addEventListener('hashchange', () => this.onHashChange());
    new ResizeObserver(() => this.stage.resize()).observe(stage.container);
    requestAnimationFrame(this.loop);
  }

  static async create(root: HTMLElement, viewport: HTMLElement, options: AppOptions = {}): Promise<App> {
    let app: App | null = null;
    const stage = await Stage.create(viewport, {
      forceWebGL: options.forceWebGL,
      lite: options.lite,
      onFallback: (reason) => {
        app?.overlay.message(`WebGPU device lost (${reason}); switched to WebGL2.`, 'notice');
        app?.afterRendererSwitch();
      },
      onFallbackFailed: (message) => app?.overlay.message(`WebGPU device lost: ${message}. Reload the page to try again.`),
    });
    app = new App(root, stage, options);
    return app;
  }

  private afterRendererSwitch(): void {
    this.dirty = true;
    // the GPU simulation lived on the lost device: go on on the CPU from the last positions read back
    if (this.sim?.kind === 'gpu') {
      const frame = this.sim.mirrors[0]?.frame ?? 0;
      this.gpuLost = true;
      const capBefore = this.capNote;
      this.switchBackend(true);
      this.overlay.message(this.capNote !== capBefore
        ? `WebGPU device lost; switched to WebGL2. The simulation moves to the CPU, which takes a smaller cloth (${this.capNote}): it restarts.`
        : `WebGPU device lost; switched to WebGL2. The simulation continues on the CPU from the last positions read back from the GPU (frame ${frame}).`,
      'notice');
    } else {
      this.gpuLost = true;
      this.backendNote = this.backendChoice === 'gpu' ? 'GPU unavailable: the WebGPU device was lost' : '';
      this.panel?.sync();
    }
  }

  // ---------------------------------------------------------------- simulation backend

  /** the backend the current scene and renderer allow for the choice, and why if it differs from the choice */
  private wantedBackend(): { kind: 'cpu' | 'gpu'; note: string } {
    if (this.backendChoice === 'cpu') return { kind: 'cpu', note: '' };
    const why = this.gpuLost ? 'the WebGPU device was lost'
      : this.stage.backend !== 'webgpu' || !this.stage.device ? 'no WebGPU adapter (WebGL2)'
      : GpuSim.supports(this.scene);
    if (why) return { kind: 'cpu', note: this.backendChoice === 'gpu' || this.scene.solver.type !== 'xpbd' ? `GPU unavailable: ${why}` : '' };
    if (this.backendChoice === 'auto' && this.stage.softwareAdapter) {
      return { kind: 'cpu', note: 'auto: the WebGPU adapter is a software fallback, slower than the CPU worker; choose GPU to use it anyway' };
    }
    return { kind: 'gpu', note: '' };
  }

  private makeDriver(kind: 'cpu' | 'gpu'): SimDriver {
    const d: SimDriver = kind === 'gpu' && this.stage.device ? new GpuSim(this.stage.device) : new SimClient();
    d.onFrame = () => { this.dirty = true; };
    d.onError = (m) => this.overlay.message(m, 'error');
    d.onUnstable = (slot, frame) => this.onUnstable(slot, frame);
    return d;
  }

  /** which cloth, in words: 'the cloth', or 'cloth 3 (16 × 16)' when there are several */
  private clothName(slot: number): string {
    const r = this.sim.mirrors[slot]?.sim.scene.cloth.resolution;
    return this.sim.mirrors.length > 1 ? `cloth ${slot + 1} (${r} × ${r})` : 'the cloth';
  }

  /**
   * A cloth's positions stopped being finite numbers (a blown-up solve): the driver has stopped stepping it and
   * keeps its last finite shape on screen. Say what happened and offer Reset.
   */
  private onUnstable(slot: number, frame: number): void {
    this.dirty = true;
    this.overlay.message(
      `The simulation became unstable at frame ${frame} (${this.clothName(slot)}: positions no longer finite numbers) and is ` +
      'stopped, showing the last finite shape. Reset to start again; more substeps or a softer material may help.',
      'error', { label: 'Reset', run: () => this.reset() });
  }

  /** why the cloths cannot be exported now ('' when they can): never a file with NaN in it */
  private exportProblem(): string {
    for (const [k, m] of this.sim.mirrors.entries()) {
      if (m.unstableAt >= 0) return `${this.clothName(k)} became unstable at frame ${m.unstableAt}; reset it first`;
      const x = m.sim.state.positions;
      for (let i = 0; i < x.length; i++) if (!Number.isFinite(x[i])) return `${this.clothName(k)} has positions that are not finite; reset it first`;
    }
    return '';
  }

  /**
   * Puts the simulation on the backend the choice and scene ask for. `keep`: the cloths go on from where they are
   * (positions, and velocities where the old backend has them) instead of restarting.
   */
  private switchBackend(keep: boolean): boolean {
    const { kind, note } = this.wantedBackend();
    this.backendNote = note;
    this.capToBackend(kind);
    const old = this.sim as SimDriver | undefined;
    if (old && old.kind === kind && !(old instanceof GpuSim && old.lost)) return false;
    this.interaction?.cancel();
    const paused = old?.paused ?? false;
    const oldMirrors = old ? old.mirrors.slice() : [];
    old?.dispose();
    this.sim = this.makeDriver(kind);
    this.sim.paused = paused;
    if (!keep || !old) return true;
    let scenes = this.slotScenes();
    try {
      this.sim.load(scenes);
    } catch (e) {
      // accepted before, so only a clamp (a smaller cloth under the same colliders) can make it refused here
      this.overlay.message(`${refusal(e)} — showing the default scene instead`);
      this.scene = builtinScene(SCENE_NAMES[0]);
      this.sceneKey = SCENE_NAMES[0];
      this.capNote = '';
      this.sweepIndex = 0;
      scenes = this.slotScenes();
      this.sim.load(scenes);
      oldMirrors.length = 0;
      this.frameCamera(true);
      this.scheduleHash();
    }
    this.sim.mirrors.forEach((m, k) => {
      const from = oldMirrors[k];
      if (!from || from.sim.model.particleCount !== m.sim.model.particleCount) return;
      const st = from.sim.state;
      if (this.sim instanceof SimClient) {
        this.sim.setState(k, st, from.frame);
      } else if (this.sim instanceof GpuSim) {
        // the worker's mirrors carry positions only: the cloth goes on from there at rest
        m.sim.state.positions.set(st.positions);
        m.sim.state.previousPositions.set(st.positions);
        m.sim.state.velocities.fill(0);
        this.sim.upload(k, from.frame);
      }
    });
    const all = scenes.flatMap((s) => s.colliders);
    this.stage.setColliders(all);
    this.rebuildViews();
    this.hud?.clearPlot();
    this.panel?.sync();
    return true;
  }

  /**
   * Clamps the scene to what the backend takes (README: CPU 256 faces per side, GPU 1024) and says so: a link, a
   * file or a backend switch never builds a cloth that would freeze the page. Returns the note when it clamped.
   */
  private capToBackend(kind: 'cpu' | 'gpu'): string {
    const { scene, note } = capResolution(this.scene, kind);
    if (!note) return '';
    this.scene = scene;
    this.capNote = note;
    this.overlay.message(note, 'notice');
    this.panel?.sync();
    this.scheduleHash();
    return note;
  }

  setBackend(choice: BackendChoice): void {
    this.backendChoice = choice;
    this.backendInLink = true;
    const sweepBefore = this.sweepList().length;
    const kindBefore = this.sim.kind;
    const capBefore = this.capNote;
    this.backendNote = this.wantedBackend().note;
    if (this.wantedBackend().kind !== kindBefore) {
      this.switchBackend(true);
      if (this.sweepList().length !== sweepBefore) { this.sweepIndex = 0; this.loadSlots(); this.frameCamera(true); }
    }
    const capped = this.capNote !== capBefore ? this.capNote : '';
    if (this.backendNote || capped) this.overlay.message([this.backendNote, capped].filter(Boolean).join('. '), 'notice');
    this.panel.sync();
    this.scheduleHash();
    this.dirty = true;
  }

  /**
   * Resolutions of a sweep scene; on the GPU the built-in Mesh Resolution scene, one after another, goes on to
   * 1024 faces per side (side by side keeps the scene's own list: a row of eleven cloths up to 1025² is too much).
   */
  sweepList(): number[] {
    const sweep = this.scene.resolutionSweep ?? [];
    // side by side: as many cloths as the backend simulates at once (see limits.ts)
    if (sweep.length && this.sweepLayout === 'side-by-side') return fitSideBySide(sweep, this.sim?.kind ?? 'cpu').list;
    if (!sweep.length || this.sim?.kind !== 'gpu' || this.sweepLayout !== 'sequence') return sweep;
    const builtin = builtinScene('resolution').resolutionSweep ?? [];
    if (JSON.stringify(builtin) !== JSON.stringify(sweep)) return sweep;
    return [...sweep, ...GPU_SWEEP_EXTRA.filter((r) => r > Math.max(...sweep))];
  }

  /** largest resolution the panel offers now */
  get maxResolution(): number {
    return MAX_RESOLUTION[this.sim?.kind ?? 'cpu'];
  }

  // ---------------------------------------------------------------- scenes and slots

  /** The scenes of the cloths on screen: one, or one per resolution of a sweep. */
  private slotScenes(): Scene[] {
    const s = this.scene;
    const sweep = this.sweepList();
    if (!sweep.length) return [s];
    const at = (res: number, dx: number): Scene => {
      const next = structuredClone(s);
      delete next.resolutionSweep;
      next.cloth.resolution = res;
      next.cloth.position = [s.cloth.position[0] + dx, s.cloth.position[1], s.cloth.position[2]];
      next.colliders = s.colliders.map((c) => (c.type === 'sphere' ? { ...c, center: [c.center[0] + dx, c.center[1], c.center[2]] } : c));
      next.pins = s.pins.filter((p) => typeof p === 'string');
      return next;
    };
    if (this.sweepLayout === 'sequence') return [at(sweep[this.sweepIndex % sweep.length], 0)];
    return sweep.map((r, k) => at(r, (k - (sweep.length - 1) / 2) * SIDE_BY_SIDE_SPACING));
  }

  /**
   * Replaces the scene: new cloths from their start, camera framed, panel and link updated. A scene the simulation
   * refuses (the core's SceneError: a collider cutting through the cloth where it starts, a pin inside one) throws,
   * and the page keeps what it had.
   */
  private applyScene(scene: Scene, key: string): void {
    this.interaction?.cancel();
    const before = { scene: this.scene as Scene | undefined, sceneKey: this.sceneKey, sweepIndex: this.sweepIndex, capNote: this.capNote };
    this.scene = scene;
    this.sceneKey = key;
    this.sweepIndex = 0;
    this.capNote = '';
    this.sweepHalted = false;
    try {
      this.loadSlots();
    } catch (e) {
      if (!(e instanceof SceneError) || !before.scene) throw e;
      this.scene = before.scene;
      this.sceneKey = before.sceneKey;
      this.sweepIndex = before.sweepIndex;
      this.capNote = before.capNote;
      this.restoreSlots();
      throw e;
    }
    this.frameCamera(true);
    this.hud?.clearPlot();
    this.panel?.sync();
    this.scheduleHash();
  }

  /**
   * After a refused change: the scene is the one before again. The cloths on screen still are too (loads are
   * all-or-nothing) unless the backend changed on the way, which left none: then they start again.
   */
  private restoreSlots(): void {
    if (!this.sim.mirrors.length) this.loadSlots();
    this.backendNote = this.wantedBackend().note;
    this.panel?.sync();
    this.scheduleHash();
    this.dirty = true;
  }

  private loadSlots(): void {
    this.switchBackend(false);
    const scenes = this.slotScenes();
    this.sim.load(scenes);
    const all = scenes.flatMap((s) => s.colliders);
    this.stage.setColliders(all);
    this.rebuildViews();
  }

  private rebuildViews(): void {
    for (const v of this.views) { this.stage.content.remove(v.group); v.dispose(); }
    const look = fabricLook(fabricFor(this.scene.name));
    const gpu = this.sim.kind === 'gpu';
    this.views = this.sim.mirrors.map((m) => {
      const v = new ClothView(m.sim.model, look, gpu);
      v.setView(this.view);
      this.stage.content.add(v.group);
      return v;
    });
    this.makeLabels();
    this.dirty = true;
  }

  private frameCamera(moveCamera: boolean): void {
    const box = new Box3();
    for (const m of this.sim.mirrors) {
      const x = m.sim.model.restPositions;
      for (let i = 0; i < x.length; i += 3) box.expandByPoint(new Vector3(x[i], x[i + 1], x[i + 2]));
      for (const c of m.sim.scene.colliders) {
        if (c.type === 'sphere') {
          box.expandByPoint(new Vector3(c.center[0] - c.radius, c.center[1] - c.radius, c.center[2] - c.radius));
          box.expandByPoint(new Vector3(c.center[0] + c.radius, c.center[1] + c.radius, c.center[2] + c.radius));
        }
      }
    }
    const size = box.getSize(new Vector3());
    const center = box.getCenter(new Vector3());
    center.y = Math.max(0.55, center.y - 0.1 * size.y);
    const row = this.sim.mirrors.length > 1;
    // a row of cloths is framed from the front, by its width; a single cloth from the front right
    this.stage.frame(row ? size.x * 0.72 : Math.max(size.x, size.y, size.z) * 0.75, center);
    this.stage.defaultView = row ? 'front' : 'reset';
    if (moveCamera) this.stage.setCamera(this.stage.defaultView);
  }

  private makeLabels(): void {
    for (const l of this.labels) l.remove();
    this.labels = [];
    if (!this.scene.resolutionSweep?.length) return;
    this.sim.mirrors.forEach((m) => {
      const l = document.createElement('div');
      l.className = 'drape-label';
      l.dataset.testid = 'sweep-label';
      const r = m.sim.scene.cloth.resolution;
      const faces = r * r;
      const total = this.sweepList().length;
      const scaling = this.scene.material.scaleWithResolution ? 'scaled with resolution' : 'seed constants (not scaled)';
      const title = h('b', null, `${faces.toLocaleString('en')} face${faces > 1 ? 's' : ''}`);
      if (this.sweepLayout === 'sequence') {
        append(l, [h('small', null, `${this.sweepIndex % total + 1} / ${total}`), title,
          h('small', null, `${r}×${r} grid · ${((r + 1) ** 2).toLocaleString('en')} particles`), h('small', null, scaling)]);
      } else {
        append(l, [title, h('small', null, `${r}×${r} · ${this.scene.material.scaleWithResolution ? 'scaled' : 'seed constants'}`)]);
      }
      this.overlay.labelLayer.append(l);
      this.labels.push(l);
    });
  }

  private placeLabels(): void {
    const rect = this.stage.container.getBoundingClientRect();
    const v = new Vector3();
    this.sim.mirrors.forEach((m, k) => {
      const l = this.labels[k];
      if (!l) return;
      const p = m.sim.scene.cloth.position;
      // one cloth: a title above it; a row: placards on the floor in front of each
      const row = this.labels.length > 1;
      if (row) v.set(p[0], 0, p[2] + 0.75);
      else v.set(p[0], p[1] + 0.3, p[2]);
      v.project(this.stage.camera);
      const visible = v.z < 1;
      l.style.display = visible ? '' : 'none';
      l.style.transform = `translate(-50%, ${row ? '0' : '-100%'}) translate(${((v.x + 1) / 2) * rect.width}px, ${((1 - v.y) / 2) * rect.height}px)`;
    });
  }

  /** Sequence layout: move on to the next resolution when the current one has had its time. */
  private advanceSweep(): void {
    const sweep = this.sweepList();
    if (!sweep.length || this.sweepLayout !== 'sequence' || this.sim.paused) return;
    const m = this.sim.mirrors[0];
    if (!m || m.frame < SWEEP_STAGE_FRAMES || this.sweepHalted) return;
    this.interaction.cancel();
    const from = this.sweepIndex;
    this.sweepIndex = (this.sweepIndex + 1) % sweep.length;
    try {
      this.sim.setScene(0, this.slotScenes()[0]);
    } catch (e) {
      // this resolution of an imported sweep cannot start where the scene puts it: stay, and say why
      this.sweepIndex = from;
      this.sweepHalted = true;
      this.overlay.message(`Mesh resolution ${sweep[(from + 1) % sweep.length]} refused: ${refusal(e)}`);
      return;
    }
    this.syncViews();
  }

  /** Rebuilds the views of slots whose cloth was rebuilt. */
  private syncViews(): void {
    let changed = false;
    this.sim.mirrors.forEach((m, k) => {
      if (this.views[k]?.model === m.sim.model) return;
      changed = true;
    });
    if (changed) this.rebuildViews();
  }

  // ---------------------------------------------------------------- PanelHost

  loadBuiltin(name: string): void {
    if (!isBuiltinScene(name)) { this.overlay.message(`unknown scene '${name}'`); return; }
    try {
      this.applyScene(builtinScene(name), name);
    } catch (e) {
      this.overlay.message(refusal(e));
    }
  }

  setPath(path: string, value: unknown): boolean {
    let next: Scene;
    try {
      let base = this.scene;
      // particle-index pins belong to one resolution: a new resolution keeps only the presets
      if (path === 'cloth.resolution') base = { ...base, pins: base.pins.filter((p) => typeof p === 'string') };
      next = setScenePath(base, path, value);
    } catch (e) {
      this.overlay.message(e instanceof SceneError ? e.message.replace(/^--set /, '') : String(e));
      this.panel.sync();
      return false;
    }
    const before = { scene: this.scene, capNote: this.capNote, slots: this.sim.mirrors.map((m) => m.sim.scene) };
    try {
      this.applyPath(path, next);
    } catch (e) {
      // refused by the simulation (a collider cutting through the cloth, a pin inside one): as it was
      const why = refusal(e);
      this.scene = before.scene;
      this.capNote = before.capNote;
      if (this.sim.mirrors.length === before.slots.length) {
        before.slots.forEach((s, k) => { if (this.sim.mirrors[k].sim.scene !== s) this.sim.setScene(k, s); });
        this.syncViews();
      } else {
        this.sim.mirrors.length = 0;
      }
      this.restoreSlots();
      this.overlay.message(why);
      return false;
    }
    this.dirty = true;
    this.scheduleHash();
    return true;
  }

  /** setPath's change, once the new scene is valid; throws SceneError when the simulation refuses it */
  private applyPath(path: string, next: Scene): void {
    this.scene = next;
    if (path === 'cloth.resolution' || path === 'resolutionSweep') this.capNote = '';
    const capBefore = this.capNote;
    if (this.wantedBackend().kind !== this.sim.kind) {
      this.switchBackend(true);
      const capped = this.capNote !== capBefore ? this.capNote : '';
      if (this.backendNote || capped) this.overlay.message([this.backendNote, capped].filter(Boolean).join('. '), 'notice');
    } else {
      this.backendNote = this.wantedBackend().note;
      this.capToBackend(this.sim.kind);
    }
    const scenes = this.slotScenes();
    if (scenes.length !== this.sim.mirrors.length) {
      this.loadSlots();
    } else {
      scenes.forEach((s, k) => {
        // keep slot-local pins (pin tool on a sweep cloth) when only parameters change
        const keep = this.scene.resolutionSweep?.length ? { ...s, pins: this.sim.mirrors[k].sim.scene.pins } : s;
        const derived = path.startsWith('cloth.') || path === 'material.scaleWithResolution' || path === 'pins';
        const rebuilt = this.sim.setScene(k, derived ? s : keep);
        if (rebuilt) this.interaction.cancel();
      });
      this.syncViews();
      if (path === 'material.scaleWithResolution') this.makeLabels();
    }
    if (path.startsWith('cloth.')) this.frameCamera(false);
  }

  reset(): void {
    this.interaction.cancel();
    this.sweepHalted = false;
    if (this.scene.resolutionSweep?.length && this.sweepLayout === 'sequence' && this.sweepIndex !== 0) {
      this.sweepIndex = 0;
      this.loadSlots();
    } else {
      this.sim.reset();
    }
    this.hud.clearPlot();
    // the unstable-cloth message (and its Reset button) has done its job
    if (this.overlay.lastMessage.startsWith('The simulation became unstable')) this.overlay.clearMessage();
    this.dirty = true;
  }

  togglePause(): void {
    this.sim.paused = !this.sim.paused;
    this.panel.updatePlay();
  }

  stepOnce(): void {
    if (!this.sim.paused) this.togglePause();
    void this.sim.step(1);
  }

  setView(view: ViewName): void {
    this.view = view;
    for (const v of this.views) v.setView(view);
    this.overlay.toast(VIEW_LABELS[view]);
    this.panel.sync();
    this.dirty = true;
    this.scheduleHash();
  }

  cycleView(): void {
    this.setView(VIEWS[(VIEWS.indexOf(this.view) + 1) % VIEWS.length]);
  }

  setCamera(preset: CameraPreset): void {
    this.stage.setCamera(preset);
  }

  setPreset(preset: PinPreset, on: boolean): void {
    const pins = this.scene.pins.filter((p) => p !== preset);
    if (on) pins.push(preset);
    this.setPath('pins', pins);
    this.panel.sync();
  }

  clearPins(): void {
    this.setPath('pins', []);
    if (this.scene.resolutionSweep?.length) this.sim.mirrors.forEach((m, k) => this.sim.setScene(k, { ...m.sim.scene, pins: [] }));
    this.panel.sync();
  }

  setPinTool(on: boolean): void {
    this.pinTool = on;
    this.stage.container.classList.toggle('pin-tool', on);
    this.panel.sync();
  }

  /** Pin tool: pins or unpins one particle; presets it breaks up become particle lists. */
  togglePin(slot: number, particle: number): void {
    const m = this.sim.mirrors[slot];
    const scene = m.sim.scene;
    const pinned = new Set(resolvePins(m.sim.model, scene.pins));
    const on = !pinned.has(particle);
    let pins: (PinPreset | number)[];
    if (on) {
      pins = [...scene.pins, particle];
    } else {
      pins = [];
      for (const p of scene.pins) {
        if (p === particle) continue;
        if (typeof p === 'string') {
          const members = resolvePins(m.sim.model, [p]);
          if (members.includes(particle)) { pins.push(...members.filter((i) => i !== particle)); continue; }
        }
        pins.push(p);
      }
    }
    if (this.scene.resolutionSweep?.length) {
      try {
        this.sim.setScene(slot, { ...scene, pins });
      } catch (e) {
        this.overlay.message(refusal(e));
        return;
      }
    } else {
      if (!this.setPath('pins', pins)) return;
      this.panel.sync();
    }
    this.overlay.toast(`${on ? 'Pinned' : 'Unpinned'} particle ${particle}`);
    this.dirty = true;
  }

  setSweepLayout(layout: SweepLayout): void {
    const before = { layout: this.sweepLayout, index: this.sweepIndex };
    this.sweepLayout = layout;
    this.sweepIndex = 0;
    this.sweepHalted = false;
    try {
      this.loadSlots();
    } catch (e) {
      const why = refusal(e);
      this.sweepLayout = before.layout;
      this.sweepIndex = before.index;
      this.restoreSlots();
      this.overlay.message(why);
      return;
    }
    this.frameCamera(true);
    this.scheduleHash();
  }

  grabChanged(active: boolean): void {
    this.stage.container.classList.toggle('grabbing', active);
  }

  showHelp(): void {
    this.overlay.help();
  }

  // ---------------------------------------------------------------- files and links

  private download(blob: Blob, name: string): void {
    const url = URL.createObjectURL(blob);
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10_000);
  }

  /** a file name from the scene's name: letters, digits, '.', '_' and '-' only, never hidden or empty */
  private fileBase(): string {
    return plainText(this.scene.name, 60).replace(/[^\w.-]+/g, '-').replace(/^[.-]+/, '') || 'scene';
  }

  exportJson(): void {
    const doc = { $schema: 'https://drape.dev/scene.schema.json', ...this.scene };
    this.download(new Blob([JSON.stringify(doc, null, 2) + '\n'], { type: 'application/json' }), `${this.fileBase()}.json`);
  }

  importJson(): void {
    this.fileInput.value = '';
    this.fileInput.click();
  }

  private async readImport(): Promise<void> {
    const file = this.fileInput.files?.[0];
    if (!file) return;
    // the file's name is shown in messages: as text, with no control or direction-changing characters
    const name = plainText(file.name, 80);
    const tooBig = importSizeProblem(file.size);
    if (tooBig) { this.overlay.message(`Import refused — ${name}: ${tooBig}`); return; }
    this.importText(await file.text(), name);
  }

  /** Loads a scene document; an invalid one is refused with a message and changes nothing. */
  importText(text: string, source = 'scene'): boolean {
    let scene: Scene;
    try {
      scene = parseScene(text, source);
    } catch (e) {
      this.overlay.message(`Import refused — ${(e as Error).message}`);
      return false;
    }
    try {
      this.applyScene(scene, SCENE_NAMES.includes(scene.name) ? scene.name : '');
    } catch (e) {
      this.overlay.message(`Import refused — ${source}: ${refusal(e)}`);
      return false;
    }
    this.overlay.message(this.capNote ? `Imported ${source} — ${this.capNote}` : `Imported ${source}`, 'notice');
    return true;
  }

  copyLink(): void {
    this.writeHash();
    const url = location.href;
    navigator.clipboard?.writeText(url).then(
      () => this.overlay.message('Link copied to the clipboard', 'notice'),
      () => this.overlay.message(`Link: ${url}`, 'notice'),
    );
  }

  private hashState() {
    return {
      scene: this.scene,
      base: this.sceneKey,
      view: {
        view: this.view === 'shaded' ? undefined : this.view,
        sweep: this.scene.resolutionSweep?.length && this.sweepLayout !== 'sequence' ? this.sweepLayout : undefined,
        backend: this.backendChoice === 'auto' || !this.backendInLink ? undefined : this.backendChoice,
      },
    };
  }

  private writeHash(): void {
    clearTimeout(this.hashTimer);
    let hash: string;
    try {
      hash = encodeHash(this.hashState());
    } catch {
      return;
    }
    if (hash !== location.hash && !(hash === '' && location.hash === '')) {
      history.replaceState(null, '', hash || location.pathname + location.search);
    }
  }

  private scheduleHash(): void {
    clearTimeout(this.hashTimer);
    this.hashTimer = window.setTimeout(() => this.writeHash(), 250);
  }

  private onHashChange(): void {
    if (location.hash === encodeHash(this.hashState())) return;
    const before = { view: this.view, sweepLayout: this.sweepLayout, backendChoice: this.backendChoice, backendInLink: this.backendInLink };
    try {
      const s = decodeHash(location.hash);
      if (!s) return;
      if (s.view.view && (VIEWS as readonly string[]).includes(s.view.view)) this.view = s.view.view as ViewName;
      this.sweepLayout = s.view.sweep === 'side-by-side' ? 'side-by-side' : 'sequence';
      if ((BACKEND_CHOICES as readonly string[]).includes(s.view.backend ?? '')) {
        this.backendChoice = s.view.backend as BackendChoice;
        this.backendInLink = true;
      }
      this.applyScene(s.scene, SCENE_NAMES.includes(s.base) ? s.base : '');
    } catch (e) {
      const why = e instanceof SceneError && !e.message.startsWith('link: ') ? `link: ${e.message}` : refusal(e);
      // as it was: the view settings too (the address bar is rewritten to what is on screen)
      const relayout = this.sweepLayout !== before.sweepLayout || this.backendChoice !== before.backendChoice;
      Object.assign(this, before);
      if (relayout) { this.loadSlots(); this.frameCamera(true); }
      this.panel.sync();
      this.scheduleHash();
      this.overlay.message(why);
    }
  }

  screenshot(): void {
    this.stage.render();
    this.stage.renderer.domElement.toBlob((blob) => {
      if (blob) this.download(blob, `drape-${this.fileBase()}.png`);
      else this.overlay.message('screenshot failed: the canvas could not be read');
    }, 'image/png');
  }

  /** The cloths as plain meshes with standard materials, at their current shape, for the exporters. */
  private exportGroup(): Group {
    const group = new Group();
    group.name = plainText(this.scene.name, 100);
    const look = fabricLook(fabricFor(this.scene.name));
    const material = new MeshStandardMaterial({ map: look.map, roughness: look.roughness, side: DoubleSide, name: `${look.kind} fabric` });
    this.sim.mirrors.forEach((m, k) => {
      const g = new BufferGeometry();
      g.setAttribute('position', new BufferAttribute(new Float32Array(m.sim.state.positions), 3));
      g.setAttribute('uv', new BufferAttribute(new Float32Array(m.sim.model.uvs), 2));
      g.setIndex(new BufferAttribute(new Uint32Array(m.sim.model.triangles), 1));
      g.computeVertexNormals();
      const mesh = new Mesh(g, material);
      mesh.name = this.sim.mirrors.length > 1 ? `cloth-${m.sim.scene.cloth.resolution}` : 'cloth';
      if (k >= 0) group.add(mesh);
    });
    return group;
  }

  exportObj(): void {
    const problem = this.exportProblem();
    if (problem) { this.overlay.message(`OBJ export refused: ${problem}.`); return; }
    void import('three/examples/jsm/exporters/OBJExporter.js').then(({ OBJExporter }) => {
      // one comment line: the name cannot break out of it (no line breaks in plainText)
      const text = `# Drape cloth, scene '${plainText(this.scene.name, 100)}'\n` + new OBJExporter().parse(this.exportGroup());
      this.download(new Blob([text], { type: 'model/obj' }), `${this.fileBase()}.obj`);
    });
  }

  exportGltf(): void {
    const problem = this.exportProblem();
    if (problem) { this.overlay.message(`glTF export refused: ${problem}.`); return; }
    void import('three/examples/jsm/exporters/GLTFExporter.js').then(async ({ GLTFExporter }) => {
      try {
        const out = await new GLTFExporter().parseAsync(this.exportGroup(), { binary: true });
        this.download(new Blob([out as ArrayBuffer], { type: 'model/gltf-binary' }), `${this.fileBase()}.glb`);
      } catch (e) {
        this.overlay.message(`glTF export failed: ${(e as Error).message}`);
      }
    });
  }

  // ---------------------------------------------------------------- keyboard and loop

  private readonly onKey = (e: KeyboardEvent): void => {
    const t = e.target as HTMLElement | null;
    // typing into a text field or a dropdown is not a shortcut; a focused checkbox or button is
    const typing = t instanceof HTMLInputElement ? !['checkbox', 'radio', 'button', 'range'].includes(t.type)
      : !!t && (t.tagName === 'SELECT' || t.tagName === 'TEXTAREA' || t.isContentEditable);
    if (typing) return;
    // space on a focused checkbox or button would also toggle or press it on key-up
    if (e.key === ' ' && t && t !== document.body && (t instanceof HTMLButtonElement || t instanceof HTMLInputElement)) t.blur();
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const k = e.key;
    let handled = true;
    if (k === 'v' || k === 'V') this.cycleView();
    else if (k === '1') this.setCamera('front');
    else if (k === '2') this.setCamera('side');
    else if (k === '3') this.setCamera('top');
    else if (k === '4') this.setCamera('reset');
    else if (k === ' ') this.togglePause();
    else if (k === 'r' || k === 'R') this.reset();
    else if (k === 's' || k === 'S') this.stepOnce();
    else if (k === 'p' || k === 'P') { this.setPinTool(!this.pinTool); this.overlay.toast(this.pinTool ? 'Pin tool on' : 'Pin tool off'); }
    else if (k === '?' || (k === '/' && e.shiftKey)) this.overlay.help();
    else if (k === 'Escape') this.overlay.help(false);
    else handled = false;
    if (handled) e.preventDefault();
  };

  private readonly loop = (now: number): void => {
    requestAnimationFrame(this.loop);
    const dt = this.lastTime ? now - this.lastTime : 0;
    this.lastTime = now;
    this.sim.tick(dt, now);
    this.advanceSweep();
    this.syncViews();
    if (this.sim instanceof GpuSim && !this.sim.lost) {
      const backend = this.stage.renderer.backend as unknown as { get(o: object): { buffer?: GPUBuffer } };
      this.views.forEach((v, k) => {
        const solver = (this.sim as GpuSim).solverOf(k);
        if (solver && !v.attached && v.model === this.sim.mirrors[k].sim.model) {
          v.attachGpu(backend, solver.positionBuffer, solver.normalBuffer);
          this.dirty = true;
        }
      });
      this.sim.eagerReadback = this.views.some((v) => v.needsCpuPositions);
    }
    const redraw = this.dirty;
    if (this.dirty) {
      this.sim.mirrors.forEach((m, k) => this.views[k]?.update(m.sim.state, m.grabbed));
      this.dirty = false;
    }
    const moved = this.stage.updateControls();
    // draw only when something changed: a paused, untouched view costs nothing
    const draw = !this.stage.busy && (redraw || moved || this.stage.needsRender || !this.firstFrameAt);
    if (draw) {
      this.placeLabels();
      this.stage.render();
      this.fpsFrames++;
      if (!this.firstFrameAt) {
        this.firstFrameAt = performance.now();
        performance.mark('drape:first-frame');
        this.firstFrameResolve();
      }
    }
    if (now - this.fpsTime >= 500) {
      this.fps = (1000 * this.fpsFrames) / (now - this.fpsTime);
      this.idle = this.fpsFrames === 0;
      this.fpsFrames = 0;
      this.fpsTime = now;
    }
    if (now - this.plotTime >= 100 && !this.sim.paused) {
      this.plotTime = now;
      this.hud.sample(this.sim.stats.energy);
    }
    if (now - this.hudTime >= 250) {
      this.hudTime = now;
      this.updateHud();
    }
  };

  private updateHud(): void {
    let particles = 0, triangles = 0, springs = 0;
    for (const m of this.sim.mirrors) {
      particles += m.sim.model.particleCount;
      triangles += m.sim.model.triangles.length / 3;
      springs += m.sim.model.restLengths.length;
    }
    const sweep = this.sweepList();
    const notes: string[] = [];
    this.sim.mirrors.forEach((m, k) => {
      if (m.unstableAt >= 0) notes.push(`${this.clothName(k)}: unstable at frame ${m.unstableAt}, stopped — Reset (R) to start again`);
    });
    if (this.capNote) notes.push(this.capNote);
    if (this.scene.resolutionSweep?.length && this.sweepLayout === 'side-by-side') {
      const fit = fitSideBySide(this.scene.resolutionSweep, this.sim.kind);
      if (fit.note) notes.push(fit.note);
    }
    this.hud.update({
      notes,
      fps: this.fps,
      idle: this.idle,
      backend: this.stage.backend === 'webgpu' ? 'WebGPU' : 'WebGL2',
      simBackend: this.sim.kind === 'gpu' ? 'GPU (WebGPU compute)'
        : `CPU (worker${this.sim.stats.kernel === 'wasm' ? ', WebAssembly SIMD' : this.sim.stats.kernel === 'ts' ? ', TypeScript' : ''})`,
      backendNote: this.backendNote,
      stepMs: this.sim.stats.stepMs,
      realTime: this.sim.stats.realTime,
      paused: this.sim.paused,
      particles, triangles, springs,
      solver: this.scene.solver.type,
      substeps: this.scene.solver.substeps,
      clamps: this.sim.stats.clamps,
      view: this.view,
      maxStrain: this.sim.stats.maxStrain,
      slots: this.sim.mirrors.length,
      extra: sweep.length && this.sweepLayout === 'sequence'
        ? `resolution ${this.sweepIndex % sweep.length + 1} of ${sweep.length}, ${SWEEP_STAGE_FRAMES / 60} s each`
        : Object.hasOwn(SCENE_LABELS, this.scene.name) ? undefined : `scene: ${plainText(this.scene.name, 100)}`,
    });
  }
}
