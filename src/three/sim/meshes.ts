/**
 * The mesh files a simulation's scenes name — its cloths' (`cloth.mesh`, `cloths[k].cloth.mesh`) and its mesh
 * colliders' (`colliders[k].mesh`) — by name, and the resolver the core's Simulation takes for them. The page keeps
 * one store (the app: its imported files; the three.js addon: the geometries it was given); the worker keeps its
 * own, filled by the page's `mesh` messages before a scene that names one. No DOM here: loaded by the worker too.
 */
import { SceneError, clothEntries, clothPath, plainText, type ClothSpec, type MeshResolver, type Scene, type TriangleMesh } from '../../core/index.js';

/** One mesh file (or geometry) a scene may name. */
export interface MeshEntry {
  /** the name the scene's cloth.mesh or colliders[k].mesh gives */
  readonly name: string;
  /** the mesh as given (the core welds and checks it when it builds a model) */
  readonly mesh: TriangleMesh;
  /**
   * particles of the cloth it makes (after welding duplicate vertices and dropping unused ones); absent for a mesh
   * not yet counted as a cloth
   */
  readonly particles?: number;
}

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

/** Meshes by name. */
export class MeshStore {
  protected readonly entries = new Map<string, MeshEntry>();

  /** `missing`: the words of the SceneError for a path the store lacks (without a field: the core names it) */
  constructor(private readonly missing: (path: string) => string = (path) => `'${plainText(path, 200)}' is a mesh this simulation was not given`) {}

  /** Adds (or replaces) a mesh under its name; returns what was there before (to put back on a refusal). */
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

  /** Forgets a mesh. */
  delete(name: string): void {
    this.entries.delete(name);
  }

  /**
   * The mesh a scene's path names: the entry of that name, else the entry of its last part (a scene file's
   * 'garments/tshirt.obj' is the imported 'tshirt.obj'). Undefined when there is none.
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

  /** The resolver for the core's Simulation: the mesh, or a SceneError with the `missing` words. */
  readonly resolve: MeshResolver = (path) => {
    const e = this.find(path);
    if (!e) throw new SceneError(this.missing(path));
    return e.mesh;
  };
}
