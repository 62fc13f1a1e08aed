import { plainText, type ClothModel, type ClothState } from '../core/index.js';

/**
 * Wavefront OBJ of the cloth as it is now: positions [m] (as many digits as the float32 they are: at least 7
 * significant), texture coordinates, triangles (1-based, v/vt). The scene's name is written on one line, without
 * control characters (a name cannot add lines to the file). A model of several cloths is one vertex list (the
 * scene's particle numbering) and one object per cloth (`o`, named by `clothNames`), its faces indexing that list.
 */
export function toOBJ(model: ClothModel, state: ClothState, name: string, clothNames?: readonly string[]): string {
  const safe = plainText(name, 100);
  const starts = model.clothStarts, cloths = starts.length - 1;
  const lines = [`# Drape cloth '${safe}': ${model.particleCount} vertices, ${model.triangles.length / 3} triangles${cloths > 1 ? `, ${cloths} cloths` : ''}`];
  const x = state.positions, uv = model.uvs, t = model.triangles;
  for (let i = 0; i < model.particleCount; i++) lines.push(`v ${x[3 * i]} ${x[3 * i + 1]} ${x[3 * i + 2]}`);
  for (let i = 0; i < model.particleCount; i++) lines.push(`vt ${uv[2 * i]} ${uv[2 * i + 1]}`);
  for (let c = 0; c < cloths; c++) {
    lines.push(`o ${cloths > 1 ? plainText(clothNames?.[c] ?? `cloth ${c}`, 100) : safe}`);
    for (let k = 0; k < t.length; k += 3) {
      // a triangle is its first vertex's cloth's
      if (t[k] < starts[c] || t[k] >= starts[c + 1]) continue;
      const a = t[k] + 1, b = t[k + 1] + 1, c3 = t[k + 2] + 1;
      lines.push(`f ${a}/${a} ${b}/${b} ${c3}/${c3}`);
    }
  }
  return lines.join('\n') + '\n';
}
