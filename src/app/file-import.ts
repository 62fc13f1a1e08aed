/**
 * Importing a scene document: the hidden file input behind the panel's import button, the size check, and loading
 * what it holds (the test hook's `import` takes the same path). A refused file says why and changes nothing; one
 * refused for mesh files the page does not have (its cloth's, its colliders') waits for them: importing them loads
 * it (mesh-import.ts).
 */
import { SCENE_NAMES, parseScene, plainText, type Scene } from '../core/index.js';
import type { App } from './app.js';
import { FilePicker } from './file-picker.js';
import { loadsOnce } from './mesh-import.js';
import { missingMeshes } from './meshes.js';
import { refusal } from './refusal.js';

/** The scene-file import: file picker, size check, parse, load. */
export class FileImport {
  private readonly picker: FilePicker;

  /** Adds the (hidden) file input to `root`. */
  constructor(private readonly app: App, root: HTMLElement) {
    this.picker = new FilePicker(app.overlay, root, {
      accept: '.json,application/json', testid: 'import-file', what: 'scene file', refused: 'Import refused',
      // the file's name is shown in messages: as text, with no control or direction-changing characters
      onFile: (file, bytes) => { this.importText(new TextDecoder().decode(bytes), plainText(file.name, 80)); },
    });
  }

  /** Opens the file picker. */
  open(): void {
    this.picker.open();
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
    const key = SCENE_NAMES.includes(scene.name) ? scene.name : '';
    try {
      app.slots.apply(scene, key);
    } catch (e) {
      const why = refusal(e);
      // the core names the first file that is missing; the scene waits for all of them
      const missing = missingMeshes(scene, (p) => app.meshes.has(p));
      let then = '';
      if (missing.length) {
        app.waiting = { scene, key, source };
        then = `; ${loadsOnce(app.waiting, missing)}`;
      }
      app.overlay.message(`Import refused — ${source}: ${why}${then}`);
      return false;
    }
    app.overlay.message(app.capNote ? `Imported ${source} — ${app.capNote}` : `Imported ${source}`, 'notice');
    return true;
  }
}
