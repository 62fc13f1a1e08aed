/**
 * Page overlays: the view-name toast, the '?' shortcut sheet, the message banner (errors and notices) and the
 * labels that float above cloths in the Mesh Resolution scene.
 */
import { VIEWS } from '../render/cloth-view.js';
import { append, h } from './dom.js';

export const SHORTCUTS: [string, string][] = [
  ['V', `cycle views: ${VIEWS.join(' → ')}`],
  ['1 / 2 / 3 / 4', 'camera: front / side / top / reset'],
  ['Space', 'pause / play'],
  ['S', 'step one frame (while paused)'],
  ['R', 'reset / replay the scene'],
  ['P', 'pin tool on / off (click a particle to pin or unpin it)'],
  ['H', 'hide / show the HUD and the panel (remembered; also the button at the bottom left)'],
  ['E', 'explain: what the scene shows and what to try (remembered)'],
  ['?', 'show / hide this help'],
  ['drag the cloth', 'grab a particle and pull it in the camera plane'],
  ['drag elsewhere', 'orbit · right-drag or two fingers: pan · wheel or pinch: zoom'],
];

export class Overlay {
  private readonly toastEl: HTMLElement;
  private readonly helpEl: HTMLElement;
  private readonly messageEl: HTMLElement;
  private readonly messageText: HTMLElement;
  private readonly messageAction: HTMLButtonElement;
  private actionRun: (() => void) | null = null;
  readonly labelLayer: HTMLElement;
  private toastTimer = 0;
  private messageTimer = 0;
  /** last message shown, for the test hook */
  lastMessage = '';
  lastMessageKind: 'error' | 'notice' | '' = '';

  constructor(parent: HTMLElement) {
    this.toastEl = el('div', 'drape-toast', parent);
    this.toastEl.dataset.testid = 'toast';
    this.helpEl = el('div', 'drape-help', parent);
    this.helpEl.dataset.testid = 'help';
    this.helpEl.setAttribute('role', 'dialog');
    const rows = SHORTCUTS.map(([k, v]) => h('tr', null, h('td', null, h('kbd', null, k)), h('td', null, v)));
    append(this.helpEl, [
      h('h2', null, 'Shortcuts'),
      h('table', null, h('tbody', null, ...rows)),
      h('p', null, 'Press ', h('kbd', null, '?'), ' or ', h('kbd', null, 'Esc'), ' to close.'),
    ]);
    this.helpEl.addEventListener('click', () => this.help(false));
    this.messageEl = el('div', 'drape-message', parent);
    this.messageEl.dataset.testid = 'message';
    this.messageEl.setAttribute('role', 'alert');
    this.messageText = el('span', '', this.messageEl);
    this.messageAction = el('button', 'drape-message-action', this.messageEl) as HTMLButtonElement;
    this.messageAction.dataset.testid = 'message-action';
    this.messageAction.hidden = true;
    this.messageAction.addEventListener('click', () => {
      const run = this.actionRun;
      this.clearMessage();
      run?.();
    });
    const close = el('button', 'drape-message-close', this.messageEl);
    close.textContent = '×';
    close.title = 'dismiss';
    close.addEventListener('click', () => this.clearMessage());
    this.labelLayer = el('div', 'drape-labels', parent);
  }

  toast(text: string): void {
    this.toastEl.textContent = text;
    this.toastEl.classList.add('show');
    clearTimeout(this.toastTimer);
    this.toastTimer = window.setTimeout(() => this.toastEl.classList.remove('show'), 1400);
  }

  get helpOpen(): boolean {
    return this.helpEl.classList.contains('show');
  }

  help(show = !this.helpOpen): void {
    this.helpEl.classList.toggle('show', show);
  }

  /**
   * A one-line message at the top of the page (as text: it may quote a link or a file); errors fade after 15 s,
   * notices after 6 s, unless replaced or dismissed first. `action`: a button beside it (e.g. Reset); a message with
   * one stays until used or dismissed.
   */
  message(text: string, kind: 'error' | 'notice' = 'error', action?: { label: string; run: () => void }): void {
    this.lastMessage = text;
    this.lastMessageKind = kind;
    this.messageText.textContent = text;
    this.messageEl.dataset.kind = kind;
    this.messageEl.classList.add('show');
    this.actionRun = action?.run ?? null;
    this.messageAction.hidden = !action;
    this.messageAction.textContent = action?.label ?? '';
    clearTimeout(this.messageTimer);
    if (!action) this.messageTimer = window.setTimeout(() => this.clearMessage(), kind === 'error' ? 15000 : 6000);
  }

  clearMessage(): void {
    this.messageEl.classList.remove('show');
    this.actionRun = null;
    this.messageAction.hidden = true;
  }
}

function el(tag: string, className: string, parent: HTMLElement): HTMLElement {
  const e = document.createElement(tag);
  if (className) e.className = className;
  parent.append(e);
  return e;
}
