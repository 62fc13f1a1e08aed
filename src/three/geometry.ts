/**
 * A three.js `BufferGeometry` as the core's `TriangleMesh` (what a cloth or a mesh collider is made from): its
 * positions, optionally transformed, its triangles (indexed or not; draw groups and ranges ignored) and its uvs.
 * The core welds duplicate vertices (a sphere's seam, a non-indexed geometry) when it builds the cloth. Pure.
 */
import { Vector3, type BufferGeometry, type Matrix4 } from 'three';
import type { TriangleMesh } from '../core/index.js';

const p = new Vector3();

/** The geometry's triangles, positions × `matrix` when given. Throws a TypeError starting with `label` for a geometry that cannot be one. */
export function meshOfGeometry(geometry: BufferGeometry, label: string, matrix?: Matrix4): TriangleMesh {
  const position = geometry.getAttribute('position');
  if (!position || position.itemSize < 3) throw new TypeError(`${label}: the geometry has no position attribute of 3 components`);
  const n = position.count;
  const positions = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) {
    p.fromBufferAttribute(position, i);
    if (matrix) p.applyMatrix4(matrix);
    positions[3 * i] = p.x; positions[3 * i + 1] = p.y; positions[3 * i + 2] = p.z;
  }
  const index = geometry.getIndex();
  const count = index ? index.count : n;
  if (count < 3 || count % 3 !== 0) throw new TypeError(`${label}: the geometry is not triangles (${count} indices)`);
  const triangles = new Uint32Array(count);
  for (let k = 0; k < count; k++) triangles[k] = index ? index.getX(k) : k;
  const uv = geometry.getAttribute('uv');
  let uvs: Float32Array | undefined;
  if (uv && uv.count === n && uv.itemSize >= 2) {
    uvs = new Float32Array(2 * n);
    for (let i = 0; i < n; i++) { uvs[2 * i] = uv.getX(i); uvs[2 * i + 1] = uv.getY(i); }
  }
  return uvs ? { positions, triangles, uvs } : { positions, triangles };
}
