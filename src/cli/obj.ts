import { plainText, type ClothModel, type ClothState } from '../core/index.js';

/**
 * Wavefront OBJ of the cloth as it is now: positions [m], texture coordinates, triangles (1-based, v/vt). The
 * scene's name is written on one line, without control characters (a name cannot add lines to the file).
 */
export function toOBJ(model: ClothModel, state: ClothState, name: string): string {
  const safe = plainText(name, 100);
  const lines = [`# Drape cloth '${safe}': ${model.particleCount} vertices, ${model.triangles.length / 3} triangles`, `o ${safe}`];
  const x = state.positions, uv = model.uvs, t = model.triangles;
  for (let i = 0; i < model.particleCount; i++) lines.push(`v ${x[3 * i]} ${x[3 * i + 1]} ${x[3 * i + 2]}`);
  for (let i = 0; i < model.particleCount; i++) lines.push(`vt ${uv[2 * i]} ${uv[2 * i + 1]}`);
  for (let k = 0; k < t.length; k += 3) {
    const a = t[k] + 1, b = t[k + 1] + 1, c = t[k + 2] + 1;
    lines.push(`f ${a}/${a} ${b}/${b} ${c}/${c}`);
  }
  return lines.join('\n') + '\n';
}
