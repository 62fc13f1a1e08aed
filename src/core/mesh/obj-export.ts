/**
 * Wavefront OBJ and its MTL of a model's cloths as they are now: positions [m] (as many digits as the float32 they
 * are: at least 7 significant), texture coordinates, vertex normals and triangles (1-based, v/vt/vn), one object
 * (`o`) per cloth over one vertex list in the scene's particle numbering, each with its material (`usemtl`). Strings
 * from the scene are written on one line each, without control characters: a name cannot add lines to the file.
 */
import { plainText } from '../text.js';
import type { GlbInput, GlbMaterial } from './glb.js';
import { vertexNormals } from './normals.js';

/** What the OBJ writer takes: the glb writer's input without a bake; `mtllib` names the MTL file beside it. */
export type ObjInput = Omit<GlbInput, 'bake'> & { readonly mtllib?: string };

/** one word: OBJ and MTL names end at white space */
const word = (s: string) => plainText(s, 60).replace(/\s+/g, '_') || 'material';

/** Each distinct material of the cloths with a name of its own (a repeated name gets a number). */
function materialNames(input: ObjInput): Map<GlbMaterial, string> {
  const names = new Map<GlbMaterial, string>(), used = new Set<string>();
  for (const { material } of input.cloths) {
    if (names.has(material)) continue;
    let name = word(material.name);
    for (let k = 2; used.has(name); k++) name = `${word(material.name)}_${k}`;
    used.add(name);
    names.set(material, name);
  }
  return names;
}

/** The OBJ text (see the module's comment). */
export function toOBJ(input: ObjInput): string {
  const { model, positions: x } = input;
  const safe = plainText(input.name, 100);
  const starts = model.clothStarts, cloths = starts.length - 1, n = model.particleCount;
  const materials = materialNames(input);
  const lines = [`# Drape cloth '${safe}': ${n} vertices, ${model.triangles.length / 3} triangles${cloths > 1 ? `, ${cloths} cloths` : ''}`];
  if (input.mtllib !== undefined) lines.push(`mtllib ${plainText(input.mtllib, 200)}`);
  const normals = new Float32Array(3 * n);
  for (let c = 0; c < cloths; c++) {
    normals.set(vertexNormals(x, (model.clothParts?.[c] ?? model).triangles, starts[c], starts[c + 1] - starts[c]), 3 * starts[c]);
  }
  const uv = model.uvs, t = model.triangles;
  for (let i = 0; i < n; i++) lines.push(`v ${x[3 * i]} ${x[3 * i + 1]} ${x[3 * i + 2]}`);
  for (let i = 0; i < n; i++) lines.push(`vt ${uv[2 * i]} ${uv[2 * i + 1]}`);
  for (let i = 0; i < n; i++) lines.push(`vn ${normals[3 * i]} ${normals[3 * i + 1]} ${normals[3 * i + 2]}`);
  for (let c = 0; c < cloths; c++) {
    lines.push(`o ${cloths > 1 ? plainText(input.cloths[c].name, 100) : safe}`);
    if (input.mtllib !== undefined) lines.push(`usemtl ${materials.get(input.cloths[c].material)}`);
    for (let k = 0; k < t.length; k += 3) {
      // a triangle is its first vertex's cloth's
      if (t[k] < starts[c] || t[k] >= starts[c + 1]) continue;
      const a = t[k] + 1, b = t[k + 1] + 1, c3 = t[k + 2] + 1;
      lines.push(`f ${a}/${a}/${a} ${b}/${b}/${b} ${c3}/${c3}/${c3}`);
    }
  }
  return lines.join('\n') + '\n';
}

const channel = (v: number) => Math.min(1, Math.max(0, v)).toFixed(4);

/**
 * The MTL text of the cloths' materials: the colour as Kd (sRGB), the roughness as Pr (the PBR extension Blender
 * reads) and as the Phong exponent Ns = 1000·(1 − roughness)² for readers without it; not metallic, opaque.
 */
export function toMTL(input: ObjInput): string {
  const lines = [`# Drape materials of '${plainText(input.name, 100)}'`];
  for (const [m, name] of materialNames(input)) {
    const r = Math.min(1, Math.max(0, m.roughness));
    lines.push('', `newmtl ${name}`, `Kd ${m.color.map(channel).join(' ')}`, 'Ka 0 0 0', 'Ks 0.04 0.04 0.04',
      `Ns ${(1000 * (1 - r) ** 2).toFixed(1)}`, `Pr ${r}`, 'Pm 0', 'd 1', 'illum 2');
  }
  return lines.join('\n') + '\n';
}
