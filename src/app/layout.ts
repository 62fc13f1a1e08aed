/**
 * What of the page's furniture shows around the 3D view: the HUD and the panel can be hidden and shown (the H key,
 * or the button in the bottom-left corner); the scene's explanation (the caption) with E, its close button or the
 * panel; and on a narrow screen (a phone) the panel starts collapsed, the HUD compact and the caption off, so the
 * cloth keeps most of the screen. The choices — hidden, the caption, and the panel open or collapsed once the user
 * has opened or closed it — persist in the browser's localStorage.
 */
import type GUI from 'lil-gui';
import { Caption } from '../ui/captions.js';
import type { Hud } from '../ui/hud.js';

/** a viewport at most this wide [CSS px] is narrow: the panel starts collapsed and the HUD compact */
export const NARROW_WIDTH = 700;
const STORAGE_KEY = 'drape.layout';

/** What is remembered between visits. */
export interface SavedLayout {
  /** HUD and panel hidden */
  hidden?: boolean;
  /** the panel open (true) or collapsed (false), as the user last left it */
  panelOpen?: boolean;
  /** the scene's explanation shown */
  explain?: boolean;
}

/** The saved layout read from a stored string: anything unreadable or of the wrong type counts as not saved. */
export function parseSavedLayout(text: string | null): SavedLayout {
  let v: unknown;
  try {
    v = JSON.parse(text ?? '{}');
  } catch {
    return {};
  }
  if (!v || typeof v !== 'object') return {};
  const o = v as Record<string, unknown>;
  const out: SavedLayout = {};
  if (typeof o.hidden === 'boolean') out.hidden = o.hidden;
  if (typeof o.panelOpen === 'boolean') out.panelOpen = o.panelOpen;
  if (typeof o.explain === 'boolean') out.explain = o.explain;
  return out;
}

/** The furniture's visibility, applied to the HUD and the panel, and its toggle button. */
export class Layout {
  private saved: SavedLayout;
  private readonly button: HTMLButtonElement;
  private readonly narrow: boolean;
  /** the scene's explanation at the bottom of the view */
  readonly caption: Caption;

  /** `onChange`: the space the panel covers changed (the 3D view refits) */
  constructor(root: HTMLElement, private readonly hud: Hud, private readonly panel: GUI, private readonly onChange: () => void) {
    this.saved = parseSavedLayout(read());
    const narrow = window.innerWidth <= NARROW_WIDTH;
    this.narrow = narrow;
    this.caption = new Caption(root, () => this.toggleExplain(false));
    hud.compact = narrow;
    hud.el.classList.toggle('compact', narrow);
    if (!(this.saved.panelOpen ?? !narrow)) panel.close();
    panel.onOpenClose((g) => {
      if (g !== panel) return; // a folder, not the panel
      this.saved.panelOpen = !panel._closed;
      write(this.saved);
      onChange();
    });
    this.button = document.createElement('button');
    this.button.className = 'drape-layout-toggle';
    this.button.dataset.testid = 'layout-toggle';
    this.button.addEventListener('click', () => this.toggle());
    root.append(this.button);
    this.apply();
  }

  /** HUD and panel hidden */
  get hidden(): boolean {
    return this.saved.hidden === true;
  }

  /** the scene's explanation shown (unless everything is hidden) */
  get explain(): boolean {
    return this.saved.explain ?? !this.narrow;
  }

  /** Shows or hides the scene's explanation (E), and remembers it. */
  toggleExplain(on = !this.explain): void {
    this.saved.explain = on;
    write(this.saved);
    this.apply();
  }

  /** Hides or shows the HUD and the panel (H), and remembers it. */
  toggle(hidden = !this.hidden): void {
    this.saved.hidden = hidden;
    write(this.saved);
    this.apply();
  }

  private apply(): void {
    const hidden = this.hidden;
    this.hud.el.hidden = hidden;
    this.panel.domElement.hidden = hidden;
    this.caption.el.hidden = hidden || !this.explain;
    this.button.textContent = hidden ? 'show panels (H)' : 'hide panels (H)';
    this.button.setAttribute('aria-pressed', String(hidden));
    this.onChange();
  }
}

/** localStorage can be missing or refuse (a private window, storage off): the layout then lasts for the visit */
function read(): string | null {
  try {
    return window.localStorage.getItem(STORAGE_KEY);
  } catch {
    return null;
  }
}

function write(saved: SavedLayout): void {
  try {
    window.localStorage.setItem(STORAGE_KEY, JSON.stringify(saved));
  } catch {
    // not stored: the choice holds until the page is left
  }
}
