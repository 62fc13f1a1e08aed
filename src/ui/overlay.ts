/**
 * Page overlays: the view-name toast, the '?' shortcut sheet, the message banner (errors and notices) and the
 * labels that float above cloths in the Mesh Resolution scene.
 */

export const SHORTCUTS: [string, string][] = [
  ['V', 'cycle views: shaded → wireframe → particles → springs → strain'],
  ['1 / 2 / 3 / 4', 'camera: front / side / top / reset'],
  ['Space', 'pause / play'],
  ['S', 'step one frame (while paused)'],
  ['R', 'reset / replay the scene'],
  ['P', 'pin tool on / off (click a particle to pin or unpin it)'],
  ['?', 'show / hide this help'],
  ['drag the cloth', 'grab a particle and pull it in the camera plane'],
  ['drag elsewhere', 'orbit · right-drag or two fingers: pan · wheel or pinch: zoom'],
];

export class Overlay {
  private readonly toastEl: HTMLElement;
  private readonly helpEl: HTMLElement;
  private readonly messageEl: HTMLElement;
  private readonly messageText: HTMLElement;
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
    this.helpEl.innerHTML =
      '<h2>Shortcuts</h2><table>' +
      SHORTCUTS.map(([k, v]) => `<tr><td><kbd>${k}</kbd></td><td>${v}</td></tr>`).join('') +
      '</table><p>Press <kbd>?</kbd> or <kbd>Esc</kbd> to close.</p>';
    this.helpEl.addEventListener('click', () => this.help(false));
    this.messageEl = el('div', 'drape-message', parent);
    this.messageEl.dataset.testid = 'message';
    this.messageEl.setAttribute('role', 'alert');
    this.messageText = el('span', '', this.messageEl);
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

  /** A one-line message at the top of the page; errors stay until dismissed or replaced, notices fade. */
  message(text: string, kind: 'error' | 'notice' = 'error'): void {
    this.lastMessage = text;
    this.lastMessageKind = kind;
    this.messageText.textContent = text;
    this.messageEl.dataset.kind = kind;
    this.messageEl.classList.add('show');
    clearTimeout(this.messageTimer);
    this.messageTimer = window.setTimeout(() => this.clearMessage(), kind === 'error' ? 15000 : 6000);
  }

  clearMessage(): void {
    this.messageEl.classList.remove('show');
  }
}

function el(tag: string, className: string, parent: HTMLElement): HTMLElement {
  const e = document.createElement(tag);
  if (className) e.className = className;
  parent.append(e);
  return e;
}
