#!/usr/bin/env node
// The numbers of docs/performance.md "Mesh collider": build time of the mesh collider (weld, topology, SAH BVH,
// distance grid) and the cost of a signed-distance query (a particle 1 cm from the surface, `within` 5 mm as the
// contact loop asks; a particle 4 mm from it, a hit) and of a triangle contact query (a 3 cm cloth triangle 4 mm
// above), on UV spheres of about 1k, 10k and 100k triangles. Needs `npx tsc -p tsconfig.build.json` (reads dist/).
//   node scripts/bench-bvh.mjs
import { MeshCollider } from '../dist/core/colliders/mesh.js';
import { uvSphereMesh } from '../dist/core/colliders/mesh-shapes.js';

const n = new Float64Array(3), bary = new Float64Array(3), tri = new Float32Array(9);
const dir = (i) => { const z = 1 - (2 * ((i * 0.618034) % 1)), r = Math.sqrt(1 - z * z), ph = i * 2.39996; return [r * Math.cos(ph), z, r * Math.sin(ph)]; };
for (const [rings, segments] of [[16, 32], [50, 100], [158, 316]]) {
  const m = uvSphereMesh(rings, segments, 0.5);
  let t0 = performance.now();
  const shape = new MeshCollider(m.positions, m.triangles, 'sphere');
  const build = performance.now() - t0;
  const Q = 200000;
  const query = (gap, within) => {
    let acc = 0; t0 = performance.now();
    for (let i = 0; i < Q; i++) { const d = dir(i); const r = 0.5 + gap; acc += shape.signedDistance(r * d[0], r * d[1], r * d[2], n, within); }
    return ((performance.now() - t0) / Q) * 1e3;
  };
  const miss = query(0.01, 0.005), hit = query(0.004, 0.005), far = query(0.3, 0.005);
  const T = 50000;
  t0 = performance.now();
  for (let i = 0; i < T; i++) {
    const d = dir(i), r = 0.504, t = [Math.abs(d[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0]][0];
    const u = [d[1] * t[2] - d[2] * t[1], d[2] * t[0] - d[0] * t[2], d[0] * t[1] - d[1] * t[0]], ul = Math.hypot(...u);
    const v = [d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]];
    for (let k = 0; k < 3; k++) {
      const a = (2 * Math.PI * k) / 3, s = 0.017;
      for (let c = 0; c < 3; c++) tri[3 * k + c] = r * d[c] + s * (Math.cos(a) * u[c] / ul + Math.sin(a) * v[c] / ul);
    }
    shape.triangleDeepest(tri, 0, tri, 3, tri, 6, bary, n, 0.005);
  }
  const triangle = ((performance.now() - t0) / T) * 1e3;
  console.log(`${(m.triangles.length / 3).toString().padStart(6)} triangles: build ${build.toFixed(1)} ms (${shape.bvh.nodeCount} nodes, depth ${shape.bvh.depth}); ` +
    `signedDistance: hit ${hit.toFixed(2)} µs, miss at 1 cm ${miss.toFixed(2)} µs, 30 cm out ${far.toFixed(2)} µs; triangleDeepest ${triangle.toFixed(2)} µs`);
}
