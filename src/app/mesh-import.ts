/**
 * Importing a mesh file as the cloth (the panel's "import mesh…"): the hidden file input, the size check, parsing
 * and checking the file in the page, keeping it in the page's mesh store under the file's name, and making it the
 * scene's cloth (cloth.mesh; the rest of the scene stays). A file that is refused — unreadable, not a manifold
 * mesh, more particles than the backend takes, a cloth the colliders cut through — says why and changes nothing.
 */
import { MESH_EXTENSIONS, SceneError, plainText } from '../core/index.js';
import type { App } from './app.js';
import { FilePicker } from './file-picker.js';
import { readMeshFile } from './meshes.js';
import { refusal } from './refusal.js';
import { withMesh } from './shape-change.js';

/** what the app says wherever a mesh cloth meets a link */
export const linkCannotCarry = (name: string): string =>
  `a link cannot carry an imported mesh (${plainText(name, 80)}): whoever opens a link to this scene must import that file too`;

/** The mesh-file import: file picker, size check, parse, store, load. */
export class MeshImport {
  private readonly picker: FilePicker;

  /** Adds the (hidden) file input to `root`. */
  constructor(private readonly app: App, root: HTMLElement) {
    this.picker = new FilePicker(app.overlay, root, {
      accept: MESH_EXTENSIONS.join(','), testid: 'import-mesh-file', what: 'mesh file', refused: 'Mesh import refused',
      onFile: async (file) => { this.importBytes(new Uint8Array(await file.arrayBuffer()), file.name); },
    });
  }

  /** Opens the file picker. */
  open(): void {
    this.picker.open();
  }

  /**
   * Makes a mesh file the scene's cloth: parsed and checked here, kept under its name (a scene file naming it finds
   * it), sent to the simulation with the scene. False, with a message, when refused; nothing changes then.
   */
  importBytes(bytes: Uint8Array, name: string): boolean {
    const app = this.app;
    const shown = plainText(name, 80);
    let entry;
    try {
      entry = readMeshFile(bytes, name);
    } catch (e) {
      // the core's message names the file; anything else a file can make the parser throw is still the file's fault
      const why = e instanceof SceneError ? e.message : `${shown}: not a mesh file Drape can read (${plainText(String((e as Error)?.message ?? e), 200)})`;
      app.overlay.message(`Mesh import refused — ${why}`);
      return false;
    }
    const before = app.meshes.add(entry);
    try {
      app.slots.apply(withMesh(app.scene, name, app.meshes.resolve), app.sceneKey);
    } catch (e) {
      app.meshes.restore(name, before);
      // the caps name the file already ('big.obj: 67,600 particles, more than…')
      const why = refusal(e);
      app.overlay.message(`Mesh import refused — ${why.startsWith(`${plainText(name, 200)}: `) ? why : `${shown}: ${why}`}`);
      return false;
    }
    app.overlay.message(`Imported mesh ${shown}: ${entry.particles.toLocaleString('en')} particles. Note: ${linkCannotCarry(name)}.`, 'notice');
    return true;
  }
}
