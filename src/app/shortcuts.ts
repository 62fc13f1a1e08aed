/** The page's keyboard shortcuts (the `?` sheet lists them): keys to commands. */
import type { Overlay } from '../ui/overlay.js';
import type { Commands } from './commands.js';

/**
 * The keydown listener for the shortcuts. Install it in the capture phase: lil-gui stops key events from its
 * controls, and shortcuts should work while one has focus.
 */
export function shortcutListener(commands: Commands, overlay: Overlay): (e: KeyboardEvent) => void {
  return (e) => {
    const t = e.target as HTMLElement | null;
    // typing into a text field or a dropdown is not a shortcut; a focused checkbox or button is
    const typing = t instanceof HTMLInputElement ? !['checkbox', 'radio', 'button', 'range'].includes(t.type)
      : !!t && (t.tagName === 'SELECT' || t.tagName === 'TEXTAREA' || t.isContentEditable);
    if (typing) return;
    // space on a focused checkbox or button would also toggle or press it on key-up
    if (e.key === ' ' && t && t !== document.body && (t instanceof HTMLButtonElement || t instanceof HTMLInputElement)) t.blur();
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const k = e.key;
    let handled = true;
    if (k === 'v' || k === 'V') commands.cycleView();
    else if (k === '1') commands.setCamera('front');
    else if (k === '2') commands.setCamera('side');
    else if (k === '3') commands.setCamera('top');
    else if (k === '4') commands.setCamera('reset');
    else if (k === ' ') commands.togglePause();
    else if (k === 'r' || k === 'R') commands.reset();
    else if (k === 's' || k === 'S') commands.stepOnce();
    else if (k === 'p' || k === 'P') { commands.setPinTool(!commands.pinTool); overlay.toast(commands.pinTool ? 'Pin tool on' : 'Pin tool off'); }
    else if (k === 'h' || k === 'H') commands.toggleLayout();
    else if (k === 'e' || k === 'E') commands.toggleExplain();
    else if (k === '?' || (k === '/' && e.shiftKey)) overlay.help();
    else if (k === 'Escape') overlay.help(false);
    else handled = false;
    if (handled) e.preventDefault();
  };
}
