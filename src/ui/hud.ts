/**
 * Heads-up display, top left: frame rate, simulation cost, cloth size, solver, what the simulation is doing
 * (running, paused, slow motion, clamps), a legend for the current view, and a live uPlot chart of kinetic,
 * potential and elastic energy.
 */
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { Energy } from '../core/index.js';
import { SPRING_COLORS, STRAIN_RANGE, type ViewName } from '../render/cloth-view.js';

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
  realTime: number;
  paused: boolean;
  particles: number;
  triangles: number;
  springs: number;
  solver: string;
  substeps: number;
  clamps: string[];
  view: ViewName;
  maxStrain: number;
  slots: number;
  extra?: string;
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
    const slow = !i.paused && i.realTime < 0.9;
    this.text.innerHTML =
      `<b>Drape</b> · ${i.backend} · sim on <span data-testid="hud-sim">${i.simBackend}</span><br>` +
      `${i.idle ? 'idle' : `${i.fps.toFixed(0)} fps`} · sim ${i.stepMs.toFixed(1)} ms/frame<br>` +
      `${i.particles.toLocaleString('en')} particles · ${i.triangles.toLocaleString('en')} triangles<br>` +
      `${i.springs.toLocaleString('en')} springs · ${i.solver}, ${i.substeps} substeps` +
      (i.slots > 1 ? `<br>${i.slots} cloths side by side (totals)` : '') +
      (i.extra ? `<br>${i.extra}` : '');
    const lines: string[] = [];
    if (i.paused) lines.push('<span class="ok">paused — space to run, “Step” for one frame</span>');
    else if (slow) lines.push(`<span class="warn">slow motion: ${(100 * i.realTime).toFixed(0)}% of real time — the simulation needs ${i.stepMs.toFixed(0)} ms per 16.7 ms frame; try a lower resolution or fewer substeps</span>`);
    else lines.push('<span class="ok">real time (fixed 1/60 s frames)</span>');
    if (i.backendNote) lines.push(`<span class="warn">${escapeHtml(i.backendNote)}</span>`);
    for (const c of i.clamps) lines.push(`<span class="warn">⚠ ${escapeHtml(c)}</span>`);
    this.status.innerHTML = lines.join('<br>');
    this.status.dataset.state = i.paused ? 'paused' : slow ? 'slow' : 'realtime';
    if (i.view === 'springs') {
      this.legend.innerHTML = ['structural', 'shear', 'bend']
        .map((k, n) => `<span><i style="background:${SPRING_COLORS[n]}"></i>${k}</span>`).join(' ');
    } else if (i.view === 'strain') {
      this.legend.innerHTML = `<span class="strain-bar"></span> −${STRAIN_RANGE * 100}% … 0 … +${STRAIN_RANGE * 100}% · max ${(100 * i.maxStrain).toFixed(1)}%`;
    } else {
      this.legend.innerHTML = '';
    }
  }
}

function escapeHtml(s: string): string {
  return s.replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c] ?? c);
}
