/**
 * The edge table of a triangle mesh in flat arrays, built in linear time without hashing (a million-particle grid
 * has three million edges): each edge once, with the triangles on either side of it and the corners opposite it.
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
  const other = (k: number) => triangles[k - (k % 3) + ((k % 3) + 1) % 3];
  const high = (k: number) => Math.max(triangles[k], other(k));
  const ends: number[] = [];
  const faces: number[] = [];
  const opposite: number[] = [];
  const triangleEdges = new Uint32Array(3 * m);
  let overShared = -1;
  for (let a = 0; a < n; a++) {
    const s = start[a], e = start[a + 1];
    // within the bucket, by the higher vertex: buckets are small (the vertex's edge count)
    const bucket = Array.from(half.subarray(s, e)).sort((x, y) => high(x) - high(y) || x - y);
    for (let i = 0; i < bucket.length;) {
      const b = high(bucket[i]);
      const id = ends.length / 2;
      ends.push(a, b);
      let j = i;
      for (; j < bucket.length && high(bucket[j]) === b; j++) {
        const k = bucket[j], t = (k - (k % 3)) / 3;
        triangleEdges[k] = id;
        if (j - i < 2) {
          faces.push(t);
          opposite.push(triangles[3 * t + ((k % 3) + 2) % 3]);
        }
      }
      if (j - i === 1) { faces.push(-1); opposite.push(-1); }
      if (j - i > 2 && overShared < 0) overShared = id;
      i = j;
    }
  }
  return {
    count: ends.length / 2,
    ends: Uint32Array.from(ends),
    faces: Int32Array.from(faces),
    opposite: Int32Array.from(opposite),
    overShared,
    triangleEdges,
  };
}
