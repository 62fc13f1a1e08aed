/**
 * Wavefront OBJ as a cloth mesh: `v` positions, `vt` texture coordinates and `f` faces (polygons split into a fan
 * of triangles; 1-based and negative relative indices; `v/vt/vn`, `v//vn` and `v/vt` corners). Everything else
 * (normals, groups, materials, lines) is read past. Errors name the file and the line.
 */
import { SceneError } from '../scene.js';
import { MAX_MESH_PARTICLES, type TriangleMesh } from './triangle-mesh.js';

/** Most triangles a file may bring: a mesh of a cloth's most particles has about twice as many; this is twice that. */
const MAX_FILE_TRIANGLES = 4 * MAX_MESH_PARTICLES;

/** Parses OBJ text; `source` (the file name) starts every error message. The mesh is not yet prepared. */
export function parseObj(text: string, source: string): TriangleMesh {
  const pos: number[] = [];
  const tex: number[] = [];
  const tri: number[] = [];
  // the texture coordinate of each vertex: the first face corner that gives one
  const vertexTex: number[] = [];
  const lines = text.split(/\r?\n/);
  const fail = (line: number, why: string): never => {
    throw new SceneError(`${source}:${line}: ${why}`);
  };
  // OBJ's numbers are decimal: Number() alone also reads '0x1', '0b1' and '0o7'
  const decimal = (w: string | undefined): number => (w !== undefined && /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(w) ? Number(w) : NaN);
  for (let ln = 0; ln < lines.length; ln++) {
    const words = lines[ln].trim().split(/\s+/);
    const kind = words[0];
    if (kind === 'v') {
      if (words.length < 4) fail(ln + 1, 'a vertex needs x y z');
      for (let k = 1; k <= 3; k++) {
        const x = decimal(words[k]);
        if (!Number.isFinite(x)) fail(ln + 1, `vertex coordinate '${words[k].slice(0, 20)}' is not a number`);
        pos.push(x);
      }
    } else if (kind === 'vt') {
      const u = decimal(words[1]), v = words.length > 2 ? decimal(words[2]) : 0;
      if (!Number.isFinite(u) || !Number.isFinite(v)) fail(ln + 1, 'a texture coordinate needs numbers u [v]');
      tex.push(u, v);
    } else if (kind === 'f') {
      if (words.length < 4) fail(ln + 1, 'a face needs at least three corners');
      const corners: number[] = [];
      for (let k = 1; k < words.length; k++) {
        const [vs, ts] = words[k].split('/');
        const nv = pos.length / 3, nt = tex.length / 2;
        const integer = (w: string) => (/^-?\d{1,10}$/.test(w) ? Number(w) : NaN);
        const vi = integer(vs), ti = ts ? integer(ts) : 0;
        if (!Number.isInteger(vi) || vi === 0) fail(ln + 1, `face corner '${words[k].slice(0, 30)}' does not start with a vertex number`);
        const v = vi > 0 ? vi - 1 : nv + vi;
        if (v < 0 || v >= nv) fail(ln + 1, `face uses vertex ${vi}, but only ${nv} are defined above it`);
        if (ts) {
          if (!Number.isInteger(ti) || ti === 0) fail(ln + 1, `face corner '${words[k].slice(0, 30)}' has a texture index that is not a number`);
          const t = ti > 0 ? ti - 1 : nt + ti;
          if (t < 0 || t >= nt) fail(ln + 1, `face uses texture coordinate ${ti}, but only ${nt} are defined above it`);
          if (vertexTex[v] === undefined) vertexTex[v] = t;
        }
        corners.push(v);
      }
      for (let k = 1; k + 1 < corners.length; k++) tri.push(corners[0], corners[k], corners[k + 1]);
      if (tri.length > 3 * MAX_FILE_TRIANGLES) fail(ln + 1, `more than ${MAX_FILE_TRIANGLES} triangles`);
    }
  }
  const n = pos.length / 3;
  let uvs: Float32Array | undefined;
  if (tex.length) {
    uvs = new Float32Array(2 * n);
    for (let i = 0; i < n; i++) {
      const t = vertexTex[i];
      if (t !== undefined) { uvs[2 * i] = tex[2 * t]; uvs[2 * i + 1] = tex[2 * t + 1]; }
    }
  }
  return { positions: Float32Array.from(pos), triangles: Uint32Array.from(tri), uvs };
}
