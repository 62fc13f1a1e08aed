/**
 * The immutable description of a cloth: particles, springs by kind, rest lengths, triangles, UVs and the
 * constraint colouring used for parallel solving. Built once; a change of resolution builds a new one.
 * Everything that may change while the cloth runs (pins, stiffness, wind...) lives elsewhere.
 */

import { STRUCTURAL, SHEAR, BEND } from './layout.generated.js';
import { eulerXYZ } from './mesh/generators.js';
import type { TriangleMesh } from './mesh/triangle-mesh.js';
import { edgeTable, type EdgeTable } from './mesh/edges.js';

/** The three spring kinds of the seed design; their ids (STRUCTURAL, SHEAR, BEND) come from the one table. */
export const SPRING_KINDS = ['structural', 'shear', 'bend'] as const;
export type SpringKind = (typeof SPRING_KINDS)[number];
export { STRUCTURAL, SHEAR, BEND };

/** A run of springs of one kind and one colour: no two springs in it share a particle. */
export interface SpringBatch {
  /** index into SPRING_KINDS */
  readonly kind: number;
  /** first spring of the batch */
  readonly start: number;
  /** one past the last spring of the batch */
  readonly end: number;
}

/** A run of triangles of one colour: no two share a particle. Offsets count triangles. */
export interface TriangleBatch {
  readonly start: number;
  readonly end: number;
}

/** Grid topology of a rectangular cloth: particle (i, j) has index j * nx + i. */
export interface GridInfo {
  /** particles along the width (columns), = resolution + 1 */
  readonly nx: number;
  /** particles along the height (rows), = resolution + 1 */
  readonly ny: number;
}

/** The bending models that are stencils of a ClothModel (solver.bending other than 'springs'). */
export type StencilModel = 'hinges' | 'laplacian';

/**
 * Linear bending stencils, each a 3-vector C = Σ_k K_k x_{i_k} over a few particles, with the energy ½·B·|C|²/A
 * (docs/physics.md, "Bending at the hinges" and "Isotropic bending"): variable-sized, stored CSR (stencil s has
 * the entries offsets[s] … offsets[s + 1] − 1), sorted by colour. A hinge has 4 entries (shared edge x0–x1, wings
 * x2, x3), a vertex of the Laplacian 1 + its neighbours (the vertex first).
 */
export interface BendingStencils {
  /** first entry of each stencil, and one past the last stencil's: stencil count + 1 */
  readonly offsets: Uint32Array;
  /** the particle of each entry */
  readonly vertices: Uint32Array;
  /** the weight K of each entry: C = Σ K x; they sum to zero in each stencil, so a translation leaves C unchanged [-] */
  readonly weights: Float32Array;
  /**
   * the area A of each stencil in its energy ½·B·|C|²/A [m²]: a hinge's two triangles; for a vertex of the Laplacian
   * A_v²/(A_v + its share of the border's area), A_v its mixed Voronoi area (buildLaplacian)
   */
  readonly areas: Float32Array;
  /** colour batches (in stencils); stencils of a batch share no particle */
  readonly batches: readonly TriangleBatch[];
  /** most entries of one stencil (4 for hinges; 1 + the most weighted neighbours of an interior vertex for the Laplacian) */
  readonly maxSize: number;
}

export interface ClothModel {
  /** number of particles */
  readonly particleCount: number;
  /** rest positions [m], xyz interleaved (stride 3); also the start pose */
  readonly restPositions: Float32Array;
  /** texture coordinates, uv interleaved (stride 2), in [0, 1] */
  readonly uvs: Float32Array;
  /**
   * each particle's share of its cloth's mass (its mixed Voronoi area / its cloth's area: lumpedMassWeights); sums to
   * 1 over each cloth
   */
  readonly massWeights: Float32Array;
  /** spring end points, pairs (a, b), sorted by kind then colour */
  readonly springs: Uint32Array;
  /** spring rest lengths [m], one per spring */
  readonly restLengths: Float32Array;
  /**
   * per-spring geometric factor that makes a stiffness in continuum units act the same at every resolution
   * (see docs/physics.md, "Resolution independence"); 1 for square cells except bend springs
   */
  readonly stiffnessScales: Float32Array;
  /** kind of each spring (index into SPRING_KINDS) */
  readonly springKinds: Uint8Array;
  /** colour batches in solve order; springs of a batch share no particle */
  readonly batches: readonly SpringBatch[];
  /** number of springs of each kind, indexed like SPRING_KINDS */
  readonly springCounts: readonly [number, number, number];
  /** triangle vertex indices, triples, sorted by colour (orientation as given to the builder) */
  readonly triangles: Uint32Array;
  /** colour batches of triangles (in triangles, not indices); triangles of a batch share no particle */
  readonly triangleBatches: readonly TriangleBatch[];
  /** longest rest edge of any triangle [m]; bounds the reach of triangle contact */
  readonly maxTriangleEdge: number;
  /** most triangles that share one particle [-] (6 inside a grid) */
  readonly maxTriangleValence: number;
  /** total rest area of the cloth [m²] */
  readonly area: number;
  /** the mesh's edges, pairs (a, b) with a < b, each once */
  readonly edges: Uint32Array;
  /**
   * bending pairs: one per edge shared by two triangles, as quadruples (a, b, c, d): the shared edge a–b and the
   * two corners c, d opposite it
   */
  readonly bendingPairs: Uint32Array;
  /**
   * the bending stencils of the two stencil models of solver.bending (Bergou et al. 2006's hinges, the cotangent
   * Laplacian at the vertices); the xpbd solver's `bending` phase solves those of the params' model
   * (`bendingStencils`)
   */
  readonly stencils: { readonly hinges: BendingStencils; readonly laplacian: BendingStencils };
  /** connected piece of each particle, 0 … pieceCount − 1 (for per-piece material and pins) */
  readonly pieces: Uint32Array;
  /** number of connected pieces [-] */
  readonly pieceCount: number;
  /** grid layout when the cloth is a rectangular grid */
  readonly grid?: GridInfo;
  /**
   * where each cloth's particles are: cloth c has particles clothStarts[c] … clothStarts[c + 1] − 1 ([0, n] for one
   * cloth); its springs, triangles and stencils are those whose particles are its own
   */
  readonly clothStarts: Uint32Array;
  /** the model of each cloth by itself, when the model is several (mergeModels): for their pins and materials */
  readonly clothParts?: readonly ClothModel[];
  /** largest extent of the rest shape [m]; the size used by sanity bounds */
  readonly size: number;
}

export interface ModelInput {
  restPositions: Float32Array;
  uvs?: Float32Array;
  triangles: Uint32Array;
  /** springs per kind as index pairs */
  springs: readonly [Uint32Array, Uint32Array, Uint32Array];
  /** optional per-spring stiffness factors per kind (default 1) */
  stiffnessScales?: readonly [Float32Array, Float32Array, Float32Array];
  grid?: GridInfo;
  /** meshTopology of these triangles, when the caller has it already (else derived here) */
  topology?: MeshTopology;
}

const MAX_COLOURS = 32;

/**
 * Greedy colouring of elements (springs: arity 2, triangles: arity 3): each element gets the lowest colour not
 * yet used at any of its particles. Returns the colour of each element. Grid springs generated row by row come
 * out with 2 colours per direction, grid triangles with 6.
 */
function colourElements(indices: Uint32Array, arity: number, particleCount: number): { colours: Uint8Array; count: number } {
  const used = new Uint32Array(particleCount);
  const m = indices.length / arity;
  const colours = new Uint8Array(m);
  let count = 0;
  for (let e = 0; e < m; e++) {
    let taken = 0;
    for (let k = 0; k < arity; k++) taken |= used[indices[arity * e + k]];
    const free = ~taken >>> 0;
    if (free === 0) throw new Error(`constraint colouring needs more than ${MAX_COLOURS} colours`);
    const c = 31 - Math.clz32(free & -free);
    colours[e] = c;
    for (let k = 0; k < arity; k++) used[indices[arity * e + k]] |= 1 << c;
    if (c + 1 > count) count = c + 1;
  }
  return { colours, count };
}

/** Start offset of each colour (length count + 1) from element colours: a counting sort's prefix sums. */
function colourOffsets(colours: ArrayLike<number>, count: number): Uint32Array {
  const offsets = new Uint32Array(count + 1);
  for (let e = 0; e < colours.length; e++) offsets[colours[e] + 1]++;
  for (let c = 0; c < count; c++) offsets[c + 1] += offsets[c];
  return offsets;
}

/** Distance of point c from the line through a and b, |ab| = `ab` [m]: a triangle's height over its edge ab. */
function heightOver(p: Float32Array, a: number, b: number, c: number, ab: number): number {
  const ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1], uz = p[3 * b + 2] - p[3 * a + 2];
  const vx = p[3 * c] - p[3 * a], vy = p[3 * c + 1] - p[3 * a + 1], vz = p[3 * c + 2] - p[3 * a + 2];
  return Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx) / ab;
}

function distance(p: Float32Array, a: number, b: number): number {
  const dx = p[3 * a] - p[3 * b];
  const dy = p[3 * a + 1] - p[3 * b + 1];
  const dz = p[3 * a + 2] - p[3 * b + 2];
  return Math.sqrt(dx * dx + dy * dy + dz * dz);
}

/** What meshTopology derives from the triangles (see ClothModel). */
export interface MeshTopology { edges: Uint32Array; bendingPairs: Uint32Array; pieces: Uint32Array; pieceCount: number }

/** Edges, bending pairs and connected pieces of a triangle mesh (see ClothModel), from its edge table. */
export function meshTopology(triangles: Uint32Array, n: number, table: EdgeTable = edgeTable(triangles, n)): MeshTopology {
  let shared = 0;
  for (let e = 0; e < table.count; e++) if (table.faces[2 * e + 1] >= 0) shared++;
  const bendingPairs = new Uint32Array(4 * shared);
  const parent = new Uint32Array(n);
  for (let i = 0; i < n; i++) parent[i] = i;
  const find = (i: number): number => {
    while (parent[i] !== i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (let e = 0, k = 0; e < table.count; e++) {
    const a = table.ends[2 * e], b = table.ends[2 * e + 1];
    const ra = find(a), rb = find(b);
    if (ra !== rb) parent[Math.max(ra, rb)] = Math.min(ra, rb);
    if (table.faces[2 * e + 1] < 0) continue;
    bendingPairs[k++] = a; bendingPairs[k++] = b;
    bendingPairs[k++] = table.opposite[2 * e]; bendingPairs[k++] = table.opposite[2 * e + 1];
  }
  // pieces numbered in order of their lowest particle
  const pieces = new Uint32Array(n);
  const id = new Int32Array(n).fill(-1);
  let pieceCount = 0;
  for (let i = 0; i < n; i++) {
    const r = find(i);
    if (id[r] < 0) id[r] = pieceCount++;
    pieces[i] = id[r];
  }
  return { edges: table.ends, bendingPairs, pieces, pieceCount };
}

/** Cotangent of the angle between u and v. */
function cotangent(ux: number, uy: number, uz: number, vx: number, vy: number, vz: number): number {
  const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
  return (ux * vx + uy * vy + uz * vz) / Math.sqrt(cx * cx + cy * cy + cz * cz);
}

/**
 * Greedy colouring of variable-sized stencils (CSR: stencil s over vertices[offsets[s]] …): each stencil gets the
 * lowest colour not yet used at any of its particles, as colourElements, with as many colours as it takes (a
 * vertex stencil of the Laplacian meets every stencil within two edges of it: 13 colours on the grid, more on an
 * irregular mesh). For 4-particle hinges it gives colourElements' colours.
 */
function colourStencils(offsets: Uint32Array, vertices: Uint32Array, particleCount: number): { colours: Uint16Array; count: number } {
  const m = offsets.length - 1;
  for (let words = 1; ; words *= 2) {
    const used = new Uint32Array(words * particleCount);
    const taken = new Uint32Array(words);
    const colours = new Uint16Array(m);
    let count = 0, overflow = false;
    for (let e = 0; e < m && !overflow; e++) {
      taken.fill(0);
      for (let k = offsets[e]; k < offsets[e + 1]; k++) {
        const at = words * vertices[k];
        for (let q = 0; q < words; q++) taken[q] |= used[at + q];
      }
      let c = -1;
      for (let q = 0; q < words && c < 0; q++) {
        const free = ~taken[q] >>> 0;
        if (free !== 0) c = 32 * q + 31 - Math.clz32(free & -free);
      }
      if (c < 0) { overflow = true; break; }
      colours[e] = c;
      for (let k = offsets[e]; k < offsets[e + 1]; k++) used[words * vertices[k] + (c >> 5)] |= 1 << (c & 31);
      if (c + 1 > count) count = c + 1;
    }
    if (!overflow) return { colours, count };
  }
}

/**
 * Stencils (CSR, in any order) sorted by colour into BendingStencils: a stencil keeps its entries' order, and
 * stencils of one colour keep theirs.
 */
function sortStencils(offsets: Uint32Array, vertices: Uint32Array, weights: Float64Array, areas: Float64Array, n: number): BendingStencils {
  const m = offsets.length - 1;
  const { colours, count } = colourStencils(offsets, vertices, n);
  const starts = colourOffsets(colours, count);
  const batches: TriangleBatch[] = [];
  for (let c = 0; c < count; c++) batches.push({ start: starts[c], end: starts[c + 1] });
  const order = new Uint32Array(m), fill = starts.slice(0, count);
  for (let e = 0; e < m; e++) order[fill[colours[e]]++] = e;
  const outOffsets = new Uint32Array(m + 1), outVertices = new Uint32Array(vertices.length);
  const outWeights = new Float32Array(vertices.length), outAreas = new Float32Array(m);
  let at = 0, maxSize = 0;
  for (let d = 0; d < m; d++) {
    const e = order[d];
    outOffsets[d] = at;
    outAreas[d] = areas[e];
    for (let k = offsets[e]; k < offsets[e + 1]; k++, at++) {
      outVertices[at] = vertices[k];
      outWeights[at] = weights[k];
    }
    maxSize = Math.max(maxSize, offsets[e + 1] - offsets[e]);
  }
  outOffsets[m] = at;
  return { offsets: outOffsets, vertices: outVertices, weights: outWeights, areas: outAreas, batches, maxSize };
}

/**
 * The hinges of the isometric bending model (Bergou, Wardetzky, Harmon, Zorin & Grinspun 2006, "A Quadratic
 * Bending Model for Inextensible Surfaces"), one per bending pair (x0, x1, x2, x3): with α0, α1 the angles of
 * triangle (x0, x1, x2) at x0 and x1, and β0, β1 those of (x0, x1, x3),
 *   K = (cot α1 + cot β1, cot α0 + cot β0, −cot α0 − cot α1, −cot β0 − cot β1),
 * so that C = Σ K_i x_i = −|e|·(û2 + û3), û_k the unit vector in triangle k from the edge to its wing: zero for a
 * flat pair, |e|·2 sin(θ/2) for a dihedral angle θ. The angles are the rest triangles' (intrinsic: the same for a
 * pair that rests folded), so K stays fixed while the cloth bends without stretching. A pair with a degenerate
 * triangle gets K = 0 (no bending). Its area is the two triangles'. Coloured so that no two hinges of a batch share
 * a particle.
 */
function buildHinges(pairs: Uint32Array, p: Float32Array, n: number): BendingStencils {
  const m = pairs.length / 4;
  const offsets = new Uint32Array(m + 1), weights = new Float64Array(4 * m), areas = new Float64Array(m);
  for (let h = 0; h < m; h++) {
    offsets[h + 1] = 4 * (h + 1);
    const x0 = 3 * pairs[4 * h], x1 = 3 * pairs[4 * h + 1], x2 = 3 * pairs[4 * h + 2], x3 = 3 * pairs[4 * h + 3];
    const ex = p[x1] - p[x0], ey = p[x1 + 1] - p[x0 + 1], ez = p[x1 + 2] - p[x0 + 2];
    const a2x = p[x2] - p[x0], a2y = p[x2 + 1] - p[x0 + 1], a2z = p[x2 + 2] - p[x0 + 2];
    const a3x = p[x3] - p[x0], a3y = p[x3 + 1] - p[x0 + 1], a3z = p[x3 + 2] - p[x0 + 2];
    const b2x = p[x2] - p[x1], b2y = p[x2 + 1] - p[x1 + 1], b2z = p[x2 + 2] - p[x1 + 2];
    const b3x = p[x3] - p[x1], b3y = p[x3 + 1] - p[x1 + 1], b3z = p[x3 + 2] - p[x1 + 2];
    const ca0 = cotangent(ex, ey, ez, a2x, a2y, a2z), ca1 = cotangent(-ex, -ey, -ez, b2x, b2y, b2z);
    const cb0 = cotangent(ex, ey, ez, a3x, a3y, a3z), cb1 = cotangent(-ex, -ey, -ez, b3x, b3y, b3z);
    const area2 = 0.5 * Math.hypot(ey * a2z - ez * a2y, ez * a2x - ex * a2z, ex * a2y - ey * a2x);
    const area3 = 0.5 * Math.hypot(ey * a3z - ez * a3y, ez * a3x - ex * a3z, ex * a3y - ey * a3x);
    areas[h] = area2 + area3;
    const k = [ca1 + cb1, ca0 + cb0, -ca0 - ca1, -cb0 - cb1];
    if (k.every(Number.isFinite) && area2 > 0 && area3 > 0) weights.set(k, 4 * h);
  }
  return sortStencils(offsets, pairs, weights, areas, n);
}

/** Cotan weights smaller than this share of the largest at their vertex are dropped (the grid's diagonals: 0). */
const NEGLIGIBLE_WEIGHT = 1e-5;

/**
 * The vertex stencils of the cotangent Laplacian (Wardetzky, Bergou, Harmon, Zorin & Grinspun 2007, "Discrete
 * Quadratic Curvature Energies"; Meyer, Desbrun, Schröder & Barr 2003 for the areas), one per interior vertex v:
 *   C_v = Σ_j w_vj (x_j − x_v),  w_vj = ½(cot α_vj + cot β_vj),
 * α, β the rest angles opposite the edge v–j, so that C_v ≈ A_v·(κ1 + κ2)·n for a surface with principal curvatures
 * κ1, κ2 and normal n, A_v the vertex's mixed Voronoi area (Meyer et al.: Voronoi in non-obtuse triangles, half or
 * a quarter of an obtuse one). The energy ½·B·|C_v|²/A_v sums to the plate's ½·B·(κ1 + κ2)² per unit area,
 * isotropically on the grid, whose diagonals get weight 0 (right triangles: C_v is the five-point stencil).
 * Entries: v first (−Σ w), then its neighbours with a weight above NEGLIGIBLE_WEIGHT of the largest.
 *
 * Only interior vertices have a stencil: at a border vertex the flat sheet's cotan Laplacian is not zero (it points
 * out of the sheet's edge), so no linear stencil there rests flat. Their rest area is handed in equal shares to the
 * interior vertices of their one-ring (none: it is lost), so that a sheet bent uniformly stores ½·B·κ²·A over its
 * whole area; a vertex's stored area is then A_v²/(A_v + its shares), its C being A_v·κ. A vertex with a degenerate
 * triangle gets no stencil. Coloured so that no two stencils of a batch share a particle.
 *
 * `lumpBorder` false leaves the border's area out (each stencil's area A_v): for tests measuring what the shares do.
 */
export function buildLaplacian(triangles: Uint32Array, edges: Uint32Array, p: Float32Array, n: number, lumpBorder = true): BendingStencils {
  // each vertex's one-ring from the edge list (CSR), with a weight and a triangle count per directed edge
  const start = new Uint32Array(n + 1);
  for (let k = 0; k < edges.length; k++) start[edges[k] + 1]++;
  for (let i = 0; i < n; i++) start[i + 1] += start[i];
  const ring = new Uint32Array(edges.length), fill = start.slice(0, n);
  for (let k = 0; k < edges.length; k += 2) {
    const a = edges[k], b = edges[k + 1];
    ring[fill[a]++] = b;
    ring[fill[b]++] = a;
  }
  const w = new Float64Array(edges.length), faces = new Uint8Array(edges.length);
  const slot = (a: number, b: number): number => {
    for (let k = start[a]; k < start[a + 1]; k++) if (ring[k] === b) return k;
    throw new Error('model: a triangle edge missing from the edge list');
  };
  const addEdge = (a: number, b: number, cot: number): void => {
    const ab = slot(a, b), ba = slot(b, a);
    w[ab] += 0.5 * cot; w[ba] += 0.5 * cot;
    faces[ab]++; faces[ba]++;
  };
  const area = new Float64Array(n);
  const bad = new Uint8Array(n);
  for (let t = 0; t < triangles.length; t += 3) {
    const v = [triangles[t], triangles[t + 1], triangles[t + 2]];
    const cot = [0, 0, 0], len2 = [0, 0, 0];
    let twice = 0;
    for (let c = 0; c < 3; c++) {
      const o = 3 * v[c], a = 3 * v[(c + 1) % 3], b = 3 * v[(c + 2) % 3];
      const ux = p[a] - p[o], uy = p[a + 1] - p[o + 1], uz = p[a + 2] - p[o + 2];
      const vx = p[b] - p[o], vy = p[b + 1] - p[o + 1], vz = p[b + 2] - p[o + 2];
      cot[c] = cotangent(ux, uy, uz, vx, vy, vz);
      // the squared length of the edge opposite corner c
      len2[c] = (p[b] - p[a]) ** 2 + (p[b + 1] - p[a + 1]) ** 2 + (p[b + 2] - p[a + 2]) ** 2;
      if (c === 0) twice = Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
    }
    for (let c = 0; c < 3; c++) addEdge(v[(c + 1) % 3], v[(c + 2) % 3], cot[c]);
    if (!(twice > 0) || !cot.every(Number.isFinite)) {
      for (const i of v) bad[i] = 1;
      continue;
    }
    const obtuse = cot.findIndex((c) => c < 0);
    for (let c = 0; c < 3; c++) {
      // mixed Voronoi area (Meyer et al. 2003): the Voronoi part, ⅛·Σ|e|²·cot of the two edges at the corner
      area[v[c]] += obtuse < 0
        ? (len2[(c + 1) % 3] * cot[(c + 1) % 3] + len2[(c + 2) % 3] * cot[(c + 2) % 3]) / 8
        : (obtuse === c ? twice / 4 : twice / 8);
    }
  }
  const border = new Uint8Array(n);
  for (let i = 0; i < n; i++) for (let k = start[i]; k < start[i + 1]; k++) if (faces[k] < 2) border[i] = 1;
  const interior = (i: number) => border[i] === 0 && bad[i] === 0 && start[i + 1] > start[i];
  // the border's area, in equal shares to the interior vertices of each border vertex's one-ring
  const shares = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    if (!border[i]) continue;
    let inner = 0;
    for (let k = start[i]; k < start[i + 1]; k++) if (interior(ring[k])) inner++;
    for (let k = start[i]; k < start[i + 1]; k++) if (interior(ring[k])) shares[ring[k]] += area[i] / inner;
  }
  let count = 0, entries = 0;
  for (let i = 0; i < n; i++) if (interior(i)) { count++; entries += 1 + start[i + 1] - start[i]; }
  const offsets = new Uint32Array(count + 1), vertices = new Uint32Array(entries), weights = new Float64Array(entries);
  const areas = new Float64Array(count);
  let s = 0, at = 0;
  for (let i = 0; i < n; i++) {
    if (!interior(i)) continue;
    let largest = 0;
    for (let k = start[i]; k < start[i + 1]; k++) largest = Math.max(largest, Math.abs(w[k]));
    const centre = at++;
    vertices[centre] = i;
    let sum = 0;
    for (let k = start[i]; k < start[i + 1]; k++) {
      if (Math.abs(w[k]) <= NEGLIGIBLE_WEIGHT * largest) continue;
      vertices[at] = ring[k];
      weights[at++] = w[k];
      sum += w[k];
    }
    weights[centre] = -sum;
    areas[s] = lumpBorder ? (area[i] * area[i]) / (area[i] + shares[i]) : area[i];
    offsets[++s] = at;
  }
  return sortStencils(offsets, vertices.subarray(0, at), weights.subarray(0, at), areas, n);
}

/** The bending stencils a params' bending model solves (model.stencils), or null for the bend springs. */
export function bendingStencils(model: ClothModel, bending: 'springs' | StencilModel): BendingStencils | null {
  return bending === 'springs' ? null : model.stencils[bending];
}

/**
 * Each particle's share of the cloth's area, and the area [m²]: the mixed Voronoi areas of Meyer, Desbrun, Schröder
 * & Barr 2003 ("Discrete Differential-Geometry Operators for Triangulated 2-Manifolds", §3.3, the A_mixed of their
 * Fig. 4). A triangle with no obtuse angle gives each corner the part of it nearer that corner than the other two
 * (its Voronoi region within the triangle): for the corner P of triangle PQR, (|PR|²·cot Q + |PQ|²·cot R)/8. An
 * obtuse triangle, whose circumcentre lies outside it, gives its obtuse corner half its area and the other two a
 * quarter each. Either way the three parts add up to the triangle's area, and the parts depend on the triangle's
 * shape only, not on the order or the way a quad was split: a right isosceles triangle gives its right-angle
 * corner ½ and the others ¼, so each corner of a rectangle gets ¼ of the cell whichever way its diagonal runs
 * (the old lumping, a third of each triangle to each corner, gave two corners 1/6 of the cell and two 1/3), an
 * edge particle ½ and an interior one a whole cell. The parts of each triangle are rescaled to add up to its area
 * exactly (in f64: rounding is all they can differ by), and the shares are divided by their sum, so they add up to
 * 1 to rounding. A particle that belongs to no triangle (only models built by hand have them) gets the mean share
 * of those that do, or all get 1/n when no triangle has area.
 */
export function lumpedMassWeights(p: Float32Array, triangles: Uint32Array, n: number): { weights: Float32Array; area: number } {
  const acc = new Float64Array(n);
  let area = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    // edge vectors ab, bc, ca
    const abx = p[3 * b] - p[3 * a], aby = p[3 * b + 1] - p[3 * a + 1], abz = p[3 * b + 2] - p[3 * a + 2];
    const bcx = p[3 * c] - p[3 * b], bcy = p[3 * c + 1] - p[3 * b + 1], bcz = p[3 * c + 2] - p[3 * b + 2];
    const cax = p[3 * a] - p[3 * c], cay = p[3 * a + 1] - p[3 * c + 1], caz = p[3 * a + 2] - p[3 * c + 2];
    const cx = aby * caz - abz * cay, cy = abz * cax - abx * caz, cz = abx * cay - aby * cax;
    const ta = 0.5 * Math.sqrt(cx * cx + cy * cy + cz * cz);
    if (!(ta > 0)) continue;
    area += ta;
    // the dot products of the two edges at each corner (their sign: the angle is obtuse where it is negative)
    const da = -(abx * cax + aby * cay + abz * caz), db = -(abx * bcx + aby * bcy + abz * bcz), dc = -(bcx * cax + bcy * cay + bcz * caz);
    let pa: number, pb: number, pc: number;
    if (da < 0) { pa = ta / 2; pb = pc = ta / 4; }
    else if (db < 0) { pb = ta / 2; pa = pc = ta / 4; }
    else if (dc < 0) { pc = ta / 2; pa = pb = ta / 4; }
    else {
      // cot of the angle at a corner = its dot product / (2·area); Voronoi part of P = (|PR|² cot Q + |PQ|² cot R)/8
      const ab2 = abx * abx + aby * aby + abz * abz, bc2 = bcx * bcx + bcy * bcy + bcz * bcz, ca2 = cax * cax + cay * cay + caz * caz;
      const s = 1 / (16 * ta);
      pa = (ca2 * db + ab2 * dc) * s;
      pb = (ab2 * dc + bc2 * da) * s;
      pc = (bc2 * da + ca2 * db) * s;
      const fix = ta / (pa + pb + pc);
      pa *= fix; pb *= fix; pc *= fix;
    }
    acc[a] += pa; acc[b] += pb; acc[c] += pc;
  }
  let covered = 0, sum = 0;
  for (let i = 0; i < n; i++) if (acc[i] > 0) { covered++; sum += acc[i]; }
  if (covered === 0) return { weights: new Float32Array(n).fill(1 / n), area };
  if (covered < n) {
    const mean = sum / covered;
    for (let i = 0; i < n; i++) if (!(acc[i] > 0)) { acc[i] = mean; sum += mean; }
  }
  const weights = new Float32Array(n);
  for (let i = 0; i < n; i++) weights[i] = acc[i] / sum;
  return { weights, area };
}

/** Builds a model from any particle/spring/triangle set (the grid builder and tests use it). */
export function buildModel(input: ModelInput): ClothModel {
  const { restPositions } = input;
  const n = restPositions.length / 3;
  if (!Number.isInteger(n) || n < 1) throw new Error('model: restPositions must hold 3 floats per particle');

  const { weights: massWeights, area } = lumpedMassWeights(restPositions, input.triangles, n);
  let maxTriangleEdge = 0;
  const valence = new Uint32Array(n);
  for (let t = 0; t < input.triangles.length; t += 3) {
    const a = input.triangles[t], b = input.triangles[t + 1], c = input.triangles[t + 2];
    maxTriangleEdge = Math.max(maxTriangleEdge, distance(restPositions, a, b), distance(restPositions, b, c), distance(restPositions, c, a));
    valence[a]++; valence[b]++; valence[c]++;
  }
  let maxTriangleValence = 0;
  for (let i = 0; i < n; i++) maxTriangleValence = Math.max(maxTriangleValence, valence[i]);

  // sort springs by kind, then colour
  let total = 0;
  for (const k of input.springs) total += k.length / 2;
  const springs = new Uint32Array(2 * total);
  const restLengths = new Float32Array(total);
  const stiffnessScales = new Float32Array(total);
  const springKinds = new Uint8Array(total);
  const batches: SpringBatch[] = [];
  const counts: [number, number, number] = [0, 0, 0];
  let at = 0;
  for (let kind = 0; kind < 3; kind++) {
    const pairs = input.springs[kind];
    const scales = input.stiffnessScales?.[kind];
    const m = pairs.length / 2;
    counts[kind] = m;
    if (m === 0) continue;
    const { colours, count } = colourElements(pairs, 2, n);
    const offsets = colourOffsets(colours, count);
    for (let c = 0; c < count; c++) batches.push({ kind, start: at + offsets[c], end: at + offsets[c + 1] });
    const fill = offsets.slice(0, count);
    // within a batch, springs in order of their lower particle index: a contiguous share of a batch is then a
    // contiguous region of the cloth (threads splitting a batch write different cache lines)
    const order = Array.from({ length: m }, (_, s) => s);
    order.sort((s, t) => Math.min(pairs[2 * s], pairs[2 * s + 1]) - Math.min(pairs[2 * t], pairs[2 * t + 1]) || s - t);
    for (const s of order) {
      const dst = at + fill[colours[s]]++;
      const a = pairs[2 * s], b = pairs[2 * s + 1];
      springs[2 * dst] = a;
      springs[2 * dst + 1] = b;
      restLengths[dst] = distance(restPositions, a, b);
      stiffnessScales[dst] = scales ? scales[s] : 1;
      springKinds[dst] = kind;
    }
    at += m;
  }

  // triangles sorted by colour too: contact visits them in this order, and a GPU can take a colour at a time
  const tc = colourElements(input.triangles, 3, n);
  const triOffsets = colourOffsets(tc.colours, tc.count);
  const triangleBatches: TriangleBatch[] = [];
  for (let c = 0; c < tc.count; c++) triangleBatches.push({ start: triOffsets[c], end: triOffsets[c + 1] });
  const triangles = new Uint32Array(input.triangles.length);
  const triFill = triOffsets.slice(0, tc.count);
  for (let t = 0; t < tc.colours.length; t++) {
    const dst = triFill[tc.colours[t]]++;
    triangles[3 * dst] = input.triangles[3 * t];
    triangles[3 * dst + 1] = input.triangles[3 * t + 1];
    triangles[3 * dst + 2] = input.triangles[3 * t + 2];
  }

  let uvs = input.uvs;
  if (!uvs) uvs = new Float32Array(2 * n);
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], restPositions[3 * i + k]);
      hi[k] = Math.max(hi[k], restPositions[3 * i + k]);
    }
  }
  const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3);
  // the same for the triangles in any order: a caller that derived it already passes it on
  const topology = input.topology ?? meshTopology(triangles, n);
  const stencils = {
    hinges: buildHinges(topology.bendingPairs, restPositions, n),
    laplacian: buildLaplacian(triangles, topology.edges, restPositions, n),
  };

  return {
    particleCount: n,
    restPositions,
    uvs,
    massWeights,
    springs,
    restLengths,
    stiffnessScales,
    springKinds,
    batches,
    springCounts: counts,
    triangles,
    triangleBatches,
    maxTriangleEdge,
    maxTriangleValence,
    area,
    ...topology,
    stencils,
    grid: input.grid,
    clothStarts: new Uint32Array([0, n]),
    size,
  };
}

/**
 * One model of several cloths (a scene's `cloths`): their particles one after another (cloth c's from
 * clothStarts[c]), their springs, triangles and stencils over those, coloured together (no two cloths share a
 * particle, so every colour batch still shares none). Each particle keeps its share of its own cloth's mass.
 */
export function mergeModels(parts: readonly ClothModel[]): ClothModel {
  if (parts.length === 1) return parts[0];
  const starts = new Uint32Array(parts.length + 1);
  parts.forEach((m, c) => { starts[c + 1] = starts[c] + m.particleCount; });
  const n = starts[parts.length];
  const restPositions = new Float32Array(3 * n), uvs = new Float32Array(2 * n), massWeights = new Float32Array(n);
  const triangles = new Uint32Array(parts.reduce((t, m) => t + m.triangles.length, 0));
  const counts = [0, 1, 2].map((kind) => parts.reduce((t, m) => t + m.springCounts[kind], 0));
  const springs = counts.map((k) => new Uint32Array(2 * k)) as [Uint32Array, Uint32Array, Uint32Array];
  const scales = counts.map((k) => new Float32Array(k)) as [Float32Array, Float32Array, Float32Array];
  const fill = [0, 0, 0];
  let t = 0;
  parts.forEach((m, c) => {
    const o = starts[c];
    restPositions.set(m.restPositions, 3 * o);
    uvs.set(m.uvs, 2 * o);
    massWeights.set(m.massWeights, o);
    for (let j = 0; j < m.triangles.length; j++) triangles[t++] = m.triangles[j] + o;
    for (let s = 0; s < m.restLengths.length; s++) {
      const kind = m.springKinds[s], at = fill[kind]++;
      springs[kind][2 * at] = m.springs[2 * s] + o;
      springs[kind][2 * at + 1] = m.springs[2 * s + 1] + o;
      scales[kind][at] = m.stiffnessScales[s];
    }
  });
  const merged = buildModel({ restPositions, uvs, triangles, springs, stiffnessScales: scales });
  return { ...merged, massWeights, clothStarts: starts, clothParts: parts };
}

/** The cloth particle i belongs to (model.clothStarts). */
export function clothOf(model: ClothModel, i: number): number {
  const starts = model.clothStarts;
  let c = 0;
  while (i >= starts[c + 1]) c++;
  return c;
}

/** How a grid cloth is laid out at the start. */
export interface GridClothSpec {
  /** faces per side, 1 … 1024 */
  resolution: number;
  /** extent along the cloth's u axis [m] */
  width: number;
  /** extent along the cloth's v axis [m] */
  height: number;
  /** 'horizontal': lies in the xz plane, row 0 at -z; 'hanging': in the xy plane, row 0 at the top */
  orientation: 'horizontal' | 'hanging';
  /** centre of the cloth [m] */
  position: readonly [number, number, number];
  /** extra rotation applied about the centre, Euler XYZ [degrees] */
  rotation: readonly [number, number, number];
  /** bend and stretch stiffness scaling to keep continuum behaviour (true) or the seed's per-spring one (false) */
  scaleWithResolution: boolean;
  /**
   * height of a smooth bulge sin(πu)·sin(πv) out of the cloth's plane (u, v ∈ [0, 1] across it, zero on its
   * edges), before the rotation; the start pose and the rest shape both have it [m]; 0 or absent: flat
   */
  imperfection?: number;
}

/** Spacing at which material stiffnesses are given: a 1 m cloth at 32 faces per side [m]. */
export const REFERENCE_SPACING = 1 / 32;

/**
 * The seed's cloth: a grid of (resolution + 1)² particles at the corners of each face; structural springs between
 * horizontal/vertical neighbours, shear springs on both diagonals, bend springs between skip-one neighbours;
 * two triangles per face.
 */
export function buildGridModel(spec: GridClothSpec): ClothModel {
  const r = spec.resolution;
  if (!Number.isInteger(r) || r < 1 || r > 1024) throw new Error(`cloth.resolution must be an integer in 1…1024, got ${r}`);
  const nx = r + 1, ny = r + 1;
  const n = nx * ny;
  const dx = spec.width / r, dy = spec.height / r;
  const R = eulerXYZ(spec.rotation);
  const [px, py, pz] = spec.position;
  const bulge = spec.imperfection ?? 0;
  const pos = new Float32Array(3 * n);
  const uvs = new Float32Array(2 * n);
  for (let j = 0; j < ny; j++) {
    for (let i = 0; i < nx; i++) {
      const p = j * nx + i;
      const u = i * dx - spec.width / 2; // along +x
      const v = j * dy - spec.height / 2; // row index grows away from row 0
      // out of the plane: +y when horizontal, +z when hanging (exactly 0 for a flat cloth)
      const off = bulge === 0 ? 0 : bulge * Math.sin((Math.PI * i) / r) * Math.sin((Math.PI * j) / r);
      let lx: number, ly: number, lz: number;
      if (spec.orientation === 'horizontal') {
        lx = u; ly = off; lz = v; // row 0 at -z
      } else {
        lx = u; ly = -v; lz = off; // row 0 at the top
      }
      pos[3 * p] = px + R[0] * lx + R[1] * ly + R[2] * lz;
      pos[3 * p + 1] = py + R[3] * lx + R[4] * ly + R[5] * lz;
      pos[3 * p + 2] = pz + R[6] * lx + R[7] * ly + R[8] * lz;
      uvs[2 * p] = i / r;
      uvs[2 * p + 1] = 1 - j / r;
    }
  }
  const id = (i: number, j: number) => j * nx + i;

  // structural: all horizontal edges first, then all vertical ones (keeps the greedy colouring at 2 + 2)
  const structural = new Uint32Array(2 * (2 * r * (r + 1)));
  const sScale = new Float32Array(structural.length / 2);
  let s = 0;
  for (let j = 0; j < ny; j++) for (let i = 0; i < r; i++) { structural[2 * s] = id(i, j); structural[2 * s + 1] = id(i + 1, j); sScale[s++] = dy / dx; }
  for (let i = 0; i < nx; i++) for (let j = 0; j < r; j++) { structural[2 * s] = id(i, j); structural[2 * s + 1] = id(i, j + 1); sScale[s++] = dx / dy; }

  const shear = new Uint32Array(2 * (2 * r * r));
  s = 0;
  for (let j = 0; j < r; j++) for (let i = 0; i < r; i++) { shear[2 * s] = id(i, j); shear[2 * s + 1] = id(i + 1, j + 1); s++; }
  for (let j = 0; j < r; j++) for (let i = 0; i < r; i++) { shear[2 * s] = id(i + 1, j); shear[2 * s + 1] = id(i, j + 1); s++; }

  const bendCount = r >= 2 ? 2 * (r - 1) * (r + 1) : 0;
  const bend = new Uint32Array(2 * bendCount);
  const bScale = new Float32Array(bendCount);
  s = 0;
  // bend energy of a spring over two cells is quartic in curvature: E ∝ k·l⁴·κ⁴ per unit area (docs/physics.md)
  const bx = Math.pow(REFERENCE_SPACING / dx, 4) * (dy / dx);
  const by = Math.pow(REFERENCE_SPACING / dy, 4) * (dx / dy);
  for (let j = 0; j < ny; j++) for (let i = 0; i + 2 < nx; i++) { bend[2 * s] = id(i, j); bend[2 * s + 1] = id(i + 2, j); bScale[s++] = bx; }
  for (let i = 0; i < nx; i++) for (let j = 0; j + 2 < ny; j++) { bend[2 * s] = id(i, j); bend[2 * s + 1] = id(i, j + 2); bScale[s++] = by; }

  const triangles = new Uint32Array(6 * r * r);
  let t = 0;
  for (let j = 0; j < r; j++) {
    for (let i = 0; i < r; i++) {
      const a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      // counter-clockwise seen from +y for a horizontal cloth (row 0 at -z): a, d, c and a, c, b
      triangles[t++] = a; triangles[t++] = d; triangles[t++] = c;
      triangles[t++] = a; triangles[t++] = c; triangles[t++] = b;
    }
  }
  const ones = (m: number) => new Float32Array(m).fill(1);
  return buildModel({
    restPositions: pos,
    uvs,
    triangles,
    springs: [structural, shear, bend],
    stiffnessScales: spec.scaleWithResolution ? [sScale, ones(shear.length / 2), bScale] : undefined,
    grid: { nx, ny },
  });
}


/**
 * A model from any prepared triangle mesh (mesh/triangle-mesh.ts prepareMesh): the springs come from the
 * triangles. Structural springs are the mesh's edges, with the per-edge factor Σ A_t / |e|² over the edge's
 * triangles (Van Gelder 1998, "Approximate simulation of elastic membranes by triangulated spring meshes"), which
 * gives a lattice of equilateral triangles (and the axis springs of the grid) the sheet's tensile stiffness. There
 * are no separate shear springs: a triangle lattice resists shear with its edges. With `weave` the mesh is a woven
 * lattice whose threads run along its uvs' u and v, `weave.cellSize` apart (mesh/generators.ts wovenDiscMesh): only
 * the edges along a thread are structural, the others shear springs, and a whole cell gets both diagonals, as the
 * rectangle has (docs/physics.md, "The woven disc"). Bend springs join the two corners opposite each edge two
 * triangles share; their factor follows the grid's skip-one springs, (s₀/ℓ)⁴·(|e|/ℓ) with ℓ half the pair's unfolded
 * width (the mean of the two triangles' heights over the edge) and s₀ = REFERENCE_SPACING. With `scaleWithResolution`
 * off every factor is 1.
 */
export function buildMeshModel(mesh: TriangleMesh, scaleWithResolution: boolean, weave?: Weave): ClothModel {
  const p = mesh.positions, tri = mesh.triangles, n = p.length / 3;
  const table = edgeTable(tri, n);
  const topology = meshTopology(tri, n, table);
  const { edges, bendingPairs } = topology;
  const triArea = (t: number) => {
    const a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    const ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1], uz = p[3 * b + 2] - p[3 * a + 2];
    const vx = p[3 * c] - p[3 * a], vy = p[3 * c + 1] - p[3 * a + 1], vz = p[3 * c + 2] - p[3 * a + 2];
    const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    return 0.5 * Math.sqrt(cx * cx + cy * cy + cz * cz);
  };
  const m = edges.length / 2;
  const edgeArea = (e: number) => triArea(table.faces[2 * e]) + (table.faces[2 * e + 1] >= 0 ? triArea(table.faces[2 * e + 1]) : 0);
  if (!weave) {
    const sScale = new Float32Array(m);
    for (let e = 0; e < m; e++) {
      const l = distance(p, edges[2 * e], edges[2 * e + 1]);
      sScale[e] = edgeArea(e) / (l * l);
    }
    return meshModel(mesh, topology, edges, sScale, new Uint32Array(0), new Float32Array(0), scaleWithResolution);
  }
  // woven: an edge along a thread (within 3° of u or v) is structural, any other a shear spring of the cell area it
  // spans; a whole cell (two triangles making a rectangle of thread edges) gets its other diagonal as well. An edge
  // the cut tilted off its thread is a shear spring: as structural it would stiffen the rim's shear (1.8 × G over a
  // disc of 24 cells at 22.5°), as a shear spring the rim is a little soft, as a cut fabric's edge is (0.94 × G)
  const uv = mesh.uvs;
  if (!uv) throw new Error('buildMeshModel: a woven mesh needs uvs (the threads run along u and v)');
  const along = new Uint8Array(m);
  const edgeOf = new Map<number, number>();
  let threads = 0;
  for (let e = 0; e < m; e++) {
    const a = edges[2 * e], b = edges[2 * e + 1];
    const du = Math.abs(uv[2 * b] - uv[2 * a]), dv = Math.abs(uv[2 * b + 1] - uv[2 * a + 1]);
    along[e] = Math.min(du, dv) <= Math.tan((3 * Math.PI) / 180) * Math.max(du, dv) ? 1 : 0;
    threads += along[e];
    edgeOf.set(Math.min(a, b) * n + Math.max(a, b), e);
  }
  const isThread = (a: number, b: number) => along[edgeOf.get(Math.min(a, b) * n + Math.max(a, b)) ?? -1] === 1;
  const cell = weave.cellSize * weave.cellSize;
  const structural = new Uint32Array(2 * threads), sScale = new Float32Array(threads);
  const shear: number[] = [], dScale: number[] = [];
  let s = 0;
  for (let e = 0; e < m; e++) {
    const a = edges[2 * e], b = edges[2 * e + 1];
    if (along[e]) {
      const l = distance(p, a, b);
      structural[2 * s] = a; structural[2 * s + 1] = b; sScale[s++] = edgeArea(e) / (l * l);
    } else {
      shear.push(a, b); dScale.push(edgeArea(e) / cell);
    }
  }
  for (let k = 0; k < bendingPairs.length; k += 4) {
    const a = bendingPairs[k], b = bendingPairs[k + 1], c = bendingPairs[k + 2], d = bendingPairs[k + 3];
    if (isThread(a, b) || !isThread(a, c) || !isThread(c, b) || !isThread(b, d) || !isThread(d, a)) continue;
    const e = edgeOf.get(Math.min(a, b) * n + Math.max(a, b))!;
    shear.push(c, d); dScale.push(edgeArea(e) / cell);
  }
  return meshModel(mesh, topology, structural, sScale, Uint32Array.from(shear), Float32Array.from(dScale), scaleWithResolution);
}

/** A woven mesh's lattice (buildMeshModel): its threads run along the uvs' u and v, `cellSize` [m] apart. */
export interface Weave {
  cellSize: number;
}

/** The springs of a mesh model: structural and shear as given, bend springs across each interior edge. */
function meshModel(mesh: TriangleMesh, topology: MeshTopology, structural: Uint32Array, sScale: Float32Array, shear: Uint32Array, dScale: Float32Array, scaleWithResolution: boolean): ClothModel {
  const p = mesh.positions;
  const { bendingPairs } = topology;
  const nb = bendingPairs.length / 4;
  const bend = new Uint32Array(2 * nb);
  const bScale = new Float32Array(nb);
  for (let k = 0; k < nb; k++) {
    const c = bendingPairs[4 * k + 2], d = bendingPairs[4 * k + 3];
    bend[2 * k] = c;
    bend[2 * k + 1] = d;
    // ℓ: half the pair's width unfolded (the two corners' distances from the hinge line), so that a pair folded
    // flat in the rest shape (a pleat, a hem) is as stiff as when it lies open
    const a = bendingPairs[4 * k], b = bendingPairs[4 * k + 1], hinge = distance(p, a, b);
    const half = (heightOver(p, a, b, c, hinge) + heightOver(p, a, b, d, hinge)) / 2;
    bScale[k] = Math.pow(REFERENCE_SPACING / half, 4) * (hinge / half);
  }
  return buildModel({
    restPositions: p,
    uvs: mesh.uvs,
    triangles: mesh.triangles,
    springs: [structural, shear, bend],
    stiffnessScales: scaleWithResolution ? [sScale, dScale, bScale] : undefined,
    topology,
  });
}
