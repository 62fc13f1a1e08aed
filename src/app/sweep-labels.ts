/**
 * The floating labels of a sweep scene's cloths (faces, grid, particles, scaling): made when the cloths are, and
 * kept over them on screen, as text in the overlay's label layer.
 */
import { Vector3 } from 'three/webgpu';
import { append, h } from '../ui/dom.js';
import type { App } from './app.js';
import { sweeps } from './sweep.js';

/** The labels over a sweep's cloths (text only). */
export class SweepLabels {
  private labels: HTMLElement[] = [];
  /** a label's anchor, projected (reused: placing allocates nothing) */
  private readonly anchor = new Vector3();

  constructor(private readonly app: App) {}

  /** One label per cloth on screen when the scene is a sweep (none otherwise). */
  make(): void {
    const app = this.app;
    for (const l of this.labels) l.remove();
    this.labels = [];
    if (!sweeps(app.scene)) return;
    app.sim.mirrors.forEach((m) => {
      const l = document.createElement('div');
      l.className = 'drape-label';
      l.dataset.testid = 'sweep-label';
      const r = m.sim.scene.cloth.resolution;
      const faces = r * r;
      const total = app.sweep.list().length;
      const scaling = app.scene.material.scaleWithResolution ? 'scaled with resolution' : 'seed constants (not scaled)';
      const title = h('b', null, `${faces.toLocaleString('en')} face${faces > 1 ? 's' : ''}`);
      if (app.sweep.layout === 'sequence') {
        append(l, [h('small', null, `${app.sweep.index % total + 1} / ${total}`), title,
          h('small', null, `${r}×${r} grid · ${((r + 1) ** 2).toLocaleString('en')} particles`), h('small', null, scaling)]);
      } else {
        append(l, [title, h('small', null, `${r}×${r} · ${app.scene.material.scaleWithResolution ? 'scaled' : 'seed constants'}`)]);
      }
      app.overlay.labelLayer.append(l);
      this.labels.push(l);
    });
  }

  /**
   * Moves the labels (every drawn frame). One cloth (one after another): a title at the top of the view, centred
   * in the free space between the HUD and the panel, or at the bottom when that space is too narrow (a phone) — a
   * place in the scene above the cloth can be off-screen. A row: placards on the floor in front of each cloth.
   */
  place(): void {
    const app = this.app;
    const rect = app.stage.container.getBoundingClientRect();
    if (app.sweep.layout === 'sequence' && this.labels.length === 1) {
      const l = this.labels[0];
      const hud = app.hud.el.hidden ? 0 : app.hud.el.getBoundingClientRect().right;
      const right = rect.width - app.stage.viewInset;
      const top = right - hud >= l.offsetWidth + 24;
      const x = top ? (hud + right) / 2 : rect.width / 2;
      // at the bottom: above the scene's caption when it shows
      const caption = app.layout.caption.el;
      const bottom = caption.offsetHeight > 0 ? caption.getBoundingClientRect().top - rect.top - 8 : rect.height - 44;
      l.style.display = '';
      l.style.transform = `translate(-50%, ${top ? '0' : '-100%'}) translate(${x}px, ${top ? 12 : bottom}px)`;
      return;
    }
    const v = this.anchor;
    app.sim.mirrors.forEach((m, k) => {
      const l = this.labels[k];
      if (!l) return;
      const p = m.sim.scene.cloth.position;
      v.set(p[0], 0, p[2] + 0.75);
      v.project(app.stage.camera);
      const visible = v.z < 1;
      l.style.display = visible ? '' : 'none';
      l.style.transform = `translate(-50%, 0) translate(${((v.x + 1) / 2) * rect.width}px, ${((1 - v.y) / 2) * rect.height}px)`;
    });
  }
}
