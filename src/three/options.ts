/**
 * The options of the three.js addon, with every unit and default, and the checks that turn a bad one into a
 * one-line error naming it. Scene-level values are checked by the core's scene schema (its errors name the scene
 * path, which `optionError` turns into the option's name).
 */
import type { Object3D } from 'three';
import { SceneError, type FabricName, type PinEntry, type SolverType, type BendingModel, type StretchSolve, type BendingSolve, type Vec3 } from '../core/index.js';
import type { ColliderShapeOption } from './colliders.js';

/** Where a world simulates: 'auto' (default), 'gpu' (the renderer's WebGPU device) or 'cpu' (a Web Worker). */
export type DrapeBackend = 'auto' | 'gpu' | 'cpu';
export const DRAPE_BACKENDS: readonly DrapeBackend[] = ['auto', 'gpu', 'cpu'];

/**
 * A renderer as the world takes it: three.js `WebGPURenderer`, `WebGLRenderer` or any other. (`object &`: a type
 * whose members are all optional would refuse a `WebGLRenderer`, which has none of them.)
 */
export type RendererLike = object & {
  readonly isWebGPURenderer?: boolean;
  readonly backend?: object;
  init?(): Promise<unknown>;
};

export interface DrapeWorldOptions {
  /**
   * the renderer the cloths are drawn with. A three.js `WebGPURenderer` on a WebGPU device lets the world simulate
   * on that device and draw straight from the solver's buffers; any other (a `WebGLRenderer`, a `WebGPURenderer`
   * on its WebGL2 backend) or none: the CPU worker. Default: none
   */
  renderer?: RendererLike;
  /** where to simulate (see DrapeBackend; the fallback order is in docs/three.md). Default 'auto' */
  backend?: DrapeBackend;
  /** gravity [m/s², y up]. Default [0, −9.81, 0] */
  gravity?: Vec3;
  /** the air: given, it pushes the cloths where it blows and drags on them where they move; not given (the default), no air at all */
  wind?: {
    /** wind speed [m/s], 0 … 30. Default 0 (still air: the drag alone) */
    strength?: number;
    /** direction it blows towards (any length; zero: still air) [-]. Default [1, 0, 0] */
    direction?: Vec3;
    /** random gusts on top of it. Default false */
    gusts?: boolean;
    /** the gusts' seed (the same seed, the same gusts) [-]. Default 1 */
    seed?: number;
  };
  /** the solver; defaults as the scene schema's */
  solver?: {
    /** 'xpbd' (default; CPU and GPU) or 'mass-spring' (CPU only) */
    type?: SolverType;
    /** substeps per 1/60 s frame [-], 1 … 200. Default 20 */
    substeps?: number;
    /** constraint passes per substep [-], 1 … 20. Default 1 */
    iterations?: number;
    /** bending model: 'springs' (default), 'hinges' or 'laplacian' */
    bending?: BendingModel;
    /**
     * keep each cloth from passing through itself and the world's cloths from passing through each other. Default:
     * true when the world has two cloths or more, false for one (it costs a frame several times over on the GPU)
     */
    selfContact?: boolean;
    /**
     * with self-contact, the speed of cloth against cloth it is made to catch [m/s], 0 … 100: the substeps are raised
     * until cloth this fast moves at most the contact distance in one substep, and a grab drags no faster; 0 keeps
     * `substeps`. Default 6
     */
    selfContactSpeed?: number;
    /** fastest a cloth is pushed out of a collider it did not move into [m/s], 0.01 … 100. Default 0.25 */
    depenetrationSpeed?: number;
    /** how the xpbd solver solves its springs: 'gauss-seidel' (default, one at a time) or 'global' (together; CPU only, docs/physics.md) */
    stretch?: StretchSolve;
    /** how the xpbd solver solves the hinges' or the Laplacian's bending: 'gauss-seidel' (default, one stencil at a time) or 'global' (together, exactly; on the CPU and on WebGPU, with the CPU's factor: docs/physics.md) */
    bendingSolve?: BendingSolve;
  };
  /** a floor plane at this height [m] besides the colliders. Default: none */
  floor?: number | null;
  /**
   * step by itself: the world runs its own requestAnimationFrame loop calling `update()` with the time measured.
   * Default false (call `update(dt)` from your own loop)
   */
  autoUpdate?: boolean;
  /** called with a one-line message when the simulation reports an error. Default: console.error */
  onError?: (message: string) => void;
}

/** A pin: fixed in the world, or attached to an object it then follows. */
export type DrapePin =
  /** a particle of the cloth (counted from its first), a preset ('top-left', 'top-edge'…) or a region {min, max} of start positions [m] */
  | PinEntry
  /** those particles, carried by `to` (any Object3D, a collider's mesh or not): they keep their offset from it */
  | { at: PinEntry; to: Object3D };

export interface DrapeClothOptions {
  /**
   * the cloth's own triangles: a `BufferGeometry` (positions in metres; indexed or not: the core welds duplicate
   * vertices; uvs kept), placed by `position`, `rotation` and `scale` (the centre of its bounding box at `position`).
   * Default: none, a generated `shape`
   */
  geometry?: import('three').BufferGeometry;
  /** a generated shape when there is no geometry: 'rectangle' (default), 'disc' or 'tube' */
  shape?: 'rectangle' | 'disc' | 'tube';
  /** a rectangle's extent along x; a disc's or tube's diameter [m]. Default 1 */
  width?: number;
  /** a rectangle's other extent (z when horizontal, y when hanging); a tube's length [m]. Default 1 */
  height?: number;
  /** faces per side of a rectangle; across a disc; along a tube's longer side [-], 1 … 1024. Default 32 */
  resolution?: number;
  /** a generated shape lies in the xz plane ('horizontal', default) or hangs in the xy plane ('hanging') */
  orientation?: 'horizontal' | 'hanging';
  /** where the cloth's centre starts [m]. Default [0, 1, 0] */
  position?: Vec3;
  /** extra rotation about its centre, Euler angles about x, then y, then z (three.js order 'ZYX') [degrees]. Default [0, 0, 0] */
  rotation?: Vec3;
  /** metres per unit of `geometry` [m]. Default 1 */
  scale?: number;
  /** how far the cloth keeps from colliders and other cloths [m], 0 … 0.1. Default 0.005 */
  thickness?: number;
  /** the fabric whose measured values fill what `fabricValues` leaves out: 'cotton' (default), 'silk', 'denim', 'wool', 'leather', 'rubber' */
  fabric?: FabricName;
  /** the fabric's values, each instead of the fabric's (units: docs/three.md, from the scene schema) */
  fabricValues?: {
    /** mass per area [kg/m²] */ arealDensity?: number;
    /** tensile stiffness [N/m] */ structuralStiffness?: number;
    /** in-plane shear stiffness [N/m] */ shearStiffness?: number;
    /** bending rigidity per unit width [N·m] */ bendingRigidity?: number;
    /** damping along every spring [N·s/m] */ damping?: number;
    /** longest a spring may get, × its rest length [-] */ stretchFactor?: number;
    /** kinetic friction against colliders [-] */ friction?: number;
    /** static friction against colliders [-] */ staticFriction?: number;
  };
  /** pins. Default none */
  pins?: DrapePin[];
  /** the three.js material it is drawn with. Default: a double-sided MeshStandardMaterial (disposed with the world) */
  material?: import('three').Material;
  /** the mesh's name (and the cloth's in errors). Default 'cloth k', k counting the cloths added before it */
  name?: string;
}

export interface DrapeColliderOptions {
  /** the collider's shape; 'auto' (default) infers it from the geometry (docs/three.md) */
  shape?: ColliderShapeOption;
  /** follow the mesh's world transform each update (translation and rotation; its scale is read once). Default true */
  follow?: boolean;
}

/** Throws a TypeError naming `field` of `where` unless `value` is one of `allowed` (or undefined). */
export function checkOneOf<T>(where: string, field: string, value: unknown, allowed: readonly T[]): void {
  if (value !== undefined && !allowed.includes(value as T)) {
    throw new TypeError(`${where}: ${field} must be ${allowed.map((a) => `'${String(a)}'`).join(', ')}, got ${JSON.stringify(value)}`);
  }
}

/** Throws a TypeError naming `field` unless `value` is an object (or undefined). */
export function checkObject(where: string, field: string, value: unknown): void {
  if (value !== undefined && (value === null || typeof value !== 'object' || Array.isArray(value))) {
    throw new TypeError(`${where}: ${field} must be an object, got ${value === null ? 'null' : Array.isArray(value) ? 'an array' : typeof value}`);
  }
}

/**
 * A scene error (its message "source: path: what") as the option's: `cloths[0].cloth.resolution` is the cloth's
 * `resolution`, `cloths[0].material.damping` its `fabricValues.damping`, `cloths[0].pins[2]` its `pins[2]`.
 */
export function optionError(e: unknown): unknown {
  if (!(e instanceof SceneError)) return e;
  const message = e.message
    .replace(/cloths\[\d+\]\.cloth\.|(?<![\w.])cloth\./g, '')
    .replace(/cloths\[\d+\]\.material\.|(?<![\w.])material\./g, 'fabricValues.')
    .replace(/cloths\[\d+\]\.pins/g, 'pins')
    .replace(/fabricValues\.fabric\b/g, 'fabric')
    // the world's wind options are flat: its gusts' seed and switch are wind.seed and wind.gusts
    .replace(/\bwind\.gusts\.seed\b/g, 'wind.seed').replace(/\bwind\.gusts\.enabled\b/g, 'wind.gusts');
  return new SceneError(message);
}
