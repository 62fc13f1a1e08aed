/**
 * The resolution sweep (the Mesh Resolution scene, or any scene with `resolutionSweep`): which resolutions it
 * shows on the backend in use, the slot scenes it makes — one after another (sequence) or side by side — and
 * moving the sequence on.
 */
import { builtinScene, type ColliderSpec, type PinBall, type PinRegion, type Scene, type Vec3 } from '../core/index.js';
import type { SweepLayout } from '../ui/panel.js';
import type { App } from './app.js';
import { fitSideBySide, resolutionPins } from './limits.js';
import { refusal } from './refusal.js';

/** frames each resolution runs for in the Mesh Resolution sequence (3 s) */
export const SWEEP_STAGE_FRAMES = 180;
/** spacing of cloths laid side by side [m] */
const SIDE_BY_SIDE_SPACING = 1.6;
/** the Mesh Resolution scene on the GPU goes on past the CPU's 64 faces per side */
export const GPU_SWEEP_EXTRA = [128, 256, 512, 1024];

/**
 * Whether a scene's cloths come from its resolution sweep: the sweep is of one rectangle's resolutions, so a disc,
 * a tube or a mesh with one runs as it is (one cloth; sweepIgnored says so), and so does a scene of several cloths.
 */
export function sweeps(scene: Scene): boolean {
  return !!scene.resolutionSweep?.length && !scene.cloths && scene.cloth.shape === 'rectangle';
}

/** The note for a scene with a sweep that its cloth does not take ('' when none). */
export function sweepIgnored(scene: Scene): string {
  if (!scene.resolutionSweep?.length || sweeps(scene)) return '';
  if (scene.cloths) return `the resolution sweep is of one rectangle's resolutions: this scene's ${scene.cloths.length} cloths run as they are`;
  const c = scene.cloth;
  return `the resolution sweep is of a rectangle's resolutions: this ${c.shape} runs as it is` +
    (c.shape === 'mesh' ? '' : ` (resolution ${c.resolution})`);
}

/** The sweep's layout and progress, and the slot scenes it makes. */
export class Sweep {
  layout: SweepLayout = 'sequence';
  /** which resolution of the sweep is showing (sequence layout) */
  index = 0;
  /** the Mesh Resolution sequence met a resolution the simulation refuses: it stays where it is until a reset */
  halted = false;

  constructor(private readonly app: App) {}

  /**
   * Resolutions of a sweep scene; on the GPU the built-in Mesh Resolution scene, one after another, goes on to
   * 1024 faces per side (side by side keeps the scene's own list: a row of eleven cloths up to 1025² is too much).
   */
  list(): number[] {
    const sweep = sweeps(this.app.scene) ? this.app.scene.resolutionSweep ?? [] : [];
    // side by side: as many cloths as the backend simulates at once (see limits.ts)
    if (sweep.length && this.layout === 'side-by-side') return fitSideBySide(sweep, this.app.sim?.kind ?? 'cpu').list;
    if (!sweep.length || this.app.sim?.kind !== 'gpu' || this.layout !== 'sequence') return sweep;
    const builtin = builtinScene('resolution').resolutionSweep ?? [];
    if (JSON.stringify(builtin) !== JSON.stringify(sweep)) return sweep;
    return [...sweep, ...GPU_SWEEP_EXTRA.filter((r) => r > Math.max(...sweep))];
  }

  /** The scenes of the cloths on screen: one, or one per resolution of a sweep. */
  scenes(): Scene[] {
    const s = this.app.scene;
    const sweep = this.list();
    if (!sweep.length) return [s];
    const at = (res: number, dx: number): Scene => {
      const next = structuredClone(s);
      delete next.resolutionSweep;
      next.cloth.resolution = res;
      next.cloth.position = [s.cloth.position[0] + dx, s.cloth.position[1], s.cloth.position[2]];
      next.colliders = s.colliders.map((c) => shifted(c, dx));
      // a region is a box in space: it moves with its cloth, as the colliders do
      next.pins = resolutionPins(s.pins).map((p) => (typeof p === 'object' ? shiftedRegion(p, dx) : p));
      return next;
    };
    if (this.layout === 'sequence') return [at(sweep[this.index % sweep.length], 0)];
    return sweep.map((r, k) => at(r, (k - (sweep.length - 1) / 2) * SIDE_BY_SIDE_SPACING));
  }

  /** Sequence layout: move on to the next resolution when the current one has had its time. */
  advance(): void {
    const app = this.app;
    const sweep = this.list();
    if (!sweep.length || this.layout !== 'sequence' || app.sim.paused) return;
    const m = app.sim.mirrors[0];
    if (!m || m.frame < SWEEP_STAGE_FRAMES || this.halted) return;
    app.interaction.cancel();
    const from = this.index;
    this.index = (this.index + 1) % sweep.length;
    try {
      app.sim.setScene(0, this.scenes()[0]);
    } catch (e) {
      // this resolution of an imported sweep cannot start where the scene puts it: stay, and say why
      this.index = from;
      this.halted = true;
      app.overlay.message(`Mesh resolution ${sweep[(from + 1) % sweep.length]} refused: ${refusal(e)}`);
      return;
    }
    app.slots.syncViews();
    app.panel.sync(); // the resolution menu shows the one now on screen
  }

  /** The panel's sweep layout: the sweep starts again in it; a layout the simulation refuses leaves things as they were. */
  setLayout(layout: SweepLayout): void {
    const app = this.app;
    const before = { layout: this.layout, index: this.index };
    this.layout = layout;
    this.index = 0;
    this.halted = false;
    try {
      app.slots.load();
    } catch (e) {
      const why = refusal(e);
      this.layout = before.layout;
      this.index = before.index;
      app.slots.restore();
      app.overlay.message(why);
      return;
    }
    app.slots.frameCamera(true);
    app.link.schedule();
  }
}

/** A collider moved dx along x with its cloth (side-by-side sweeps); a floor is the same everywhere. */
/** A pin region moved dx [m] along x with its cloth. */
function shiftedRegion(r: PinRegion | PinBall, dx: number): PinRegion | PinBall {
  if ('center' in r) return { center: [r.center[0] + dx, r.center[1], r.center[2]], radius: r.radius };
  return { min: [r.min[0] + dx, r.min[1], r.min[2]], max: [r.max[0] + dx, r.max[1], r.max[2]] };
}

function shifted(c: ColliderSpec, dx: number): ColliderSpec {
  const x = (p: Vec3): Vec3 => [p[0] + dx, p[1], p[2]];
  switch (c.type) {
    case 'floor': return c;
    case 'plane': return { ...c, point: x(c.point) };
    case 'capsule': return { ...c, a: x(c.a), b: x(c.b) };
    case 'mesh': return { ...c, position: x(c.position) };
    default: return { ...c, center: x(c.center) };
  }
}
