import { validateBytes } from 'gltf-validator';
import type { BufferGeometry, Mesh, MeshStandardMaterial, Object3D } from 'three';
import { GLTFLoader, type GLTF } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { describe, expect, it } from 'vitest';
import { exportCloths, LOOKS, Simulation, validateScene, type Scene } from '../index.js';
import { bakeBytes, modelCloths, toGLB, type GlbBake } from './glb.js';
import { parseGltf } from './gltf.js';

/** The Khronos validator's report on a .glb: every issue but the infos (an unused TEXCOORD_0 without a texture). */
async function validate(glb: Uint8Array) {
  const report = await validateBytes(glb, { maxIssues: 100 });
  return { errors: report.issues.numErrors, warnings: report.issues.numWarnings, messages: report.issues.messages.filter((m) => m.severity < 2) };
}

/** three.js's GLTFLoader on a .glb, as the app and a viewer load it. */
function load(glb: Uint8Array): Promise<GLTF> {
  const buffer = glb.buffer.slice(glb.byteOffset, glb.byteOffset + glb.byteLength) as ArrayBuffer;
  return new Promise((done, fail) => new GLTFLoader().parse(buffer, '', done, fail));
}

/** the file's JSON chunk */
const json = (glb: Uint8Array) => JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + new DataView(glb.buffer, glb.byteOffset).getUint32(12, true))));

const meshes = (root: Object3D) => {
  const out: Mesh[] = [];
  root.traverse((o) => { if ((o as Mesh).isMesh) out.push(o as Mesh); });
  return out;
};

/** a scene run for `frames` frames, with the shapes of the frames a bake keeps (every frame after the first) */
function run(scene: Scene, frames: number): { sim: Simulation; first: Float32Array; shapes: Float32Array[]; bake: GlbBake } {
  const sim = new Simulation(scene, { kernel: 'ts' });
  const first = sim.state.positions.slice(), shapes: Float32Array[] = [], numbers: number[] = [];
  for (let f = 1; f <= frames; f++) {
    sim.advance(1);
    shapes.push(sim.state.positions.slice());
    numbers.push(f);
  }
  return { sim, first, shapes, bake: { times: numbers.map((f) => f / 60), frameNumbers: numbers } };
}

/** the largest difference between two position arrays, relative to the larger coordinate (at least 1 m) */
function worst(a: ArrayLike<number>, b: ArrayLike<number>): number {
  let w = 0;
  for (let i = 0; i < a.length; i++) w = Math.max(w, Math.abs(a[i] - b[i]) / Math.max(1, Math.abs(b[i])));
  return w;
}

describe('the .glb writer', () => {
  const one = validateScene({ name: 'one', cloth: { resolution: 6 }, material: { fabric: 'silk' } });
  const three = validateScene({
    name: 'three "quoted"\u0007',
    cloths: [
      { name: 'a', cloth: { resolution: 3, position: [0, 1, 0] }, material: { fabric: 'leather' } },
      { name: 'b', cloth: { shape: 'disc', resolution: 5, position: [0, 1.4, 0] } },
      { name: 'c\nd', cloth: { resolution: 2, position: [0, 1.8, 0] }, material: { fabric: 'leather' } },
    ],
  });

  it('a static cloth: valid, its positions as they are, unit normals, the look\'s material', async () => {
    const { sim } = run(one, 20);
    const glb = toGLB({ name: one.name, cloths: modelCloths(sim.model, sim.state.positions, exportCloths(one)) });
    expect(await validate(glb)).toEqual({ errors: 0, warnings: 0, messages: [] });
    const gltf = await load(glb);
    const [mesh] = meshes(gltf.scene);
    expect(mesh.name).toBe('cloth');
    const g = mesh.geometry as BufferGeometry;
    // float32 as the simulation holds them: exact
    expect(Array.from(g.attributes.position.array)).toEqual(Array.from(sim.state.positions));
    const n = g.attributes.normal.array;
    for (let i = 0; i < n.length; i += 3) expect(Math.hypot(n[i], n[i + 1], n[i + 2])).toBeCloseTo(1, 5);
    // the cloth sags onto the sphere: its normals are not all the flat start's
    expect(Math.min(...Array.from({ length: n.length / 3 }, (_, i) => n[3 * i + 1]))).toBeLessThan(0.99);
    expect(g.attributes.uv.getY(0)).toBeCloseTo(1 - sim.model.uvs[1], 6);
    expect(g.index!.count).toBe(sim.model.triangles.length);
    const m = mesh.material as MeshStandardMaterial;
    expect(m.roughness).toBeCloseTo(LOOKS.silk.roughness, 6);
    expect(m.metalness).toBe(0);
    // three reads the linear factor back as its own linear colour; in sRGB it is the look's colour
    expect(m.color.getHexString()).toBe('9c1e3a');
    expect(gltf.animations).toHaveLength(0);
  });

  it('several cloths: one node and mesh each by its name (made plain), their materials shared by look', async () => {
    const { sim } = run(three, 5);
    const glb = toGLB({ name: three.name, cloths: modelCloths(sim.model, sim.state.positions, exportCloths(three)) });
    expect(await validate(glb)).toEqual({ errors: 0, warnings: 0, messages: [] });
    const gltf = await load(glb);
    // three.js makes names fit its animation paths ('three_"quoted"_1'): the file's own are in its JSON
    const { nodes, meshes: fileMeshes } = json(glb);
    expect(nodes.map((n: { name: string }) => n.name)).toEqual(['three "quoted"\ufffd', 'a', 'b', 'c\ufffdd']);
    expect(nodes[0].children).toEqual([1, 2, 3]);
    expect(fileMeshes.map((m: { name: string }) => m.name)).toEqual(['a', 'b', 'c\ufffdd']);
    const parts = meshes(gltf.scene);
    expect(parts).toHaveLength(3);
    expect(parts[0].material).toBe(parts[2].material);
    expect((parts[1].material as MeshStandardMaterial).name).toBe(LOOKS.cotton.name);
    const starts = sim.model.clothStarts;
    parts.forEach((p, c) => {
      expect(Array.from(p.geometry.attributes.position.array)).toEqual(Array.from(sim.state.positions.subarray(3 * starts[c], 3 * starts[c + 1])));
      expect(p.userData).toEqual({ name: fileMeshes[c].name, firstParticle: starts[c], particles: starts[c + 1] - starts[c] });
    });
    // Drape's own glTF reader (a cloth from a file) takes it back: the cloths' vertices in order, every triangle
    const back = parseGltf(glb, 'three.glb');
    expect(Array.from(back.positions)).toEqual(Array.from(sim.state.positions));
    expect(back.triangles.length).toBe(sim.model.triangles.length);
  });

  it('a bake: one morph target per frame, an animation that three.js plays, each frame\'s positions back to 7 digits', async () => {
    const frames = 12;
    const { sim, first, shapes, bake } = run(three, frames);
    const glb = toGLB({ name: three.name, cloths: modelCloths(sim.model, first, exportCloths(three), shapes), bake });
    expect(await validate(glb)).toEqual({ errors: 0, warnings: 0, messages: [] });
    const gltf = await load(glb);
    expect(gltf.animations).toHaveLength(1);
    const clip = gltf.animations[0];
    expect(clip.tracks).toHaveLength(3);
    expect(clip.duration).toBeCloseTo(frames / 60, 6);
    const parts = meshes(gltf.scene), starts = sim.model.clothStarts;
    // three's LINEAR weights track: at frame k's time, target k − 1 alone has weight 1
    const track = clip.tracks[0];
    expect(track.times.length).toBe(frames + 1);
    expect(track.values.slice(5 * frames, 6 * frames).indexOf(1)).toBe(4);
    for (const [c, p] of parts.entries()) {
      const morphs = p.geometry.morphAttributes.position ?? [];
      expect(morphs).toHaveLength(frames);
      expect(p.geometry.morphAttributes.normal).toHaveLength(frames);
      expect(Object.keys(p.morphTargetDictionary!)[frames - 1]).toBe(`frame ${frames}`);
      const base = p.geometry.attributes.position.array;
      for (const k of [0, 6, frames - 1]) {
        const shape = Float32Array.from(base, (x, i) => x + morphs[k].array[i]);
        const want = shapes[k].subarray(3 * starts[c], 3 * starts[c + 1]);
        expect(worst(shape, want), `cloth ${c} frame ${k + 1}`).toBeLessThan(2e-7);
      }
    }
    // the size the app and the CLI announce is what the file holds beyond the static one, give or take its JSON
    const still = toGLB({ name: three.name, cloths: modelCloths(sim.model, first, exportCloths(three)) });
    const added = glb.length - still.length, predicted = bakeBytes(sim.model.particleCount, frames);
    expect(added).toBeGreaterThan(predicted);
    expect(added - predicted).toBeLessThan(3 * frames * 500);
  });

  it('bakeBytes refuses what is not a count', () => {
    expect(bakeBytes(2, 3)).toBe(3 * 2 * 24 + 4 * 4 * 3 + 4 * 4);
    expect(() => bakeBytes(NaN, 3)).toThrow(/^bakeBytes: vertices must be an integer ≥ 0, got NaN$/);
    expect(() => bakeBytes(2, -1)).toThrow(/^bakeBytes: frames must be an integer ≥ 0, got -1$/);
    expect(() => bakeBytes(2, 1.5)).toThrow(RangeError);
  });

  it('a texture: the PNG embedded, repeated by KHR_texture_transform, the colour factor white', async () => {
    const { sim } = run(one, 1);
    // a 1 × 1 PNG
    const png = Uint8Array.from(atob('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5ErkJggg=='), (c) => c.charCodeAt(0));
    const material = { ...LOOKS.cotton, texture: { png, repeat: 4 } };
    const glb = toGLB({ name: 'textured', cloths: modelCloths(sim.model, sim.state.positions, [{ name: 'cloth', material }]) });
    const report = await validate(glb);
    expect(report).toEqual({ errors: 0, warnings: 0, messages: [] });
    const file = json(glb);
    expect(file.extensionsUsed).toEqual(['KHR_texture_transform']);
    expect(file.materials[0].pbrMetallicRoughness).toMatchObject({ baseColorTexture: { index: 0, extensions: { KHR_texture_transform: { scale: [4, 4] } } }, roughnessFactor: 0.9 });
    expect(file.materials[0].pbrMetallicRoughness.baseColorFactor).toBeUndefined();
    expect(file.images).toEqual([{ bufferView: expect.any(Number), mimeType: 'image/png' }]);
  });

  it('refuses positions that are not finite, and a bake or cloths that do not match', () => {
    const { sim, first, shapes, bake } = run(one, 2);
    const dress = exportCloths(one), bad = first.slice();
    bad[7] = NaN;
    expect(() => toGLB({ name: 'x', cloths: modelCloths(sim.model, bad, dress) })).toThrow(/^glb: cloth 'cloth' has positions that are not finite \(vertex 2\)$/);
    expect(() => toGLB({ name: 'x', cloths: modelCloths(sim.model, first, dress, [shapes[0], bad]), bake })).toThrow(/cloth 'cloth''s baked frame 2 has positions that are not finite/);
    expect(() => toGLB({ name: 'x', cloths: modelCloths(sim.model, first, dress, shapes), bake: { ...bake, times: [0.1, 0.1] } })).toThrow(/times must increase/);
    // what a file cannot hold: a time past float32 (written as Infinity before), frame numbers that are not counts
    const cloths = modelCloths(sim.model, first, dress, shapes);
    expect(() => toGLB({ name: 'x', cloths, bake: { ...bake, times: [0.1, 1e308] } })).toThrow(/^glb: the baked frames' times must increase from 0 \[s\], each a finite float32$/);
    expect(() => toGLB({ name: 'x', cloths, bake: { ...bake, times: [0.1, 0.1 + 1e-12] } })).toThrow(/times must increase/); // one float32
    for (const frameNumbers of [[1, NaN], [2, 1], [1, 1.5], [1, '\u001b[31m']]) {
      expect(() => toGLB({ name: 'x', cloths, bake: { ...bake, frameNumbers: frameNumbers as number[] } })).toThrow(/^glb: the baked frames' numbers must be integers increasing from 1, got /);
    }
    for (const input of [null, {}, { name: 'x', cloths: 3 }]) expect(() => toGLB(input as never)).toThrow(/^glb: the input must be \{ name, cloths: \[\.\.\.\] \}/);
    expect(() => toGLB({ name: 'x', cloths, bake: 5 as never })).toThrow(/^glb: bake must be/);
    expect(() => toGLB({ name: 'x', cloths: modelCloths(sim.model, first, dress, shapes.slice(1)), bake })).toThrow(/has 1 baked frames for 2 times/);
    expect(() => toGLB({ name: 'x', cloths: modelCloths(sim.model, first, dress), bake })).toThrow(/has 0 baked frames for 2 times/);
    expect(() => modelCloths(sim.model, first, [])).toThrow(/0 cloths given for a model of 1/);
    // a material a library caller made, with a colour or roughness that is no number: refused, not written as null
    const [c] = modelCloths(sim.model, first, dress);
    for (const material of [{ ...c.material, roughness: NaN }, { ...c.material, color: [NaN, 0, 0] as [number, number, number] }]) {
      expect(() => toGLB({ name: 'x', cloths: [{ ...c, material }] })).toThrow(/^glb: material '.*' has a colour or roughness that is not a finite number$/);
    }
  });
});
