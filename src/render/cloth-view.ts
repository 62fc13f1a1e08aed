/**
 * Draws one model in the six views ('V' cycles them): shaded, wireframe, particles, springs coloured by kind, a
 * strain heat map and the self-contacts; plus markers for pinned particles and the grabbed one. The cloths themselves
 * are the addon's: a DrapeCloth per cloth of the model (a scene's `cloths`), shaded with its own fabric's look and
 * drawn by a ClothDrawing as a DrapeWorld draws its cloths (src/three/cloth-drawing.ts), from the CPU state or the
 * GPU solver's buffers. Reads a model and a state; never changes them.
 */
import {
  BufferAttribute, BufferGeometry, Color, DoubleSide, DynamicDrawUsage, Group, IcosahedronGeometry, InstancedMesh,
  LineBasicNodeMaterial, LineSegments, Mesh, MeshPhysicalNodeMaterial, MeshStandardNodeMaterial, Object3D,
  SphereGeometry,
} from 'three/webgpu';
import { BEND, selfContacts, STRUCTURAL, type ClothEntry, type ClothModel, type ClothState, type FabricKind } from '../core/index.js';
import { DrapeCloth } from '../three/cloth.js';
import { ClothDrawing } from '../three/cloth-drawing.js';
import type { AttributeBuffers } from '../three/sim/solver-buffers.js';
import type { FabricLook } from './textures.js';

export const VIEWS = ['shaded', 'wireframe', 'particles', 'springs', 'strain', 'contacts'] as const;
export type ViewName = (typeof VIEWS)[number];
export const VIEW_LABELS: Record<ViewName, string> = {
  shaded: 'Shaded',
  wireframe: 'Wireframe mesh',
  particles: 'Particles',
  springs: 'Springs by kind',
  strain: 'Strain heat map',
  contacts: 'Self-contacts',
};

/** the contact view's colours: a particle lying on another part of the cloth, and one that is not */
export const CONTACT_COLOR = '#e0432d';
const FREE_COLOR = new Color('#d9dde3');
const IN_CONTACT = new Color(CONTACT_COLOR);

/** spring colours by kind: structural, shear, bend */
export const SPRING_COLORS = ['#2f6fd6', '#2ea043', '#e0832d'] as const;
/** strain shown at full colour [-]: woven fabrics stretch a few per cent at most */
export const STRAIN_RANGE = 0.02;

const tmpColor = new Color();

/** Diverging map: compression blue, rest near white, stretch yellow → red. */
export function strainColor(e: number, out: Color): Color {
  const t = Math.max(-1, Math.min(1, e / STRAIN_RANGE));
  if (t < 0) return out.setRGB(1 + 0.85 * t, 1 + 0.6 * t, 1 + 0.05 * t, 'srgb');
  if (t < 0.5) { const u = t / 0.5; return out.setRGB(1, 1 - 0.15 * u, 1 - 0.85 * u, 'srgb'); }
  const u = (t - 0.5) / 0.5;
  return out.setRGB(1 - 0.2 * u, 0.85 - 0.75 * u, 0.15 - 0.1 * u, 'srgb');
}

/** One cloth of a slot's model, as the view draws it. */
export interface ViewCloth {
  /** its scene entry (clothEntries) */
  readonly entry: ClothEntry;
  /** its name (clothName) */
  readonly name: string;
  /** its fabric's look in the shaded view */
  readonly look: FabricLook;
}

export class ClothView {
  readonly group = new Group();
  /** the cloths, as the addon draws a world's (drape/three's DrapeCloth, ClothDrawing): one per cloth of the model */
  readonly cloths: readonly DrapeCloth[];
  private readonly drawing: ClothDrawing;
  /** one per cloth of the model, in its order */
  private readonly shadedMaterials: MeshPhysicalNodeMaterial[];
  private readonly strainMaterial: MeshStandardNodeMaterial;
  private readonly wire: LineSegments;
  private readonly springs: LineSegments;
  private readonly springPos: BufferAttribute;
  private readonly points: InstancedMesh;
  private pins: InstancedMesh;
  private readonly grabMarker: Mesh;
  private view: ViewName = 'shaded';
  private readonly strainSum: Float32Array;
  private readonly strainCount: Uint16Array;
  /** the contact view: how near another part of the cloth a particle must be to be marked [m], and the marks */
  private contactDistance = 0;
  private readonly contactFlags: Uint8Array;
  /** the particles the contact view marked at its last update */
  contacts = 0;

  /**
   * `gpu`: the cloths will be drawn from a GpuClothSolver's buffers (attachGpu). `cloths`: one per cloth of the
   * model (model.clothStarts), in its order.
   */
  constructor(readonly model: ClothModel, cloths: readonly ViewCloth[], readonly gpu = false) {
    const n = model.particleCount, count = model.clothStarts.length - 1;
    if (cloths.length !== count) throw new RangeError(`${cloths.length} cloths to view a model of ${count}`);
    this.shadedMaterials = cloths.map(({ look }) => new MeshPhysicalNodeMaterial({
      map: look.map, roughness: look.roughness, metalness: 0, side: DoubleSide,
      sheen: look.sheen, sheenRoughness: 0.6, sheenColor: new Color(look.sheenColor), clearcoat: look.clearcoat,
      clearcoatRoughness: 0.4, userData: { look: look.kind },
    }));
    this.cloths = cloths.map((c, k) => {
      const cloth = new DrapeCloth({ entry: c.entry, model: model.clothParts?.[k] ?? model }, this.shadedMaterials[k], c.name, false);
      cloth.castShadow = true;
      cloth.receiveShadow = true;
      return cloth;
    });
    // the strain and contact views colour the particles (the drawing's colour attribute)
    this.drawing = new ClothDrawing(model, this.cloths, { gpu, colors: true });
    this.strainMaterial = new MeshStandardNodeMaterial({ vertexColors: true, roughness: 0.8, side: DoubleSide });

    // wireframe: each triangle edge once, sharing the cloth's positions
    const edges = new Set<number>();
    const tri = model.triangles;
    const edgeList: number[] = [];
    for (let k = 0; k < tri.length; k += 3) {
      for (let e = 0; e < 3; e++) {
        const a = tri[k + e], b = tri[k + ((e + 1) % 3)];
        const key = a < b ? a * n + b : b * n + a;
        if (!edges.has(key)) { edges.add(key); edgeList.push(a, b); }
      }
    }
    const wg = new BufferGeometry();
    wg.setAttribute('position', this.drawing.position);
    wg.setIndex(new BufferAttribute(new Uint32Array(edgeList), 1));
    this.wire = new LineSegments(wg, new LineBasicNodeMaterial({ color: 0x26303d }));
    this.wire.frustumCulled = false;

    // springs: two vertices per spring so each can carry its kind's colour
    const sCount = model.restLengths.length;
    const sg = new BufferGeometry();
    this.springPos = new BufferAttribute(new Float32Array(6 * sCount), 3).setUsage(DynamicDrawUsage);
    const sCol = new Float32Array(6 * sCount);
    const kindColors = SPRING_COLORS.map((c) => new Color(c));
    for (let s = 0; s < sCount; s++) {
      const c = kindColors[model.springKinds[s]];
      sCol.set([c.r, c.g, c.b, c.r, c.g, c.b], 6 * s);
    }
    sg.setAttribute('position', this.springPos);
    sg.setAttribute('color', new BufferAttribute(sCol, 3));
    this.springs = new LineSegments(sg, new LineBasicNodeMaterial({ vertexColors: true }));
    this.springs.frustumCulled = false;

    const spacing = this.spacing();
    this.points = new InstancedMesh(
      new IcosahedronGeometry(Math.min(0.012, spacing * 0.22), 1),
      new MeshStandardNodeMaterial({ color: 0x33485f, roughness: 0.5 }), n,
    );
    this.points.frustumCulled = false;
    this.points.castShadow = true;
    const o = new Object3D();
    for (let i = 0; i < n; i++) { o.position.set(0, 0, 0); o.updateMatrix(); this.points.setMatrixAt(i, o.matrix); }

    this.pins = this.makePins(16);
    this.grabMarker = new Mesh(
      new SphereGeometry(0.022, 16, 12),
      new MeshStandardNodeMaterial({ color: 0x1e88e5, emissive: new Color(0x0d47a1), roughness: 0.3 }),
    );
    this.grabMarker.visible = false;

    this.contactFlags = new Uint8Array(n);
    this.strainSum = new Float32Array(n);
    this.strainCount = new Uint16Array(n);
    for (let s = 0; s < sCount; s++) {
      if (model.springKinds[s] === BEND) continue;
      this.strainCount[model.springs[2 * s]]++;
      this.strainCount[model.springs[2 * s + 1]]++;
    }

    this.group.add(...this.cloths, this.wire, this.springs, this.points, this.pins, this.grabMarker);
    this.setView('shaded');
  }

  /** typical particle spacing [m] */
  spacing(): number {
    const rest = this.model.restLengths;
    for (let s = 0; s < rest.length; s++) if (this.model.springKinds[s] === STRUCTURAL) return rest[s];
    return 0.03;
  }

  private makePins(capacity: number): InstancedMesh {
    const r = Math.max(0.014, Math.min(0.03, this.spacing() * 0.45));
    const m = new InstancedMesh(
      new SphereGeometry(r, 16, 12),
      new MeshStandardNodeMaterial({ color: 0xd93a2b, emissive: new Color(0x5a0d07), roughness: 0.35 }),
      capacity,
    );
    m.count = 0;
    m.frustumCulled = false;
    m.castShadow = true;
    m.name = 'pins';
    return m;
  }

  setView(view: ViewName): void {
    this.view = view;
    const colours = view === 'strain' || view === 'contacts';
    this.cloths.forEach((c, k) => {
      c.visible = view === 'shaded' || colours;
      c.material = colours ? this.strainMaterial : this.shadedMaterials[k];
    });
    this.wire.visible = view === 'wireframe';
    this.springs.visible = view === 'springs';
    this.points.visible = view === 'particles';
  }

  /** Each cloth's look (one per cloth, as the constructor's): a cloth whose fabric changed is shaded anew. */
  setLooks(looks: readonly FabricLook[]): void {
    looks.forEach((look, c) => {
      const m = this.shadedMaterials[c];
      if (!m || m.userData.look === look.kind) return;
      m.userData.look = look.kind;
      m.map = look.map;
      m.roughness = look.roughness;
      m.sheen = look.sheen;
      m.sheenColor.set(look.sheenColor);
      m.clearcoat = look.clearcoat;
      m.needsUpdate = true;
    });
  }

  /** What the shaded view draws for each cloth: its look and its triangles. */
  get drawnCloths(): { look: FabricKind; triangles: number }[] {
    return this.cloths.map((c, k) => ({ look: this.shadedMaterials[k].userData.look as FabricKind, triangles: c.geometry.getIndex()!.count / 3 }));
  }

  /**
   * Draws the cloths from a GPU solver's position and normal buffers (`array<vec4f>`, VERTEX usage) on the
   * renderer's WebGPU backend (ClothDrawing.attach): the shaded, strain, contact and wireframe views then never
   * touch positions on the CPU. Dispose the view and the solver together.
   */
  attachGpu(backend: AttributeBuffers, positions: GPUBuffer, normals: GPUBuffer): void {
    this.drawing.attach(backend, positions, normals);
  }

  get attached(): boolean {
    return this.drawing.attached;
  }

  /** whether the current view draws from CPU positions (springs, particles, strain and contact colours) */
  get needsCpuPositions(): boolean {
    return this.view === 'springs' || this.view === 'particles' || this.view === 'strain' || this.view === 'contacts';
  }

  /**
   * The contact view marks the particles within `distance` [m] of a triangle not their own (core selfContacts: the
   * app gives 1.5 × the self-contact distance, where a particle resting on another layer sits).
   */
  setContactDistance(distance: number): void {
    this.contactDistance = distance;
  }

  /** Copies the state into the GPU buffers of the current view. */
  update(state: ClothState, grabbed: number): void {
    const x = state.positions;
    const model = this.model;
    this.drawing.update(x, this.view === 'shaded' || this.view === 'strain' || this.view === 'contacts');
    if (this.view === 'strain') this.updateStrain(x);
    if (this.view === 'contacts') this.updateContacts(x);
    if (this.view === 'springs') {
      const sp = model.springs, out = this.springPos.array as Float32Array;
      for (let s = 0; s < model.restLengths.length; s++) {
        const a = 3 * sp[2 * s], b = 3 * sp[2 * s + 1], o = 6 * s;
        out[o] = x[a]; out[o + 1] = x[a + 1]; out[o + 2] = x[a + 2];
        out[o + 3] = x[b]; out[o + 4] = x[b + 1]; out[o + 5] = x[b + 2];
      }
      this.springPos.needsUpdate = true;
    }
    if (this.view === 'particles') {
      const m = this.points.instanceMatrix.array as Float32Array;
      for (let i = 0; i < model.particleCount; i++) {
        m[16 * i + 12] = x[3 * i]; m[16 * i + 13] = x[3 * i + 1]; m[16 * i + 14] = x[3 * i + 2];
      }
      this.points.instanceMatrix.needsUpdate = true;
    }
    this.updatePins(state);
    if (grabbed >= 0 && grabbed < model.particleCount) {
      this.grabMarker.visible = true;
      this.grabMarker.position.set(x[3 * grabbed], x[3 * grabbed + 1], x[3 * grabbed + 2]);
    } else {
      this.grabMarker.visible = false;
    }
  }

  private updatePins(state: ClothState): void {
    const pinned = state.pinned, x = state.positions;
    let count = 0;
    for (let i = 0; i < pinned.length; i++) if (pinned[i]) count++;
    if (count > this.pins.instanceMatrix.count) {
      this.group.remove(this.pins);
      this.pins.geometry.dispose();
      this.pins.dispose();
      this.pins = this.makePins(Math.max(count, 2 * this.pins.instanceMatrix.count));
      this.group.add(this.pins);
    }
    const m = this.pins.instanceMatrix.array as Float32Array;
    let k = 0;
    for (let i = 0; i < pinned.length; i++) {
      if (!pinned[i]) continue;
      // a translation (no array made per pinned particle per frame: the cantilever pins hundreds)
      const o = 16 * k;
      m.fill(0, o, o + 16);
      m[o] = 1; m[o + 5] = 1; m[o + 10] = 1; m[o + 15] = 1;
      m[o + 12] = x[3 * i]; m[o + 13] = x[3 * i + 1]; m[o + 14] = x[3 * i + 2];
      k++;
    }
    this.pins.count = count;
    this.pins.instanceMatrix.needsUpdate = true;
  }

  private updateContacts(x: Float32Array): void {
    const model = this.model, flags = this.contactFlags;
    this.contacts = selfContacts(model.triangles, x, model.particleCount, this.contactDistance, flags);
    const color = this.drawing.color!, col = color.array as Float32Array;
    for (let i = 0; i < model.particleCount; i++) {
      const c = flags[i] ? IN_CONTACT : FREE_COLOR;
      col[3 * i] = c.r; col[3 * i + 1] = c.g; col[3 * i + 2] = c.b;
    }
    color.needsUpdate = true;
  }

  private updateStrain(x: Float32Array): void {
    const model = this.model, sp = model.springs, rest = model.restLengths;
    const sum = this.strainSum;
    sum.fill(0);
    for (let s = 0; s < rest.length; s++) {
      if (model.springKinds[s] === BEND) continue;
      const a = sp[2 * s], b = sp[2 * s + 1];
      const dx = x[3 * a] - x[3 * b], dy = x[3 * a + 1] - x[3 * b + 1], dz = x[3 * a + 2] - x[3 * b + 2];
      const e = Math.sqrt(dx * dx + dy * dy + dz * dz) / rest[s] - 1;
      sum[a] += e; sum[b] += e;
    }
    const color = this.drawing.color!, col = color.array as Float32Array;
    for (let i = 0; i < model.particleCount; i++) {
      strainColor(this.strainCount[i] ? sum[i] / this.strainCount[i] : 0, tmpColor);
      col[3 * i] = tmpColor.r; col[3 * i + 1] = tmpColor.g; col[3 * i + 2] = tmpColor.b;
    }
    color.needsUpdate = true;
  }

  dispose(): void {
    this.drawing.dispose();
    this.wire.geometry.dispose();
    this.springs.geometry.dispose();
    this.points.geometry.dispose();
    this.points.dispose();
    this.pins.geometry.dispose();
    this.pins.dispose();
    this.grabMarker.geometry.dispose();
    for (const m of this.shadedMaterials) m.dispose();
    this.strainMaterial.dispose();
    (this.wire.material as LineBasicNodeMaterial).dispose();
    (this.springs.material as LineBasicNodeMaterial).dispose();
  }
}


