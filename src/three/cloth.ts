/**
 * One cloth of a DrapeWorld as a `THREE.Mesh`: the user adds it to their scene and draws it with their camera and
 * renderer. Its vertices are the simulated particles in world coordinates, so it belongs in the scene itself (or
 * under parents that do not move it); its geometry is made and refreshed by its world's ClothDrawing
 * (cloth-drawing.ts): triangles indexed from the cloth's first particle into attributes every cloth of the world
 * shares — filled from the worker's positions on the CPU path, the solver's own buffers on the GPU path. The app's
 * cloths are DrapeCloths too, drawn the same way (src/render/cloth-view.ts).
 */
import { BufferGeometry, DoubleSide, Mesh, MeshStandardMaterial, type Material } from 'three';
import type { ClothEntry, ClothModel, DeepPartial } from '../core/index.js';
import { ClothDrawing } from './cloth-drawing.js';

/** The world's side of a cloth: what it was made from, and where its particles are in the world's model. */
export interface ClothPart {
  /** the cloth's scene entry as given (shape, start pose, material, fixed pins; the schema fills the rest) */
  readonly entry: DeepPartial<ClothEntry>;
  /** the cloth alone, as the core builds it (its particles, triangles, uvs) */
  readonly model: ClothModel;
}

export class DrapeCloth extends Mesh<BufferGeometry, Material | Material[]> {
  /** whether the world made the material (and so disposes it) */
  private readonly ownMaterial: boolean;
  /** the cloth's first particle in the model it is drawn from (its world's; set by its ClothDrawing) */
  start = 0;
  /** its drawing alone, at its start pose, until a world draws it with its other cloths */
  private solo: ClothDrawing | null = null;
  /** the positions the cloth was last drawn or read back with [m], xyz per particle (see `positions`) */
  private readonly latest: Float32Array;

  /**
   * @internal made by DrapeWorld.addCloth (and the app's views); `alone` false: no drawing of its own at its start
   * pose (a ClothDrawing draws it at once)
   */
  constructor(readonly part: ClothPart, material: Material | undefined, name: string, alone = true) {
    super(new BufferGeometry(), material ?? new MeshStandardMaterial({ color: 0xd7dde8, roughness: 0.85, side: DoubleSide }));
    this.ownMaterial = material === undefined;
    this.name = name;
    this.latest = new Float32Array(part.model.restPositions);
    // the vertices move every frame, anywhere: no bounds to cull by
    this.frustumCulled = false;
    // until its world simulates it: drawn alone, at its start pose
    if (alone) this.solo = new ClothDrawing(part.model, [this]);
  }

  /** particles of the cloth [-] */
  get particleCount(): number {
    return this.part.model.particleCount;
  }

  /**
   * The cloth's particle positions [m], xyz interleaved, world coordinates: as of the last frame drawn on the CPU
   * path, as of the last readback (at most ~0.1 s old) on the GPU path. Read-only; the world overwrites it.
   */
  get positions(): Float32Array {
    return this.latest;
  }

  /**
   * @internal Drawn as the cloth starting at particle `start` of a ClothDrawing's model, by `geometry` (over the
   * drawing's attributes). The drawing it had alone, before its world simulated it, is freed.
   */
  draw(start: number, geometry: BufferGeometry): void {
    const solo = this.solo;
    this.solo = null;
    solo?.dispose();
    this.start = start;
    this.geometry = geometry;
  }

  /** @internal The drawing's model's positions [m] (all its particles, xyz): the cloth's own are kept as `positions`. */
  take(world: Float32Array): void {
    this.latest.set(world.subarray(3 * this.start, 3 * (this.start + this.part.model.particleCount)));
  }

  /**
   * @internal Frees its drawing alone if it still has it (a world's drawing is the world's to free:
   * ClothDrawing.dispose), and the material when the world made it.
   */
  disposeCloth(): void {
    this.solo?.dispose();
    this.solo = null;
    if (this.ownMaterial) (this.material as Material).dispose();
  }
}
