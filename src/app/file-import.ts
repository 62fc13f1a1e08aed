/**
 * Importing a scene document: the hidden file input behind the panel's import button, the size check, and loading
 * what it holds (the test hook's `import` takes the same path). A refused file says why and changes nothing.
 */
import { SCENE_NAMES, parseScene, plainText, type Scene } from '../core/index.js';
import type { App } from './app.js';
import { importSizeProblem } from './limits.js';
import { refusal } from './refusal.js';

/** The scene-file import: file picker, size check, parse, load. */
export class FileImport {
  private readonly input: HTMLInputElement;

  /** Adds the (hidden) file input to `root`. */
  constructor(private readonly app: App, root: HTMLElement) {
    this.input = document.createElement('input');
    this.input.type = 'file';
    this.input.accept = '.json,application/json';
    this.input.hidden = true;
    this.input.dataset.testid = 'import-file';
    this.input.addEventListener('change', () => void this.read());
    root.append(this.input);
  }

  /** Opens the file picker. */
  open(): void {
    this.input.value = '';
    this.input.click();
  }

  private async read(): Promise<void> {
    const file = this.input.files?.[0];
    if (!file) return;
    // the file's name is shown in messages: as text, with no control or direction-changing characters
    const name = plainText(file.name, 80);
    const tooBig = importSizeProblem(file.size);
    if (tooBig) { this.app.overlay.message(`Import refused — ${name}: ${tooBig}`); return; }
    this.importText(await file.text(), name);
  }

  /** Loads a scene document; an invalid one is refused with a message and changes nothing. */
  importText(text: string, source = 'scene'): boolean {
    const app = this.app;
    let scene: Scene;
    try {
      scene = parseScene(text, source);
    } catch (e) {
      app.overlay.message(`Import refused — ${(e as Error).message}`);
      return false;
    }
    try {
      app.slots.apply(scene, SCENE_NAMES.includes(scene.name) ? scene.name : '');
    } catch (e) {
      app.overlay.message(`Import refused — ${source}: ${refusal(e)}`);
      return false;
    }
    app.overlay.message(app.capNote ? `Imported ${source} — ${app.capNote}` : `Imported ${source}`, 'notice');
    return true;
  }
}
