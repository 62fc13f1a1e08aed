/**
 * The page's link: the hash holds the scene (as a diff from a built-in one) and the view settings. The page starts
 * from it, rewrites it (a moment after each change) to what is on screen, follows it when it is edited, and copies
 * it to the clipboard.
 */
import { SCENE_NAMES, SceneError, plainText, type Scene } from '../core/index.js';
import { VIEWS, type ViewName } from '../render/cloth-view.js';
import type { App } from './app.js';
import { BACKEND_CHOICES, type BackendChoice } from './backend.js';
import { linkCannotCarry } from './mesh-import.js';
import { meshNames } from './meshes.js';
import { refusal } from './refusal.js';
import { sweeps } from './sweep.js';
import { decodeHash, encodeHash, linkScene, type HashState } from './url-state.js';

/** What a link's view setting may be, per key (its other values are ignored, and the page says so). */
const VIEW_VALUES: Record<keyof HashState['view'], readonly string[]> = {
  view: VIEWS, sweep: ['side-by-side', 'sequence'], backend: BACKEND_CHOICES,
};

/** One line naming a link's view settings that the page does not know, or '' when there are none. */
export function badViewSettings(view: HashState['view']): string {
  const bad = (Object.keys(VIEW_VALUES) as (keyof HashState['view'])[]).filter((k) => view[k] !== undefined && !VIEW_VALUES[k].includes(view[k]!));
  return bad.map((k) => `link: ${k}: must be one of ${VIEW_VALUES[k].join(', ')}, got '${plainText(view[k]!, 40)}' (ignored)`).join('; ');
}

/** The link in the address bar, kept in step with what is on screen. */
export class UrlSync {
  private timer = 0;

  constructor(private readonly app: App) {}

  /**
   * Starts from the link: its view settings and its scene. False when there is no link, or it is refused (a bad
   * link, a scene the simulation refuses), which says why: then the caller shows the default scene.
   */
  start(): boolean {
    const app = this.app;
    let start: HashState | null = null;
    try {
      start = decodeHash(location.hash);
    } catch (e) {
      app.overlay.message(`${(e as Error).message} — showing the default scene instead`, 'error');
    }
    if (start?.view.backend && (BACKEND_CHOICES as readonly string[]).includes(start.view.backend)) {
      app.backend.choice = start.view.backend as BackendChoice;
      app.backend.inLink = true;
    }
    if (!start) return false;
    const ignored = badViewSettings(start.view);
    if (ignored) app.overlay.message(ignored, 'error');
    if (start.view.sweep === 'side-by-side' || start.view.sweep === 'sequence') app.sweep.layout = start.view.sweep;
    if (start.view.view && (VIEWS as readonly string[]).includes(start.view.view)) app.view = start.view.view as ViewName;
    const shown = linkScene(start.scene, (p) => app.meshes.has(p));
    const key = start.base && start.base === start.scene.name ? start.base : SCENE_NAMES.includes(start.base) ? start.base : '';
    try {
      app.slots.apply(shown.scene, key);
    } catch (e) {
      // a scene the simulation refuses (a collider cutting through the cloth, …)
      app.overlay.message(`${shown.note ? `${shown.note}. But ` : ''}link: ${refusal(e)} — showing the default scene instead`, 'error');
      return false;
    }
    this.waitFor(start.scene, key, shown);
    return true;
  }

  /** A link's scene shown without the mesh files it names and the page lacks: it waits for them, and says so. */
  private waitFor(scene: Scene, key: string, shown: ReturnType<typeof linkScene>): void {
    if (!shown.missing.length) return;
    this.app.waiting = { scene, key, source: 'the link' };
    this.app.overlay.message(shown.note, 'error');
  }

  /** Writes the link now and copies it to the clipboard (or shows it where the clipboard is out of reach). */
  copy(): void {
    this.write();
    const url = location.href;
    // the link names an imported mesh file but cannot carry it: say so rather than pretend it reproduces the scene
    const meshes = meshNames(this.app.scene);
    const but = meshes.length ? ` — but ${linkCannotCarry(meshes)}` : '';
    // (no clipboard API outside a secure context, e.g. a page served over plain http from a LAN address)
    if (!navigator.clipboard) {
      this.app.overlay.message(`Link: ${url}${but}`, 'notice');
      return;
    }
    navigator.clipboard.writeText(url).then(
      () => this.app.overlay.message(`Link copied to the clipboard${but}`, 'notice'),
      () => this.app.overlay.message(`Link: ${url}${but}`, 'notice'),
    );
  }

  private state(): HashState {
    const app = this.app;
    return {
      scene: app.scene,
      base: app.sceneKey,
      view: {
        view: app.view === 'shaded' ? undefined : app.view,
        sweep: sweeps(app.scene) && app.sweep.layout !== 'sequence' ? app.sweep.layout : undefined,
        backend: app.backend.choice === 'auto' || !app.backend.inLink ? undefined : app.backend.choice,
      },
    };
  }

  private write(): void {
    clearTimeout(this.timer);
    let hash: string;
    try {
      hash = encodeHash(this.state());
    } catch {
      return;
    }
    if (hash !== location.hash && !(hash === '' && location.hash === '')) {
      history.replaceState(null, '', hash || location.pathname + location.search);
    }
  }

  /** Rewrites the link a moment from now (changes in a row write it once). */
  schedule(): void {
    clearTimeout(this.timer);
    this.timer = window.setTimeout(() => this.write(), 250);
  }

  /** The link was edited (hashchange): show what it says; a link that is refused says why and changes nothing. */
  onHashChange(): void {
    const app = this.app;
    if (location.hash === encodeHash(this.state())) return;
    const before = { view: app.view, sweepLayout: app.sweep.layout, backendChoice: app.backend.choice, backendInLink: app.backend.inLink };
    try {
      const s = decodeHash(location.hash);
      if (!s) return;
      const ignored = badViewSettings(s.view);
      if (ignored) app.overlay.message(ignored, 'error');
      // a setting the link leaves out is the default, as on a page opened with it
      app.view = s.view.view && (VIEWS as readonly string[]).includes(s.view.view) ? s.view.view as ViewName : 'shaded';
      app.sweep.layout = s.view.sweep === 'side-by-side' ? 'side-by-side' : 'sequence';
      if ((BACKEND_CHOICES as readonly string[]).includes(s.view.backend ?? '')) {
        app.backend.choice = s.view.backend as BackendChoice;
        app.backend.inLink = true;
      } else if (s.view.backend === undefined) {
        app.backend.choice = app.backend.defaultChoice;
        app.backend.inLink = false;
      }
      const shown = linkScene(s.scene, (p) => app.meshes.has(p));
      const key = SCENE_NAMES.includes(s.base) ? s.base : '';
      app.slots.apply(shown.scene, key);
      this.waitFor(s.scene, key, shown);
    } catch (e) {
      const why = e instanceof SceneError && !e.message.startsWith('link: ') ? `link: ${e.message}` : refusal(e);
      // as it was: the view settings too (the address bar is rewritten to what is on screen)
      const relayout = app.sweep.layout !== before.sweepLayout || app.backend.choice !== before.backendChoice;
      app.view = before.view;
      app.sweep.layout = before.sweepLayout;
      app.backend.choice = before.backendChoice;
      app.backend.inLink = before.backendInLink;
      if (relayout) { app.slots.load(); app.slots.frameCamera(true); }
      app.panel.sync();
      this.schedule();
      app.overlay.message(why);
    }
  }
}
