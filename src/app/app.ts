/**
 * The app's composition root. It holds the state every job reads — the current scene (what a link or an exported
 * file reproduces), the simulation driver, the views of the cloths on screen ("slots") — and wires the jobs to it
 * and to the page: backend (backend.ts), slots (slots.ts), resolution sweep (sweep.ts, sweep-labels.ts), commands
 * from the panel, keyboard and pointer (commands.ts, shortcuts.ts), files (file-import.ts, file-export.ts, recorder.ts), the
 * link (url-sync.ts) and the frame loop (loop.ts, hud-feed.ts); imported mesh files (meshes.ts, mesh-import.ts).
 * It holds no physics: everything it knows about the cloth comes from the core's model and the worker's frames.
 */
import { SCENE_NAMES, builtinScene, type Scene, type SceneMannequin } from '../core/index.js';
import type { ClothView, ViewName } from '../render/cloth-view.js';
import { Stage } from '../render/stage.js';
import { Hud } from '../ui/hud.js';
import { Overlay } from '../ui/overlay.js';
import { Panel } from '../ui/panel.js';
import { Backend } from './backend.js';
import { Commands } from './commands.js';
import { ContactBudget } from './contact-budget.js';
import { ContactMeter } from './contact-meter.js';
import { FileExport } from './file-export.js';
import { FileImport } from './file-import.js';
import { Interaction } from './interaction.js';
import { Layout } from './layout.js';
import { FrameLoop } from './loop.js';
import { MeshImport, type WaitingScene } from './mesh-import.js';
import { PageMeshStore } from './meshes.js';
import { Recorder } from './recorder.js';
import { shortcutListener } from './shortcuts.js';
import type { SimDriver } from '../three/sim/sim-client.js';
import { Slots } from './slots.js';
import { Sweep } from './sweep.js';
import { SweepLabels } from './sweep-labels.js';
import { UrlSync } from './url-sync.js';

/** Page options from the query (main.ts). */
export interface AppOptions {
  forceWebGL?: boolean;
  lite?: boolean;
  /** `?backend=`: the backend choice when the link does not name one (not written into the link) */
  backend?: string | null;
}

/** The running app: shared state, and the jobs wired to it. */
export class App {
  /** the current scene: what a link or an exported file reproduces */
  scene!: Scene;
  /** the scene dropdown's value: a built-in name, or '' for an imported scene */
  sceneKey = 'cotton-basic';
  /** the scene's mannequin (a built-in scene's, as its colliders pose it now), or null: the panel's Mannequin controls */
  mannequin: SceneMannequin | null = null;
  /** the cloth the panel's Cloth & material and Pins folders edit, of a scene of several (0 for one cloth) */
  cloth = 0;
  view: ViewName = 'shaded';
  pinTool = false;
  /** what the backend's size cap changed in the scene ('' when nothing): shown in the HUD until the next scene */
  capNote = '';
  /** the simulation (CPU worker or GPU): one mirror per cloth on screen */
  sim!: SimDriver;
  /** one view per cloth on screen */
  views: ClothView[] = [];
  /** something changed that the next frame must draw */
  dirty = true;
  readonly stage: Stage;
  readonly overlay: Overlay;
  readonly hud: Hud;
  readonly panel: Panel;
  /** the HUD and the panel shown or hidden, compact on a narrow screen */
  readonly layout: Layout;
  readonly interaction: Interaction;
  readonly fileImport: FileImport;
  readonly meshImport: MeshImport;
  /** a scene file or link refused for mesh files this page does not have: importing them loads it (mesh-import.ts) */
  waiting: WaitingScene | null = null;
  /** the mesh files imported into this page, for the scenes that name them (cloth, mesh colliders; a link cannot carry them) */
  readonly meshes = new PageMeshStore();
  /** the HUD's count of particles lying on another part of their cloth */
  readonly contactMeter = new ContactMeter();
  /** switches self-contact off where the frame budget does not allow it (a scene's own setting, not one chosen by hand) */
  readonly contactBudget = new ContactBudget();
  readonly backend = new Backend(this);
  readonly slots = new Slots(this);
  readonly sweep = new Sweep(this);
  readonly labels = new SweepLabels(this);
  readonly commands = new Commands(this);
  readonly link = new UrlSync(this);
  readonly fileExport = new FileExport(this);
  readonly recorder = new Recorder(this);
  readonly loop = new FrameLoop(this);

  private constructor(readonly root: HTMLElement, stage: Stage, options: AppOptions = {}) {
    this.stage = stage;
    this.overlay = new Overlay(root);
    this.hud = new Hud(root);
    this.interaction = new Interaction(stage.container, this.commands);

    // start from the link, or the first built-in scene; a bad link says why and falls back
    this.backend.setDefault(options.backend);
    if (!this.link.start()) this.slots.apply(builtinScene(SCENE_NAMES[0]), SCENE_NAMES[0]);
    this.panel = new Panel(this.commands);
    this.fileImport = new FileImport(this, root);
    this.meshImport = new MeshImport(this, root);

    // capture phase: lil-gui stops key events from its controls, and shortcuts should work while one has focus
    window.addEventListener('keydown', shortcutListener(this.commands, this.overlay), { capture: true });
    const fit = () => {
      // a collapsed panel is a title bar: the view is centred on the whole width
      const gui = this.panel.gui;
      this.stage.insetRight = gui._closed ? 0 : gui.domElement.getBoundingClientRect().width;
      this.stage.resize();
      // what the panel covers, for the overlays centred on the view (CSSOM: no style attribute for the CSP)
      root.style.setProperty('--view-inset', `${this.stage.viewInset}px`);
    };
    this.layout = new Layout(root, this.hud, this.panel.gui, fit);
    window.addEventListener('resize', fit);
    window.addEventListener('hashchange', () => this.link.onHashChange());
    new ResizeObserver(() => this.stage.resize()).observe(stage.container);
    requestAnimationFrame(this.loop.frame);
  }

  /** Creates the renderer (WebGPU, else WebGL2) in `viewport` and the app around it, in `root`. */
  static async create(root: HTMLElement, viewport: HTMLElement, options: AppOptions = {}): Promise<App> {
    let app: App | null = null;
    const stage = await Stage.create(viewport, {
      forceWebGL: options.forceWebGL,
      lite: options.lite,
      onFallback: (reason) => {
        app?.overlay.message(`WebGPU device lost (${reason}); switched to WebGL2.`, 'notice');
        app?.backend.deviceLost();
      },
      onFallbackFailed: (message) => app?.overlay.message(`WebGPU device lost: ${message}. Reload the page to try again.`),
    });
    app = new App(root, stage, options);
    return app;
  }
}
