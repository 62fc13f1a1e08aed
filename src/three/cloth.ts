/**
 * One cloth of a DrapeWorld as a `THREE.Mesh`: the user adds it to their scene and draws it with their camera and
 * renderer. Its vertices are the simulated particles in world coordinates, so it belongs in the scene itself (or
 * under parents that do not move it); its geometry is made and refreshed by its world — on the CPU path from the
 * worker's positions (its own position and normal attributes), on the GPU path straight from the solver's buffers
 * (attributes every cloth of the world shares, vec4, indexed from the cloth's first particle).
 */
import { BufferAttribute, BufferGeometry, DoubleSide, DynamicDrawUsage, Mesh, MeshStandardMaterial, type Material } from 'three';
import type { ClothEntry, ClothModel, DeepPartial } from '../core/index.js';

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
  /** the cloth's first particle in the world's model (set by the world when it builds the simulation) */
  start = 0;
  /** the positions the cloth was last drawn or read back with [m], xyz per particle (see `positions`) */
  private readonly latest: Float32Array;

  /** @internal made by DrapeWorld.addCloth */
  constructor(readonly part: ClothPart, material: Material | undefined, name: string) {
    super(new BufferGeometry(), material ?? new MeshStandardMaterial({ color: 0xd7dde8, roughness: 0.85, side: DoubleSide }));
    this.ownMaterial = material === undefined;
    this.name = name;
    this.latest = new Float32Array(part.model.restPositions);
    // the vertices move every frame, anywhere: no bounds to cull by
    this.frustumCulled = false;
    this.useCpuGeometry();
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

  /** @internal Draws from CPU positions: attributes of its own, refreshed by `setPositions`. */
  useCpuGeometry(): void {
    const { model } = this.part;
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(new Float32Array(this.latest), 3).setUsage(DynamicDrawUsage));
    g.setAttribute('normal', new BufferAttribute(new Float32Array(3 * model.particleCount), 3).setUsage(DynamicDrawUsage));
    g.setAttribute('uv', new BufferAttribute(new Float32Array(model.uvs), 2));
    g.setIndex(new BufferAttribute(new Uint32Array(model.triangles), 1));
    g.computeVertexNormals();
    this.replaceGeometry(g);
  }

  /**
   * @internal Draws from the world's shared vec4 position and normal attributes (the GPU solver's buffers once
   * attached), its triangles indexed from its first particle.
   */
  useGpuGeometry(position: BufferAttribute, normal: BufferAttribute): void {
    const { model } = this.part;
    const g = new BufferGeometry();
    g.setAttribute('position', position);
    g.setAttribute('normal', normal);
    // the uvs of every particle of the world, its own at its place (the shared attributes index the whole model)
    const uv = new Float32Array(2 * position.count);
    uv.set(model.uvs, 2 * this.start);
    g.setAttribute('uv', new BufferAttribute(uv, 2));
    const tri = new Uint32Array(model.triangles.length);
    for (let k = 0; k < tri.length; k++) tri[k] = model.triangles[k] + this.start;
    g.setIndex(new BufferAttribute(tri, 1));
    this.replaceGeometry(g);
  }

  /** @internal The world's positions [m] (all its particles, xyz): the cloth's own are copied and drawn (CPU path). */
  setPositions(world: Float32Array, draw: boolean): void {
    const n = this.part.model.particleCount;
    this.latest.set(world.subarray(3 * this.start, 3 * (this.start + n)));
    if (!draw) return;
    const position = this.geometry.getAttribute('position') as BufferAttribute;
    (position.array as Float32Array).set(this.latest);
    position.needsUpdate = true;
    this.geometry.computeVertexNormals();
    this.geometry.boundingSphere = null;
  }

  private replaceGeometry(g: BufferGeometry): void {
    const old = this.geometry;
    this.geometry = g;
    // (the world replaces every cloth's GPU geometry at once, when the solver its shared attributes drew from is gone)
    old.dispose();
  }

  /** @internal Frees the geometry, and the material when the world made it. */
  disposeCloth(): void {
    this.geometry.dispose();
    if (this.ownMaterial) (this.material as Material).dispose();
  }
}
