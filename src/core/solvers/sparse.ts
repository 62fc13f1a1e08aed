/**
 * Direct solvers for sparse symmetric positive definite systems. The global stretch step (solvers/global-stretch.ts)
 * orders its matrix by nested dissection (nestedDissection) and factors it by the pattern elimination fills
 * (SparseCholesky): at 128² its factor holds 0.6 M entries where the envelope of a reverse Cuthill–McKee order held
 * 2.8 M. The envelope solver (reverseCuthillMcKee, EnvelopeCholesky: the rows ordered so that their nonzeros gather
 * near the diagonal, L·Lᵀ inside that envelope; George & Liu 1981, "Computer Solution of Large Sparse Positive
 * Definite Systems", ch. 4) serves the solver prototypes in scripts/ (gn-solver.mjs). Three right-hand sides (x, y,
 * z) share one factor. Everything is allocated at construction; factor() and the solves allocate nothing.
 */

/**
 * Reverse Cuthill–McKee order of an undirected graph in compressed rows (neighbours of u: cols[rowStart[u]] …
 * cols[rowStart[u + 1] − 1]). Each connected piece starts at a pseudo-peripheral vertex (the lowest-degree vertex of
 * the last breadth-first level, found twice). Returns order[k] = the vertex placed k-th.
 */
export function reverseCuthillMcKee(rowStart: Int32Array, cols: Int32Array): Int32Array {
  const n = rowStart.length - 1;
  const degree = (u: number) => rowStart[u + 1] - rowStart[u];
  const placed = new Uint8Array(n);
  const visited = new Int32Array(n).fill(-1);
  const order = new Int32Array(n);
  const queue = new Int32Array(n);
  let count = 0;
  /** breadth-first levels from `start` over unplaced vertices; returns the lowest-degree vertex of the last level */
  const farthest = (start: number, stamp: number): number => {
    let head = 0, tail = 0;
    queue[tail++] = start;
    visited[start] = stamp;
    let levelStart = 0;
    while (head < tail) {
      levelStart = head;
      const levelEnd = tail;
      for (; head < levelEnd; head++) {
        const u = queue[head];
        for (let k = rowStart[u]; k < rowStart[u + 1]; k++) {
          const v = cols[k];
          if (placed[v] === 0 && visited[v] !== stamp) { visited[v] = stamp; queue[tail++] = v; }
        }
      }
    }
    let best = queue[levelStart];
    for (let k = levelStart + 1; k < tail; k++) if (degree(queue[k]) < degree(best)) best = queue[k];
    return best;
  };
  let stamp = 0;
  for (let s = 0; s < n; s++) {
    if (placed[s] !== 0) continue;
    let start = farthest(s, stamp++);
    start = farthest(start, stamp++);
    // Cuthill–McKee from `start`: neighbours in order of increasing degree
    let head = count;
    order[count++] = start;
    placed[start] = 1;
    while (head < count) {
      const u = order[head++];
      const from = count;
      for (let k = rowStart[u]; k < rowStart[u + 1]; k++) {
        const v = cols[k];
        if (placed[v] === 0) { placed[v] = 1; order[count++] = v; }
      }
      // insertion sort of the new run by degree (runs are a vertex's few neighbours)
      for (let a = from + 1; a < count; a++) {
        const v = order[a], d = degree(v);
        let b = a - 1;
        while (b >= from && degree(order[b]) > d) { order[b + 1] = order[b]; b--; }
        order[b + 1] = v;
      }
    }
  }
  order.reverse();
  return order;
}

/**
 * Cholesky factor L·Lᵀ of an n × n symmetric positive definite matrix stored by its envelope: row i holds columns
 * first[i] … i (first[i] ≤ i). Fill it with clear() and add(), then factor() in place; solve3() solves for three
 * interleaved right-hand sides.
 */
export class EnvelopeCholesky {
  readonly n: number;
  /** first column of each row's envelope */
  readonly first: Int32Array;
  /** where each row starts in `values`; row i's entry (i, j) is values[start[i] + j − first[i]] */
  readonly start: Int32Array;
  /** the matrix's lower envelope, then its factor L */
  readonly values: Float64Array;

  constructor(first: Int32Array) {
    const n = first.length;
    this.n = n;
    this.first = first;
    this.start = new Int32Array(n + 1);
    for (let i = 0; i < n; i++) {
      if (!(first[i] >= 0 && first[i] <= i)) throw new RangeError(`EnvelopeCholesky: first[${i}] = ${first[i]} is not in 0…${i}`);
      this.start[i + 1] = this.start[i] + (i - first[i] + 1);
    }
    this.values = new Float64Array(this.start[n]);
  }

  /** Sets every entry to zero (before adding a new matrix). */
  clear(): void {
    this.values.fill(0);
  }

  /** Adds v to entry (i, j) and (j, i); the entry must lie in the envelope. */
  add(i: number, j: number, v: number): void {
    if (j > i) { const t = i; i = j; j = t; }
    this.values[this.start[i] + j - this.first[i]] += v;
  }

  /** Factors in place (left-looking, row by row). Throws where a pivot is not positive (not positive definite). */
  factor(): void {
    const { n, first, start, values: L } = this;
    for (let i = 0; i < n; i++) {
      const fi = first[i], si = start[i] - fi; // L[si + k] is L(i, k)
      for (let j = fi; j < i; j++) {
        const fj = first[j], sj = start[j] - fj;
        let s = L[si + j];
        for (let k = fi > fj ? fi : fj; k < j; k++) s -= L[si + k] * L[sj + k];
        L[si + j] = s / L[sj + j];
      }
      let d = L[si + i];
      for (let k = fi; k < i; k++) d -= L[si + k] * L[si + k];
      if (!(d > 0)) throw new Error(`EnvelopeCholesky: the matrix is not positive definite (row ${i})`);
      L[si + i] = Math.sqrt(d);
    }
  }

  /** Solves A·x = b for three right-hand sides interleaved in b (b[3i + c]); b is overwritten by x. */
  solve3(b: Float64Array): void {
    const { n, first, start, values: L } = this;
    for (let i = 0; i < n; i++) {
      const fi = first[i], si = start[i] - fi;
      let s0 = b[3 * i], s1 = b[3 * i + 1], s2 = b[3 * i + 2];
      for (let k = fi; k < i; k++) {
        const l = L[si + k];
        s0 -= l * b[3 * k]; s1 -= l * b[3 * k + 1]; s2 -= l * b[3 * k + 2];
      }
      const d = 1 / L[si + i];
      b[3 * i] = s0 * d; b[3 * i + 1] = s1 * d; b[3 * i + 2] = s2 * d;
    }
    for (let i = n - 1; i >= 0; i--) {
      const fi = first[i], si = start[i] - fi;
      const d = 1 / L[si + i];
      const x0 = (b[3 * i] *= d), x1 = (b[3 * i + 1] *= d), x2 = (b[3 * i + 2] *= d);
      for (let k = fi; k < i; k++) {
        const l = L[si + k];
        b[3 * k] -= l * x0; b[3 * k + 1] -= l * x1; b[3 * k + 2] -= l * x2;
      }
    }
  }

  /** Solves A·x = b for one right-hand side; b is overwritten by x. */
  solve(b: Float64Array): void {
    const { n, first, start, values: L } = this;
    for (let i = 0; i < n; i++) {
      const fi = first[i], si = start[i] - fi;
      let s = b[i];
      for (let k = fi; k < i; k++) s -= L[si + k] * b[k];
      b[i] = s / L[si + i];
    }
    for (let i = n - 1; i >= 0; i--) {
      const fi = first[i], si = start[i] - fi;
      const x = (b[i] /= L[si + i]);
      for (let k = fi; k < i; k++) b[k] -= L[si + k] * x;
    }
  }
}

/**
 * Nested dissection order of an undirected graph in compressed rows (as reverseCuthillMcKee), by rooted level
 * structures (George 1973, "Nested dissection of a regular finite element mesh"; George & Liu 1981, ch. 8, "automatic
 * nested dissection"): a piece of the graph is searched breadth-first from a pseudo-peripheral vertex, the vertices
 * of its middle level that touch the next level separate it, they are numbered last, and the parts left are dissected
 * the same way; a piece of at most ND_LEAF vertices, or of fewer than three levels, is numbered whole. On a 2D mesh the
 * Cholesky factor then holds O(n log n) entries instead of the envelope's O(n^1.5). Returns order[k] = the vertex
 * placed k-th.
 */
export function nestedDissection(rowStart: Int32Array, cols: Int32Array): Int32Array {
  const n = rowStart.length - 1;
  const degree = (u: number) => rowStart[u + 1] - rowStart[u];
  const order = new Int32Array(n);
  const numbered = new Uint8Array(n);
  const level = new Int32Array(n).fill(-1);
  const seen = new Int32Array(n).fill(-1);
  const queue = new Int32Array(n);
  const seeds = new Int32Array(n);
  const flood = new Int32Array(n);
  let next = n, stamp = 0, seedCount = 0;
  /** breadth-first levels of `start`'s piece (unnumbered vertices) into queue[0…size) and level[]; returns the size */
  const levels = (start: number, mark: number): number => {
    let head = 0, tail = 0;
    queue[tail++] = start;
    seen[start] = mark;
    level[start] = 0;
    while (head < tail) {
      const u = queue[head++];
      for (let k = rowStart[u]; k < rowStart[u + 1]; k++) {
        const v = cols[k];
        if (numbered[v] === 0 && seen[v] !== mark) { seen[v] = mark; level[v] = level[u] + 1; queue[tail++] = v; }
      }
    }
    return tail;
  };
  /** the lowest-degree vertex of the last level of the search whose queue holds `size` vertices */
  const farthest = (size: number): number => {
    const last = level[queue[size - 1]];
    let best = queue[size - 1];
    for (let k = size - 2; k >= 0 && level[queue[k]] === last; k--) if (degree(queue[k]) < degree(best)) best = queue[k];
    return best;
  };
  for (let s = 0; s < n; s++) {
    if (numbered[s] !== 0) continue;
    seeds[seedCount++] = s;
    while (seedCount > 0) {
      const seed = seeds[--seedCount];
      if (numbered[seed] !== 0) continue;
      // a pseudo-peripheral root (the far end of a search, found twice), and its level structure
      let size = levels(seed, stamp++);
      size = levels(farthest(size), stamp++);
      const root = farthest(size);
      size = levels(root, stamp++);
      const depth = level[queue[size - 1]];
      if (size <= ND_LEAF || depth < 2) {
        // numbered whole, in the search's order from the top down (the root gets the piece's highest number)
        for (let k = 0; k < size; k++) { order[--next] = queue[k]; numbered[queue[k]] = 1; }
        continue;
      }
      const middle = depth >> 1;
      for (let k = 0; k < size; k++) {
        const u = queue[k];
        if (level[u] !== middle) continue;
        for (let j = rowStart[u]; j < rowStart[u + 1]; j++) {
          const v = cols[j];
          if (numbered[v] === 0 && seen[v] === stamp - 1 && level[v] === middle + 1) { order[--next] = u; numbered[u] = 2; break; }
        }
      }
      for (let k = 0; k < size; k++) if (numbered[queue[k]] === 2) numbered[queue[k]] = 1;
      // the pieces left: one seed each (a piece's vertices are all reached from any of them)
      const mark = stamp++;
      for (let k = 0; k < size; k++) {
        const u = queue[k];
        if (numbered[u] !== 0 || seen[u] === mark) continue;
        seeds[seedCount++] = u;
        // u's piece, marked so that it gets no second seed
        let top = 0;
        flood[top++] = u;
        seen[u] = mark;
        while (top > 0) {
          const a = flood[--top];
          for (let j = rowStart[a]; j < rowStart[a + 1]; j++) {
            const v = cols[j];
            if (numbered[v] === 0 && seen[v] !== mark) { seen[v] = mark; flood[top++] = v; }
          }
        }
      }
    }
  }
  return order;
}

/**
 * A graph in compressed rows renumbered by `order` (order[k]: the vertex placed k-th, as nestedDissection gives it):
 * each vertex's row (`row[v]`), and the graph with its rows and their neighbours in the new numbers (what
 * SparseCholesky takes).
 */
export function orderedGraph(rowStart: Int32Array, cols: Int32Array, order: Int32Array): { row: Int32Array; rowStart: Int32Array; cols: Int32Array } {
  const n = order.length;
  const row = new Int32Array(n);
  for (let r = 0; r < n; r++) row[order[r]] = r;
  const start = new Int32Array(n + 1);
  for (let r = 0; r < n; r++) start[r + 1] = start[r] + rowStart[order[r] + 1] - rowStart[order[r]];
  const list = new Int32Array(start[n]);
  for (let r = 0; r < n; r++) {
    const v = order[r];
    for (let k = rowStart[v]; k < rowStart[v + 1]; k++) list[start[r] + k - rowStart[v]] = row[cols[k]];
  }
  return { row, rowStart: start, cols: list };
}

/** Pieces of at most this many vertices are not dissected further (nestedDissection). */
const ND_LEAF = 16;

/**
 * Cholesky factor L·Lᵀ of an n × n sparse symmetric positive definite matrix, row by row ("up-looking": each row of L
 * from a sparse triangular solve with the rows above; Davis 2006, "Direct Methods for Sparse Linear Systems", §4.8),
 * over the pattern that elimination fills, found once from the matrix's graph and its elimination tree (Liu 1990).
 * The graph is given in the order the rows are to be eliminated (nestedDissection's, say). Fill it with clear() and
 * add(), then factor(); solve3() solves for three interleaved right-hand sides. Everything is allocated at
 * construction; factor() and the solves allocate nothing.
 */
export class SparseCholesky {
  readonly n: number;
  /** A's lower triangle by rows: row i's columns (ascending, the diagonal last) from aStart[i], and their values */
  private readonly aStart: Int32Array;
  private readonly aCols: Int32Array;
  private readonly aValues: Float64Array;
  /**
   * L by columns: column j's rows from colStart[j] (the diagonal first, then ascending) and their values (read by
   * the WebAssembly kernel's solves, wasm/factored-wasm.ts; written only by factor())
   */
  readonly colStart: Int32Array;
  readonly rows: Int32Array;
  readonly values: Float64Array;
  /** factor() calls so far: the values of L change with each */
  factors = 0;
  /** each row's off-diagonal entries in L, each after the entries below it in the elimination tree */
  private readonly patternStart: Int32Array;
  private readonly pattern: Int32Array;
  private readonly work: Float64Array;
  private readonly cursor: Int32Array;

  /** The matrix's graph in compressed rows (the neighbours of row i: cols[rowStart[i]] … cols[rowStart[i + 1] − 1]). */
  constructor(rowStart: Int32Array, cols: Int32Array) {
    const n = rowStart.length - 1;
    this.n = n;
    // A's lower triangle: the neighbours below each row, sorted, each once, then the diagonal
    const aStart = new Int32Array(n + 1);
    const aCols = new Int32Array(rowStart[n] + n);
    let at = 0;
    for (let i = 0; i < n; i++) {
      const from = at;
      for (let k = rowStart[i]; k < rowStart[i + 1]; k++) {
        const j = cols[k];
        if (!(Number.isInteger(j) && j >= 0 && j < n && j !== i)) throw new RangeError(`SparseCholesky: row ${i} lists ${j}, not another row in 0…${n - 1}`);
        if (j > i) continue;
        // insertion into the row's sorted run, each column once (a row has a few neighbours)
        let p = at - 1;
        while (p >= from && aCols[p] > j) p--;
        if (p >= from && aCols[p] === j) continue;
        aCols.copyWithin(p + 2, p + 1, at);
        aCols[p + 1] = j;
        at++;
      }
      aCols[at++] = i;
      aStart[i + 1] = at;
    }
    this.aStart = aStart;
    this.aCols = aCols.slice(0, at);
    this.aValues = new Float64Array(aStart[n]);

    // the elimination tree (Liu's algorithm, with path compression through `ancestor`)
    const parent = new Int32Array(n).fill(-1), ancestor = new Int32Array(n).fill(-1);
    for (let k = 0; k < n; k++) {
      for (let p = aStart[k]; p < aStart[k + 1] - 1; p++) {
        let i = this.aCols[p];
        while (i !== -1 && i < k) {
          const up = ancestor[i];
          ancestor[i] = k;
          if (up === -1) parent[i] = k;
          i = up;
        }
      }
    }
    // row k's pattern in L: the paths up the tree from A's entries of row k to k (Davis's ereach), twice: to count, to fill
    const mark = new Int32Array(n).fill(-1), path = new Int32Array(n), reach = new Int32Array(n);
    const rowReach = (k: number): number => {
      let top = n;
      mark[k] = k;
      for (let p = aStart[k]; p < aStart[k + 1] - 1; p++) {
        let len = 0;
        for (let i = this.aCols[p]; mark[i] !== k; i = parent[i]) { path[len++] = i; mark[i] = k; }
        while (len > 0) reach[--top] = path[--len];
      }
      return top;
    };
    const count = new Int32Array(n);
    const patternStart = new Int32Array(n + 1);
    for (let k = 0; k < n; k++) {
      const top = rowReach(k);
      patternStart[k + 1] = patternStart[k] + n - top;
      for (let q = top; q < n; q++) count[reach[q]]++;
    }
    this.patternStart = patternStart;
    this.pattern = new Int32Array(patternStart[n]);
    this.colStart = new Int32Array(n + 1);
    for (let j = 0; j < n; j++) this.colStart[j + 1] = this.colStart[j] + count[j] + 1;
    this.rows = new Int32Array(this.colStart[n]);
    this.values = new Float64Array(this.colStart[n]);
    this.cursor = new Int32Array(n);
    for (let j = 0; j < n; j++) { this.rows[this.colStart[j]] = j; this.cursor[j] = this.colStart[j] + 1; }
    mark.fill(-1);
    for (let k = 0; k < n; k++) {
      const top = rowReach(k);
      this.pattern.set(reach.subarray(top, n), patternStart[k]);
      for (let q = top; q < n; q++) this.rows[this.cursor[reach[q]]++] = k;
    }
    this.work = new Float64Array(n);
  }

  /** entries of L, its diagonal included (the fill of this order) */
  get entries(): number {
    return this.colStart[this.n];
  }

  /** Sets every entry to zero (before adding a new matrix). */
  clear(): void {
    this.aValues.fill(0);
  }

  /** Adds v to entry (i, j) and (j, i); the entry must be in the graph (or on the diagonal). */
  add(i: number, j: number, v: number): void {
    if (j > i) { const t = i; i = j; j = t; }
    const cols = this.aCols;
    let lo = this.aStart[i], hi = this.aStart[i + 1] - 1;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (cols[mid] < j) lo = mid + 1; else hi = mid;
    }
    if (cols[lo] !== j) throw new RangeError(`SparseCholesky.add: (${i}, ${j}) is not in the matrix's graph`);
    this.aValues[lo] += v;
  }

  /** Factors (row by row). Throws where a pivot is not positive (not positive definite). */
  factor(): void {
    const { n, aStart, aCols, aValues, colStart, rows, values, pattern, patternStart, work: x, cursor } = this;
    this.factors++;
    for (let j = 0; j < n; j++) cursor[j] = colStart[j] + 1;
    for (let k = 0; k < n; k++) {
      for (let p = aStart[k]; p < aStart[k + 1]; p++) x[aCols[p]] = aValues[p];
      let d = x[k];
      x[k] = 0;
      // L(k, 0…k−1) from L(0…k−1, 0…k−1)·l = A(0…k−1, k), over row k's pattern in the tree's order
      for (let q = patternStart[k]; q < patternStart[k + 1]; q++) {
        const i = pattern[q];
        const l = x[i] / values[colStart[i]];
        x[i] = 0;
        for (let p = colStart[i] + 1; p < cursor[i]; p++) x[rows[p]] -= values[p] * l;
        d -= l * l;
        values[cursor[i]++] = l;
      }
      if (!(d > 0)) throw new Error(`SparseCholesky: the matrix is not positive definite (row ${k})`);
      values[colStart[k]] = Math.sqrt(d);
    }
  }

  /** Solves A·x = b for three right-hand sides interleaved in b (b[3i + c]); b is overwritten by x. */
  solve3(b: Float64Array): void {
    const { n, colStart, rows, values: L } = this;
    for (let j = 0; j < n; j++) {
      const d = 1 / L[colStart[j]];
      const x0 = (b[3 * j] *= d), x1 = (b[3 * j + 1] *= d), x2 = (b[3 * j + 2] *= d);
      for (let p = colStart[j] + 1; p < colStart[j + 1]; p++) {
        const l = L[p], r = 3 * rows[p];
        b[r] -= l * x0; b[r + 1] -= l * x1; b[r + 2] -= l * x2;
      }
    }
    for (let j = n - 1; j >= 0; j--) {
      let s0 = b[3 * j], s1 = b[3 * j + 1], s2 = b[3 * j + 2];
      for (let p = colStart[j] + 1; p < colStart[j + 1]; p++) {
        const l = L[p], r = 3 * rows[p];
        s0 -= l * b[r]; s1 -= l * b[r + 1]; s2 -= l * b[r + 2];
      }
      const d = 1 / L[colStart[j]];
      b[3 * j] = s0 * d; b[3 * j + 1] = s1 * d; b[3 * j + 2] = s2 * d;
    }
  }

  /** Solves A·x = b for one right-hand side; b is overwritten by x. */
  solve(b: Float64Array): void {
    const { n, colStart, rows, values: L } = this;
    for (let j = 0; j < n; j++) {
      const x = (b[j] /= L[colStart[j]]);
      for (let p = colStart[j] + 1; p < colStart[j + 1]; p++) b[rows[p]] -= L[p] * x;
    }
    for (let j = n - 1; j >= 0; j--) {
      let s = b[j];
      for (let p = colStart[j] + 1; p < colStart[j + 1]; p++) s -= L[p] * b[rows[p]];
      b[j] = s / L[colStart[j]];
    }
  }
}

/**
 * A sparse matrix P over a system's particles that a solve adds to its right-hand side as P·v (the global bending
 * step's damping): particle i's row has the diagonal entry diagonal[i] and the entries values[p] at the particles
 * cols[p], p from start[i] to start[i + 1]; it adds to the system's row row[i]. `version` changes with the values.
 */
export interface SparseProduct {
  readonly diagonal: Float64Array;
  readonly start: Int32Array;
  readonly cols: Int32Array;
  readonly values: Float64Array;
  readonly row: Int32Array;
  version: number;
}

/**
 * b += P·v, three coordinates interleaved (v by particle, b by the system's rows): for each particle, its diagonal
 * term and then its entries in order, summed, then added (the order the kernel's productAdd3 keeps).
 */
export function multiplyAdd3(m: SparseProduct, v: Float64Array, b: Float64Array): void {
  const { diagonal, start, cols, values, row } = m;
  for (let i = 0; i < diagonal.length; i++) {
    const d = diagonal[i], j = 3 * i;
    let sx = d * v[j], sy = d * v[j + 1], sz = d * v[j + 2];
    for (let p = start[i]; p < start[i + 1]; p++) {
      const w = values[p], c = 3 * cols[p];
      sx += w * v[c]; sy += w * v[c + 1]; sz += w * v[c + 2];
    }
    const q = 3 * row[i];
    b[q] += sx; b[q + 1] += sy; b[q + 2] += sz;
  }
}

/**
 * Who solves with a factor, each substep: the reference (multiplyAdd3 and the factor's own solve3) or the
 * WebAssembly kernel's (wasm/factored-wasm.ts), which gives the same solution bit for bit.
 */
export interface FactorSolver {
  /**
   * Solves A·x = b (+ P·v where `product` P and `v` are given) with chol's factor, b holding three interleaved
   * right-hand sides (overwritten by x).
   */
  solve3(chol: SparseCholesky, b: Float64Array, product?: SparseProduct, v?: Float64Array): void;
}

/** The reference's solves: multiplyAdd3, then SparseCholesky.solve3. */
export const REFERENCE_SOLVER: FactorSolver = {
  solve3: (chol, b, product, v) => {
    if (product && v) multiplyAdd3(product, v, b);
    chol.solve3(b);
  },
};
