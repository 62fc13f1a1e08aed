/**
 * A collider made of a triangle mesh from a file (a figure, a chair, a bowl, a terrain), in its own coordinates ×
 * scale: the LOCAL frame. Placing it in the scene (position, rotation) is createColliders' separate rigid step
 * (placed.ts), so the shape never knows where it stands.
 *
 * **Pieces.** Vertices are welded as for a cloth (triangle-mesh.ts), triangles without area dropped, and each
 * connected piece oriented consistently. A piece whose every edge joins exactly two of its triangles is **closed**:
 * a solid, turned so that its volume is positive (normals outward), with a signed distance — negative inside. Any
 * other piece (a boundary edge, an edge of three or more triangles, a Möbius strip) is **open**: a two-sided thin
 * shell whose distance is unsigned, the normal pointing from the surface to the side the point is on, so contact
 * keeps the cloth at its thickness on whichever side it is. A particle that crosses an open shell within one
 * substep by more than the thickness stays on the far side (nothing remembers the side).
 *
 * **Signed distance** of a closed piece: the nearest point of the mesh (a BVH query, bvh.ts) and the sign of
 * (p − c)·n for the angle-weighted pseudo-normal n of the feature c lies on — the face's normal, the sum of the two
 * face normals at an edge, the angle-weighted sum of the face normals around a vertex. Bærentzen & Aanæs 2005,
 * "Signed distance computation using the angle weighted pseudonormal", IEEE TVCG 11(3): this sign is exact for any
 * closed, consistently oriented 2-manifold. The `within` early out bounds the BVH query by `within`: a point with no
 * triangle that near is outside (returned as `within`) unless it lies in the box of a closed piece, which then takes
 * the unbounded query for its sign.
 *
 * **Triangle contact** (`triangleDeepest`). The distance to a mesh is smallest over a cloth triangle either at one
 * of its vertices (which particle contact keeps out) or where a **sharp** edge of the mesh — or a corner, an end of
 * one — comes nearest the triangle: a convex edge of a closed piece turning more than SHARP_EDGE_DEGREES, any edge
 * of an open piece turning that much (it is convex from one side), a boundary edge (a rim) or an edge of three
 * triangles. Flat and concave edges cannot poke between a triangle's vertices: the distance to the two faces there is
 * the smaller of two affine functions, whose minimum over a triangle is at a vertex. So the deepest point is the
 * triangle's point nearest the sharp edges within reach (a BVH walk over the triangles' boxes, each triangle owning
 * its sharp edges once; `segmentTriangleClosest` of convex.ts, exact), its depth and normal from `signedDistance`.
 * Where a sharp edge passes through the triangle, or that point is inside a closed piece, the triangle crosses the
 * surface and the deepest point is searched (the golden-section search of convex.ts: the solid is convex near a
 * corner poking through); a sharp edge of an open shell through it pushes the crossing point to the side the
 * triangle's vertices are on. A cloth triangle through a face of an open shell with its vertices on both sides (it
 * got there between substeps) is not found: nothing tells which side is right. A mesh with no sharp edge has minCurvatureRadius Infinity (no triangle contact);
 * otherwise 0, and triangle contact runs for every cloth.
 */
import type { MeshResolver } from '../cloth-shape.js';
// per-triangle flags (the one table: the GPU reads them too): SIGNED, the triangle belongs to a closed piece (signed
// distance); SHARP_EDGE << e, the triangle owns edge e (corner e → e + 1) and it is sharp
import { MESH_SHARP_EDGE as SHARP_EDGE, MESH_SIGNED as SIGNED } from '../layout.generated.js';
import { edgeTable } from '../mesh/edges.js';
import { NOT_A_MESH, isTriangleMesh, weldMap, weldTolerance, type TriangleMesh } from '../mesh/triangle-mesh.js';
import { SceneError } from '../scene.js';
import { plainText } from '../text.js';
import { TriangleBvh } from './bvh.js';
import { goldenDeepest, segmentTriangleIn } from './convex.js';
import { QUERY, TRIANGLE, deepestOf, distanceOf, pointQuery, type ColliderShape } from './shape.js';

// (module constants: see shape.ts QUERY)
const { X: QUERY_X, Y: QUERY_Y, Z: QUERY_Z, WITHIN: QUERY_WITHIN, D: QUERY_D } = QUERY;
const { WITHIN: TRIANGLE_WITHIN, D: TRIANGLE_D } = TRIANGLE;

/** Most triangles a mesh collider may have (before dropping those without area): a million, ~1 s to build. */
export const MAX_COLLIDER_TRIANGLES = 1_000_000;
/** An edge whose faces turn by more than this [degrees] is sharp: it pokes into a cloth triangle of size e by ~e·sin(θ/2)/2. */
export const SHARP_EDGE_DEGREES = 1;

/** Cells of the coarse distance grid along the longest side of the mesh's box. */
export const GRID_CELLS = 32;


const bary = new Float64Array(3);
const vn = new Float64Array(3);
const edgeBary = new Float64Array(3);
const segT = new Float64Array(1);
/** the cloth triangle's box (min xyz, max xyz) in triangleDeepestIn, and (slot 6) boxGap2's answer */
const triBox = new Float64Array(7);
const GAP = 6;
/** segmentTriangleIn's record: a sharp edge p–q and the cloth triangle a, b, c, then the squared distance */
const edgeTriangle = new Float64Array(16);
/** the point queries a mesh makes of itself: through the record, not signedDistance (shape.ts) */
const own = pointQuery();

/** Squared gap between node k's box (of `bounds`) and the box `t` (min xyz, max xyz), into t[GAP]. */
function boxGap2(bounds: Float32Array, k: number, t: Float64Array): void {
  const o = 6 * k;
  const gx = Math.max(bounds[o] - t[3], t[0] - bounds[o + 3], 0);
  const gy = Math.max(bounds[o + 1] - t[4], t[1] - bounds[o + 4], 0);
  const gz = Math.max(bounds[o + 2] - t[5], t[2] - bounds[o + 5], 0);
  t[GAP] = gx * gx + gy * gy + gz * gz;
}

const fail = (source: string, why: string): never => {
  throw new SceneError(`${source}: ${why}`);
};

export class MeshCollider implements ColliderShape {
  readonly type = 'mesh';
  readonly minCurvatureRadius: number;
  /** the hierarchy: triangles in its leaf order, positions [m] in the local frame */
  readonly bvh: TriangleBvh;
  /** unit face normals (leaf order), xyz */
  readonly faceNormals: Float32Array;
  /** angle-weighted pseudo-normal of each vertex (closed pieces; not normalised), xyz */
  readonly vertexNormals: Float32Array;
  /** the triangle across each triangle's edge e (corner e → e + 1), or −1 (boundary, or an edge of three or more) */
  readonly neighbours: Int32Array;
  /** per triangle: SIGNED, and SHARP_EDGE << e for each sharp edge it owns */
  readonly flags: Uint8Array;
  /** number of sharp edges */
  readonly sharpEdges: number;
  /** number of closed and open pieces */
  readonly closedPieces: number;
  readonly openPieces: number;
  /** triangles dropped for having no area */
  readonly dropped: number;
  /**
   * A coarse grid over the root box (GRID_CELLS along its longest side): the signed distance at each cell's centre.
   * sd is 1-Lipschitz, so a cell whose centre is more than `cellReach` (half its diagonal) from the surface is wholly
   * on that side: a point there farther out than `within` needs no BVH query, and a point with nothing within
   * `within` needs the unbounded query (for its sign) only where the grid cannot say it is outside.
   */
  readonly grid: Float32Array;
  readonly gridCells: readonly [number, number, number];
  private readonly cell: readonly [number, number, number];
  private readonly cellReach: number;

  /**
   * A collider from a mesh in the local frame [m] (already scaled); `source` names it in errors (SceneError: no
   * triangles, an index out of range, a coordinate that is not finite, more than MAX_COLLIDER_TRIANGLES, all
   * vertices at one point, no triangle with area).
   */
  constructor(positions: Float32Array, triangles: Uint32Array, source: string) {
    const n0 = positions.length / 3;
    if (!Number.isInteger(n0) || n0 === 0) fail(source, 'no vertices');
    if (triangles.length === 0 || triangles.length % 3 !== 0) fail(source, 'no triangles: a mesh collider needs faces');
    if (triangles.length / 3 > MAX_COLLIDER_TRIANGLES) {
      fail(source, `${triangles.length / 3} triangles; a mesh collider may have at most ${MAX_COLLIDER_TRIANGLES} (decimate it)`);
    }
    for (let j = 0; j < positions.length; j++) if (!Number.isFinite(positions[j])) fail(source, `vertex ${Math.floor(j / 3) + 1} has a coordinate that is not a finite number`);
    for (let k = 0; k < triangles.length; k++) {
      if (triangles[k] >= n0) fail(source, `face ${Math.floor(k / 3) + 1} uses vertex ${triangles[k] + 1}, but there are only ${n0}`);
    }
    let size = 0;
    for (let k = 0; k < 3; k++) {
      let lo = Infinity, hi = -Infinity;
      for (let j = k; j < positions.length; j += 3) { lo = Math.min(lo, positions[j]); hi = Math.max(hi, positions[j]); }
      size = Math.max(size, hi - lo);
    }
    if (!(size > 0)) fail(source, 'all vertices are at one point');

    // weld (files split vertices at seams: the surface must not come apart there), renumber, drop faces without area
    const rep = weldMap(positions, weldTolerance(positions, triangles, size));
    const index = new Int32Array(n0).fill(-1);
    let n = 0;
    for (let k = 0; k < triangles.length; k++) { const r = rep[triangles[k]]; if (index[r] < 0) index[r] = n++; }
    const p = new Float32Array(3 * n);
    for (let i = 0; i < n0; i++) if (index[i] >= 0) p.set(positions.subarray(3 * i, 3 * i + 3), 3 * index[i]);
    const kept: number[] = [];
    let dropped = 0;
    for (let t = 0; t < triangles.length; t += 3) {
      const a = index[rep[triangles[t]]], b = index[rep[triangles[t + 1]]], c = index[rep[triangles[t + 2]]];
      const ux = p[3 * b] - p[3 * a], uy = p[3 * b + 1] - p[3 * a + 1], uz = p[3 * b + 2] - p[3 * a + 2];
      const vx = p[3 * c] - p[3 * a], vy = p[3 * c + 1] - p[3 * a + 1], vz = p[3 * c + 2] - p[3 * a + 2];
      const cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      const wx = vx - ux, wy = vy - uy, wz = vz - uz;
      const longest2 = Math.max(ux * ux + uy * uy + uz * uz, vx * vx + vy * vy + vz * vz, wx * wx + wy * wy + wz * wz);
      if (a === b || b === c || c === a || Math.sqrt(cx * cx + cy * cy + cz * cz) <= 1e-7 * longest2) { dropped++; continue; }
      kept.push(a, b, c);
    }
    if (kept.length === 0) fail(source, 'no triangle has any area');
    const tri = Uint32Array.from(kept);
    const m = tri.length / 3;
    this.dropped = dropped;

    // pieces, oriented like their first triangle across the edges of exactly two triangles
    const table0 = edgeTable(tri, n);
    const uses = new Uint32Array(table0.count);
    for (let k = 0; k < tri.length; k++) uses[table0.triangleEdges[k]]++;
    const slot = (t: number, id: number, te: Uint32Array) => (te[3 * t] === id ? 0 : te[3 * t + 1] === id ? 1 : 2);
    const piece = new Int32Array(m).fill(-1), flip = new Uint8Array(m);
    const closed: boolean[] = [];
    const queue = new Int32Array(m);
    for (let first = 0; first < m; first++) {
      if (piece[first] >= 0) continue;
      const id = closed.length;
      let isClosed = true, head = 0, tail = 0;
      piece[first] = id;
      queue[tail++] = first;
      while (head < tail) {
        const t = queue[head++];
        for (let e = 0; e < 3; e++) {
          const edge = table0.triangleEdges[3 * t + e];
          if (uses[edge] !== 2) { isClosed = false; continue; }
          const u = table0.faces[2 * edge] === t ? table0.faces[2 * edge + 1] : table0.faces[2 * edge];
          // as stored, the two agree when they run the shared edge in opposite directions
          const eu = slot(u, edge, table0.triangleEdges);
          const agree = tri[3 * t + e] === tri[3 * u + (eu + 1) % 3];
          const want = flip[t] ^ (agree ? 0 : 1);
          if (piece[u] < 0) { piece[u] = id; flip[u] = want; queue[tail++] = u; }
          else if (flip[u] !== want) isClosed = false; // not orientable: a shell
        }
      }
      closed.push(isClosed);
    }
    // a closed piece turned inside out (negative volume) is turned back
    const volume = new Float64Array(closed.length);
    for (let t = 0; t < m; t++) {
      const a = 3 * tri[3 * t], b = 3 * tri[3 * t + (flip[t] ? 2 : 1)], c = 3 * tri[3 * t + (flip[t] ? 1 : 2)];
      volume[piece[t]] += p[a] * (p[b + 1] * p[c + 2] - p[b + 2] * p[c + 1]) + p[a + 1] * (p[b + 2] * p[c] - p[b] * p[c + 2]) + p[a + 2] * (p[b] * p[c + 1] - p[b + 1] * p[c]);
    }
    for (let t = 0; t < m; t++) {
      if (flip[t] ^ (closed[piece[t]] && volume[piece[t]] < 0 ? 1 : 0)) { const s = tri[3 * t + 1]; tri[3 * t + 1] = tri[3 * t + 2]; tri[3 * t + 2] = s; }
    }
    this.closedPieces = closed.filter(Boolean).length;
    this.openPieces = closed.length - this.closedPieces;

    // face normals, neighbours, sharp edges, vertex pseudo-normals (input order for now)
    const table = edgeTable(tri, n);
    const fn = new Float64Array(3 * m);
    for (let t = 0; t < m; t++) {
      const a = 3 * tri[3 * t], b = 3 * tri[3 * t + 1], c = 3 * tri[3 * t + 2];
      const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
      const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
      const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const l = Math.hypot(nx, ny, nz);
      fn[3 * t] = nx / l; fn[3 * t + 1] = ny / l; fn[3 * t + 2] = nz / l;
    }
    const nb = new Int32Array(3 * m).fill(-1);
    const flags = new Uint8Array(m);
    for (let t = 0; t < m; t++) if (closed[piece[t]]) flags[t] = SIGNED;
    const cosSharp = Math.cos((SHARP_EDGE_DEGREES * Math.PI) / 180);
    let sharp = 0;
    for (let edge = 0; edge < table.count; edge++) {
      const f0 = table.faces[2 * edge], f1 = table.faces[2 * edge + 1];
      let isSharp = true;
      if (uses[edge] === 2) {
        nb[3 * f0 + slot(f0, edge, table.triangleEdges)] = f1;
        nb[3 * f1 + slot(f1, edge, table.triangleEdges)] = f0;
        const cos = fn[3 * f0] * fn[3 * f1] + fn[3 * f0 + 1] * fn[3 * f1 + 1] + fn[3 * f0 + 2] * fn[3 * f1 + 2];
        if (cos >= cosSharp) isSharp = false;
        else if (flags[f0] & SIGNED) {
          // convex when the other face's far corner lies behind this face's plane
          const o = 3 * table.opposite[2 * edge + 1], a = 3 * table.ends[2 * edge];
          isSharp = fn[3 * f0] * (p[o] - p[a]) + fn[3 * f0 + 1] * (p[o + 1] - p[a + 1]) + fn[3 * f0 + 2] * (p[o + 2] - p[a + 2]) < 0;
        }
      }
      if (isSharp) { flags[f0] |= SHARP_EDGE << slot(f0, edge, table.triangleEdges); sharp++; }
    }
    this.sharpEdges = sharp;
    this.minCurvatureRadius = sharp > 0 ? 0 : Infinity;
    const vnorm = new Float64Array(3 * n);
    for (let t = 0; t < m; t++) {
      if (!(flags[t] & SIGNED)) continue;
      for (let k = 0; k < 3; k++) {
        const i = tri[3 * t + k], j = tri[3 * t + (k + 1) % 3], l = tri[3 * t + (k + 2) % 3];
        const ux = p[3 * j] - p[3 * i], uy = p[3 * j + 1] - p[3 * i + 1], uz = p[3 * j + 2] - p[3 * i + 2];
        const vx = p[3 * l] - p[3 * i], vy = p[3 * l + 1] - p[3 * i + 1], vz = p[3 * l + 2] - p[3 * i + 2];
        const cos = (ux * vx + uy * vy + uz * vz) / (Math.hypot(ux, uy, uz) * Math.hypot(vx, vy, vz));
        const angle = Math.acos(Math.min(1, Math.max(-1, cos)));
        vnorm[3 * i] += angle * fn[3 * t]; vnorm[3 * i + 1] += angle * fn[3 * t + 1]; vnorm[3 * i + 2] += angle * fn[3 * t + 2];
      }
    }
    this.vertexNormals = Float32Array.from(vnorm);

    // the hierarchy, and every per-triangle array in its leaf order
    this.bvh = new TriangleBvh(p, tri);
    const order = this.bvh.order;
    const inverse = new Int32Array(m);
    for (let i = 0; i < m; i++) inverse[order[i]] = i;
    this.faceNormals = new Float32Array(3 * m);
    this.neighbours = new Int32Array(3 * m);
    this.flags = new Uint8Array(m);
    for (let i = 0; i < m; i++) {
      const t = order[i];
      this.flags[i] = flags[t];
      for (let k = 0; k < 3; k++) {
        this.faceNormals[3 * i + k] = fn[3 * t + k];
        this.neighbours[3 * i + k] = nb[3 * t + k] < 0 ? -1 : inverse[nb[3 * t + k]];
      }
    }
    this.bvh.normals = this.faceNormals;

    // the grid of centre distances
    const B = this.bvh.bounds, ext = [B[3] - B[0], B[4] - B[1], B[5] - B[2]], longest = Math.max(...ext);
    const cells = ext.map((e) => Math.max(1, Math.ceil((GRID_CELLS * e) / longest))) as [number, number, number];
    this.gridCells = cells;
    this.cell = [ext[0] / cells[0], ext[1] / cells[1], ext[2] / cells[2]];
    this.cellReach = 0.5 * Math.hypot(...this.cell) * (1 + 1e-6) + 1e-9 * longest;
    this.grid = new Float32Array(cells[0] * cells[1] * cells[2]);
    for (let k = 0, g = 0; k < cells[2]; k++) for (let j = 0; j < cells[1]; j++) for (let i = 0; i < cells[0]; i++, g++) {
      own[QUERY_X] = B[0] + (i + 0.5) * this.cell[0]; own[QUERY_Y] = B[1] + (j + 0.5) * this.cell[1]; own[QUERY_Z] = B[2] + (k + 0.5) * this.cell[2];
      this.distanceTo(this.bvh.closest(own[QUERY_X], own[QUERY_Y], own[QUERY_Z], Infinity, bary), own, vn);
      this.grid[g] = own[QUERY_D];
    }
  }

  /** Triangles (after dropping those without area). */
  get triangleCount(): number {
    return this.bvh.triangles.length / 3;
  }

  signedDistance(px: number, py: number, pz: number, normal: Float64Array, within = Infinity): number {
    return distanceOf(this, px, py, pz, normal, within);
  }

  distanceIn(q: Float64Array, normal: Float64Array): void {
    const px = q[QUERY_X], py = q[QUERY_Y], pz = q[QUERY_Z], within = q[QUERY_WITHIN];
    const bvh = this.bvh;
    let t: number;
    if (within > 0 && within !== Infinity) {
      // the grid's bound: the centre's distance less the cell's reach
      const B = bvh.bounds;
      const i = Math.floor((px - B[0]) / this.cell[0]), j = Math.floor((py - B[1]) / this.cell[1]), k = Math.floor((pz - B[2]) / this.cell[2]);
      const c = this.gridCells, inGrid = i >= 0 && j >= 0 && k >= 0 && i < c[0] && j < c[1] && k < c[2];
      const centre = inGrid ? this.grid[i + c[0] * (j + c[1] * k)] : 0;
      if (inGrid && centre - this.cellReach >= within) { q[QUERY_D] = within; return; }
      const bq = bvh.query;
      bq[0] = px; bq[1] = py; bq[2] = pz; bq[3] = within * within;
      t = bvh.closestIn(bary);
      if (t < 0) {
        // nothing within reach: outside, unless the point may be inside a closed piece (in its box, and the grid
        // cannot say it is out)
        if (this.closedPieces === 0 || !inGrid || centre > this.cellReach) { q[QUERY_D] = within; return; }
        bq[3] = Infinity;
        t = bvh.closestIn(bary);
      }
    } else {
      const bq = bvh.query;
      bq[0] = px; bq[1] = py; bq[2] = pz; bq[3] = Infinity;
      t = bvh.closestIn(bary);
    }
    this.distanceTo(t, q, normal);
  }

  /**
   * The signed distance (to q[QUERY_D]) and normal of the point q[QUERY_X…Z] from its closest point: triangle t
   * (leaf order) at weights `bary`.
   */
  private distanceTo(t: number, q: Float64Array, normal: Float64Array): void {
    const px = q[QUERY_X], py = q[QUERY_Y], pz = q[QUERY_Z];
    const p = this.bvh.positions, tri = this.bvh.triangles, fn = this.faceNormals;
    const ia = tri[3 * t], ib = tri[3 * t + 1], ic = tri[3 * t + 2];
    const u = bary[0], v = bary[1], w = bary[2];
    const vx = px - (u * p[3 * ia] + v * p[3 * ib] + w * p[3 * ic]);
    const vy = py - (u * p[3 * ia + 1] + v * p[3 * ib + 1] + w * p[3 * ic + 1]);
    const vz = pz - (u * p[3 * ia + 2] + v * p[3 * ib + 2] + w * p[3 * ic + 2]);
    const d = Math.sqrt(vx * vx + vy * vy + vz * vz);
    let nx = fn[3 * t], ny = fn[3 * t + 1], nz = fn[3 * t + 2];
    if (!(this.flags[t] & SIGNED)) {
      // an open shell: unsigned, away from the surface
      if (d > 1e-12) { normal[0] = vx / d; normal[1] = vy / d; normal[2] = vz / d; }
      else { normal[0] = nx; normal[1] = ny; normal[2] = nz; }
      q[QUERY_D] = d;
      return;
    }
    // the pseudo-normal of the feature the closest point lies on (closestPointOnTriangle gives exact 0 and 1)
    if (u === 1 || v === 1 || w === 1) {
      const k = 3 * (u === 1 ? ia : v === 1 ? ib : ic), vnm = this.vertexNormals;
      nx = vnm[k]; ny = vnm[k + 1]; nz = vnm[k + 2];
    } else if (u === 0 || v === 0 || w === 0) {
      // edge e runs corner e → e + 1: the one whose weight is not zero on either end
      const e = u === 0 ? 1 : v === 0 ? 2 : 0;
      const o = this.neighbours[3 * t + e];
      if (o >= 0) { nx += fn[3 * o]; ny += fn[3 * o + 1]; nz += fn[3 * o + 2]; }
    }
    const sign = vx * nx + vy * ny + vz * nz < 0 ? -1 : 1;
    if (d > 1e-12) {
      normal[0] = (sign * vx) / d; normal[1] = (sign * vy) / d; normal[2] = (sign * vz) / d;
    } else {
      const l = Math.hypot(nx, ny, nz) || 1;
      normal[0] = nx / l; normal[1] = ny / l; normal[2] = nz / l;
    }
    q[QUERY_D] = sign * d;
  }

  triangleDeepest(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    bary: Float64Array, normal: Float64Array, within = Infinity,
  ): number {
    return deepestOf(this, a, ia, b, ib, c, ic, bary, normal, within);
  }

  /** See the file's comment: the point of the triangle nearest the mesh's sharp edges and corners. */
  triangleDeepestIn(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    baryOut: Float64Array, normal: Float64Array, out: Float64Array,
  ): void {
    const within = out[TRIANGLE_WITHIN];
    const ax = a[ia], ay = a[ia + 1], az = a[ia + 2], bx = b[ib], by = b[ib + 1], bz = b[ib + 2];
    const cx = c[ic], cy = c[ic + 1], cz = c[ic + 2];
    if (this.sharpEdges === 0) { this.vertexDeepest(a, ia, b, ib, c, ic, baryOut, normal, out); return; }
    const lx = Math.min(ax, bx, cx), ly = Math.min(ay, by, cy), lz = Math.min(az, bz, cz);
    const hx = Math.max(ax, bx, cx), hy = Math.max(ay, by, cy), hz = Math.max(az, bz, cz);
    const box = triBox;
    box[0] = lx; box[1] = ly; box[2] = lz; box[3] = hx; box[4] = hy; box[5] = hz;
    // the triangle's unit normal and plane offset: an edge wholly farther than the best from its plane is skipped
    let tnx = (by - ay) * (cz - az) - (bz - az) * (cy - ay), tny = (bz - az) * (cx - ax) - (bx - ax) * (cz - az), tnz = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    const tl = Math.sqrt(tnx * tnx + tny * tny + tnz * tnz);
    if (tl > 0) { tnx /= tl; tny /= tl; tnz /= tl; }
    const toff = tnx * ax + tny * ay + tnz * az;
    const bvh = this.bvh, nodes = bvh.nodes, bounds = bvh.bounds, tri = bvh.triangles, p = bvh.positions, stack = bvh.stack;
    const flags = this.flags;
    const bound = Math.max(within, 0), bound2 = within === Infinity ? Infinity : bound * bound;
    let best2 = bound2, found = false, crossing = -1, top = 0, n = 0;
    boxGap2(bounds, 0, box);
    if (box[GAP] > best2) { out[TRIANGLE_D] = within; return; }
    const et = edgeTriangle;
    et[6] = ax; et[7] = ay; et[8] = az; et[9] = bx; et[10] = by; et[11] = bz; et[12] = cx; et[13] = cy; et[14] = cz;
    walk: for (;;) {
      const count = nodes[2 * n + 1];
      if (count > 0) {
        const first = nodes[2 * n];
        for (let t = first; t < first + count; t++) {
          const f = flags[t];
          if (f < SHARP_EDGE) continue;
          for (let e = 0; e < 3; e++) {
            if (!(f & (SHARP_EDGE << e))) continue;
            const s = 3 * tri[3 * t + e], q = 3 * tri[3 * t + (e + 1) % 3];
            // the edge's box against the triangle's
            const gx = Math.max(Math.min(p[s], p[q]) - hx, lx - Math.max(p[s], p[q]), 0);
            const gy = Math.max(Math.min(p[s + 1], p[q + 1]) - hy, ly - Math.max(p[s + 1], p[q + 1]), 0);
            const gz = Math.max(Math.min(p[s + 2], p[q + 2]) - hz, lz - Math.max(p[s + 2], p[q + 2]), 0);
            if (gx * gx + gy * gy + gz * gz > best2) continue;
            if (tl > 0) {
              const hs = tnx * p[s] + tny * p[s + 1] + tnz * p[s + 2] - toff, hq = tnx * p[q] + tny * p[q + 1] + tnz * p[q + 2] - toff;
              const near = hs > 0 && hq > 0 ? Math.min(hs, hq) : hs < 0 && hq < 0 ? -Math.max(hs, hq) : 0;
              if (near * near > best2) continue;
            }
            et[0] = p[s]; et[1] = p[s + 1]; et[2] = p[s + 2]; et[3] = p[q]; et[4] = p[q + 1]; et[5] = p[q + 2];
            segmentTriangleIn(et, edgeBary, segT);
            const d2 = et[15];
            if (d2 <= 1e-24) {
              crossing = t;
              baryOut[0] = edgeBary[0]; baryOut[1] = edgeBary[1]; baryOut[2] = edgeBary[2];
              break walk;
            }
            if (d2 < best2) {
              best2 = d2; found = true;
              baryOut[0] = edgeBary[0]; baryOut[1] = edgeBary[1]; baryOut[2] = edgeBary[2];
            }
          }
        }
      } else {
        const l = nodes[2 * n], r = l + 1;
        boxGap2(bounds, l, box);
        const dl = box[GAP];
        boxGap2(bounds, r, box);
        const dr = box[GAP];
        if (dl < dr) {
          if (dr <= best2) stack[top++] = r;
          if (dl <= best2) { n = l; continue; }
        } else {
          if (dl <= best2) stack[top++] = l;
          if (dr <= best2) { n = r; continue; }
        }
      }
      let next = -1;
      while (top > 0) {
        const k = stack[--top];
        boxGap2(bounds, k, box);
        if (box[GAP] <= best2) { next = k; break; }
      }
      if (next < 0) break;
      n = next;
    }
    if (crossing >= 0) {
      if (flags[crossing] & SIGNED) { goldenDeepest(this, a, ia, b, ib, c, ic, baryOut, normal, out); return; }
      // an open shell's sharp edge through the triangle: push the crossing point to the side its vertices are on
      let sx = 0, sy = 0, sz = 0;
      for (let k = 0; k < 3; k++) {
        const src = k === 0 ? a : k === 1 ? b : c, o = k === 0 ? ia : k === 1 ? ib : ic;
        own[QUERY_X] = src[o]; own[QUERY_Y] = src[o + 1]; own[QUERY_Z] = src[o + 2]; own[QUERY_WITHIN] = Infinity;
        this.distanceIn(own, vn);
        sx += vn[0]; sy += vn[1]; sz += vn[2];
      }
      let l = Math.sqrt(sx * sx + sy * sy + sz * sz);
      if (l < 1e-9) {
        // vertices on both sides: the triangle's own normal
        sx = (by - ay) * (cz - az) - (bz - az) * (cy - ay); sy = (bz - az) * (cx - ax) - (bx - ax) * (cz - az); sz = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
        l = Math.sqrt(sx * sx + sy * sy + sz * sz) || 1;
      }
      normal[0] = sx / l; normal[1] = sy / l; normal[2] = sz / l;
      out[TRIANGLE_D] = 0;
      return;
    }
    if (!found) {
      if (within === Infinity) this.vertexDeepest(a, ia, b, ib, c, ic, baryOut, normal, out);
      else out[TRIANGLE_D] = within;
      return;
    }
    const u = baryOut[0], v = baryOut[1], w = baryOut[2];
    own[QUERY_X] = u * ax + v * bx + w * cx; own[QUERY_Y] = u * ay + v * by + w * cy; own[QUERY_Z] = u * az + v * bz + w * cz;
    own[QUERY_WITHIN] = Infinity;
    this.distanceIn(own, normal);
    const d = own[QUERY_D];
    // inside a closed piece: the triangle crosses the surface
    if (d < 0) goldenDeepest(this, a, ia, b, ib, c, ic, baryOut, normal, out);
    else out[TRIANGLE_D] = d;
  }

  /** The deepest of the triangle's vertices (a mesh without sharp edges has no deeper point): its distance to out[TRIANGLE_D]. */
  private vertexDeepest(
    a: Float32Array, ia: number, b: Float32Array, ib: number, c: Float32Array, ic: number,
    baryOut: Float64Array, normal: Float64Array, out: Float64Array,
  ): void {
    let best = Infinity;
    for (let k = 0; k < 3; k++) {
      const src = k === 0 ? a : k === 1 ? b : c, o = k === 0 ? ia : k === 1 ? ib : ic;
      own[QUERY_X] = src[o]; own[QUERY_Y] = src[o + 1]; own[QUERY_Z] = src[o + 2]; own[QUERY_WITHIN] = Infinity;
      this.distanceIn(own, vn);
      const d = own[QUERY_D];
      if (d < best) {
        best = d;
        baryOut[0] = k === 0 ? 1 : 0; baryOut[1] = k === 1 ? 1 : 0; baryOut[2] = k === 2 ? 1 : 0;
        normal[0] = vn[0]; normal[1] = vn[1]; normal[2] = vn[2];
      }
    }
    out[TRIANGLE_D] = best;
  }
}

/** The colliders built from each mesh a resolver returned, by scale: a parameter change rebuilds no hierarchy. */
const built = new WeakMap<TriangleMesh, Map<number, MeshCollider>>();

/** A mesh (file units) as a collider at `scale` [m per unit]; `source` names it in errors. Reused per (mesh, scale). */
export function meshCollider(mesh: TriangleMesh, scale: number, source: string): MeshCollider {
  let byScale = built.get(mesh);
  const hit = byScale?.get(scale);
  if (hit) return hit;
  const scaled = new Float32Array(mesh.positions.length);
  for (let j = 0; j < scaled.length; j++) scaled[j] = mesh.positions[j] * scale;
  const shape = new MeshCollider(scaled, mesh.triangles, source);
  if (!byScale) built.set(mesh, (byScale = new Map()));
  byScale.set(scale, shape);
  return shape;
}

/**
 * The collider of a scene's `colliders[k]` of type 'mesh': its file read by `meshes` (the host's resolver, as for
 * cloth.mesh: relative to the scene file), in the file's coordinates × scale. Any failure is one SceneError line
 * naming `field` (colliders[k].mesh).
 */
export function loadMeshCollider(path: string, scale: number, field: string, meshes?: MeshResolver): MeshCollider {
  const shown = plainText(path, 200);
  if (!meshes) {
    throw new SceneError(`${field}: '${shown}' is a file, and nothing here reads files; load the scene with its files (drape run, loadSceneFile from drape/node)`);
  }
  const oneLine = (e: unknown) => plainText(e instanceof Error ? e.message : String(e), 500);
  let mesh: TriangleMesh;
  try {
    mesh = meshes(path);
  } catch (e) {
    throw new SceneError(`${field}: ${oneLine(e)}`);
  }
  if (!isTriangleMesh(mesh)) throw new SceneError(`${field}: ${shown}: ${NOT_A_MESH}`);
  try {
    return meshCollider(mesh, scale, shown);
  } catch (e) {
    if (e instanceof SceneError) throw new SceneError(`${field}: ${oneLine(e)}`);
    throw e;
  }
}
