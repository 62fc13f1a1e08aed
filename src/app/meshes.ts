/**
 * The meshes imported into the page: each file's parsed triangle mesh, keyed by the file's name, and the resolver
 * the core's Simulation takes for a scene that names mesh files — its cloths (`cloth.mesh`, `cloths[k].cloth.mesh`)
 * and its mesh colliders (`colliders[k].mesh`). The page keeps one store (filled by the mesh import); the worker keeps its own, filled by
 * the page's `mesh` messages before a scene that names one. A link cannot carry a mesh: a scene naming one that is
 * not here is refused with a message naming the field and saying which file to import. No DOM here: unit-tested in
 * meshes.test.ts, and loaded by the worker too.
 */
import {
  SceneError, clothEntries, clothPath, parseMeshFile, plainText, prepareMesh, type ClothSpec, type MeshResolver, type Scene, type TriangleMesh,
} from '../core/index.js';

/** One imported mesh file. */
export interface MeshEntry {
  /** the file's name, as the scene's cloth.mesh names it */
  readonly name: string;
  /** the mesh as the file holds it (the core welds and checks it when it builds a model, as for the CLI) */
  readonly mesh: TriangleMesh;
  /**
   * particles of the cloth it makes (after welding duplicate vertices and dropping unused ones); absent for a file
   * imported for a collider until a scene makes it a cloth (MeshStore.particles counts it then)
   */
  readonly particles?: number;
}

/** A mesh file checked as a cloth: its particles are counted. */
export type ClothEntry = MeshEntry & { readonly particles: number };

/** One mesh file a scene names: the field that names it and the path it gives. */
export interface SceneMeshFile {
  /** 'cloth.mesh', 'cloths[k].cloth.mesh' or 'colliders[k].mesh' */
  readonly field: string;
  readonly path: string;
  /** k of a mesh collider's file (absent for a cloth's) */
  readonly collider?: number;
  /** k of a cloth's file (of clothEntries; absent for a collider's) */
  readonly cloth?: number;
}

/** the last part of a path: 'garments/tshirt.obj' and 'C:\\x\\tshirt.obj' both name 'tshirt.obj' */
export function baseName(path: string): string {
  return path.slice(Math.max(path.lastIndexOf('/'), path.lastIndexOf('\\')) + 1);
}

/** Whether a scene's mesh path names the imported file `name` (by its whole path or its last part, as MeshStore.find). */
export function namesFile(path: string, name: string): boolean {
  return path === name || baseName(path) === name;
}

/** The mesh file name a cloth is made from, or null when it is a generated shape. */
export function clothMesh(cloth: ClothSpec): string | null {
  return cloth.shape === 'mesh' && cloth.mesh !== undefined ? cloth.mesh : null;
}

/** Every mesh file a scene names: its cloths', in their order, then its mesh colliders'. */
export function sceneMeshes(scene: Scene): SceneMeshFile[] {
  const files: SceneMeshFile[] = [];
  clothEntries(scene).forEach((e, k) => {
    const path = clothMesh(e.cloth);
    if (path !== null) files.push({ field: clothPath(scene, k, 'cloth.mesh'), path, cloth: k });
  });
  scene.colliders.forEach((c, k) => { if (c.type === 'mesh') files.push({ field: `colliders[${k}].mesh`, path: c.mesh, collider: k }); });
  return files;
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

  /**
   * The resolver for the core's Simulation: the mesh, or a SceneError saying which file to import (without a field:
   * the core names colliders[k].mesh before it; a cloth's is asked for by `particles`, before any model is built).
   */
  readonly resolve: MeshResolver = (path) => {
    const e = this.find(path);
    if (!e) throw new SceneError(notImported(path));
    return e.mesh;
  };

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
