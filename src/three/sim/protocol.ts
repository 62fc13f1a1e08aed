/**
 * Messages between the page (src/app/sim-client.ts) and the simulation worker (src/app/sim.worker.ts).
 *
 * The worker holds one Simulation per "slot" (one cloth; the Mesh Resolution scene side by side has seven). The
 * page never steps physics: it sends commands and renders the positions the worker sends back. Messages are
 * handled in order, so a command sent before an `advance` applies before those frames are stepped.
 */
import type { ColliderPose, Energy, ParticleRange, Scene } from '../../core/index.js';
import type { MeshEntry } from './meshes.js';

export type ToWorker =
  /**
   * an imported mesh file, sent before the first scene that names it (a scene's cloth.mesh or colliders[k].mesh
   * resolves to it in the worker as in the page); a later one of the same name replaces it
   */
  | { type: 'mesh'; entry: MeshEntry }
  /** replace every slot with a fresh Simulation of each scene */
  | { type: 'load'; gen: number; scenes: Scene[] }
  /** change one slot's scene (Simulation.setScene: rebuilds only when the geometry changed) */
  | { type: 'setScene'; gen: number; slot: number; scene: Scene; carry: ParticleRange[] }
  /** restart slots at their start pose (all when slot is undefined); frames of older generations are dropped */
  | { type: 'reset'; gen: number; slot?: number }
  /** step every slot `frames` frames of 1/60 s and answer with a `frame` message */
  | { type: 'advance'; id: number; frames: number }
  /** grab (or move the grab of) a particle toward target */
  | { type: 'grab'; slot: number; particle: number; target: [number, number, number] }
  | { type: 'release'; slot: number }
  /** drive collider `index` of a slot from now on (Simulation.setColliderPose; null: back to its scene motion) */
  | { type: 'colliderPose'; slot: number; index: number; pose: ColliderPose | null }
  /** test hook only: makes a particle's position NaN, as a blown-up solver would (see `unstableAt`) */
  | { type: 'poison'; slot: number }
  /** continue a slot from another backend's state (GPU → CPU after a device loss or a backend switch) */
  | {
    type: 'setState'; slot: number; frame: number; time: number; substeps: number;
    positions: Float32Array; previous: Float32Array; velocities: Float32Array;
  };

export interface SlotFrame {
  /** generation of the model these positions belong to (see SimClient) */
  gen: number;
  /** frames stepped since the slot's (re)start */
  frame: number;
  positions: Float32Array;
  pinned: Uint8Array;
  grabbed: number;
  /**
   * frame at which the cloth's positions stopped being finite numbers (-1: they are finite). Such a slot is no
   * longer stepped, and its positions are not to be drawn or exported; a reset or rebuild starts it again.
   */
  unstableAt: number;
}

export type FromWorker =
  | {
    type: 'frame';
    /** id of the `advance` this answers */
    id: number;
    /** frames stepped for this answer (0 when only the state was requested) */
    frames: number;
    slots: SlotFrame[];
    /** wall time of the stepping, per frame, summed over slots [ms] */
    stepMs: number;
    /** energy of slot 0 (or summed over slots) [J] */
    energy: Energy;
    maxStrain: number;
    clamps: string[];
    /** CPU kernel of slot 0: 'wasm' (WebAssembly SIMD) or 'ts' */
    kernel: string;
    /** threads sharing slot 0's substeps now (1 until helper threads have started) */
    threads: number;
  }
  | { type: 'error'; message: string };
