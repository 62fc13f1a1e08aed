/**
 * The GPU solver's answer for the collider shapes it has and has not: every shape, analytic or a mesh, moving or not,
 * carrying pins or not, is taken; a shape its kernels do not know, or a mesh too deep for their walks, is named in one
 * line, for the CLI and the app. And the mesh colliders' tables as the kernels read them (meshes.ts).
 */
import { cubeMesh, icosphereMesh, terrainMesh } from '../core/colliders/mesh-shapes.js';
import { describe, expect, it } from 'vitest';
import {
  COLLIDER_TYPES, MeshCollider, PosedCollider, QUERY, Simulation, SphereCollider, createColliders, meshCollider, validateScene,
  type ColliderShape,
} from '../core/index.js';
import { assignPhases } from '../core/schedule.js';
import { GPU_PHASES, sceneRefusal } from './encoder.js';
import { gpuCollider } from './colliders.js';
import { MESH_NODE, MESH_STACK, MESH_TRIANGLE } from './layout.js';
import { meshLayout, packMeshes } from './meshes.js';

const IDENTITY = [1, 0, 0, 0, 1, 0, 0, 0, 1];

describe('sceneRefusal', () => {
  it('takes every shape, moving, driven or carrying pins, a mesh without reading its file; refuses the mass-spring solver', () => {
    const every = COLLIDER_TYPES.map((type) => (type === 'mesh' ? { type, mesh: 'never-read.obj' } : { type }));
    expect(sceneRefusal(validateScene({ colliders: every }))).toBeNull();
    const motion = { keyframes: [{ time: 0 }, { time: 1, translation: [0.1, 0, 0], rotation: [0, 30, 0] }] };
    for (const c of every) {
      expect(sceneRefusal(validateScene({ colliders: [{ ...c, motion, pins: ['top-left'] }] })), c.type).toBeNull();
    }
    expect(sceneRefusal(validateScene({ solver: { type: 'mass-spring' } }))).toBe('the mass-spring solver runs on the CPU only');
    // the springs solved together run on the GPU (global-stretch.ts), and their coarse correction (coarse-stretch.ts),
    // the bending stencils too (global-bending.ts), as does the global bending step without stencils (nothing)
    expect(sceneRefusal(validateScene({ solver: { stretch: 'two-level' } }))).toBeNull();
    expect(sceneRefusal(validateScene({ solver: { stretch: 'global' } }))).toBeNull();
    expect(sceneRefusal(validateScene({ solver: { bending: 'hinges', bendingSolve: 'global' } }))).toBeNull();
    expect(sceneRefusal(validateScene({ solver: { bendingSolve: 'global' } }))).toBeNull();
    // self-contact runs on the GPU too
    expect(sceneRefusal(validateScene({ solver: { selfContact: true } }))).toBeNull();
  });

  it('follows gpuCollider: a type is refused exactly when the GPU has no encoding for it', () => {
    for (const type of COLLIDER_TYPES) {
      // a mesh collider names its file (read here from memory)
      const scene = validateScene({ colliders: [type === 'mesh' ? { type, mesh: 'cube.obj' } : { type }] });
      expect(sceneRefusal(scene) === null, type).toBe(gpuCollider(createColliders(scene.colliders, () => cubeMesh())[0]) !== null);
    }
  });
  it('a mesh whose hierarchy is deeper than the kernels\' fixed stack: its contact refused by name and place', () => {
    const cube = meshCollider(cubeMesh(), 1, 'cube.obj');
    // binned SAH makes no such tree of any mesh a scene may have (24 levels of a million triangles): a stand-in
    const deep: MeshCollider = Object.assign(Object.create(MeshCollider.prototype) as MeshCollider, cube, { bvh: { ...cube.bvh, depth: MESH_STACK + 1 } });
    const sim = new Simulation(validateScene({ cloth: { resolution: 4 }, colliders: [] }), { kernel: 'ts' });
    const ok = new PosedCollider(cube, IDENTITY, [0, 0, 0]), bad = new PosedCollider(deep, IDENTITY, [0, 0, 0]);
    expect(assignPhases(GPU_PHASES, sim.model, { ...sim.params, colliders: [ok] })).toBeGreaterThan(0);
    expect(() => assignPhases(GPU_PHASES, sim.model, { ...sim.params, colliders: [ok, bad] }))
      .toThrow(`GPU solver: the mesh of colliders[1] does not fit the GPU's walk: its hierarchy is ${MESH_STACK + 1} levels deep; the GPU walks at most ${MESH_STACK}`);
  });

  it('a shape the kernels do not know: its contact refused by name', () => {
    const blob: ColliderShape = {
      type: 'blob', minCurvatureRadius: Infinity,
      signedDistance: (_x, y, _z, n) => { n[0] = 0; n[1] = 1; n[2] = 0; return y; },
      distanceIn: (q, n) => { n[0] = 0; n[1] = 1; n[2] = 0; q[QUERY.D] = q[QUERY.Y]; },
    };
    const shape = new PosedCollider(blob, [1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 0, 0]);
    expect(gpuCollider(shape)).toBeNull();
    const sim = new Simulation(validateScene({ cloth: { resolution: 4 }, colliders: [] }), { kernel: 'ts' });
    const params = { ...sim.params, colliders: [shape] };
    expect(() => assignPhases(GPU_PHASES, sim.model, params))
      .toThrow("GPU solver: collider type 'blob' is not supported on the GPU (it has sphere, floor, plane, box, capsule, cylinder and mesh)");
  });
});

describe('mesh tables', () => {
  it('every distinct mesh once, one after another, its indices made absolute; each collider its root', () => {
    const ball = meshCollider(icosphereMesh(1, 0.5), 1, 'ball.obj');
    const land = meshCollider(terrainMesh(4, 1, (x, z) => 0.1 * x * z), 1, 'land.obj');
    const pose = (shape: ColliderShape) => new PosedCollider(shape, IDENTITY, [0, 0, 0]);
    const layout = meshLayout([pose(ball), pose(new SphereCollider(0, 0, 0, 1)), pose(land), pose(ball)]);
    expect(layout.meshes).toEqual([ball, land]);
    expect([...layout.roots]).toEqual([0, 0, ball.bvh.nodeCount, 0]);
    expect([...layout.closed]).toEqual([1, 0, 0, 1]);
    expect(layout.nodeCount).toBe(ball.bvh.nodeCount + land.bvh.nodeCount);
    expect(layout.triangleCount).toBe(ball.triangleCount + land.triangleCount);
    const { nodes, triangles } = packMeshes(layout);
    const nv = new DataView(nodes), tv = new DataView(triangles);
    const f32 = (v: DataView, at: number) => [0, 1, 2].map((j) => v.getFloat32(at + 4 * j, true));
    let nodeBase = 0, triangleBase = 0;
    for (const mesh of [ball, land]) {
      const bvh = mesh.bvh, m = mesh.triangleCount;
      // each node as the hierarchy has it; the leaves cover the mesh's triangles once, in its own range
      const covered = new Uint8Array(m);
      for (let i = 0; i < bvh.nodeCount; i++) {
        const at = (nodeBase + i) * MESH_NODE.size, count = nv.getUint32(at + MESH_NODE.count, true), first = nv.getUint32(at + MESH_NODE.first, true);
        expect(f32(nv, at + MESH_NODE.lo)).toEqual([...bvh.bounds.subarray(6 * i, 6 * i + 3)]);
        expect(f32(nv, at + MESH_NODE.hi)).toEqual([...bvh.bounds.subarray(6 * i + 3, 6 * i + 6)]);
        expect(count).toBe(bvh.nodes[2 * i + 1]);
        if (count === 0) expect(first).toBe(nodeBase + bvh.nodes[2 * i]);
        else for (let t = first; t < first + count; t++) covered[t - triangleBase]++;
      }
      expect(covered.every((c) => c === 1)).toBe(true);
      // each triangle: corners, face and corner normals, flags, the triangles across its edges
      for (let i = 0; i < m; i++) {
        const at = (triangleBase + i) * MESH_TRIANGLE.size, tri = bvh.triangles;
        const corners = [MESH_TRIANGLE.a, MESH_TRIANGLE.b, MESH_TRIANGLE.c], normals = [MESH_TRIANGLE.normalA, MESH_TRIANGLE.normalB, MESH_TRIANGLE.normalC];
        const across = [MESH_TRIANGLE.across0, MESH_TRIANGLE.across1, MESH_TRIANGLE.across2];
        for (let k = 0; k < 3; k++) {
          const v = tri[3 * i + k];
          expect(f32(tv, at + corners[k])).toEqual([...bvh.positions.subarray(3 * v, 3 * v + 3)]);
          expect(f32(tv, at + normals[k])).toEqual([...mesh.vertexNormals.subarray(3 * v, 3 * v + 3)]);
          const o = mesh.neighbours[3 * i + k];
          expect(tv.getInt32(at + across[k], true)).toBe(o < 0 ? -1 : triangleBase + o);
        }
        expect(f32(tv, at + MESH_TRIANGLE.normal)).toEqual([...mesh.faceNormals.subarray(3 * i, 3 * i + 3)]);
        expect(tv.getUint32(at + MESH_TRIANGLE.flags, true)).toBe(mesh.flags[i]);
      }
      nodeBase += bvh.nodeCount;
      triangleBase += m;
    }
  });
});
