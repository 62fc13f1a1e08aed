/**
 * Triangle meshes made in code, for the mesh collider's tests and its benchmark (scripts/bench-bvh.mjs): a cube, an
 * icosphere, a UV sphere of a chosen size, an open bowl and an open terrain. Positions [m], triangles outward
 * (counter-clockwise seen from outside) for the closed ones.
 */
import type { TriangleMesh } from '../mesh/triangle-mesh.js';

/** The cube of half size h about c, two triangles per face, outward. */
export function cubeMesh(c: readonly number[] = [0, 0, 0], h = 0.5): TriangleMesh {
  const positions = new Float32Array(24);
  for (let k = 0; k < 8; k++) {
    positions[3 * k] = c[0] + (k & 1 ? h : -h);
    positions[3 * k + 1] = c[1] + (k & 2 ? h : -h);
    positions[3 * k + 2] = c[2] + (k & 4 ? h : -h);
  }
  // faces as quads a b c d counter-clockwise from outside
  const quads = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]];
  const triangles = new Uint32Array(36);
  quads.forEach((q, f) => triangles.set([q[0], q[1], q[2], q[0], q[2], q[3]], 6 * f));
  return { positions, triangles };
}

/** An icosahedron subdivided `levels` times and pushed onto the sphere of radius r about c: 20·4^levels triangles. */
export function icosphereMesh(levels: number, r = 1, c: readonly number[] = [0, 0, 0]): TriangleMesh {
  const t = (1 + Math.sqrt(5)) / 2;
  let verts: number[][] = [
    [-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
    [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1],
  ].map((v) => { const l = Math.hypot(v[0], v[1], v[2]); return [v[0] / l, v[1] / l, v[2] / l]; });
  let faces = [
    [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
    [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
  ];
  for (let l = 0; l < levels; l++) {
    const mid = new Map<string, number>();
    const midpoint = (a: number, b: number) => {
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      let i = mid.get(key);
      if (i === undefined) {
        const v = [0, 1, 2].map((k) => verts[a][k] + verts[b][k]);
        const len = Math.hypot(v[0], v[1], v[2]);
        i = verts.length;
        verts.push(v.map((x) => x / len));
        mid.set(key, i);
      }
      return i;
    };
    const next: number[][] = [];
    for (const [a, b, cc] of faces) {
      const ab = midpoint(a, b), bc = midpoint(b, cc), ca = midpoint(cc, a);
      next.push([a, ab, ca], [b, bc, ab], [cc, ca, bc], [ab, bc, ca]);
    }
    faces = next;
    verts = [...verts];
  }
  const positions = new Float32Array(3 * verts.length);
  verts.forEach((v, i) => { positions[3 * i] = c[0] + r * v[0]; positions[3 * i + 1] = c[1] + r * v[1]; positions[3 * i + 2] = c[2] + r * v[2]; });
  return { positions, triangles: Uint32Array.from(faces.flat()) };
}

/**
 * A sphere of radius r about c by latitude rings and longitude segments, fans at the poles: 2·segments·(rings − 1)
 * triangles (the benchmark picks the size).
 */
export function uvSphereMesh(rings: number, segments: number, r = 1, c: readonly number[] = [0, 0, 0]): TriangleMesh {
  const pos: number[] = [c[0], c[1] + r, c[2]];
  for (let i = 1; i < rings; i++) {
    const th = (Math.PI * i) / rings;
    for (let j = 0; j < segments; j++) {
      const ph = (2 * Math.PI * j) / segments;
      pos.push(c[0] + r * Math.sin(th) * Math.cos(ph), c[1] + r * Math.cos(th), c[2] - r * Math.sin(th) * Math.sin(ph));
    }
  }
  pos.push(c[0], c[1] - r, c[2]);
  const south = pos.length / 3 - 1, at = (i: number, j: number) => 1 + (i - 1) * segments + (j % segments);
  const tri: number[] = [];
  for (let j = 0; j < segments; j++) tri.push(0, at(1, j), at(1, j + 1));
  for (let i = 1; i < rings - 1; i++) {
    for (let j = 0; j < segments; j++) tri.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
  }
  for (let j = 0; j < segments; j++) tri.push(south, at(rings - 1, j + 1), at(rings - 1, j));
  return { positions: Float32Array.from(pos), triangles: Uint32Array.from(tri) };
}

/** The lower half of a UV sphere (radius r about c), open at the top: a bowl. */
export function bowlMesh(rings: number, segments: number, r = 1, c: readonly number[] = [0, 0, 0]): TriangleMesh {
  const full = uvSphereMesh(2 * rings, segments, r, c);
  const keep: number[] = [];
  const t = full.triangles, p = full.positions;
  for (let k = 0; k < t.length; k += 3) {
    if ([0, 1, 2].every((i) => p[3 * t[k + i] + 1] <= c[1] + 1e-6 * r)) keep.push(t[k], t[k + 1], t[k + 2]);
  }
  return { positions: p, triangles: Uint32Array.from(keep) };
}

/**
 * An open height field over [−half, half]² in x and z, `cells` squares per side, each cut along its x-then-z
 * diagonal: y = height(x, z). Triangles face up.
 */
export function terrainMesh(cells: number, half: number, height: (x: number, z: number) => number): TriangleMesh {
  const n = cells + 1, positions = new Float32Array(3 * n * n);
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      const x = -half + (2 * half * j) / cells, z = -half + (2 * half * i) / cells, k = 3 * (i * n + j);
      positions[k] = x; positions[k + 1] = height(x, z); positions[k + 2] = z;
    }
  }
  const tri: number[] = [];
  for (let i = 0; i < cells; i++) {
    for (let j = 0; j < cells; j++) {
      const a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      tri.push(a, c, d, a, d, b);
    }
  }
  return { positions, triangles: Uint32Array.from(tri) };
}
