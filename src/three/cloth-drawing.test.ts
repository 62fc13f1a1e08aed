import { BufferGeometry, Mesh, Vector3 } from 'three';
import { describe, expect, it } from 'vitest';
import { modelFor, validateScene, type ClothModel } from '../core/index.js';
import { DrapeCloth } from './cloth.js';
import { ClothDrawing } from './cloth-drawing.js';

/** a model of two cloths: a 4 × 4 rectangle at y = 1 and a 6-ring disc at y = 2 */
function twoCloths(): ClothModel {
  return modelFor(validateScene({
    cloths: [
      { name: 'square', cloth: { resolution: 4, position: [0, 1, 0] } },
      { name: 'round', cloth: { shape: 'disc', resolution: 6, position: [0, 2, 0] } },
    ],
  }));
}

const clothsOf = (model: ClothModel) => model.clothParts!.map((part, k) => new DrapeCloth({ entry: {}, model: part }, undefined, `cloth ${k}`));

describe('ClothDrawing: the one path from a model\'s positions to its cloths on screen (the addon\'s worlds and the app\'s views)', () => {
  it('draws each cloth by its own triangles, numbered into attributes the whole model shares', () => {
    const model = twoCloths(), cloths = clothsOf(model);
    const drawing = new ClothDrawing(model, cloths);
    const [a, b] = cloths, n0 = model.clothParts![0].particleCount;
    expect(a.start).toBe(0);
    expect(b.start).toBe(n0);
    for (const [k, c] of cloths.entries()) {
      const own = model.clothParts![k].triangles, index = c.geometry.getIndex()!.array;
      expect(Array.from(index)).toEqual(Array.from(own, (i) => i + c.start));
      expect(c.geometry.getAttribute('position')).toBe(drawing.position);
      expect(c.geometry.getAttribute('normal')).toBe(drawing.normal);
      expect(c.geometry.getAttribute('uv')).toBe(drawing.uv);
      // the cloth's uvs at its own particles
      expect(Array.from(drawing.uv.array.slice(2 * c.start, 2 * (c.start + c.particleCount)))).toEqual(Array.from(model.clothParts![k].uvs));
    }
    expect(drawing.color).toBeNull();
    expect(drawing.position.itemSize).toBe(3);
    expect(Array.from(drawing.position.array)).toEqual(Array.from(model.restPositions));
  });

  it('takes new positions: the attributes, the normals of every triangle, and each cloth\'s own `positions`', () => {
    const model = twoCloths(), cloths = clothsOf(model);
    const drawing = new ClothDrawing(model, cloths);
    // both cloths stood up: turned 90° about x, their normals now along ±z
    const x = new Float32Array(model.restPositions);
    for (let i = 0; i < model.particleCount; i++) { const y = x[3 * i + 1], z = x[3 * i + 2]; x[3 * i + 1] = -z; x[3 * i + 2] = y; }
    drawing.update(x);
    expect(Array.from(drawing.position.array)).toEqual(Array.from(x));
    const nrm = new Vector3();
    for (let i = 0; i < model.particleCount; i++) expect(Math.abs(nrm.fromBufferAttribute(drawing.normal, i).z)).toBeCloseTo(1, 5);
    expect(Array.from(cloths[1].positions)).toEqual(Array.from(x.subarray(3 * cloths[1].start)));
    // a view without a surface leaves the normals as they were
    const before = Float32Array.from(drawing.normal.array as Float32Array);
    drawing.update(model.restPositions, false);
    expect(Array.from(drawing.normal.array)).toEqual(Array.from(before));
  });

  it('on the GPU path: vec4 attributes (the solver\'s layout) until the solver\'s buffers are attached, then nothing is copied', () => {
    const model = twoCloths(), cloths = clothsOf(model);
    const drawing = new ClothDrawing(model, cloths, { gpu: true, colors: true });
    expect(drawing.position.itemSize).toBe(4);
    expect(drawing.normal.itemSize).toBe(4);
    expect(drawing.color!.count).toBe(model.particleCount);
    for (const c of cloths) expect(c.geometry.getAttribute('color')).toBe(drawing.color);
    const p = drawing.position.array as Float32Array, i = model.particleCount - 1;
    expect([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]).toEqual([...model.restPositions.slice(3 * i, 3 * i + 3), 0]);
    // the start pose is drawn shaded: normals up
    expect(new Vector3().fromBufferAttribute(drawing.normal, i).y).toBeCloseTo(1, 5);
    // attached (a stand-in of three.js's WebGPU backend): the solver's buffers take the attributes' place
    const kept = new Map<object, { buffer?: GPUBuffer }>();
    const backend = { get: (o: object) => kept.get(o) ?? kept.set(o, {}).get(o)! };
    const positions = { destroy() {} } as GPUBuffer, normals = { destroy() {} } as GPUBuffer;
    drawing.attach(backend, positions, normals);
    expect(drawing.attached).toBe(true);
    expect(kept.get(drawing.position)!.buffer).toBe(positions);
    expect(kept.get(drawing.normal)!.buffer).toBe(normals);
    const moved = new Float32Array(model.restPositions).map((v) => v + 1);
    const version = drawing.position.version;
    drawing.update(moved);
    expect(drawing.position.version).toBe(version);
    // each cloth's positions still follow (the readbacks)
    expect(cloths[0].positions[0]).toBe(moved[0]);
  });

  it('a cloth not yet simulated draws alone at its start pose; the drawing that takes it frees that one', () => {
    const model = twoCloths(), cloths = clothsOf(model);
    const solo = cloths[1].geometry;
    expect(solo.getIndex()!.count).toBe(model.clothParts![1].triangles.length);
    let freed = false;
    solo.addEventListener('dispose', () => { freed = true; });
    const drawing = new ClothDrawing(model, cloths);
    expect(freed).toBe(true);
    expect(cloths[1].geometry).not.toBe(solo);
    // a newer drawing takes the cloths: freeing the old one leaves their new geometries alone
    const next = new ClothDrawing(model, cloths);
    const now = cloths.map((c) => c.geometry);
    let freedNow = false;
    for (const g of now) g.addEventListener('dispose', () => { freedNow = true; });
    drawing.dispose();
    expect(freedNow).toBe(false);
    next.dispose();
    expect(freedNow).toBe(true);
    expect(() => new ClothDrawing(model, cloths.slice(1))).toThrow('1 cloths to draw a model of 2');
    expect(cloths[0]).toBeInstanceOf(Mesh);
    expect(cloths[0].geometry).toBeInstanceOf(BufferGeometry);
  });
});
