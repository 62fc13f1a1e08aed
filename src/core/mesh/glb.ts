/**
 * Binary glTF 2.0 (.glb) of cloths: one node and one mesh per cloth (named by the cloth) under a root node
 * named by the scene, each mesh one indexed triangle primitive with POSITION, NORMAL and TEXCOORD_0 and its cloth's
 * material (pbrMetallicRoughness, double-sided). A bake adds, to every cloth's mesh, one morph target per baked
 * frame (POSITION and NORMAL as differences from the first shape) and one animation whose channels turn each mesh's
 * weights from one target to the next at the frames' times (LINEAR: between two frames the shape goes linearly from
 * one to the other). Metres, y up, float32 (7 significant digits); never a NaN: non-finite positions are refused.
 * Layout and sizes: docs/architecture.md, "Exported files".
 */
import type { LookMaterial } from '../looks.js';
import type { ClothModel } from '../model.js';
import { plainText, shownValue } from '../text.js';
import { vertexNormals } from './normals.js';

/** A colour texture: a PNG (sRGB), repeated `repeat` times across the cloth's texture coordinates 0…1. */
export interface GlbTexture {
  readonly png: Uint8Array;
  readonly repeat: number;
}

/** A cloth's material: its look's colour and roughness; with a texture, the colour is the texture's (factor white). */
export interface GlbMaterial extends LookMaterial {
  readonly texture?: GlbTexture;
}

/** One cloth: its own vertices and triangles (numbered from 0), its name and material. */
export interface ExportCloth {
  readonly name: string;
  /** cloths given the same material object share it */
  readonly material: GlbMaterial;
  /** the shape written as the mesh [m] (stride 3); a bake's first frame */
  readonly positions: Float32Array;
  /** texture coordinates (stride 2), v from the texture's bottom as OBJ's and the model's */
  readonly uvs: Float32Array;
  readonly triangles: Uint32Array;
  /** a bake's later shapes, one per GlbInput.bake time (stride 3, as many as `positions`) */
  readonly frames?: readonly Float32Array[];
  /** the node's extras (where its particles are in the scene's numbering) */
  readonly extras?: Readonly<Record<string, number>>;
}

/** A bake's frames after the first shape (at time 0): their times and simulation frame numbers. */
export interface GlbBake {
  /** each frame's time [s] from the first shape's, increasing */
  readonly times: readonly number[];
  /** each frame's number in the simulation (the animation's extras) */
  readonly frameNumbers: readonly number[];
}

export interface GlbInput {
  /** the scene's name: the root node's */
  readonly name: string;
  readonly cloths: readonly ExportCloth[];
  readonly bake?: GlbBake;
}

/**
 * A model's cloths as the writer takes them, over `positions` (the model's particles; `frames`: a bake's later
 * shapes of them) and cloth c named and dressed by `dress[c]`: views into the arrays, no copies.
 */
export function modelCloths(model: ClothModel, positions: Float32Array, dress: readonly { readonly name: string; readonly material: GlbMaterial }[], frames?: readonly Float32Array[]): ExportCloth[] {
  const starts = model.clothStarts;
  if (dress.length !== starts.length - 1) throw new RangeError(`glb: ${dress.length} cloths given for a model of ${starts.length - 1}`);
  return dress.map((d, c) => {
    const first = starts[c], last = starts[c + 1];
    return {
      ...d,
      positions: positions.subarray(3 * first, 3 * last),
      uvs: model.uvs.subarray(2 * first, 2 * last),
      triangles: (model.clothParts?.[c] ?? model).triangles,
      ...(frames ? { frames: frames.map((f) => f.subarray(3 * first, 3 * last)) } : {}),
      extras: { firstParticle: first, particles: last - first },
    };
  });
}

/** Bytes a bake adds per vertex per baked frame: a POSITION and a NORMAL difference, float32 vec3 each. */
export const BAKE_BYTES_PER_VERTEX = 24;

/**
 * The bytes a bake adds to the file for `vertices` vertices and `frames` baked frames (after the first): the morph
 * targets, the weights (one per target per key) and the keys' times; the JSON adds about 0.5 kB per frame and cloth.
 */
export function bakeBytes(vertices: number, frames: number): number {
  if (!(Number.isSafeInteger(vertices) && vertices >= 0)) throw new RangeError(`bakeBytes: vertices must be an integer ≥ 0, got ${shownValue(vertices)}`);
  if (!(Number.isSafeInteger(frames) && frames >= 0)) throw new RangeError(`bakeBytes: frames must be an integer ≥ 0, got ${shownValue(frames)}`);
  return frames * vertices * BAKE_BYTES_PER_VERTEX + 4 * (frames + 1) * frames + 4 * (frames + 1);
}

const FLOAT = 5126, UINT = 5125, ARRAY_BUFFER = 34962, ELEMENT_ARRAY_BUFFER = 34963;

/** sRGB channel 0…1 → linear (glTF's baseColorFactor is linear) */
const linear = (c: number) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);

/** The JSON and binary chunks as they grow: every view 4-byte aligned. */
class Builder {
  readonly parts: Uint8Array[] = [];
  length = 0;
  readonly bufferViews: object[] = [];
  readonly accessors: object[] = [];

  view(bytes: Uint8Array, target?: number): number {
    this.parts.push(bytes);
    this.bufferViews.push({ buffer: 0, byteOffset: this.length, byteLength: bytes.byteLength, ...(target ? { target } : {}) });
    this.length += bytes.byteLength;
    const pad = (4 - (this.length % 4)) % 4;
    if (pad) { this.parts.push(new Uint8Array(pad)); this.length += pad; }
    return this.bufferViews.length - 1;
  }

  /** a float accessor of `size` components (1, 2, 3), with min and max when asked (POSITION, animation input) */
  floats(data: Float32Array, size: 1 | 2 | 3, bounds: boolean, target?: number): number {
    const count = data.length / size;
    const accessor: Record<string, unknown> = {
      bufferView: this.view(new Uint8Array(data.buffer, data.byteOffset, data.byteLength), target),
      componentType: FLOAT, count, type: size === 1 ? 'SCALAR' : size === 2 ? 'VEC2' : 'VEC3',
    };
    if (bounds) {
      const min = new Array<number>(size).fill(Infinity), max = new Array<number>(size).fill(-Infinity);
      for (let i = 0; i < data.length; i++) {
        const k = i % size;
        if (data[i] < min[k]) min[k] = data[i];
        if (data[i] > max[k]) max[k] = data[i];
      }
      Object.assign(accessor, { min, max });
    }
    this.accessors.push(accessor);
    return this.accessors.length - 1;
  }

  indices(data: Uint32Array): number {
    this.accessors.push({
      bufferView: this.view(new Uint8Array(data.buffer, data.byteOffset, data.byteLength), ELEMENT_ARRAY_BUFFER),
      componentType: UINT, count: data.length, type: 'SCALAR',
    });
    return this.accessors.length - 1;
  }
}

/** Throws RangeError, `format` first, unless every position of `x` (stride 3) is finite. */
export function checkFinite(x: Float32Array, what: string, format = 'glb'): void {
  for (let i = 0; i < x.length; i++) if (!Number.isFinite(x[i])) throw new RangeError(`${format}: ${what} has positions that are not finite (vertex ${Math.floor(i / 3)})`);
}

/** Throws RangeError, `format` first, unless the material's colour and roughness are finite numbers (a file never holds a NaN). */
export function checkMaterial(m: GlbMaterial, format: string): void {
  if (![...m.color, m.roughness].every(Number.isFinite)) {
    throw new RangeError(`${format}: material '${plainText(m.name, 40)}' has a colour or roughness that is not a finite number`);
  }
}

/** Throws TypeError unless `input` is a writer's input: `{ name, cloths: [...] }` (the library's callers pass anything). */
export function checkInput(input: { name: string; cloths: readonly ExportCloth[] }, format: string): void {
  if (input === null || typeof input !== 'object' || !Array.isArray(input.cloths)) {
    throw new TypeError(`${format}: the input must be { name, cloths: [...] } (modelCloths makes the cloths), got ${shownValue(input)}`);
  }
}

/** Throws RangeError naming what is wrong with `input`: non-finite positions, arrays of the wrong size, a bad bake. */
function check(input: GlbInput): void {
  checkInput(input, 'glb');
  const { bake } = input;
  if (bake !== undefined && (bake === null || typeof bake !== 'object' || !Array.isArray(bake.times) || !Array.isArray(bake.frameNumbers))) {
    throw new TypeError('glb: bake must be { times: [...], frameNumbers: [...] }');
  }
  const targets = bake?.times.length ?? 0;
  if (bake) {
    if (targets < 1 || bake.frameNumbers.length !== targets) throw new RangeError('glb: a bake needs at least one frame, each with a time and a number');
    // the times as the file holds them, float32: each finite and after the one before (1e308 was written as Infinity)
    bake.times.forEach((t, k) => {
      const f32 = typeof t === 'number' ? Math.fround(t) : NaN;
      if (!(Number.isFinite(f32) && f32 > (k ? Math.fround(bake.times[k - 1]) : 0))) throw new RangeError('glb: the baked frames\' times must increase from 0 [s], each a finite float32');
    });
    bake.frameNumbers.forEach((f, k) => {
      if (!(Number.isSafeInteger(f) && f > (k ? bake.frameNumbers[k - 1] : 0))) throw new RangeError(`glb: the baked frames' numbers must be integers increasing from 1, got ${shownValue(f)}`);
    });
  }
  for (const c of input.cloths) {
    const n = c.positions.length / 3, what = `cloth '${plainText(c.name, 40)}'`;
    if (c.uvs.length !== 2 * n) throw new RangeError(`glb: ${what} has ${c.uvs.length / 2} texture coordinates for ${n} vertices`);
    for (let i = 0; i < c.triangles.length; i++) if (c.triangles[i] >= n) throw new RangeError(`glb: ${what} has a triangle on vertex ${c.triangles[i]} of ${n}`);
    checkFinite(c.positions, what);
    checkMaterial(c.material, 'glb');
    if ((c.frames?.length ?? 0) !== targets) throw new RangeError(`glb: ${what} has ${c.frames?.length ?? 0} baked frames for ${targets} times`);
    c.frames?.forEach((f, k) => {
      if (f.length !== c.positions.length) throw new RangeError(`glb: ${what}'s baked frame ${bake!.frameNumbers[k]} has ${f.length / 3} vertices for ${n}`);
      checkFinite(f, `${what}'s baked frame ${bake!.frameNumbers[k]}`);
    });
  }
}

/** The .glb file of `input` (see the module's comment). Throws RangeError on non-finite positions or a bad bake. */
export function toGLB(input: GlbInput): Uint8Array<ArrayBuffer> {
  check(input);
  const { bake } = input;
  const targets = bake?.times.length ?? 0;
  const b = new Builder();
  const images: object[] = [], textures: object[] = [], materials: object[] = [];
  const materialIndex = new Map<GlbMaterial, number>();
  let textureTransform = false;
  const material = (m: GlbMaterial): number => {
    const known = materialIndex.get(m);
    if (known !== undefined) return known;
    const pbr: Record<string, unknown> = { metallicFactor: 0, roughnessFactor: Math.min(1, Math.max(0, m.roughness)) };
    if (m.texture) {
      images.push({ bufferView: b.view(m.texture.png), mimeType: 'image/png' });
      textures.push({ sampler: 0, source: images.length - 1 });
      const repeat = m.texture.repeat;
      textureTransform ||= repeat !== 1;
      pbr.baseColorTexture = { index: textures.length - 1, ...(repeat !== 1 ? { extensions: { KHR_texture_transform: { scale: [repeat, repeat] } } } : {}) };
    } else {
      pbr.baseColorFactor = [...m.color.map((c) => linear(Math.min(1, Math.max(0, c)))), 1];
    }
    materials.push({ name: plainText(m.name, 100), pbrMetallicRoughness: pbr, doubleSided: true });
    materialIndex.set(m, materials.length - 1);
    return materials.length - 1;
  };

  const meshes: object[] = [], nodes: object[] = [{ name: plainText(input.name, 100), children: [] as number[] }];
  const channels: object[] = [], samplers: object[] = [];
  let times = -1, weights = -1;
  if (bake) {
    // keys: the first shape (every weight 0), then frame k (target k alone at weight 1)
    times = b.floats(Float32Array.from([0, ...bake.times]), 1, true);
    const w = new Float32Array((targets + 1) * targets);
    for (let k = 0; k < targets; k++) w[(k + 1) * targets + k] = 1;
    weights = b.floats(w, 1, false);
  }
  const targetNames = bake ? bake.frameNumbers.map((f) => `frame ${f}`) : [];
  for (const cloth of input.cloths) {
    const { triangles, positions: base } = cloth, n = base.length / 3;
    const normals = vertexNormals(base, triangles);
    const uv = cloth.uvs.slice();
    // glTF's texture coordinates start at the image's top, the model's (as OBJ's and three.js's) at its bottom
    for (let i = 1; i < uv.length; i += 2) uv[i] = 1 - uv[i];
    const primitive: Record<string, unknown> = {
      attributes: { POSITION: b.floats(base, 3, true, ARRAY_BUFFER), NORMAL: b.floats(normals, 3, false, ARRAY_BUFFER), TEXCOORD_0: b.floats(uv, 2, false, ARRAY_BUFFER) },
      indices: b.indices(triangles),
      material: material(cloth.material),
      mode: 4,
    };
    const mesh: Record<string, unknown> = { name: plainText(cloth.name, 100), primitives: [primitive] };
    if (bake) {
      primitive.targets = cloth.frames!.map((frame) => {
        const dx = new Float32Array(3 * n), dn = vertexNormals(frame, triangles);
        for (let i = 0; i < 3 * n; i++) { dx[i] = frame[i] - base[i]; dn[i] -= normals[i]; }
        return { POSITION: b.floats(dx, 3, true, ARRAY_BUFFER), NORMAL: b.floats(dn, 3, false, ARRAY_BUFFER) };
      });
      mesh.weights = new Array<number>(targets).fill(0);
      mesh.extras = { targetNames };
      samplers.push({ input: times, output: weights, interpolation: 'LINEAR' });
      channels.push({ sampler: samplers.length - 1, target: { node: nodes.length, path: 'weights' } });
    }
    meshes.push(mesh);
    (nodes[0] as { children: number[] }).children.push(nodes.length);
    nodes.push({ name: plainText(cloth.name, 100), mesh: meshes.length - 1, ...(cloth.extras ? { extras: cloth.extras } : {}) });
  }

  const gltf: Record<string, unknown> = {
    asset: { version: '2.0', generator: 'Drape' },
    ...(textureTransform ? { extensionsUsed: ['KHR_texture_transform'] } : {}),
    scene: 0,
    scenes: [{ name: plainText(input.name, 100), nodes: [0] }],
    nodes, meshes, materials,
    ...(textures.length ? { textures, images, samplers: [{ magFilter: 9729, minFilter: 9987, wrapS: 10497, wrapT: 10497 }] } : {}),
    ...(bake ? { animations: [{ name: 'simulation', channels, samplers, extras: { frames: bake.frameNumbers } }] } : {}),
    accessors: b.accessors,
    bufferViews: b.bufferViews,
    buffers: [{ byteLength: b.length }],
  };
  const json = new TextEncoder().encode(JSON.stringify(gltf));
  const jsonLength = json.length + ((4 - (json.length % 4)) % 4);
  const total = 12 + 8 + jsonLength + 8 + b.length;
  if (total > 0xffffffff) throw new RangeError(`glb: ${total} bytes, more than a .glb can hold (4 GiB)`);
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true); // 'glTF'
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true); // 'JSON'
  out.set(json, 20);
  out.fill(0x20, 20 + json.length, 20 + jsonLength);
  let at = 20 + jsonLength;
  view.setUint32(at, b.length, true);
  view.setUint32(at + 4, 0x004e4942, true); // 'BIN'
  at += 8;
  for (const p of b.parts) { out.set(p, at); at += p.byteLength; }
  return out;
}
