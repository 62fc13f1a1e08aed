/**
 * The triangles of a model of several cloths, cloth by cloth. The model's triangle list is sorted by colour, so the
 * cloths' triangles interleave; drawing each cloth with its own material (a geometry group per cloth) needs them in
 * runs. Pure: no three.js, unit-tested in cloth-parts.test.ts. (The exports take each cloth's own triangles from
 * model.clothParts: core/mesh/glb.ts, modelCloths.)
 */
import { clothOf, type ClothModel } from '../core/index.js';

/** A model's triangles in runs of one cloth each. */
export interface ClothTriangles {
  /** the model's triangles (scene particle numbers, 3 per triangle), cloth 0's first, each cloth's in the model's order */
  readonly indices: Uint32Array;
  /** cloth c's triangles are indices[3·first[c]] … indices[3·first[c + 1]] − 1 (one more entry than cloths) */
  readonly first: Uint32Array;
}

/** The model's triangles regrouped by cloth (a triangle is its first particle's cloth's: cloths share no particle). */
export function trianglesByCloth(model: ClothModel): ClothTriangles {
  const cloths = model.clothStarts.length - 1, t = model.triangles, count = t.length / 3;
  const clothOfTriangle = new Uint32Array(count);
  const first = new Uint32Array(cloths + 1);
  for (let k = 0; k < count; k++) {
    const c = clothOf(model, t[3 * k]);
    clothOfTriangle[k] = c;
    first[c + 1]++;
  }
  for (let c = 0; c < cloths; c++) first[c + 1] += first[c];
  const indices = new Uint32Array(t.length), at = first.slice(0, cloths);
  for (let k = 0; k < count; k++) {
    const o = 3 * at[clothOfTriangle[k]]++;
    indices[o] = t[3 * k]; indices[o + 1] = t[3 * k + 1]; indices[o + 2] = t[3 * k + 2];
  }
  return { indices, first };
}
