/**
 * The edge table of a triangle mesh in flat arrays, built without hashing in time linear in the mesh while vertices
 * have few edges (a million-particle grid has three million edges): each edge once, with the triangles on either
 * side of it and the corners opposite it.
 */

/** Every edge of a mesh, each once; the arrays are indexed by edge. */
export interface EdgeTable {
  /** edge count */
  count: number;
  /** end points, pairs (a, b) with a < b, sorted by a then b */
  ends: Uint32Array;
  /** first and second triangle on the edge, pairs; the second is −1 on the boundary */
  faces: Int32Array;
  /** corner opposite the edge in the first and second triangle, pairs; −1 where there is no second */
  opposite: Int32Array;
  /** the first edge found shared by more than two triangles, or −1 */
  overShared: number;
  /** the edge id of each triangle's three edges (e = 0, 1, 2: corners e → e + 1), triples */
  triangleEdges: Uint32Array;
}

/** Builds the edge table of `triangles` (triples of indices into `n` vertices). */
export function edgeTable(triangles: Uint32Array, n: number): EdgeTable {
  const m = triangles.length / 3;
  // half-edges bucketed by their lower vertex (counting sort)
  const start = new Uint32Array(n + 1);
  for (let k = 0; k < triangles.length; k++) {
    const t = k - (k % 3), e = k % 3;
    const a = triangles[k], b = triangles[t + (e + 1) % 3];
    start[Math.min(a, b) + 1]++;
  }
  for (let i = 0; i < n; i++) start[i + 1] += start[i];
  const fill = start.slice(0, n);
  const half = new Uint32Array(triangles.length); // half-edge k (corner k → next corner) in its bucket
  for (let k = 0; k < triangles.length; k++) {
    const t = k - (k % 3), e = k % 3;
    half[fill[Math.min(triangles[k], triangles[t + (e + 1) % 3])]++] = k;
  }
  // the higher vertex of each half-edge
  const high = new Uint32Array(triangles.length);
  for (let k = 0; k < triangles.length; k++) {
    const t = k - (k % 3);
    high[k] = Math.max(triangles[k], triangles[t + ((k % 3) + 1) % 3]);
  }
  // at most one edge per half-edge: sized for the worst case, trimmed at the end
  const ends = new Uint32Array(2 * triangles.length);
  const faces = new Int32Array(2 * triangles.length);
  const opposite = new Int32Array(2 * triangles.length);
  const triangleEdges = new Uint32Array(3 * m);
  let overShared = -1, count = 0;
  for (let a = 0; a < n; a++) {
    const s = start[a], e = start[a + 1];
    // sort the bucket by the higher vertex (then half-edge): insertion sort for a vertex's few edges, the library's
    // sort for a fan of many (a file may have one; prepareMesh then refuses it)
    if (e - s > 32) {
      const sorted = Array.from(half.subarray(s, e)).sort((x, y) => high[x] - high[y] || x - y);
      half.set(sorted, s);
    } else for (let i = s + 1; i < e; i++) {
      const k = half[i], hk = high[k];
      let j = i - 1;
      while (j >= s && (high[half[j]] > hk || (high[half[j]] === hk && half[j] > k))) { half[j + 1] = half[j]; j--; }
      half[j + 1] = k;
    }
    for (let i = s; i < e;) {
      const b = high[half[i]];
      const id = count++;
      ends[2 * id] = a;
      ends[2 * id + 1] = b;
      let j = i;
      for (; j < e && high[half[j]] === b; j++) {
        const k = half[j], t = (k - (k % 3)) / 3;
        triangleEdges[k] = id;
        if (j - i < 2) {
          faces[2 * id + j - i] = t;
          opposite[2 * id + j - i] = triangles[3 * t + ((k % 3) + 2) % 3];
        }
      }
      if (j - i === 1) { faces[2 * id + 1] = -1; opposite[2 * id + 1] = -1; }
      if (j - i > 2 && overShared < 0) overShared = id;
      i = j;
    }
  }
  return {
    count,
    ends: ends.slice(0, 2 * count),
    faces: faces.slice(0, 2 * count),
    opposite: opposite.slice(0, 2 * count),
    overShared,
    triangleEdges,
  };
}
