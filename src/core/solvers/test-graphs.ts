/**
 * Sparse graphs the solver tests share (test-only: not built into the package, tsconfig.build.json).
 */

/** An m × m grid graph with diagonals, numbered in a shuffled order (seed); its edges and compressed rows. */
export function grid(m: number, seed: number): { n: number; edges: [number, number][]; rowStart: Int32Array; cols: Int32Array } {
  const n = m * m;
  const shuffled = Array.from({ length: n }, (_, i) => i);
  let s = seed;
  for (let i = n - 1; i > 0; i--) {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    const j = s % (i + 1);
    [shuffled[i], shuffled[j]] = [shuffled[j], shuffled[i]];
  }
  const edges: [number, number][] = [];
  for (let j = 0; j < m; j++) for (let i = 0; i < m; i++) {
    const id = (a: number, b: number) => shuffled[b * m + a];
    if (i + 1 < m) edges.push([id(i, j), id(i + 1, j)]);
    if (j + 1 < m) edges.push([id(i, j), id(i, j + 1)]);
    if (i + 1 < m && j + 1 < m) edges.push([id(i, j), id(i + 1, j + 1)]);
  }
  const lists = Array.from({ length: n }, () => [] as number[]);
  for (const [a, b] of edges) { lists[a].push(b); lists[b].push(a); }
  const rowStart = new Int32Array(n + 1);
  for (let i = 0; i < n; i++) rowStart[i + 1] = rowStart[i] + lists[i].length;
  return { n, edges, rowStart, cols: Int32Array.from(lists.flat()) };
}
