/**
 * The control panel on the right (lil-gui), as in the seed: the scene dropdown and Reset/Replay at the top, then
 * simulation, material, solver, wind, gravity, pins, view and file controls. Slider ranges, defaults and tooltips
 * come from the scene schema (core's sceneSchema); the panel only sends changes to its host. In a scene of several
 * cloths, a cloth control at the top of Cloth & material chooses the cloth that folder and Pins edit: their
 * controls read that cloth's fields and write its paths (`cloths[k].material.damping`).
 */
import GUI, { type Controller } from 'lil-gui';
// lil-gui's stylesheet as a file of the build: the panel injects no <style> element (the site's CSP has no inline styles)
import 'lil-gui/dist/lil-gui.css';
import {
  MANNEQUIN_ANIMATIONS, MANNEQUIN_POSES, SCENE_NAMES, clothCount, clothEntries, clothName, clothPath, plainText, sceneSchema,
  type ClothEntry, type MannequinOptions, type PinPreset, type Scene,
} from '../core/index.js';
import { VIEWS, VIEW_LABELS, type ViewName } from '../render/cloth-view.js';
import type { CameraPreset } from '../render/stage.js';
import { SCENE_LABELS, clothOptions } from './menu-labels.js';

export type SweepLayout = 'sequence' | 'side-by-side';

/** The screenshot sizes offered: the view as on screen (its free part, at the screen's pixel ratio), or pixels */
export const PNG_SIZES: Record<string, string> = {
  'the view, as on screen': 'view',
  '1280 × 720': '1280x720',
  '1920 × 1080': '1920x1080',
  '1080 × 1080 (square)': '1080x1080',
  '3840 × 2160 (4K)': '3840x2160',
};
export const CORNER_PINS: readonly PinPreset[] = ['top-left', 'top-right', 'bottom-left', 'bottom-right', 'center'];

/** What the panel drives. */
export interface PanelHost {
  readonly scene: Scene;
  /** dropdown value: a built-in name, or '' for an imported scene */
  readonly sceneKey: string;
  /** the cloth the Cloth & material and Pins folders edit: an index into clothEntries(scene) */
  readonly cloth: number;
  /** chooses that cloth (a scene of several) */
  selectCloth(k: number): void;
  readonly paused: boolean;
  readonly view: ViewName;
  readonly pinTool: boolean;
  readonly sweepLayout: SweepLayout;
  /** whether the scene's resolution sweep runs (one rectangle's; a scene of several cloths runs as it is) */
  readonly sweeping: boolean;
  /** simulation backend asked for: auto, gpu, cpu */
  readonly backendChoice: 'auto' | 'gpu' | 'cpu';
  /** the scene's mannequin's pose and animation; null when the scene has no mannequin (the controls hide) */
  readonly mannequin: MannequinOptions | null;
  /** poses or moves the mannequin anew, the cloth going on */
  setMannequin(change: MannequinOptions): void;
  /** the resolution of the cloth on screen: a sweep's current one (one after another), else the scene's */
  readonly shownResolution: number;
  /** largest cloth resolution offered (the GPU goes further) */
  readonly maxResolution: number;
  setBackend(choice: 'auto' | 'gpu' | 'cpu'): void;
  loadBuiltin(name: string): void;
  /** live change of one scene path (a cloth's own in a scene of several: `cloths[k].…`); returns false (and shows why) when refused */
  setPath(path: string, value: unknown): boolean;
  reset(): void;
  togglePause(): void;
  stepOnce(): void;
  setView(view: ViewName): void;
  setCamera(preset: CameraPreset): void;
  setPreset(preset: PinPreset, on: boolean): void;
  clearPins(): void;
  setPinTool(on: boolean): void;
  setSweepLayout(layout: SweepLayout): void;
  exportJson(): void;
  importJson(): void;
  /** the file picker for a mesh file (OBJ, glTF) that becomes the cloth */
  importMesh(): void;
  copyLink(): void;
  /** downloads the view as PNG without the panel: `size` 'view' (as on screen) or 'WxH' pixels (PNG_SIZES) */
  screenshot(size: string): void;
  exportObj(): void;
  exportGltf(): void;
  /** starts a recording of the simulation, or stops it and downloads it as an animated .glb */
  toggleRecording(): void;
  /**
   * the recording: whether one is going and its frames so far, the animation's bytes so far, the frame cap (lowered
   * to what the page's memory holds for these cloths) and the bytes of a take that long
   */
  readonly recording: { active: boolean; frames: number; bytes: number; cap: number; capBytes: number };
  setRecordCap(frames: number): void;
  showHelp(): void;
  /** shows or hides what the scene demonstrates */
  toggleExplain(): void;
}

interface SchemaNumber { type?: string; minimum?: number; maximum?: number; default?: unknown; description?: string; enum?: readonly string[] }

/** The schema entry of a dotted scene path ('material.damping', 'gravity.1' for a vector component). */
export function schemaFor(path: string): SchemaNumber {
  let node: Record<string, unknown> = sceneSchema as unknown as Record<string, unknown>;
  for (const key of path.split('.')) {
    const props = node.properties as Record<string, Record<string, unknown>> | undefined;
    if (props && props[key]) node = props[key];
    else if (node.items && /^\d+$/.test(key)) node = node.items as Record<string, unknown>;
    else throw new Error(`no schema for ${path}`);
  }
  return node as SchemaNumber;
}

/** The value at a dotted path of a scene, or of one cloth's entry ('material.damping'). */
function get(from: Scene | ClothEntry, path: string): unknown {
  let v: unknown = from;
  for (const k of path.split('.')) v = (v as Record<string, unknown>)[k];
  return v;
}

const fmt = (v: number): string => {
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e4) return `${+(v / 1000).toPrecision(3)}k`;
  if (a >= 100) return v.toFixed(0);
  return `${+v.toPrecision(3)}`;
};

/** A slider over log10 of the value, for ranges that span decades; the left end is 0 when 0 is allowed. */
interface LogSlider { lo: number; hi: number; zeroAllowed: boolean }

function logSliderFor(s: SchemaNumber): LogSlider | null {
  const min = s.minimum ?? 0, max = s.maximum ?? 1;
  if (min > 0 && max / min >= 1000) return { lo: Math.log10(min), hi: Math.log10(max), zeroAllowed: false };
  // from zero over many decades (a spring constant up to 10⁵ N/m, a bending rigidity whose default is 10⁻⁵ of its top)
  const wide = max >= 1000 || (typeof s.default === 'number' && s.default > 0 && max / s.default >= 1e4);
  if (min === 0 && wide) return { lo: Math.log10(max) - 7, hi: Math.log10(max), zeroAllowed: true };
  return null;
}

/** What a control says when its field is absent because the scene gives it by an older path. */
const NOT_SET: Record<string, string> = { 'material.arealDensity': 'from the whole cloth\'s mass (material.mass)' };

const RESOLUTIONS = [1, 2, 4, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 512, 1024];

/** the Shape control's generated shapes ('mesh' shows when the cloth is an imported file) */
const SHAPE_LABELS: Record<string, string> = { Rectangle: 'rectangle', Disc: 'disc', Tube: 'tube' };

/** what the Shape control does (its tooltip) */
const SHAPE_TITLE = 'rectangle (the grid; the pin presets need it), disc (diameter: width) or tube (diameter: width, length: height); rebuilds the cloth. A mesh file comes from "import mesh…"';

/** a resolution as the menu shows it for a shape: faces per side, across a disc, along a tube */
function resolutionLabel(r: number, shape: string): string {
  if (shape === 'disc') return `${r} faces across`;
  if (shape === 'tube') return `${r} faces along`;
  return `${r} × ${r}  (${(r * r).toLocaleString('en')} face${r === 1 ? '' : 's'})`;
}

export class Panel {
  readonly gui: GUI;
  /** lil-gui binds to plain properties: one per control, keyed by scene path or action */
  private readonly p: Record<string, unknown> = {};
  private readonly syncers: (() => void)[] = [];
  private sceneCtl!: Controller;
  private playCtl!: Controller;
  private sweepFolder!: GUI;
  private resolutionCtl!: Controller;
  private shapeCtl!: Controller;
  private clothCtl!: Controller;
  private pinsFolder!: GUI;
  private mannequinFolder!: GUI;
  private recordCtl!: Controller;
  private recordCapCtl!: Controller;

  constructor(private readonly host: PanelHost) {
    this.gui = new GUI({ title: 'Drape', width: 300, injectStyles: false });
    this.gui.domElement.classList.add('drape-panel');
    this.build();
    this.sync();
  }

  /** the backend maximum and shape the resolution menu was made for */
  private resolutionFor = '';

  /** which cloth the Cloth & material and Pins folders edit (the host's, within the scene's) */
  private clothIndex(): number {
    return Math.min(this.host.cloth, clothCount(this.host.scene) - 1);
  }

  /** that cloth */
  private entry(): ClothEntry {
    return clothEntries(this.host.scene)[this.clothIndex()];
  }

  /** the scene path of one of that cloth's fields */
  private clothPath(field: string): string {
    return clothPath(this.host.scene, this.clothIndex(), field);
  }

  /** cloth resolutions up to the backend's maximum (1024 faces per side on the GPU), worded for the shape */
  private resolutionOptions(): Record<string, number> {
    const rs = schemaFor('cloth.resolution');
    const shape = this.entry().cloth.shape;
    this.resolutionFor = `${this.host.maxResolution} ${shape} ${this.host.shownResolution}`;
    const hi = Math.min(rs.maximum ?? 1024, this.host.maxResolution);
    const out: Record<string, number> = {};
    const shown = this.host.shownResolution;
    const list = RESOLUTIONS.includes(shown) ? RESOLUTIONS : [...RESOLUTIONS, shown].sort((a, b) => a - b);
    for (const r of list) if (r >= (rs.minimum ?? 1) && (r <= hi || r === shown)) out[resolutionLabel(r, shape)] = r;
    return out;
  }

  private tag<C extends Controller>(c: C, id: string, description?: string): C {
    c.domElement.dataset.testid = id;
    if (description) c.domElement.title = description;
    return c;
  }

  private build(): void {
    const { gui, host, p } = this;

    p.scene = host.sceneKey;
    const options: Record<string, string> = {};
    for (const name of SCENE_NAMES) options[SCENE_LABELS[name] ?? name] = name;
    this.sceneCtl = this.tag(gui.add(p, 'scene', options).name('Scene'), 'scene')
      .onChange((v: string) => { if (v) host.loadBuiltin(v); });
    p.reset = () => host.reset();
    this.tag(gui.add(p, 'reset').name('↺ Reset / Replay   (R)'), 'reset');
    p.play = () => host.togglePause();
    this.playCtl = this.tag(gui.add(p, 'play').name('Pause   (space)'), 'play');
    p.step = () => host.stepOnce();
    this.tag(gui.add(p, 'step').name('Step one frame   (S)'), 'step');

    this.sweepFolder = gui.addFolder('Mesh resolution');
    p.sweep = host.sweepLayout;
    this.tag(this.sweepFolder.add(p, 'sweep', { 'one after another': 'sequence', 'side by side': 'side-by-side' })
      .name('layout').onChange((v: SweepLayout) => host.setSweepLayout(v)), 'sweep');
    this.addParam(this.sweepFolder, 'material.scaleWithResolution', 'scale with resolution', { id: 'sweep.scaleWithResolution', cloth: true });

    this.mannequinFolder = gui.addFolder('Mannequin');
    p['mannequin.pose'] = 'stand';
    this.tag(this.mannequinFolder.add(p, 'mannequin.pose', [...MANNEQUIN_POSES]).name('pose')
      .onChange((v: MannequinOptions['pose']) => host.setMannequin({ pose: v })), 'mannequin.pose',
    'the joints\' pose: stand (arms a little away from the body) or t-pose (arms out level)');
    p['mannequin.animation'] = 'none';
    this.tag(this.mannequinFolder.add(p, 'mannequin.animation', [...MANNEQUIN_ANIMATIONS]).name('animation')
      .onChange((v: MannequinOptions['animation']) => host.setMannequin({ animation: v })), 'mannequin.animation',
    'none (holds the pose), walk (a walk cycle in place) or turn (70° to either side and back, every 4 s); the cloth goes on as it is');
    this.syncers.push(() => {
      p['mannequin.pose'] = host.mannequin?.pose ?? 'stand';
      p['mannequin.animation'] = host.mannequin?.animation ?? 'none';
    });

    const cloth = gui.addFolder('Cloth & material');
    p['cloth.which'] = 0;
    this.clothCtl = this.tag(cloth.add(p, 'cloth.which', { 'cloth 0': 0 }).name('cloth')
      .onChange((k: number) => host.selectCloth(Number(k))), 'cloth.which',
    'which of the scene\'s cloths this folder and Pins edit (the pin tool pins whichever cloth it clicks)');
    this.syncers.push(() => { p['cloth.which'] = host.cloth; });
    p['cloth.shape'] = 'rectangle';
    this.shapeCtl = this.tag(cloth.add(p, 'cloth.shape', SHAPE_LABELS).name('shape')
      .onChange((v: string) => { if (v !== 'mesh') host.setPath(this.clothPath('cloth.shape'), v); }), 'cloth.shape', SHAPE_TITLE);
    this.syncers.push(() => { p['cloth.shape'] = this.entry().cloth.shape; });
    p['cloth.resolution'] = 32;
    const rs = schemaFor('cloth.resolution');
    this.resolutionCtl = this.tag(cloth.add(p, 'cloth.resolution', this.resolutionOptions()).name('resolution')
      .onChange((v: number) => host.setPath(this.clothPath('cloth.resolution'), Number(v))), 'cloth.resolution', rs.description);
    this.syncers.push(() => { p['cloth.resolution'] = host.shownResolution; });
    this.addParam(cloth, 'material.fabric', 'fabric', { cloth: true });
    this.addParam(cloth, 'material.structuralStiffness', 'structural', { cloth: true, unit: 'N/m' });
    this.addParam(cloth, 'material.shearStiffness', 'shear', { cloth: true, unit: 'N/m' });
    this.addParam(cloth, 'material.bendingRigidity', 'bend', { cloth: true, unit: 'N·m' });
    this.addParam(cloth, 'material.damping', 'damping', { cloth: true, unit: 'N·s/m' });
    this.addParam(cloth, 'material.arealDensity', 'density', { cloth: true, unit: 'kg/m²' });
    this.addParam(cloth, 'material.stretchFactor', 'stretch factor', { cloth: true });
    this.addParam(cloth, 'material.friction', 'friction', { cloth: true });
    this.addParam(cloth, 'material.staticFriction', 'static friction', { cloth: true });
    this.addParam(cloth, 'material.scaleWithResolution', 'scale with resolution', { cloth: true });

    const solver = gui.addFolder('Solver');
    this.addParam(solver, 'solver.type', 'solver');
    this.addParam(solver, 'solver.substeps', 'substeps');
    this.addParam(solver, 'solver.iterations', 'iterations');
    this.addParam(solver, 'solver.bending', 'bending');
    this.addParam(solver, 'solver.stretch', 'stretch');
    this.addParam(solver, 'solver.bendingSolve', 'bending solve');
    this.addParam(solver, 'solver.selfContact', 'self-contact');
    this.addParam(solver, 'solver.selfContactSpeed', 'self-contact speed', { unit: 'm/s' });
    p.backend = host.backendChoice;
    this.tag(solver.add(p, 'backend', { 'auto (GPU when there is a hardware WebGPU)': 'auto', 'GPU (WebGPU compute, xpbd)': 'gpu', 'CPU (worker)': 'cpu' })
      .name('backend').onChange((v: 'auto' | 'gpu' | 'cpu') => host.setBackend(v)), 'backend',
    'where the simulation runs: auto picks the GPU when there is a WebGPU device; mass-spring runs on the CPU only');

    const wind = gui.addFolder('Wind');
    this.addParam(wind, 'wind.enabled', 'air on (wind, drag)');
    this.addParam(wind, 'wind.strength', 'strength', { unit: 'm/s' });
    // direction as a compass heading in the ground plane (keeps the vertical component)
    p.heading = 0;
    this.tag(wind.add(p, 'heading', 0, 360, 1).name('direction (°)').onChange((deg: number) => {
      const d = host.scene.wind.direction;
      const horiz = Math.hypot(d[0], d[2]) || 1;
      const a = (deg * Math.PI) / 180;
      host.setPath('wind.direction', [round(horiz * Math.cos(a)), d[1], round(horiz * Math.sin(a))]);
    }), 'wind.heading', 'compass heading the wind blows towards: 0° = +x, 90° = +z');
    this.syncers.push(() => {
      const d = host.scene.wind.direction;
      p.heading = Math.round(((Math.atan2(d[2], d[0]) * 180) / Math.PI + 360) % 360);
    });
    this.addParam(wind, 'wind.gusts.enabled', 'gusts');
    this.addParam(wind, 'wind.gusts.amplitude', 'gust amplitude');
    this.addParam(wind, 'wind.gusts.frequency', 'gust frequency', { unit: 'Hz' });

    const grav = gui.addFolder('Gravity');
    this.addParam(grav, 'gravity.1', 'gravity y', { unit: 'm/s²' });

    const pins = gui.addFolder('Pins');
    this.pinsFolder = pins;
    for (const preset of CORNER_PINS) {
      const key = `pin.${preset}`;
      p[key] = false;
      this.tag(pins.add(p, key).name(preset === 'center' ? 'centre' : preset)
        .onChange((on: boolean) => host.setPreset(preset, on)), key);
      this.syncers.push(() => { p[key] = this.entry().pins.includes(preset); });
    }
    p.pinTool = false;
    this.tag(pins.add(p, 'pinTool').name('pin tool (click cloth)   P').onChange((on: boolean) => host.setPinTool(on)),
      'pinTool', 'when on, clicking a particle pins or unpins it');
    this.syncers.push(() => { p.pinTool = host.pinTool; });
    p.clearPins = () => host.clearPins();
    this.tag(pins.add(p, 'clearPins').name('clear pins'), 'clearPins');

    const view = gui.addFolder('View');
    p.view = host.view;
    const viewOptions: Record<string, ViewName> = {};
    for (const v of VIEWS) viewOptions[VIEW_LABELS[v]] = v;
    this.tag(view.add(p, 'view', viewOptions).name('view   (V)').onChange((v: ViewName) => host.setView(v)), 'view');
    this.syncers.push(() => { p.view = host.view; });
    const cams: [CameraPreset, string][] = [['front', 'front   (1)'], ['side', 'side   (2)'], ['top', 'top   (3)'], ['reset', 'reset camera   (4)']];
    for (const [preset, label] of cams) {
      p[`cam.${preset}`] = () => host.setCamera(preset);
      this.tag(view.add(p, `cam.${preset}`).name(label), `cam.${preset}`);
    }
    p.help = () => host.showHelp();
    this.tag(view.add(p, 'help').name('shortcuts   (?)'), 'shortcuts');
    p.explain = () => host.toggleExplain();
    this.tag(view.add(p, 'explain').name('explain this scene   (E)'), 'explain');

    const file = gui.addFolder('Scene & export');
    const actions: [string, string, () => void][] = [
      ['exportJson', 'export scene JSON', () => host.exportJson()],
      ['importJson', 'import scene JSON…', () => host.importJson()],
      ['importMesh', 'import mesh (OBJ, glTF)…', () => host.importMesh()],
      ['copyLink', 'copy link to this scene', () => host.copyLink()],
      ['screenshot', 'screenshot PNG', () => host.screenshot(String(p['png.size']))],
      ['exportObj', 'export cloth OBJ', () => host.exportObj()],
      ['exportGltf', 'export cloth glTF', () => host.exportGltf()],
    ];
    for (const [key, label, fn] of actions) {
      p[key] = fn;
      this.tag(file.add(p, key).name(label), key);
      if (key === 'copyLink') {
        p['png.size'] = 'view';
        this.tag(file.add(p, 'png.size', PNG_SIZES).name('PNG size'), 'png.size',
          'the screenshot\'s size in pixels; it shows the view without the panel, centred as on screen');
      }
    }
    p.record = () => host.toggleRecording();
    this.recordCtl = this.tag(file.add(p, 'record'), 'record', 'records the simulation from now on as an animated glTF (one morph target per frame); press again to stop and download');
    p['record.cap'] = 600;
    this.recordCapCtl = this.tag(file.add(p, 'record.cap', 30, 3600, 30).onFinishChange((v: number) => host.setRecordCap(v)), 'record.cap',
      'the most frames a recording takes (1/60 s each); it stops and downloads there. The size is the animation\'s, for the cloths on screen');
    this.syncers.push(() => this.syncRecording());
    for (const f of [grav, solver, file]) f.close();
    // a dropdown keeps the focus after a choice, and would eat the shortcut keys: give it back to the page
    gui.domElement.addEventListener('change', (e) => {
      if (e.target instanceof HTMLSelectElement) e.target.blur();
    });
  }

  /** The Record button and the frame cap say what a recording is doing and what a take of the cap would weigh. */
  syncRecording(): void {
    const r = this.host.recording, mb = (b: number) => `${(b / 1e6).toFixed(1)} MB`;
    // the frames as the file will hold them: the first shape and those after it (as the message at the end counts);
    // the size is the animation's, without the textures the file also carries
    const held = r.frames + 1;
    this.recordCtl.name(r.active ? `■ stop recording (${held} frame${held === 1 ? '' : 's'}, animation ${mb(r.bytes)})` : '● record glTF animation');
    this.recordCapCtl.name(`frame cap (${r.cap < (this.p['record.cap'] as number) ? `${r.cap} fit, ` : ''}${mb(r.capBytes)})`);
  }

  /**
   * A control for one scene path, shaped by its schema: checkbox, dropdown, linear or logarithmic slider. `cloth`:
   * the path is a cloth's field ('material.damping'), read from and written to the edited cloth's; `id`: the
   * control's key (the path when not given); `unit`: shown in its label.
   */
  private addParam(folder: GUI, path: string, label: string, opts: { id?: string; unit?: string; cloth?: boolean } = {}): void {
    const { host, p } = this;
    const { id = path, unit = '' } = opts;
    const s = schemaFor(path);
    const suffix = unit ? ` (${unit})` : '';
    const read = () => get(opts.cloth ? this.entry() : host.scene, path);
    const write = (v: unknown) => host.setPath(opts.cloth ? this.clothPath(path) : path, v);
    let ctl: Controller;
    if (s.type === 'boolean') {
      p[id] = false;
      ctl = folder.add(p, id).name(label).onChange((v: boolean) => write(v));
      this.syncers.push(() => { p[id] = read(); });
    } else if (s.enum) {
      p[id] = s.default;
      // a named fabric puts every material field to its value: the other controls show them at once
      ctl = folder.add(p, id, [...s.enum]).name(label).onChange((v: string) => { write(v); this.sync(); });
      this.syncers.push(() => { p[id] = read(); });
    } else {
      const log = logSliderFor(s);
      const min = s.minimum ?? 0, max = s.maximum ?? 1;
      if (log) {
        p[id] = 0;
        const toValue = (x: number) => (log.zeroAllowed && x <= log.lo + 1e-9 ? 0 : +(10 ** x).toPrecision(3));
        const toSlider = (v: number) => (v <= 0 ? log.lo : Math.min(log.hi, Math.max(log.lo, Math.log10(v))));
        ctl = folder.add(p, id, log.lo, log.hi, 0.01).onChange((x: number) => {
          const v = toValue(x);
          ctl.name(`${label} ${fmt(v)}${unit ? ' ' + unit : ''}`);
          write(v);
        });
        ctl.domElement.classList.add('drape-log');
        this.syncers.push(() => {
          const v = read() as number | undefined;
          // a field the scene leaves to its older path (material.mass for the density) has no value to show
          p[id] = typeof v === 'number' ? toSlider(v) : log.lo;
          ctl.name(typeof v === 'number' ? `${label} ${fmt(v)}${unit ? ' ' + unit : ''}` : `${label}: ${NOT_SET[path] ?? 'not set'}`);
        });
      } else {
        p[id] = 0;
        const step = s.type === 'integer' ? 1 : niceStep((max - min) / 500);
        ctl = folder.add(p, id, min, max, step).name(label + suffix)
          .onChange((v: number) => write(s.type === 'integer' ? Math.round(v) : v));
        this.syncers.push(() => { p[id] = read(); });
      }
      // substeps 1…200 and similar: fine as linear sliders
    }
    this.tag(ctl, id, s.description);
  }

  /** Re-reads every control from the host (after a scene load, import, link or reset). */
  sync(): void {
    const { host, p } = this;
    p.scene = host.sceneKey;
    // an imported scene shows in the dropdown without becoming a built-in (OptionController.options updates in place)
    const opts: Record<string, string> = {};
    // lil-gui writes option names as text; plainText keeps control and direction-changing characters out
    if (host.sceneKey === '') opts[`Imported: ${plainText(host.scene.name, 60)}`] = '';
    for (const name of SCENE_NAMES) opts[SCENE_LABELS[name] ?? name] = name;
    this.sceneCtl.options(opts);
    p.sweep = host.sweepLayout;
    p.backend = host.backendChoice;
    // several cloths: the cloth control shows, and Pins says whose pins it shows
    const several = clothCount(host.scene) > 1;
    this.clothCtl.options(clothOptions(host.scene));
    this.clothCtl.show(several);
    this.pinsFolder.title(several ? `Pins: ${plainText(clothName(this.entry(), this.clothIndex()), 40)}` : 'Pins');
    const cloth = this.entry().cloth;
    // an imported mesh shows in the Shape control by its file's name (as text)
    const shapes: Record<string, string> = { ...SHAPE_LABELS };
    if (cloth.shape === 'mesh') shapes[`Mesh: ${plainText(cloth.mesh ?? '', 60)}`] = 'mesh';
    this.shapeCtl.options(shapes);
    // a sweep's resolution that the menu does not list (an imported scene's) is added, so that the menu shows it
    const shown = host.shownResolution;
    if (this.resolutionFor !== `${host.maxResolution} ${cloth.shape} ${shown}`) this.resolutionCtl.options(this.resolutionOptions());
    for (const f of this.syncers) f();
    // a sweep is of one rectangle's resolutions (another shape, or several cloths, run as they are); a mesh file has
    // its own resolution
    const sweep = host.sweeping;
    this.sweepFolder.show(sweep);
    this.mannequinFolder.show(host.mannequin !== null);
    // a garment on the mannequin is fitted to it: the figure carries its pins (the cape's top edge, the skirt's
    // waist ring), which another shape would not have, and another shape would start inside the figure
    const garment = host.mannequin !== null;
    this.shapeCtl.enable(!garment);
    this.shapeCtl.name(garment ? 'shape: the garment’s' : 'shape');
    this.shapeCtl.domElement.title = garment
      ? 'this cloth is a garment fitted to the mannequin, which carries its pins: its shape is the scene’s (choose a scene without a mannequin to change it)'
      : SHAPE_TITLE;
    this.resolutionCtl.enable(!sweep && cloth.shape !== 'mesh');
    this.resolutionCtl.name(cloth.shape === 'mesh' ? 'resolution: the mesh has its own'
      : !sweep ? 'resolution' : host.sweepLayout === 'sequence' ? 'resolution (the sweep’s, now)' : 'resolution (one per cloth)');
    this.updatePlay();
    for (const c of this.gui.controllersRecursive()) c.updateDisplay();
  }

  updatePlay(): void {
    this.playCtl.name(this.host.paused ? 'Play   (space)' : 'Pause   (space)');
  }
}

function niceStep(x: number): number {
  const e = 10 ** Math.floor(Math.log10(x));
  const m = x / e;
  return (m < 2 ? 1 : m < 5 ? 2 : 5) * e;
}

function round(v: number): number {
  return Math.round(v * 1e4) / 1e4;
}

