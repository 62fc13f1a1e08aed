/**
 * The meshes imported into the page: each file's parsed triangle mesh, keyed by the file's name (the drivers' store,
 * three/sim/meshes.ts, which the worker keeps too), the files a scene names that the page lacks, and reading a file
 * as a cloth or a collider. A link cannot carry a mesh: a scene naming one that is not here is refused with a
 * message naming the field and saying which file to import. No DOM here: unit-tested in meshes.test.ts.
 */
import { SceneError, parseMeshFile, plainText, prepareMesh, type Scene, type TriangleMesh } from '../core/index.js';
import { MeshStore, baseName, sceneMeshes, type MeshEntry, type SceneMeshFile } from '../three/sim/meshes.js';

export { baseName, clothMesh, sceneMeshes, type MeshEntry, type SceneMeshFile } from '../three/sim/meshes.js';

/** A mesh file checked as a cloth: its particles are counted. */
export type ClothEntry = MeshEntry & { readonly particles: number };

/** Whether a scene's mesh path names the imported file `name` (by its whole path or its last part, as MeshStore.find). */
export function namesFile(path: string, name: string): boolean {
  return path === name || baseName(path) === name;
}

/** The paths of the mesh files a scene names, each once. */
export function meshNames(scene: Scene): string[] {
  return [...new Set(sceneMeshes(scene).map((f) => f.path))];
}

/** The mesh files a scene names that `has` does not have, in sceneMeshes' order. */
export function missingMeshes(scene: Scene, has: (path: string) => boolean): SceneMeshFile[] {
  return sceneMeshes(scene).filter((f) => !has(f.path));
}

/** the words asking for a mesh file that is not here, without the field (the core's collider error puts its own first) */
function notImported(path: string): string {
  const name = plainText(baseName(path) || path, 200);
  return `'${plainText(path, 200)}' is a mesh file that is not imported in this page: import the mesh file ${name} too (Scene & export → import mesh…)`;
}

/** the words asking for a mesh file that is not here, naming the field that names it */
export function missingMesh(path: string, field = 'cloth.mesh'): string {
  return `${field}: ${notImported(path)}`;
}

/** particles of the cloth a mesh makes, checked as the core will build it (manifold, not degenerate, not too many vertices) */
const clothParticles = (mesh: TriangleMesh, name: string): number => prepareMesh(mesh, plainText(name, 200)).positions.length / 3;

/**
 * Reads a mesh file's bytes as the app imports a cloth: parsed by its extension (.obj, .gltf with embedded buffers,
 * .glb) and checked as the core will build it (manifold, not degenerate, not too many vertices), so that a bad file
 * is refused at once, naming the file. Throws SceneError.
 */
export function readMeshFile(bytes: Uint8Array, name: string): ClothEntry {
  const mesh = parseMeshFile(bytes, name);
  return { name, mesh, particles: clothParticles(mesh, name) };
}

/**
 * Reads a mesh file's bytes as the app imports a collider's: parsed by its extension only. A collider need not be a
 * manifold (open shells, edges of three faces are fine); the core checks the rest when it builds the collider, and
 * its error names the field (colliders[k].mesh) and the file. Throws SceneError naming the file.
 */
export function readColliderFile(bytes: Uint8Array, name: string): MeshEntry {
  return { name, mesh: parseMeshFile(bytes, name) };
}

/** The page's imported mesh files by name: the store the drivers read, asking for a file that is not imported. */
export class PageMeshStore extends MeshStore {
  constructor() {
    super(notImported);
  }

  /**
   * Particles of the cloth a mesh path makes (for the backends' caps): a SceneError when it is not imported, or when
   * a file imported for a collider is no cloth (checked, and counted once, the first time a scene makes it one).
   */
  particles(path: string): number {
    const e = this.find(path);
    if (!e) throw new SceneError(missingMesh(path));
    if (e.particles !== undefined) return e.particles;
    const particles = clothParticles(e.mesh, e.name);
    this.entries.set(e.name, { ...e, particles });
    return particles;
  }
}
