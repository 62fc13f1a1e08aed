/**
 * Importing a mesh file (the panel's "import mesh…"): the hidden file input, the size check, parsing and checking
 * the file in the page, and keeping it in the page's mesh store under the file's name. A file that a waiting scene
 * names — a scene file or a link refused for mesh files this page did not have, as a cloth or a collider — goes
 * to that scene: once it has all its files, it loads. Any other file becomes the scene's cloth (cloth.mesh; in a
 * scene of several, the cloth the panel edits: cloths[k].cloth.mesh; the rest of the scene stays). A file that is refused — unreadable, not a manifold mesh (for a cloth), not a collider
 * the core can build, more particles than the backend takes, a cloth the colliders cut through — says why and
 * changes nothing.
 */
import { MESH_EXTENSIONS, SceneError, editCloth, plainText, type Scene } from '../core/index.js';
import type { App } from './app.js';
import { FilePicker } from './file-picker.js';
import {
  meshNames, missingMesh, missingMeshes, namesFile, readColliderFile, readMeshFile, sceneMeshes, type ClothEntry, type MeshEntry,
} from './meshes.js';
import { refusal } from './refusal.js';
import { withMesh } from './shape-change.js';

/** A scene (from a file or a link) that names mesh files the page does not have: it loads once they are imported. */
export interface WaitingScene {
  scene: Scene;
  /** its scene key (a built-in name, or '' for an imported scene) */
  key: string;
  /** where it came from, in messages ('dress.json', 'the link') */
  source: string;
}

/** what the app says wherever a scene naming mesh files meets a link */
export const linkCannotCarry = (names: readonly string[]): string => {
  const list = names.map((n) => plainText(n, 80)).join(', ');
  return names.length === 1
    ? `a link cannot carry an imported mesh (${list}): whoever opens a link to this scene must import that file too`
    : `a link cannot carry imported meshes (${list}): whoever opens a link to this scene must import those files too`;
};

/** the end of a message on a scene that is waiting for mesh files: what loads it */
export function loadsOnce(waiting: WaitingScene, missing: readonly { path: string }[]): string {
  const names = [...new Set(missing.map((f) => plainText(f.path, 80)))];
  return `${waiting.source} loads once ${names.join(', ')} ${names.length > 1 ? 'are' : 'is'} imported`;
}

/** The mesh-file import: file picker, size check, parse, store, load. */
export class MeshImport {
  private readonly picker: FilePicker;

  /** Adds the (hidden) file input to `root`. */
  constructor(private readonly app: App, root: HTMLElement) {
    this.picker = new FilePicker(app.overlay, root, {
      accept: MESH_EXTENSIONS.join(','), testid: 'import-mesh-file', what: 'mesh file', refused: 'Mesh import refused',
      onFile: (file, bytes) => { this.importBytes(new Uint8Array(bytes), file.name); },
    });
  }

  /** Opens the file picker. */
  open(): void {
    this.picker.open();
  }

  /**
   * Takes a mesh file: parsed and checked here, kept under its name (a scene naming it finds it), sent to the
   * simulation with the scene; for the waiting scene if it names the file, else as the cloth. False, with a
   * message, when refused; nothing changes then.
   */
  importBytes(bytes: Uint8Array, name: string): boolean {
    const waiting = this.app.waiting;
    const uses = waiting ? sceneMeshes(waiting.scene).filter((f) => namesFile(f.path, name)) : [];
    if (waiting && uses.length) return this.forWaiting(bytes, name, waiting, uses.some((f) => f.cloth !== undefined));
    const entry = this.read(name, () => readMeshFile(bytes, name));
    return entry !== null && this.asCloth(entry);
  }

  /** The file `name` as `reader` reads it (readMeshFile, readColliderFile); null, with a message, when refused. */
  private read<T extends MeshEntry>(name: string, reader: () => T): T | null {
    try {
      return reader();
    } catch (e) {
      // the core's message names the file; anything else a file can make the parser throw is still the file's fault
      const why = e instanceof SceneError ? e.message : `${plainText(name, 80)}: not a mesh file Drape can read (${plainText(String((e as Error)?.message ?? e), 200)})`;
      this.app.overlay.message(`Mesh import refused — ${why}`);
      return null;
    }
  }

  /** The file as the scene's cloth (the one the panel edits), the rest of the scene kept. */
  private asCloth(entry: ClothEntry): boolean {
    const app = this.app, name = entry.name, shown = plainText(name, 80);
    const before = app.meshes.add(entry);
    try {
      app.slots.apply(editCloth(app.scene, app.cloth, (one) => withMesh(one, name, app.meshes.resolve)), app.sceneKey);
    } catch (e) {
      app.meshes.restore(name, before);
      // the caps name the file already ('big.obj: 67,600 particles, more than…')
      const why = refusal(e);
      app.overlay.message(`Mesh import refused — ${why.startsWith(`${plainText(name, 200)}: `) ? why : `${shown}: ${why}`}`);
      return false;
    }
    app.overlay.message(`Imported mesh ${shown}: ${entry.particles.toLocaleString('en')} particles. Note: ${linkCannotCarry([name])}.`, 'notice');
    return true;
  }

  /**
   * A file the waiting scene names (`cloth`: as its cloth, checked as one; else as a collider): kept, and the scene
   * loaded once every file it names is here; a scene still missing some says which.
   */
  private forWaiting(bytes: Uint8Array, name: string, waiting: WaitingScene, cloth: boolean): boolean {
    const app = this.app, shown = plainText(name, 80);
    const entry = this.read(name, () => (cloth ? readMeshFile(bytes, name) : readColliderFile(bytes, name)));
    if (!entry) return false;
    const before = app.meshes.add(entry);
    const missing = missingMeshes(waiting.scene, (p) => app.meshes.has(p));
    if (missing.length) {
      app.overlay.message(`Imported mesh ${shown} for ${waiting.source}, which also needs ${missingMesh(missing[0].path, missing[0].field)}; ${loadsOnce(waiting, missing)}`, 'notice');
      return true;
    }
    try {
      app.slots.apply(waiting.scene, waiting.key);
    } catch (e) {
      // the file is not a collider the core can build (its error names the field and the file), or the scene is refused
      app.meshes.restore(name, before);
      app.overlay.message(`Mesh import refused — ${waiting.source}: ${refusal(e)}`);
      return false;
    }
    app.overlay.message(`Imported mesh ${shown}: loaded ${waiting.source}. Note: ${linkCannotCarry(meshNames(app.scene))}.`, 'notice');
    return true;
  }
}
