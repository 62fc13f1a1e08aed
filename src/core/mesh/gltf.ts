/**
 * glTF 2.0 (.gltf JSON or binary .glb) as a cloth mesh: every triangle primitive of every mesh the default scene
 * shows, placed by its node's world transform, in one mesh (each becomes a piece, welded where they touch).
 * Reads POSITION, TEXCOORD_0 and indices; triangle strips and fans are unrolled; points and lines are skipped.
 * Buffers come from the .glb's binary chunk, `data:` URIs, or `readExternal` for a file next to the .gltf.
 * Refused with a line naming the file: compression extensions the file requires (Draco, meshopt), sparse
 * accessors, and anything malformed.
 */
import { SceneError } from '../scene.js';
import { MAX_MESH_PARTICLES } from './triangle-mesh.js';
import type { TriangleMesh } from './triangle-mesh.js';

/** Most vertices a file may bring before welding (files split vertices at seams; welding merges them back). */
const MAX_FILE_VERTICES = 2 * MAX_MESH_PARTICLES;

/** Reads a file a .gltf names by a relative URI (its .bin buffer), or throws saying why it cannot. */
export type ExternalReader = (uri: string) => Uint8Array;

interface Accessor { bufferView?: number; byteOffset?: number; componentType: number; normalized?: boolean; count: number; type: string; sparse?: unknown }
interface BufferView { buffer: number; byteOffset?: number; byteLength: number; byteStride?: number }
interface Primitive { attributes: Record<string, number>; indices?: number; mode?: number }
interface GltfNode { mesh?: number; children?: number[]; matrix?: number[]; translation?: number[]; rotation?: number[]; scale?: number[] }
interface Gltf {
  asset?: { version?: string };
  extensionsRequired?: string[];
  buffers?: { uri?: string; byteLength: number }[];
  bufferViews?: BufferView[];
  accessors?: Accessor[];
  meshes?: { primitives: Primitive[] }[];
  nodes?: GltfNode[];
  scenes?: { nodes?: number[] }[];
  scene?: number;
}

const COMPONENTS: Record<string, number> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };
const BYTES: Record<number, number> = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };

/** Column-major 4×4 product a·b. */
function mul(a: number[], b: number[]): number[] {
  const out = new Array<number>(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) out[4 * c + r] += a[4 * k + r] * b[4 * c + k];
  return out;
}

/** A node's local transform, column-major: its matrix, or T·R·S. */
function localMatrix(node: GltfNode): number[] {
  if (node.matrix) return node.matrix;
  const [tx, ty, tz] = node.translation ?? [0, 0, 0];
  const [x, y, z, w] = node.rotation ?? [0, 0, 0, 1];
  const [sx, sy, sz] = node.scale ?? [1, 1, 1];
  return [
    (1 - 2 * (y * y + z * z)) * sx, 2 * (x * y + z * w) * sx, 2 * (x * z - y * w) * sx, 0,
    2 * (x * y - z * w) * sy, (1 - 2 * (x * x + z * z)) * sy, 2 * (y * z + x * w) * sy, 0,
    2 * (x * z + y * w) * sz, 2 * (y * z - x * w) * sz, (1 - 2 * (x * x + y * y)) * sz, 0,
    tx, ty, tz, 1,
  ];
}

/** Decodes a base64 `data:` URI without Node's Buffer (the core runs in browsers too). */
function dataUri(uri: string, fail: (why: string) => never): Uint8Array {
  const comma = uri.indexOf(',');
  if (comma < 0 || !uri.slice(0, comma).endsWith(';base64')) fail('a data: URI buffer must be base64');
  let bin: string;
  try {
    bin = atob(uri.slice(comma + 1));
  } catch {
    return fail('a data: URI buffer is not valid base64');
  }
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

/** Splits a .glb into its JSON and binary chunks (glTF 2.0 §4.4). */
function readGlb(bytes: Uint8Array, fail: (why: string) => never): { json: string; bin?: Uint8Array } {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 20 || view.getUint32(0, true) !== 0x46546c67) fail('not a binary glTF (.glb) file');
  if (view.getUint32(4, true) !== 2) fail(`glTF version ${view.getUint32(4, true)}; only glTF 2 is read`);
  const total = Math.min(view.getUint32(8, true), bytes.length);
  let json: string | undefined, bin: Uint8Array | undefined;
  for (let at = 12; at + 8 <= total;) {
    const length = view.getUint32(at, true), type = view.getUint32(at + 4, true);
    if (at + 8 + length > total) fail('a chunk runs past the end of the file');
    const chunk = bytes.subarray(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = new TextDecoder().decode(chunk);
    else if (type === 0x004e4942 && !bin) bin = chunk;
    at += 8 + length;
  }
  if (json === undefined) fail('the .glb has no JSON chunk');
  return { json: json!, bin };
}

/**
 * Parses a .gltf or .glb file's bytes (which one: by the 'glTF' magic number); `source` names the file in errors.
 * The mesh is not yet prepared (welding and checks: prepareMesh).
 */
export function parseGltf(bytes: Uint8Array, source: string, readExternal?: ExternalReader): TriangleMesh {
  const fail = (why: string): never => {
    throw new SceneError(`${source}: ${why}`);
  };
  const isGlb = bytes.length >= 4 && bytes[0] === 0x67 && bytes[1] === 0x6c && bytes[2] === 0x54 && bytes[3] === 0x46;
  const { json, bin } = isGlb ? readGlb(bytes, fail) : { json: new TextDecoder().decode(bytes), bin: undefined };
  let doc: Gltf;
  try {
    doc = JSON.parse(json) as Gltf;
  } catch (e) {
    return fail(`malformed glTF JSON (${(e as Error).message.split('\n')[0]})`);
  }
  if (doc === null || typeof doc !== 'object' || Array.isArray(doc)) fail('malformed glTF: not a JSON object');
  // a field of the wrong type (a number where a list belongs...) surfaces as a TypeError somewhere below: it is the
  // file's fault, said in one line; errors of the host's file reading pass through as they are
  let external: unknown;
  try {
    return readDocument(doc, bin, source, fail, readExternal && ((uri) => {
      try {
        return readExternal(uri);
      } catch (e) {
        external = e;
        throw e;
      }
    }));
  } catch (e) {
    if (e instanceof SceneError || e === external) throw e;
    return fail(`malformed glTF (${(e as Error).message.split('\n')[0].slice(0, 200)})`);
  }
}

/** The meshes of a parsed glTF document (see parseGltf). */
function readDocument(doc: Gltf, bin: Uint8Array | undefined, source: string, fail: (why: string) => never, readExternal?: ExternalReader): TriangleMesh {
  if (!String(doc.asset?.version ?? '').startsWith('2')) fail(`glTF version ${JSON.stringify(doc.asset?.version ?? null)}; only glTF 2 is read`);
  if (doc.extensionsRequired !== undefined && !Array.isArray(doc.extensionsRequired)) fail('malformed glTF: extensionsRequired is not a list');
  const required = (doc.extensionsRequired ?? []).filter((e) => typeof e === 'string');
  if (required.length) fail(`needs the extension${required.length > 1 ? 's' : ''} ${required.map((e) => e.slice(0, 60)).join(', ')}, which Drape does not read; export without compression`);

  const buffers = new Map<number, Uint8Array>();
  const buffer = (i: number): Uint8Array => {
    let b = buffers.get(i);
    if (b) return b;
    const spec = doc.buffers?.[i];
    if (!spec) return fail(`buffer ${i} does not exist`);
    if (spec.uri !== undefined && typeof spec.uri !== 'string') return fail(`buffer ${i} has a uri that is not text`);
    if (spec.uri === undefined) {
      if (!bin || i !== 0) return fail(`buffer ${i} has no data (no uri, and not the .glb's binary chunk)`);
      b = bin;
    } else if (spec.uri.startsWith('data:')) {
      b = dataUri(spec.uri, fail);
    } else {
      if (!readExternal) return fail(`buffer ${i} is a separate file (${spec.uri.slice(0, 100)}); import a .glb, or a .gltf with embedded buffers`);
      let uri: string;
      try {
        uri = decodeURIComponent(spec.uri);
      } catch {
        return fail(`buffer ${i} has a uri that is not a valid URI`);
      }
      b = readExternal(uri);
    }
    if (b.length < spec.byteLength) fail(`buffer ${i} holds ${b.length} bytes, fewer than its byteLength ${spec.byteLength}`);
    buffers.set(i, b);
    return b;
  };

  /** An accessor's values as numbers (normalised integers to [0, 1] / [−1, 1]), `count × components`. */
  const read = (index: number, want: string[]): { data: Float64Array; count: number; width: number } => {
    const acc = doc.accessors?.[index];
    if (!acc) return fail(`accessor ${index} does not exist`);
    if (acc.sparse) fail(`accessor ${index} is sparse, which Drape does not read`);
    if (!want.includes(acc.type)) fail(`accessor ${index} is ${acc.type}, expected ${want.join(' or ')}`);
    const width = COMPONENTS[acc.type], size = BYTES[acc.componentType];
    if (!size) fail(`accessor ${index} has component type ${acc.componentType}, which is not a glTF type`);
    if (!Number.isInteger(acc.count) || acc.count < 0) fail(`accessor ${index} has a count that is not a whole number`);
    // without a buffer view an accessor is all zeros (or sparse, refused above): no cloth is made of that
    if (acc.bufferView === undefined) return fail(`accessor ${index} has ${acc.count} elements and no data`);
    const bv = doc.bufferViews?.[acc.bufferView];
    if (!bv) return fail(`buffer view ${acc.bufferView} does not exist`);
    const buf = buffer(bv.buffer);
    const stride = bv.byteStride ?? width * size;
    const base = (bv.byteOffset ?? 0) + (acc.byteOffset ?? 0);
    const whole = (v: unknown) => Number.isInteger(v) && (v as number) >= 0;
    if (!whole(stride) || stride < width * size || !whole(bv.byteOffset ?? 0) || !whole(acc.byteOffset ?? 0) || !whole(bv.byteLength)) {
      fail(`accessor ${index} or its buffer view has an offset, length or stride that is not valid`);
    }
    // a view lies within its buffer's byteLength (glTF 2.0 §3.6.2.3), not only within the bytes that happen to follow
    const declared = doc.buffers?.[bv.buffer]?.byteLength;
    if (!whole(declared)) fail(`buffer ${bv.buffer} has a byteLength that is not a whole number`);
    if ((bv.byteOffset ?? 0) + bv.byteLength > (declared as number)) fail(`buffer view ${acc.bufferView} reaches past the end of buffer ${bv.buffer} (its byteLength ${declared})`);
    const last = base + (acc.count - 1) * stride + width * size;
    // checked before anything is allocated: the count is the file's word, the buffer's length is a fact
    if (acc.count > 0 && (last > (bv.byteOffset ?? 0) + bv.byteLength || last > buf.length)) fail(`accessor ${index} reads past the end of its buffer`);
    const data = new Float64Array(acc.count * width);
    const view = new DataView(buf.buffer, buf.byteOffset, buf.byteLength);
    for (let i = 0; i < acc.count; i++) {
      for (let k = 0; k < width; k++) {
        const at = base + i * stride + k * size;
        let v: number;
        switch (acc.componentType) {
          case 5126: v = view.getFloat32(at, true); break;
          case 5125: v = view.getUint32(at, true); break;
          case 5123: v = view.getUint16(at, true); if (acc.normalized) v /= 65535; break;
          case 5122: v = view.getInt16(at, true); if (acc.normalized) v = Math.max(v / 32767, -1); break;
          case 5121: v = view.getUint8(at); if (acc.normalized) v /= 255; break;
          default: v = view.getInt8(at); if (acc.normalized) v = Math.max(v / 127, -1);
        }
        data[i * width + k] = v;
      }
    }
    return { data, count: acc.count, width };
  };

  const positions: number[] = [];
  const uvs: number[] = [];
  const tri: number[] = [];
  let anyUv = false;
  const addMesh = (meshIndex: number, world: number[]) => {
    const mesh = doc.meshes?.[meshIndex];
    if (!mesh) return fail(`mesh ${meshIndex} does not exist`);
    for (const prim of mesh.primitives ?? []) {
      const mode = prim.mode ?? 4;
      if (mode < 4) continue; // points and lines are not cloth
      if (prim.attributes?.POSITION === undefined) fail(`a primitive of mesh ${meshIndex} has no POSITION`);
      const p = read(prim.attributes.POSITION, ['VEC3']);
      const t = prim.attributes.TEXCOORD_0 !== undefined ? read(prim.attributes.TEXCOORD_0, ['VEC2']) : undefined;
      if (t && t.count !== p.count) fail(`mesh ${meshIndex} has ${t.count} texture coordinates for ${p.count} positions`);
      if (positions.length / 3 + p.count > MAX_FILE_VERTICES) fail(`more than ${MAX_FILE_VERTICES} vertices (a cloth may have ${MAX_MESH_PARTICLES} once duplicates are welded)`);
      const base = positions.length / 3;
      for (let i = 0; i < p.count; i++) {
        const x = p.data[3 * i], y = p.data[3 * i + 1], z = p.data[3 * i + 2];
        positions.push(
          world[0] * x + world[4] * y + world[8] * z + world[12],
          world[1] * x + world[5] * y + world[9] * z + world[13],
          world[2] * x + world[6] * y + world[10] * z + world[14],
        );
        if (t) uvs.push(t.data[2 * i], t.data[2 * i + 1]); else uvs.push(0, 0);
      }
      if (t) anyUv = true;
      const idx = prim.indices !== undefined ? read(prim.indices, ['SCALAR']).data : Float64Array.from({ length: p.count }, (_, i) => i);
      for (let i = 0; i < idx.length; i++) {
        if (!Number.isInteger(idx[i]) || idx[i] < 0 || idx[i] >= p.count) fail(`mesh ${meshIndex} has an index ${idx[i]} outside its ${p.count} vertices`);
      }
      // a triangle list's corners come in threes: a remainder is a broken file, not something to drop
      if (mode === 4 && idx.length % 3 !== 0) fail(`a primitive of mesh ${meshIndex} has ${idx.length} ${prim.indices !== undefined ? 'indices' : 'vertices'}, not a multiple of 3 (a list of triangles)`);
      if (mode === 4) for (let i = 0; i + 2 < idx.length; i += 3) tri.push(base + idx[i], base + idx[i + 1], base + idx[i + 2]);
      else if (mode === 5) {
        for (let i = 0; i + 2 < idx.length; i++) {
          const a = idx[i], b = idx[i + 1 + (i % 2)], c = idx[i + 2 - (i % 2)];
          // a strip restarts with triangles that repeat a vertex: they join nothing and are left out
          if (a !== b && b !== c && c !== a) tri.push(base + a, base + b, base + c);
        }
      }
      else if (mode === 6) for (let i = 1; i + 1 < idx.length; i++) tri.push(base + idx[0], base + idx[i], base + idx[i + 1]);
      else fail(`a primitive of mesh ${meshIndex} has mode ${mode}, which is not a glTF mode`);
    }
  };

  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  if (doc.scene !== undefined && !doc.scenes?.[doc.scene]) fail(`scene ${doc.scene} does not exist`);
  const roots = doc.scenes?.[doc.scene ?? 0]?.nodes;
  if (roots && doc.nodes) {
    const visited = new Set<number>();
    const visit = (i: number, parent: number[], depth: number) => {
      const node = doc.nodes![i];
      if (depth > 256) return fail('the node hierarchy is more than 256 levels deep');
      if (!node) return fail(`node ${i} does not exist`);
      if (visited.has(i)) return fail(`node ${i} is reached twice (the node hierarchy must be a tree)`);
      visited.add(i);
      const world = mul(parent, localMatrix(node));
      if (node.mesh !== undefined) addMesh(node.mesh, world);
      for (const c of node.children ?? []) visit(c, world, depth + 1);
    };
    for (const r of roots) visit(r, identity, 1);
  } else {
    // no scene: every mesh as it is
    (doc.meshes ?? []).forEach((_, k) => addMesh(k, identity));
  }
  if (tri.length === 0) fail('no triangles: the file has no triangle meshes in its scene');
  return { positions: Float32Array.from(positions), triangles: Uint32Array.from(tri), uvs: anyUv ? Float32Array.from(uvs) : undefined };
}
