// UV spheres of radius 0.5 m with about 1k, 10k and 100k triangles (960, 9 800, 99 224), each with a scene that drops a
// 64² cotton cloth from 1.2 m onto it (a mesh collider centred 0.5 m up) and a floor: the mesh-collider rows of
// scripts/gpu/owed.sh.   node scripts/gpu/mesh-spheres.mjs DIR
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const dir = process.argv[2] ?? '/tmp/gpu-mesh';
mkdirSync(dir, { recursive: true });
for (const [name, rings] of [['1k', 16], ['10k', 50], ['100k', 158]]) {
  const segs = 2 * rings, v = [[0, 0.5, 0]], f = [];
  for (let i = 1; i < rings; i++) {
    const th = (Math.PI * i) / rings;
    for (let j = 0; j < segs; j++) {
      const ph = (2 * Math.PI * j) / segs;
      v.push([0.5 * Math.sin(th) * Math.cos(ph), 0.5 * Math.cos(th), 0.5 * Math.sin(th) * Math.sin(ph)]);
    }
  }
  v.push([0, -0.5, 0]);
  const at = (i, j) => 1 + (i - 1) * segs + (j % segs), last = v.length - 1;
  for (let j = 0; j < segs; j++) f.push([0, at(1, j + 1), at(1, j)]);
  for (let i = 1; i < rings - 1; i++) {
    for (let j = 0; j < segs; j++) { f.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]); f.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]); }
  }
  for (let j = 0; j < segs; j++) f.push([last, at(rings - 1, j), at(rings - 1, j + 1)]);
  writeFileSync(join(dir, `sphere-${name}.obj`), `${v.map((p) => `v ${p.join(' ')}`).join('\n')}\n${f.map((t) => `f ${t.map((k) => k + 1).join(' ')}`).join('\n')}\n`);
  writeFileSync(join(dir, `mesh-${name}.json`), JSON.stringify({
    name: `mesh-${name}`, cloth: { resolution: 64, position: [0, 1.2, 0] }, material: { fabric: 'cotton' },
    colliders: [{ type: 'mesh', mesh: `sphere-${name}.obj`, scale: 1, position: [0, 0.5, 0], rotation: [0, 0, 0] }, { type: 'floor', height: 0 }],
  }, null, 1));
  console.log(`${name}: ${f.length} triangles`);
}
