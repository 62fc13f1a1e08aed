/**
 * The drawing of one model's cloths — a DrapeWorld's, or one of the app's slots — as DrapeCloth meshes: the one path
 * by which a simulated cloth reaches the screen, for the addon and the app alike.
 *
 * Every cloth's geometry indexes attributes the drawing holds for the whole model: positions and normals (xyz on
 * the CPU path; vec4, the GPU solver's layout, on the GPU path), uvs, and, where asked, vertex colours. On the CPU
 * path the positions are copied in from the driver's state and the normals computed once for every triangle of the
 * model; on the GPU path the solver's buffers take the place of the position and normal attributes' own
 * (`attach`, solver-buffers.ts) and nothing passes through the CPU to be drawn.
 */
import { BufferAttribute, BufferGeometry, DynamicDrawUsage } from 'three';
import type { ClothModel } from '../core/index.js';
import type { DrapeCloth } from './cloth.js';
import { drawFromSolver, type AttributeBuffers } from './sim/solver-buffers.js';

export interface ClothDrawingOptions {
  /** draw from a GPU solver's buffers (vec4 positions and normals, `attach`); default false: from CPU positions */
  readonly gpu?: boolean;
  /** a vertex colour attribute (rgb per particle, white at first) in every cloth's geometry; default false */
  readonly colors?: boolean;
}

export class ClothDrawing {
  /** the model's positions [m]: xyz per particle, or vec4 (w = 0) on the GPU path */
  readonly position: BufferAttribute;
  /** the model's vertex normals [-], as `position` */
  readonly normal: BufferAttribute;
  /** each particle's uv [-] */
  readonly uv: BufferAttribute;
  /** rgb per particle [0–1], when asked for (`colors`) */
  readonly color: BufferAttribute | null;
  readonly gpu: boolean;
  /** every triangle of the model over the shared attributes: where the normals are computed */
  private readonly all: BufferGeometry;
  /** the cloths' geometries, as made (a cloth may be drawn by a newer drawing since) */
  private readonly geometries: BufferGeometry[] = [];
  private attachedToSolver = false;

  /**
   * Draws `model` as `cloths` (cloth k is the model's cloth k, `model.clothStarts`): each cloth's geometry is
   * replaced by one over the drawing's attributes, at the model's rest positions.
   */
  constructor(readonly model: ClothModel, readonly cloths: readonly DrapeCloth[], options: ClothDrawingOptions = {}) {
    const n = model.particleCount, k = model.clothStarts.length - 1;
    if (cloths.length !== k) throw new RangeError(`${cloths.length} cloths to draw a model of ${k}`);
    this.gpu = options.gpu ?? false;
    const stride = this.gpu ? 4 : 3;
    this.position = new BufferAttribute(new Float32Array(stride * n), stride);
    this.normal = new BufferAttribute(new Float32Array(stride * n), stride);
    // on the GPU path, three.js never uploads them once the solver's buffers are in their place
    if (!this.gpu) { this.position.setUsage(DynamicDrawUsage); this.normal.setUsage(DynamicDrawUsage); }
    this.uv = new BufferAttribute(new Float32Array(model.uvs), 2);
    this.color = options.colors ? new BufferAttribute(new Float32Array(3 * n).fill(1), 3).setUsage(DynamicDrawUsage) : null;
    this.all = this.geometry(new Uint32Array(model.triangles));
    cloths.forEach((cloth, c) => {
      const start = model.clothStarts[c], own = model.clothParts?.[c] ?? model;
      if (own.particleCount !== model.clothStarts[c + 1] - start) throw new RangeError(`cloth ${c} has ${own.particleCount} particles, the model ${model.clothStarts[c + 1] - start} there`);
      const tri = new Uint32Array(own.triangles.length);
      for (let t = 0; t < tri.length; t++) tri[t] = own.triangles[t] + start;
      const g = this.geometry(tri);
      this.geometries.push(g);
      cloth.draw(start, g);
    });
    this.update(model.restPositions);
  }

  /** whether the solver's buffers are drawn (`attach`) */
  get attached(): boolean {
    return this.attachedToSolver;
  }

  /**
   * Draws from the GPU solver's position and normal buffers on the renderer's WebGPU backend (once; nothing on the
   * CPU path). three.js destroys those buffers with the attributes: dispose the drawing and the solver together.
   */
  attach(backend: AttributeBuffers, positions: GPUBuffer, normals: GPUBuffer): void {
    if (!this.gpu || this.attachedToSolver) return;
    drawFromSolver(backend, [[this.position, positions], [this.normal, normals]]);
    this.attachedToSolver = true;
  }

  /**
   * Takes the model's positions [m] (xyz per particle, the driver's state): each cloth's `positions` always; the
   * attributes when drawing from the CPU (on the GPU path, until the solver's buffers are attached), with the
   * normals unless `normals` is false (a view that draws no surface).
   */
  update(positions: Float32Array, normals = true): void {
    for (const c of this.cloths) c.take(positions);
    // (a raycaster's bounds are computed again when asked: the cloths move)
    for (const g of this.geometries) g.boundingSphere = null;
    if (this.attachedToSolver) return;
    const n = this.model.particleCount, p = this.position.array as Float32Array;
    if (this.gpu) {
      for (let i = 0; i < n; i++) { p[4 * i] = positions[3 * i]; p[4 * i + 1] = positions[3 * i + 1]; p[4 * i + 2] = positions[3 * i + 2]; }
    } else {
      p.set(positions.subarray(0, 3 * n));
    }
    this.position.needsUpdate = true;
    // (until attached, the GPU path's normals too: its start pose is drawn shaded)
    if (normals || this.gpu) {
      this.all.computeVertexNormals();
      this.normal.needsUpdate = true;
    }
  }

  /** Frees the geometries (the cloths' and its own) and with them the attributes' buffers. */
  dispose(): void {
    this.attachedToSolver = false;
    for (const g of this.geometries) g.dispose();
    this.all.dispose();
  }

  /** a geometry of the given triangles over the drawing's attributes */
  private geometry(triangles: Uint32Array): BufferGeometry {
    const g = new BufferGeometry();
    g.setAttribute('position', this.position);
    g.setAttribute('normal', this.normal);
    g.setAttribute('uv', this.uv);
    if (this.color) g.setAttribute('color', this.color);
    g.setIndex(new BufferAttribute(triangles, 1));
    return g;
  }
}
