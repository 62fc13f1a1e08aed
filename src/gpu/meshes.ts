/**
 * The mesh colliders of a params' colliders as the GPU's kernels read them (layout.ts `MeshNode`, `MeshTriangle`):
 * every distinct MeshCollider's BVH nodes (colliders/bvh.ts) and triangles (leaf order, its own frame, with face
 * normals, the triangles across their edges, the angle-weighted pseudo-normals of their corners and the closed and
 * sharp-edge flags of colliders/mesh.ts), one after another in two arrays, indices made absolute. A collider's
 * record (`Collider.meshRoot`, `meshClosed`) says where its root node is; two colliders of one mesh share its tables.
 * Built on the CPU when the params' meshes change, never per frame.
 */
import type { PosedCollider } from '../core/colliders/index.js';
import { MeshCollider } from '../core/colliders/mesh.js';
import { MESH_NODE, MESH_STACK, MESH_TRIANGLE } from './layout.js';

/** Where a params' mesh colliders go in the tables. */
export interface MeshLayout {
  /** the distinct meshes, in the order of their first collider: their tables one after another */
  readonly meshes: readonly MeshCollider[];
  /** per collider of the params: its mesh's root node in the nodes (0 for a collider that is not a mesh) */
  readonly roots: Uint32Array;
  /** per collider: 1 for a mesh with a closed piece, else 0 */
  readonly closed: Uint32Array;
  /** MeshNode records of all the meshes */
  readonly nodeCount: number;
  /** MeshTriangle records of all the meshes */
  readonly triangleCount: number;
}

/** The mesh a collider is, or null. */
export function meshOf(shape: PosedCollider): MeshCollider | null {
  return shape.local instanceof MeshCollider ? shape.local : null;
}

/**
 * Why the GPU cannot walk this collider's mesh, or null (also for a collider that is not a mesh): its hierarchy is
 * deeper than the kernels' fixed stack (layout.ts MESH_STACK).
 */
export function meshRefusal(shape: PosedCollider): string | null {
  const mesh = meshOf(shape);
  if (!mesh || mesh.bvh.depth <= MESH_STACK) return null;
  return `its hierarchy is ${mesh.bvh.depth} levels deep; the GPU walks at most ${MESH_STACK}`;
}

/** Where the meshes of `colliders` go (see the file's comment). */
export function meshLayout(colliders: readonly PosedCollider[]): MeshLayout {
  const meshes: MeshCollider[] = [];
  const rootOf = new Map<MeshCollider, number>();
  const roots = new Uint32Array(colliders.length), closed = new Uint32Array(colliders.length);
  let nodeCount = 0, triangleCount = 0;
  colliders.forEach((c, k) => {
    const mesh = meshOf(c);
    if (!mesh) return;
    let root = rootOf.get(mesh);
    if (root === undefined) {
      root = nodeCount;
      rootOf.set(mesh, root);
      meshes.push(mesh);
      nodeCount += mesh.bvh.nodeCount;
      triangleCount += mesh.triangleCount;
    }
    roots[k] = root;
    closed[k] = mesh.closedPieces > 0 ? 1 : 0;
  });
  return { meshes, roots, closed, nodeCount, triangleCount };
}

/** The MeshNode and MeshTriangle records of the meshes of `layout` (at least one record each). */
export function packMeshes(layout: MeshLayout): { nodes: ArrayBuffer; triangles: ArrayBuffer } {
  const { meshes, nodeCount, triangleCount } = layout;
  const nodes = new ArrayBuffer(Math.max(1, nodeCount) * MESH_NODE.size);
  const triangles = new ArrayBuffer(Math.max(1, triangleCount) * MESH_TRIANGLE.size);
  const nv = new DataView(nodes), tv = new DataView(triangles);
  let nodeBase = 0, triangleBase = 0;
  const vec3 = (view: DataView, at: number, src: ArrayLike<number>, from: number) => {
    for (let j = 0; j < 3; j++) view.setFloat32(at + 4 * j, src[from + j], true);
  };
  for (const mesh of meshes) {
    const bvh = mesh.bvh;
    for (let i = 0; i < bvh.nodeCount; i++) {
      const at = (nodeBase + i) * MESH_NODE.size, count = bvh.nodes[2 * i + 1], first = bvh.nodes[2 * i];
      vec3(nv, at + MESH_NODE.lo, bvh.bounds, 6 * i);
      vec3(nv, at + MESH_NODE.hi, bvh.bounds, 6 * i + 3);
      nv.setUint32(at + MESH_NODE.first, count > 0 ? triangleBase + first : nodeBase + first, true);
      nv.setUint32(at + MESH_NODE.count, count, true);
    }
    const m = mesh.triangleCount, tri = bvh.triangles, p = bvh.positions;
    const corners = [MESH_TRIANGLE.a, MESH_TRIANGLE.b, MESH_TRIANGLE.c];
    const cornerNormals = [MESH_TRIANGLE.normalA, MESH_TRIANGLE.normalB, MESH_TRIANGLE.normalC];
    const across = [MESH_TRIANGLE.across0, MESH_TRIANGLE.across1, MESH_TRIANGLE.across2];
    for (let i = 0; i < m; i++) {
      const at = (triangleBase + i) * MESH_TRIANGLE.size;
      for (let k = 0; k < 3; k++) {
        vec3(tv, at + corners[k], p, 3 * tri[3 * i + k]);
        vec3(tv, at + cornerNormals[k], mesh.vertexNormals, 3 * tri[3 * i + k]);
        const o = mesh.neighbours[3 * i + k];
        tv.setInt32(at + across[k], o < 0 ? -1 : triangleBase + o, true);
      }
      vec3(tv, at + MESH_TRIANGLE.normal, mesh.faceNormals, 3 * i);
      tv.setUint32(at + MESH_TRIANGLE.flags, mesh.flags[i], true);
    }
    nodeBase += bvh.nodeCount;
    triangleBase += m;
  }
  return { nodes, triangles };
}
