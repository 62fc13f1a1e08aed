/**
 * Wavefront OBJ and its MTL of a model's cloths as they are now: positions [m] (as many digits as the float32 they
 * are: at least 7 significant), texture coordinates, vertex normals and triangles (1-based, v/vt/vn), one object
 * (`o`) per cloth over one vertex list, the cloths' vertices one after another (for a model's cloths, modelCloths in
 * glb.ts: the scene's particle numbering), each object with its material (`usemtl`). Strings
 * from the scene are written on one line each, without control characters: a name cannot add lines to the file.
 */
import { plainText } from '../text.js';
import { checkFinite, checkInput, checkMaterial, type ExportCloth, type GlbMaterial } from './glb.js';
import { vertexNormals } from './normals.js';

/** What the OBJ writer takes: the scene's name, its cloths as the glb writer's; `mtllib` names the MTL file beside it. */
export interface ObjInput {
  readonly name: string;
  readonly cloths: readonly ExportCloth[];
  readonly mtllib?: string;
}

/** one word: OBJ and MTL names end at white space */
const word = (s: string) => plainText(s, 60).replace(/\s+/g, '_') || 'material';

/**
 * An object's name (`o`): one line, no `#` (some readers take it for a comment's start), and `cloth N` for a name
 * that is empty or white space.
 */
const objectName = (s: string, k: number) => plainText(s, 100).replace(/#/g, '_').trim() || `cloth ${k + 1}`;

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

/** The OBJ text (see the module's comment). Throws RangeError on non-finite positions (a file never holds a NaN). */
export function toOBJ(input: ObjInput): string {
  checkInput(input, 'obj');
  const safe = plainText(input.name, 100), cloths = input.cloths;
  for (const c of cloths) checkFinite(c.positions, `cloth '${plainText(c.name, 40)}'`, 'obj');
  const materials = materialNames(input);
  const vertices = cloths.reduce((v, c) => v + c.positions.length / 3, 0), triangles = cloths.reduce((t, c) => t + c.triangles.length / 3, 0);
  const lines = [`# Drape cloth '${safe}': ${vertices} vertices, ${triangles} triangles${cloths.length > 1 ? `, ${cloths.length} cloths` : ''}`];
  if (input.mtllib !== undefined) lines.push(`mtllib ${plainText(input.mtllib, 200)}`);
  for (const { positions: x } of cloths) for (let i = 0; i < x.length; i += 3) lines.push(`v ${x[i]} ${x[i + 1]} ${x[i + 2]}`);
  for (const { uvs } of cloths) for (let i = 0; i < uvs.length; i += 2) lines.push(`vt ${uvs[i]} ${uvs[i + 1]}`);
  for (const c of cloths) {
    const n = vertexNormals(c.positions, c.triangles);
    for (let i = 0; i < n.length; i += 3) lines.push(`vn ${n[i]} ${n[i + 1]} ${n[i + 2]}`);
  }
  // one vertex list: cloth c's vertices follow the earlier cloths' (1-based)
  let first = 1;
  for (const c of cloths) {
    lines.push(`o ${objectName(cloths.length > 1 ? c.name : input.name, cloths.indexOf(c))}`);
    if (input.mtllib !== undefined) lines.push(`usemtl ${materials.get(c.material)}`);
    const t = c.triangles;
    for (let k = 0; k < t.length; k += 3) {
      const a = t[k] + first, b = t[k + 1] + first, c3 = t[k + 2] + first;
      lines.push(`f ${a}/${a}/${a} ${b}/${b}/${b} ${c3}/${c3}/${c3}`);
    }
    first += c.positions.length / 3;
  }
  return lines.join('\n') + '\n';
}

const channel = (v: number) => Math.min(1, Math.max(0, v)).toFixed(4);

/**
 * The MTL text of the cloths' materials: the colour as Kd (sRGB), the roughness as Pr (the PBR extension Blender
 * reads) and as the Phong exponent Ns = 1000·(1 − roughness)² for readers without it; not metallic, opaque. Throws
 * RangeError on a colour or roughness that is not finite.
 */
export function toMTL(input: ObjInput): string {
  checkInput(input, 'mtl');
  const lines = [`# Drape materials of '${plainText(input.name, 100)}'`];
  for (const [m, name] of materialNames(input)) {
    checkMaterial(m, 'mtl');
    const r = Math.min(1, Math.max(0, m.roughness));
    lines.push('', `newmtl ${name}`, `Kd ${m.color.map(channel).join(' ')}`, 'Ka 0 0 0', 'Ks 0.04 0.04 0.04',
      `Ns ${(1000 * (1 - r) ** 2).toFixed(1)}`, `Pr ${r}`, 'Pm 0', 'd 1', 'illum 2');
  }
  return lines.join('\n') + '\n';
}
