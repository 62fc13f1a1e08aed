/**
 * A direct solver for the sparse symmetric positive definite systems of the global stretch step
 * (solvers/global-stretch.ts): the matrix's rows ordered by reverse Cuthill–McKee (Cuthill & McKee 1969; George &
 * Liu 1981, "Computer Solution of Large Sparse Positive Definite Systems", ch. 4) so that its nonzeros gather near
 * the diagonal, then factored as L·Lᵀ inside that envelope (skyline storage: row i keeps columns first[i] … i, and
 * Cholesky creates fill only there). Three right-hand sides (x, y, z) share one factor. Everything is allocated at
 * construction; factor() and solve3() allocate nothing.
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
