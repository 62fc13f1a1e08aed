// Writes examples/tshirt.obj and examples/tshirt.gltf: a T-shirt-shaped open surface (front and back panels sewn
// at the shoulders, the tops and bottoms of the sleeves and the sides; open at the neck, the hem and the cuffs),
// in metres, y up, front towards +z. The garment the triangle-mesh tests and the `tshirt` example drop on a sphere.
//   node scripts/make-tshirt.mjs
import { writeFileSync } from 'node:fs';

const c = 0.025; // cell size [m]
const body = 0.25, sleeve = 0.45; // half widths [m]
const hem = -0.35, armpit = 0.05, top = 0.25, neck = 0.08; // heights and the neck's half width [m]
const depth = 0.06; // how far each panel bulges from the seams [m]

const I = Math.round(sleeve / c), J0 = Math.round(hem / c), J1 = Math.round(top / c);
const inT = (x, y) => y > hem && y < top && (Math.abs(x) < body || (Math.abs(x) < sleeve && y > armpit));
const cellIn = (i, j) => inT((i + 0.5) * c, (j + 0.5) * c);
const used = (i, j) => cellIn(i - 1, j - 1) || cellIn(i, j - 1) || cellIn(i - 1, j) || cellIn(i, j);
const interior = (i, j) => cellIn(i - 1, j - 1) && cellIn(i, j - 1) && cellIn(i - 1, j) && cellIn(i, j);
// boundary points strictly inside an opening belong to one panel; every other boundary point is on a seam
const eps = 1e-9;
function open(i, j) {
  const x = i * c, y = j * c;
  if (Math.abs(y - hem) < eps && Math.abs(x) < body - eps) return true;
  if (Math.abs(Math.abs(x) - sleeve) < eps && y > armpit + eps && y < top - eps) return true;
  return Math.abs(y - top) < eps && Math.abs(x) < neck - eps;
}
const seam = (i, j) => used(i, j) && !interior(i, j) && !open(i, j);

// distance to the nearest seam point, for the bulge
const seams = [];
for (let j = J0; j <= J1; j++) for (let i = -I; i <= I; i++) if (seam(i, j)) seams.push([i * c, j * c]);
const bulge = (x, y) => {
  let d = Infinity;
  for (const [sx, sy] of seams) d = Math.min(d, Math.hypot(x - sx, y - sy));
  return depth * Math.min(1, d / 0.1);
};

const pos = [], uv = [], tri = [];
const index = [new Map(), new Map()]; // per panel: 'i,j' → vertex
for (let side = 0; side < 2; side++) {
  for (let j = J0; j <= J1; j++) {
    for (let i = -I; i <= I; i++) {
      if (!used(i, j)) continue;
      const key = `${i},${j}`;
      if (side === 1 && seam(i, j)) { index[1].set(key, index[0].get(key)); continue; }
      const x = i * c, y = j * c, z = (side ? -1 : 1) * (seam(i, j) ? 0 : bulge(x, y));
      index[side].set(key, pos.length / 3);
      pos.push(x, y, z);
      uv.push((x / sleeve + 1) / 4 + side / 2, (y - hem) / (top - hem));
    }
  }
  const id = (i, j) => index[side].get(`${i},${j}`);
  for (let j = J0; j < J1; j++) {
    for (let i = -I; i < I; i++) {
      if (!cellIn(i, j)) continue;
      const a = id(i, j), b = id(i + 1, j), cc = id(i + 1, j + 1), d = id(i, j + 1);
      // the diagonal that does not join two seam points (both panels would share it)
      const alt = seam(i, j) && seam(i + 1, j + 1);
      const quad = alt ? [[a, b, d], [b, cc, d]] : [[a, b, cc], [a, cc, d]];
      for (const [p, q, r] of quad) tri.push(...(side ? [p, r, q] : [p, q, r])); // both panels face outwards
    }
  }
}

const f3 = (v) => Number(v.toFixed(5));
let obj = '# Drape example garment: a T-shirt-shaped open surface (scripts/make-tshirt.mjs), metres, y up\n';
for (let k = 0; k < pos.length; k += 3) obj += `v ${f3(pos[k])} ${f3(pos[k + 1])} ${f3(pos[k + 2])}\n`;
for (let k = 0; k < uv.length; k += 2) obj += `vt ${f3(uv[k])} ${f3(uv[k + 1])}\n`;
for (let k = 0; k < tri.length; k += 3) obj += `f ${tri.slice(k, k + 3).map((v) => `${v + 1}/${v + 1}`).join(' ')}\n`;
writeFileSync(new URL('../examples/tshirt.obj', import.meta.url), obj);

const P = new Float32Array(pos.map(f3)), T = new Float32Array(uv.map(f3)), X = new Uint32Array(tri);
const bin = Buffer.concat([Buffer.from(P.buffer), Buffer.from(T.buffer), Buffer.from(X.buffer)]);
const lo = [0, 1, 2].map((k) => Math.min(...pos.filter((_, n) => n % 3 === k).map(f3)));
const hi = [0, 1, 2].map((k) => Math.max(...pos.filter((_, n) => n % 3 === k).map(f3)));
const gltf = {
  asset: { version: '2.0', generator: 'drape scripts/make-tshirt.mjs' },
  scene: 0,
  scenes: [{ nodes: [0] }],
  nodes: [{ mesh: 0, name: 'tshirt' }],
  meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, mode: 4 }] }],
  buffers: [{ byteLength: bin.length, uri: `data:application/octet-stream;base64,${bin.toString('base64')}` }],
  bufferViews: [
    { buffer: 0, byteOffset: 0, byteLength: P.byteLength, target: 34962 },
    { buffer: 0, byteOffset: P.byteLength, byteLength: T.byteLength, target: 34962 },
    { buffer: 0, byteOffset: P.byteLength + T.byteLength, byteLength: X.byteLength, target: 34963 },
  ],
  accessors: [
    { bufferView: 0, componentType: 5126, count: P.length / 3, type: 'VEC3', min: lo, max: hi },
    { bufferView: 1, componentType: 5126, count: T.length / 2, type: 'VEC2' },
    { bufferView: 2, componentType: 5125, count: X.length, type: 'SCALAR' },
  ],
};
writeFileSync(new URL('../examples/tshirt.gltf', import.meta.url), JSON.stringify(gltf) + '\n');
console.log(`examples/tshirt.obj, examples/tshirt.gltf: ${pos.length / 3} vertices, ${tri.length / 3} triangles`);
