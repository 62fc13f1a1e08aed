/**
 * Heads-up display, top left: frame rate, simulation cost, cloth size, solver, what the simulation is doing
 * (running, paused, slow motion and what limits it, clamps), a legend for the current view, and a live uPlot chart
 * of kinetic, potential and elastic energy. Compact (a narrow screen, class `compact`): the first two lines, the
 * measured test and the status only.
 */
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { Energy } from '../core/index.js';
import { CONTACT_COLOR, SPRING_COLORS, STRAIN_RANGE, type ViewName } from '../render/cloth-view.js';
import { append, finite, h, setLines, type Child } from './dom.js';

/** One cloth of a scene of several, in the HUD (its name and shape as text). */
export interface HudCloth {
  name: string;
  /** '' for a rectangle, else 'disc', 'tube', 'mesh tshirt.obj' */
  shape: string;
  particles: number;
}

export interface HudInfo {
  fps: number;
  /** nothing needed drawing lately */
  idle: boolean;
  backend: string;
  /** where the simulation runs */
  simBackend: string;
  /** why it does not run where it was asked to ('' when it does) */
  backendNote: string;
  stepMs: number;
  /** no frame of the cloth now has been timed yet (a scene just loaded or rebuilt): its speed is unknown */
  measuring: boolean;
  /** why the page runs slower than real time, in words with the fix that fits ('' when it keeps up or is paused) */
  slow: string;
  /** what limits it: 'simulation' or 'drawing' ('' when nothing does) */
  slowBy: string;
  paused: boolean;
  particles: number;
  triangles: number;
  springs: number;
  /** each cloth's particles, in a scene of several cloths */
  cloths?: HudCloth[];
  solver: string;
  substeps: number;
  clamps: string[];
  view: ViewName;
  maxStrain: number;
  /** solver.selfContact, and the particles lying on another part of their cloth (app/contact-meter.ts) */
  selfContact: boolean;
  contacts: number;
  /** the distance that counts as lying on [m] */
  contactDistance: number;
  slots: number;
  /** another line of the text block (a scene's name: shown as text, never as markup) */
  extra?: string;
  /** what the scene's fabric test measures now (a cantilever's bending length, a Cusick drape coefficient) */
  test?: string;
  /** what the app had to do or stop (a clamped resolution, an unstable cloth), shown as warnings */
  notes?: string[];
}

const PLOT_POINTS = 240;
const FLOOR = 1e-6;

export class Hud {
  readonly el: HTMLElement;
  private readonly text: HTMLElement;
  private readonly status: HTMLElement;
  private readonly legend: HTMLElement;
  private readonly plot: uPlot;
  private readonly data: number[][] = [[], [], [], []];
  private t0 = performance.now();
  /** a narrow screen's HUD: the first two lines, the measured test and the status; no sizes, legend or plot */
  compact = false;

  constructor(parent: HTMLElement) {
    this.el = document.createElement('div');
    this.el.className = 'drape-hud';
    this.el.dataset.testid = 'hud';
    this.text = document.createElement('div');
    this.text.className = 'drape-hud-text';
    this.status = document.createElement('div');
    this.status.className = 'drape-hud-status';
    this.status.dataset.testid = 'hud-status';
    this.legend = document.createElement('div');
    this.legend.className = 'drape-hud-legend';
    const plotBox = document.createElement('div');
    plotBox.className = 'drape-hud-plot';
    this.el.append(this.text, this.status, this.legend, plotBox);
    parent.append(this.el);

    this.plot = new uPlot({
      width: 250,
      height: 110,
      legend: { show: true, live: false },
      cursor: { show: false },
      scales: { x: { time: false }, y: { distr: 3, range: (_u, _min, max) => [1e-4, Math.max(1e-2, max * 1.5)] } },
      axes: [
        { show: false },
        { size: 34, stroke: '#475261', font: '9px system-ui', grid: { stroke: 'rgba(0,0,0,0.08)' }, values: (_u, v) => v.map((x) => (x == null ? '' : x >= 1 ? `${x}` : x.toExponential(0))) },
      ],
      series: [
        {},
        { label: 'kinetic J', stroke: '#e0532d', width: 1.5, points: { show: false } },
        { label: 'potential J', stroke: '#2f6fd6', width: 1.5, points: { show: false } },
        { label: 'elastic J', stroke: '#2ea043', width: 1.5, points: { show: false } },
      ],
    }, this.data as uPlot.AlignedData, plotBox);
  }

  /** Adds one energy sample (call about 10×/s). */
  sample(e: Energy): void {
    // an unstable cloth's energy is not a number: the plot skips it rather than drawing garbage
    if (!Number.isFinite(e.kinetic) || !Number.isFinite(e.gravitational) || !Number.isFinite(e.elastic)) return;
    const t = (performance.now() - this.t0) / 1000;
    const d = this.data;
    d[0].push(t);
    d[1].push(Math.max(FLOOR, e.kinetic));
    d[2].push(Math.max(FLOOR, e.gravitational));
    d[3].push(Math.max(FLOOR, e.elastic));
    if (d[0].length > PLOT_POINTS) for (const s of d) s.shift();
    this.plot.setData(d as uPlot.AlignedData);
  }

  clearPlot(): void {
    for (const s of this.data) s.length = 0;
    this.plot.setData(this.data as uPlot.AlignedData);
  }

  update(i: HudInfo): void {
    const slow = !i.paused && i.slow !== '';
    const lines: Child[][] = [
      [h('b', null, 'Drape'), ` · ${i.backend} · sim on `, h('span', { testid: 'hud-sim' }, i.simBackend)],
      [`${i.idle ? 'idle' : `${i.fps.toFixed(0)} fps`} · sim ${finite(i.stepMs, 1)} ms/frame`],
      [`${i.particles.toLocaleString('en')} particles · ${i.triangles.toLocaleString('en')} triangles`],
      [`${i.springs.toLocaleString('en')} springs · ${i.solver}, ${i.substeps} substeps`],
      [h('span', { testid: 'hud-contacts' }, i.selfContact
        ? `self-contact on · ${i.contacts.toLocaleString('en')} particle${i.contacts === 1 ? '' : 's'} in contact`
        : `self-contact off (${i.contacts.toLocaleString('en')} particle${i.contacts === 1 ? '' : 's'} lying on the cloth)`)],
    ];
    if (i.cloths) {
      const each = i.cloths.map((c) => `${c.name}${c.shape ? ` (${c.shape})` : ''} ${c.particles.toLocaleString('en')}`);
      lines.splice(3, 0, [h('span', { testid: 'hud-cloths' }, `${i.cloths.length} cloths: ${each.join(' · ')} particles`)]);
    }
    if (this.compact) lines.splice(2);
    else if (i.slots > 1) lines.push([`${i.slots} cloths side by side (totals)`]);
    if (i.extra && !this.compact) lines.push([i.extra]);
    if (i.test) lines.push([h('span', { testid: 'hud-test' }, i.test)]);
    setLines(this.text, lines);
    const status: Child[][] = [];
    const ok = (t: string) => [h('span', 'ok', t)];
    const warn = (t: string) => [h('span', 'warn', t)];
    if (i.paused) status.push(ok('paused — space to run, “Step” for one frame'));
    else if (i.measuring) status.push(ok('measuring the speed… (fixed 1/60 s frames)'));
    else if (slow) status.push(warn(i.slow));
    else status.push(ok('real time (fixed 1/60 s frames)'));
    for (const n of i.notes ?? []) status.push(warn(`⚠ ${n}`));
    if (i.backendNote) status.push(warn(i.backendNote));
    for (const c of i.clamps) status.push(warn(`⚠ ${c}`));
    setLines(this.status, status);
    this.status.dataset.state = i.paused ? 'paused' : i.measuring ? 'measuring' : slow ? 'slow' : 'realtime';
    this.status.dataset.slowBy = slow ? i.slowBy : '';
    this.legend.replaceChildren();
    if (i.view === 'springs') {
      ['structural', 'shear', 'bend'].forEach((k, n) => {
        const swatch = h('i', null);
        swatch.style.background = SPRING_COLORS[n]; // through CSSOM: no style attribute for the CSP to refuse
        append(this.legend, [n > 0 && ' ', h('span', null, swatch, k)]);
      });
    } else if (i.view === 'contacts') {
      const swatch = h('i', null);
      swatch.style.background = CONTACT_COLOR;
      append(this.legend, [h('span', null, swatch, `within ${finite(1000 * i.contactDistance, 1)} mm of another part of the cloth`)]);
    } else if (i.view === 'strain') {
      append(this.legend, [h('span', 'strain-bar'), ` −${STRAIN_RANGE * 100}% … 0 … +${STRAIN_RANGE * 100}% · max ${finite(100 * i.maxStrain, 1)}%`]);
    }
  }
}
