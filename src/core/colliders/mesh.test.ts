/**
 * The mesh collider's geometry against brute force: the BVH's closest point against every triangle, the signed
 * distance of closed meshes against exact formulas (box, convex polyhedron) and ray parity (a dented, non-convex
 * mesh), the unsigned distance of open ones, the `within` early out, the triangle contact against sampling and
 * against the analytic box, the placement, and bad input.
 */
import { describe, expect, it } from 'vitest';
import { mulberry32 } from '../random.js';
import { SceneError } from '../scene.js';
import { BoxCollider } from './box.js';
import { TriangleBvh } from './bvh.js';
import { MeshCollider, meshCollider, MAX_COLLIDER_TRIANGLES } from './mesh.js';
import { bowlMesh, cubeMesh, icosphereMesh, terrainMesh, uvSphereMesh } from './mesh-shapes.js';
import { eulerXYZ } from '../mesh/generators.js';
import { PosedCollider } from './pose.js';
import { closestPointOnTriangle } from './sphere.js';
import type { TriangleMesh } from '../mesh/triangle-mesh.js';

const bary = new Float64Array(3);
const normal = new Float64Array(3);

/** Unsigned distance to the mesh over every triangle, and the closest point. */
function bruteDistance(m: TriangleMesh, p: readonly number[]): { d: number; c: number[] } {
  const x = m.positions, t = m.triangles;
  let best = Infinity, c: number[] = [];
  for (let k = 0; k < t.length; k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1], cc = 3 * t[k + 2];
    closestPointOnTriangle(p[0], p[1], p[2], x[a], x[a + 1], x[a + 2], x[b], x[b + 1], x[b + 2], x[cc], x[cc + 1], x[cc + 2], bary);
    const q = [0, 1, 2].map((i) => bary[0] * x[a + i] + bary[1] * x[b + i] + bary[2] * x[cc + i]);
    const d = Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
    if (d < best) { best = d; c = q; }
  }
  return { d: best, c };
}

/** Ray parity along a fixed odd direction (Möller–Trumbore): inside a closed mesh. */
function inside(m: TriangleMesh, p: readonly number[]): boolean {
  const dir = [0.5377, 0.8183, 0.2028], x = m.positions, t = m.triangles;
  let hits = 0;
  for (let k = 0; k < t.length; k += 3) {
    const a = [0, 1, 2].map((i) => x[3 * t[k] + i]), b = [0, 1, 2].map((i) => x[3 * t[k + 1] + i]), c = [0, 1, 2].map((i) => x[3 * t[k + 2] + i]);
    const e1 = b.map((v, i) => v - a[i]), e2 = c.map((v, i) => v - a[i]);
    const pv = [dir[1] * e2[2] - dir[2] * e2[1], dir[2] * e2[0] - dir[0] * e2[2], dir[0] * e2[1] - dir[1] * e2[0]];
    const det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (Math.abs(det) < 1e-12) continue;
    const tv = p.map((v, i) => v - a[i]);
    const u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    if (u < 0 || u > 1) continue;
    const qv = [tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]];
    const v = (dir[0] * qv[0] + dir[1] * qv[1] + dir[2] * qv[2]) / det;
    if (v < 0 || u + v > 1) continue;
    if ((e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det > 0) hits++;
  }
  return hits % 2 === 1;
}

/** A cube with a pyramid-shaped dent pushed into its top face: closed, not convex. */
function dentedCube(): TriangleMesh {
  const c = cubeMesh([0, 0, 0], 0.5);
  const p = Array.from(c.positions);
  const top = [2, 6, 7, 3]; // y = +h, counter-clockwise from above
  const centre = p.length / 3;
  p.push(0, 0.1, 0); // the dent's apex, 0.4 below the top face
  const tri: number[] = [];
  for (let k = 0; k < c.triangles.length; k += 3) {
    const f = [c.triangles[k], c.triangles[k + 1], c.triangles[k + 2]];
    if (f.every((v) => top.includes(v))) continue;
    tri.push(...f);
  }
  for (let k = 0; k < 4; k++) tri.push(top[k], centre, top[(k + 1) % 4]);
  return { positions: Float32Array.from(p), triangles: Uint32Array.from(tri) };
}

/** Random points in a box, and points within 1 cm of the mesh's vertices and edge midpoints. */
function samplePoints(m: TriangleMesh, lo: number, hi: number, count: number, seed: number): number[][] {
  const rnd = mulberry32(seed), pts: number[][] = [];
  for (let i = 0; i < count; i++) pts.push([0, 1, 2].map(() => lo + (hi - lo) * rnd()));
  const x = m.positions, t = m.triangles;
  for (let k = 0; k < Math.min(t.length, 600); k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1];
    const jitter = () => 0.02 * (rnd() - 0.5);
    pts.push([x[a] + jitter(), x[a + 1] + jitter(), x[a + 2] + jitter()]);
    pts.push([0.5 * (x[a] + x[b]) + jitter(), 0.5 * (x[a + 1] + x[b + 1]) + jitter(), 0.5 * (x[a + 2] + x[b + 2]) + jitter()]);
  }
  return pts;
}

describe('TriangleBvh', () => {
  it('finds the closest point of every triangle (brute force), and stores its arrays flat', () => {
    const m = uvSphereMesh(20, 40, 0.7, [0.1, 0.2, -0.1]);
    const bvh = new TriangleBvh(m.positions, m.triangles);
    expect(bvh.bounds).toBeInstanceOf(Float32Array);
    expect(bvh.nodes).toBeInstanceOf(Uint32Array);
    expect(bvh.nodeCount).toBeLessThanOrEqual(2 * (m.triangles.length / 3) - 1);
    // every triangle in exactly one leaf, inside its leaf's box
    const seen = new Uint8Array(m.triangles.length / 3);
    for (let n = 0; n < bvh.nodeCount; n++) {
      const count = bvh.nodes[2 * n + 1];
      if (count === 0) continue;
      for (let t = bvh.nodes[2 * n]; t < bvh.nodes[2 * n] + count; t++) {
        seen[bvh.order[t]]++;
        for (let c = 0; c < 3; c++) {
          for (let k = 0; k < 3; k++) {
            const v = bvh.positions[3 * bvh.triangles[3 * t + c] + k];
            expect(v).toBeGreaterThanOrEqual(bvh.bounds[6 * n + k]);
            expect(v).toBeLessThanOrEqual(bvh.bounds[6 * n + 3 + k]);
          }
        }
      }
    }
    expect(seen.every((s) => s === 1)).toBe(true);
    for (const p of samplePoints(m, -1.2, 1.2, 300, 7)) {
      const t = bvh.closest(p[0], p[1], p[2], Infinity, bary);
      expect(t).toBeGreaterThanOrEqual(0);
      expect(Math.sqrt(bvh.d2)).toBeCloseTo(bruteDistance(m, p).d, 9);
      // bounded: nothing nearer than the bound is missed, nothing farther is returned
      const d = bruteDistance(m, p).d;
      const miss = bvh.closest(p[0], p[1], p[2], (0.9 * d) ** 2, bary);
      expect(miss).toBe(-1);
    }
  });
});

describe('MeshCollider signed distance', () => {
  const check = (m: TriangleMesh, exact: (p: number[]) => number, pts: number[][]) => {
    const shape = new MeshCollider(m.positions, m.triangles, 'test');
    for (const p of pts) {
      const d = shape.signedDistance(p[0], p[1], p[2], normal);
      const e = exact(p);
      expect(Math.abs(d - e), `at ${p}: ${d} vs ${e}`).toBeLessThan(1e-6);
      // the normal leads from the closest surface point to p: p − d·n is on the surface
      if (Math.abs(d) > 1e-4) {
        const q = [p[0] - d * normal[0], p[1] - d * normal[1], p[2] - d * normal[2]];
        expect(bruteDistance(m, q).d).toBeLessThan(1e-5);
        expect(Math.hypot(normal[0], normal[1], normal[2])).toBeCloseTo(1, 9);
      }
    }
    return shape;
  };

  it('a cube mesh: the exact box distance, inside negative, at random points and near corners and edges', () => {
    const m = cubeMesh([0.1, 0.3, -0.2], 0.4);
    const box = new BoxCollider([0.1, 0.3, -0.2], [0.4, 0.4, 0.4]);
    const shape = check(m, (p) => box.signedDistance(p[0], p[1], p[2], new Float64Array(3)), samplePoints(m, -0.6, 1, 2000, 1));
    expect(shape.closedPieces).toBe(1);
    expect(shape.openPieces).toBe(0);
    // the 12 cube edges are sharp (convex, 90°); the face diagonals are flat
    expect(shape.sharpEdges).toBe(12);
    expect(shape.minCurvatureRadius).toBe(0);
  });

  it('an icosphere (convex): outside the brute-force distance, inside the largest face-plane distance', () => {
    const m = icosphereMesh(2, 0.5, [0, 0.5, 0]);
    const x = m.positions, t = m.triangles;
    const exact = (p: number[]) => {
      let plane = -Infinity;
      for (let k = 0; k < t.length; k += 3) {
        const a = [0, 1, 2].map((i) => x[3 * t[k] + i]), b = [0, 1, 2].map((i) => x[3 * t[k + 1] + i]), c = [0, 1, 2].map((i) => x[3 * t[k + 2] + i]);
        const u = b.map((v, i) => v - a[i]), w = c.map((v, i) => v - a[i]);
        const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
        const l = Math.hypot(n[0], n[1], n[2]);
        plane = Math.max(plane, ((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2]) / l);
      }
      return plane > 0 ? bruteDistance(m, p).d : plane;
    };
    check(m, exact, samplePoints(m, -0.7, 1.2, 1000, 2));
  });

  it('a dented cube (not convex) and an inside-out copy: the sign by ray parity', () => {
    const m = dentedCube();
    const exact = (p: number[]) => (inside(m, p) ? -1 : 1) * bruteDistance(m, p).d;
    const pts = samplePoints(m, -0.7, 0.7, 1500, 3).filter((p) => bruteDistance(m, p).d > 1e-5);
    const shape = check(m, exact, pts);
    expect(shape.closedPieces).toBe(1);
    // the dent's four valley edges are concave: not sharp; its rim (the old top edges) and the other 8 cube edges are
    expect(shape.sharpEdges).toBe(12);
    const flipped = { positions: m.positions, triangles: m.triangles.map((v, k) => m.triangles[k - (k % 3) + (2 - (k % 3))]) };
    check(flipped, exact, pts.slice(0, 300));
  });

  it('open meshes (a bowl, a terrain) are two-sided shells: the unsigned distance, the normal toward the point', () => {
    const bowl = bowlMesh(8, 24, 0.4, [0, 0.5, 0]);
    const terrain = terrainMesh(12, 1, (x, z) => 0.1 * Math.sin(3 * x) * Math.cos(2 * z));
    for (const m of [bowl, terrain]) {
      const shape = check(m, (p) => bruteDistance(m, p).d, samplePoints(m, -1.1, 1.1, 800, 4));
      expect(shape.closedPieces).toBe(0);
      expect(shape.openPieces).toBe(1);
    }
  });

  it('a file split at seams is welded; a closed and an open piece in one mesh keep their own rule', () => {
    const cube = cubeMesh([0, 0, 0], 0.3);
    // every triangle its own three vertices (as an exporter splitting normals writes it)
    const split = { positions: new Float32Array(3 * cube.triangles.length), triangles: new Uint32Array(cube.triangles.length) };
    cube.triangles.forEach((v, k) => { split.positions.set(cube.positions.subarray(3 * v, 3 * v + 3), 3 * k); split.triangles[k] = k; });
    const sheet = terrainMesh(2, 0.3, () => 1);
    const both: TriangleMesh = {
      positions: Float32Array.from([...split.positions, ...sheet.positions]),
      triangles: Uint32Array.from([...split.triangles, ...Array.from(sheet.triangles, (v) => v + split.positions.length / 3)]),
    };
    const shape = new MeshCollider(both.positions, both.triangles, 'test');
    expect(shape.closedPieces).toBe(1);
    expect(shape.openPieces).toBe(1);
    expect(shape.signedDistance(0, 0, 0, normal)).toBeCloseTo(-0.3, 6);
    expect(shape.signedDistance(0, 0.9, 0, normal)).toBeCloseTo(0.1, 6); // below the sheet at y = 1: unsigned
    expect(normal[1]).toBeCloseTo(-1, 6);
  });

  it('`within`: the exact value nearer than within, at least within farther away, and inside always the truth', () => {
    const m = dentedCube();
    const shape = new MeshCollider(m.positions, m.triangles, 'test');
    for (const p of samplePoints(m, -1.5, 1.5, 500, 5)) {
      const full = shape.signedDistance(p[0], p[1], p[2], normal);
      for (const w of [0.005, 0.05, 0.3]) {
        const d = shape.signedDistance(p[0], p[1], p[2], normal, w);
        if (full < w) expect(d).toBeCloseTo(full, 12);
        else expect(d).toBeGreaterThanOrEqual(w);
      }
    }
  });
});

describe('MeshCollider triangle contact', () => {
  const tri = new Float32Array(9);
  const put = (pts: number[][]) => pts.forEach((p, i) => tri.set(p, 3 * i));
  /** brute force: the smallest signed distance over a 40 × 40 grid of the triangle's points */
  const sampled = (shape: MeshCollider) => {
    let best = Infinity;
    for (let i = 0; i <= 40; i++) for (let j = 0; i + j <= 40; j++) {
      const u = i / 40, v = j / 40, w = 1 - u - v;
      best = Math.min(best, shape.signedDistance(w * tri[0] + u * tri[3] + v * tri[6], w * tri[1] + u * tri[4] + v * tri[7], w * tri[2] + u * tri[5] + v * tri[8], normal));
    }
    return best;
  };
  const vertexMin = (shape: MeshCollider) => Math.min(...[0, 3, 6].map((o) => shape.signedDistance(tri[o], tri[o + 1], tri[o + 2], normal)));

  it('outside a cube mesh: exactly the analytic box\'s deepest point (edges and corners under the triangle)', () => {
    const m = cubeMesh([0, 0.3, 0], 0.25);
    const shape = new MeshCollider(m.positions, m.triangles, 'test');
    const box = new BoxCollider([0, 0.3, 0], [0.25, 0.25, 0.25]);
    const rnd = mulberry32(11);
    let compared = 0;
    for (let k = 0; k < 400; k++) {
      // a 10 cm triangle near a random edge or corner of the cube
      const corner = [0, 1, 2].map(() => (rnd() < 0.5 ? -0.25 : 0.25));
      const centre = corner.map((v, i) => (i === 1 ? 0.3 : 0) + v * (rnd() < 0.3 ? 2 * rnd() - 1 : 1) + 0.04 * (rnd() - 0.5));
      put([0, 1, 2].map(() => centre.map((v) => v + 0.1 * (rnd() - 0.5))));
      const exact = box.triangleDeepest(tri, 0, tri, 3, tri, 6, bary, normal);
      if (exact <= 0.001) continue; // crossing: both search, differently
      const d = Math.min(shape.triangleDeepest(tri, 0, tri, 3, tri, 6, bary, normal), vertexMin(shape));
      expect(d).toBeCloseTo(exact, 6);
      compared++;
    }
    expect(compared).toBeGreaterThan(100);
  });

  it('never shallower than sampling, on a dented cube, an icosphere and a terrain; `within` bounds it', () => {
    const meshes = [dentedCube(), icosphereMesh(1, 0.5), terrainMesh(6, 0.6, (x, z) => 0.15 * Math.sin(4 * x + z))];
    const rnd = mulberry32(12);
    for (const m of meshes) {
      const shape = new MeshCollider(m.positions, m.triangles, 'test');
      let crossing = 0;
      for (let k = 0; k < 150; k++) {
        const centre = [0, 1, 2].map(() => 1.2 * (rnd() - 0.5));
        put([0, 1, 2].map(() => centre.map((v) => v + 0.2 * (rnd() - 0.5))));
        const d = Math.min(shape.triangleDeepest(tri, 0, tri, 3, tri, 6, bary, normal), vertexMin(shape));
        const s = sampled(shape);
        // within the grid's spacing of the surface: it may cross it (through an open shell's face with vertices on
        // both sides, nothing tells which side is right: see mesh.ts)
        if (s < 0.01) { crossing++; if (s < 0) expect(d).toBeLessThan(0.01); continue; }
        // at most the sampled minimum; the grid's spacing (0.2·√2/40) bounds how much deeper the truth can be
        expect(d).toBeLessThanOrEqual(s + 1e-9);
        expect(d).toBeGreaterThan(s - 0.01);
        // the point at bary has that distance, and the normal is a unit vector
        const dw = shape.triangleDeepest(tri, 0, tri, 3, tri, 6, bary, normal, 0.01);
        if (dw < 0.01) {
          const q = [0, 1, 2].map((i) => bary[0] * tri[i] + bary[1] * tri[3 + i] + bary[2] * tri[6 + i]);
          expect(shape.signedDistance(q[0], q[1], q[2], new Float64Array(3))).toBeCloseTo(dw, 9);
          expect(Math.hypot(normal[0], normal[1], normal[2])).toBeCloseTo(1, 6);
        }
      }
      expect(crossing).toBeLessThan(150);
    }
  });
});

describe('placement and input', () => {
  it('a placed mesh is the same shape moved and turned (distances, normals, triangle contact)', () => {
    const m = dentedCube();
    const local = new MeshCollider(m.positions, m.triangles, 'test');
    const world = new PosedCollider(local, eulerXYZ([30, -20, 70]), [1, 2, 3]);
    const r = world.R, rnd = mulberry32(13), n2 = new Float64Array(3);
    for (let k = 0; k < 200; k++) {
      const l = [0, 1, 2].map(() => 1.4 * (rnd() - 0.5));
      const w = [0, 1, 2].map((i) => [1, 2, 3][i] + r[3 * i] * l[0] + r[3 * i + 1] * l[1] + r[3 * i + 2] * l[2]);
      const dl = local.signedDistance(l[0], l[1], l[2], normal);
      expect(world.signedDistance(w[0], w[1], w[2], n2)).toBeCloseTo(dl, 5);
      for (let i = 0; i < 3; i++) expect(n2[i]).toBeCloseTo(r[3 * i] * normal[0] + r[3 * i + 1] * normal[1] + r[3 * i + 2] * normal[2], 4);
    }
  });

  it('bad meshes are refused in one line naming the source', () => {
    const cube = cubeMesh();
    const bad = (positions: Float32Array, triangles: Uint32Array) => () => new MeshCollider(positions, triangles, 'x.obj');
    expect(bad(cube.positions, new Uint32Array(0))).toThrow(/^x\.obj: no triangles/);
    expect(bad(cube.positions, Uint32Array.from([0, 1, 99]))).toThrow('x.obj: face 1 uses vertex 100, but there are only 8');
    expect(bad(Float32Array.from([0, 0, NaN, 1, 0, 0, 0, 1, 0]), Uint32Array.from([0, 1, 2]))).toThrow('not a finite number');
    expect(bad(new Float32Array(9), Uint32Array.from([0, 1, 2]))).toThrow('x.obj: all vertices are at one point');
    expect(bad(Float32Array.from([0, 0, 0, 1, 0, 0, 2, 0, 0]), Uint32Array.from([0, 1, 2]))).toThrow('x.obj: no triangle has any area');
    expect(bad(cube.positions, new Uint32Array(3 * (MAX_COLLIDER_TRIANGLES + 1)))).toThrow(`at most ${MAX_COLLIDER_TRIANGLES}`);
    try { bad(cube.positions, new Uint32Array(0))(); } catch (e) { expect(e).toBeInstanceOf(SceneError); }
  });

  it('one collider per mesh and scale: a parameter change builds no new hierarchy', () => {
    const m = cubeMesh();
    expect(meshCollider(m, 1, 'a')).toBe(meshCollider(m, 1, 'a'));
    expect(meshCollider(m, 2, 'a')).not.toBe(meshCollider(m, 1, 'a'));
    expect(meshCollider(m, 2, 'a').signedDistance(0, 0, 0, normal)).toBeCloseTo(-1, 6);
  });
});
