/**
 * The meshes imported into the page: each file's parsed triangle mesh, keyed by the file's name, and the resolver
 * the core's Simulation takes for a scene whose cloth is a mesh (`cloth.mesh`). The page keeps one store (filled by
 * the mesh import); the worker keeps its own, filled by the page's `mesh` messages before a scene that names one.
 * A link cannot carry a mesh: a scene naming one that is not here is refused with a message saying which file to
 * import. No DOM here: unit-tested in meshes.test.ts, and loaded by the worker too.
 */
import { SceneError, parseMeshFile, plainText, prepareMesh, type MeshResolver, type Scene, type TriangleMesh } from '../core/index.js';

/** One imported mesh file. */
export interface MeshEntry {
  /** the file's name, as the scene's cloth.mesh names it */
  readonly name: string;
  /** the mesh as the file holds it (the core welds and checks it when it builds a model, as for the CLI) */
  readonly mesh: TriangleMesh;
  /** particles of the cloth it makes (after welding duplicate vertices and dropping unused ones) */
  readonly particles: number;
}

/** the last part of a path: 'garments/tshirt.obj' and 'C:\\x\\tshirt.obj' both name 'tshirt.obj' */
export function baseName(path: string): string {
  return path.slice(Math.max(path.lastIndexOf('/'), path.lastIndexOf('\\')) + 1);
}

/** The mesh file name a scene's cloth is made from, or null when its cloth is a generated shape. */
export function sceneMesh(scene: Scene): string | null {
  return scene.cloth.shape === 'mesh' && scene.cloth.mesh !== undefined ? scene.cloth.mesh : null;
}

/** the words asking for a mesh file that is not here */
export function missingMesh(path: string): string {
  const name = plainText(baseName(path) || path, 200);
  return `cloth.mesh: '${plainText(path, 200)}' is a mesh file that is not imported in this page: import the mesh file ${name} too (Scene & export → import mesh…)`;
}

/**
 * Reads a mesh file's bytes as the app imports it: parsed by its extension (.obj, .gltf with embedded buffers,
 * .glb) and checked as the core will build it (manifold, not degenerate, not too many vertices), so that a bad file
 * is refused at once, naming the file. Throws SceneError.
 */
export function readMeshFile(bytes: Uint8Array, name: string): MeshEntry {
  const mesh = parseMeshFile(bytes, name);
  const prepared = prepareMesh(mesh, plainText(name, 200));
  return { name, mesh, particles: prepared.positions.length / 3 };
}

/** Imported meshes by file name. */
export class MeshStore {
  private readonly entries = new Map<string, MeshEntry>();

  /** Adds (or replaces) a mesh under its file's name; returns what was there before (to put back on a refusal). */
  add(entry: MeshEntry): MeshEntry | undefined {
    const before = this.entries.get(entry.name);
    this.entries.set(entry.name, entry);
    return before;
  }

  /** Puts back what `add` replaced (undefined: the name had no mesh before). */
  restore(name: string, before: MeshEntry | undefined): void {
    if (before) this.entries.set(name, before);
    else this.entries.delete(name);
  }

  /**
   * The mesh a scene's `cloth.mesh` path names: the file of that name, else the file of its last part (a scene
   * file's 'garments/tshirt.obj' is the imported 'tshirt.obj'). Undefined when there is none.
   */
  find(path: string): MeshEntry | undefined {
    return this.entries.get(path) ?? this.entries.get(baseName(path));
  }

  has(path: string): boolean {
    return this.find(path) !== undefined;
  }

  get size(): number {
    return this.entries.size;
  }

  /** The resolver for the core's Simulation: the mesh, or a SceneError saying which file to import. */
  readonly resolve: MeshResolver = (path) => {
    const e = this.find(path);
    if (!e) throw new SceneError(missingMesh(path));
    return e.mesh;
  };

  /** Particles of the cloth a mesh path makes (for the backends' caps); a SceneError when it is not imported. */
  particles(path: string): number {
    const e = this.find(path);
    if (!e) throw new SceneError(missingMesh(path));
    return e.particles;
  }
}
