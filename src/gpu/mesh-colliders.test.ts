/**
 * The GPU solver with mesh colliders (core/colliders/mesh.ts on the GPU: meshes.ts, meshCollider.wgsl,
 * meshTriangles.wgsl) against the TypeScript reference stepped alongside, and against the exact surface: particles
 * probing the signed distance and normal around closed, non-convex and open meshes; a cloth dropped on a closed mesh
 * with sharp edges (a cube, placed and turned) and on an open one (a terrain); one lying on a cube mesh that moves
 * and turns (keyframes). Same adapter rule as gpu.test.ts; small cloths, short runs (SwiftShader walks a BVH slowly).
 *
 * Tolerances (docs/gpu.md, "Parity"): a few times the larger of the GPU–CPU difference seen on SwiftShader and the
 * CPU's own spread when its start is nudged by 1e-7 (relative), over the same frames (scripts/gpu-mesh-parity.mjs).
 */
import { afterAll, describe, expect, it } from 'vitest';
import type {} from 'webgpu';
import {
  FRAME_DT, MeshCollider, Simulation, centroid, createState, grab, modelFor, mulberry32, resolveParams, step, validateScene,
  type Scene, type SimParams,
} from '../core/index.js';
import { cubeMesh, terrainMesh } from '../core/colliders/mesh-shapes.js';
import type { TriangleMesh } from '../core/mesh/triangle-mesh.js';
import { GpuBackend } from './backend.js';
import { GpuClothSolver } from './solver.js';
import { centroidDistance, maxDistance, testDevice } from './test-device.js';

const gpu = await testDevice('src/gpu/mesh-colliders.test.ts');
const sims: Simulation[] = [];
afterAll(() => {
  for (const s of sims) s.dispose();
});

const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };
/** A unit cube with a pyramid-shaped dent 0.4 deep pushed into its top: closed, not convex (concave edges and a concave corner). */
function dentedCube(): TriangleMesh {
  const c = cubeMesh();
  const p = [...c.positions, 0, 0.1, 0];
  const top = [2, 6, 7, 3]; // y = +0.5, counter-clockwise from above
  const tri: number[] = [];
  for (let k = 0; k < c.triangles.length; k += 3) {
    const f = [c.triangles[k], c.triangles[k + 1], c.triangles[k + 2]];
    if (!f.every((v) => top.includes(v))) tri.push(...f);
  }
  for (let k = 0; k < 4; k++) tri.push(top[k], 8, top[(k + 1) % 4]);
  return { positions: Float32Array.from(p), triangles: Uint32Array.from(tri) };
}

/** Two meshes in one file (their vertices after each other's). */
function union(a: TriangleMesh, b: TriangleMesh): TriangleMesh {
  const n = a.positions.length / 3;
  return { positions: Float32Array.from([...a.positions, ...b.positions]), triangles: Uint32Array.from([...a.triangles, ...[...b.triangles].map((i) => i + n)]) };
}

const bumps = (x: number, z: number) => 0.04 * Math.cos(7 * x) * Math.cos(6 * z) + 0.15;
const FILES: Record<string, TriangleMesh> = {
  // the unit cube about its centre: placed (scaled, moved up, turned) by the scene
  'cube.obj': cubeMesh(),
  // 0.8 m square, 12 cells a side, bumps of ±4 cm about 0.15 m
  'terrain.obj': terrainMesh(12, 0.4, bumps),
  'dented.obj': dentedCube(),
  // a closed piece (a cube of 0.2 m) and an open one (a terrain) in one mesh
  'both.obj': union(cubeMesh([0.5, 0.1, 0], 0.1), terrainMesh(6, 0.3, bumps)),
};
const meshes = (path: string) => FILES[path];

/** The scene on the CPU (TypeScript reference) and on the GPU, both from its start. */
async function pair(scene: Scene): Promise<{ cpu: Simulation; gpu: Simulation }> {
  const cpu = new Simulation(scene, { kernel: 'ts', meshes });
  const g = new Simulation(scene, { kernel: 'ts', meshes });
  g.useBackend(await GpuBackend.create(gpu!.device, g.model));
  sims.push(cpu, g);
  return { cpu, gpu: g };
}

const n3 = new Float64Array(3);
/**
 * Nearest point of the cloth to the mesh (collider 0, where it is now) [m], negative inside: over the particles and
 * 15 points of each triangle, by the CPU collider's exact signed distance (the polyhedron's, not the GPU's).
 */
function nearest(sim: Simulation): number {
  const x = sim.state.positions, t = sim.model.triangles, mesh = sim.params.colliders[0];
  let min = Infinity;
  for (let k = 0; k < t.length; k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1], c = 3 * t[k + 2];
    for (let i = 0; i <= 4; i++) for (let j = 0; i + j <= 4; j++) {
      const u = i / 4, v = j / 4, w = 1 - u - v;
      min = Math.min(min, mesh.signedDistance(w * x[a] + u * x[b] + v * x[c], w * x[a + 1] + u * x[b + 1] + v * x[c + 1], w * x[a + 2] + u * x[b + 2] + v * x[c + 2], n3));
    }
  }
  return min;
}

/** RMS speed of the particles within 2 thicknesses of the mesh [m/s]. */
function touchingSpeed(sim: Simulation): number {
  const x = sim.state.positions, v = sim.state.velocities, mesh = sim.params.colliders[0], th = sim.scene.cloth.thickness;
  let s = 0, n = 0;
  for (let i = 0; i < x.length; i += 3) {
    if (mesh.signedDistance(x[i], x[i + 1], x[i + 2], n3) > 2 * th) continue;
    s += v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2];
    n++;
  }
  return n > 0 ? Math.sqrt(s / n) : Infinity;
}

/** A 0.4 m cotton cloth of 8 faces a side dropped from `y` onto `colliders`, 10 substeps a frame. */
function drop(y: number, colliders: object[]): Scene {
  return validateScene({
    name: 'mesh drop', cloth: { resolution: 8, width: 0.4, height: 0.4, position: [0, y, 0] }, material: cotton, solver: { substeps: 10 }, colliders,
  });
}

const floor = { type: 'floor', height: 0 };
// Dropped 2–3 cm for 0.4 s (24 frames: it lands at about 0.07 s), checked every 12: GPU–CPU seen ≤ 2.9e-5 m per
// particle (the terrain; the cube 1.9e-5) and ≤ 1.3e-6 m centroid, the CPU's own spread ≤ 7.5e-5 m and ≤ 1.8e-6 m
// (scripts/gpu-mesh-parity.mjs) → 0.5 mm and 0.05 mm. Nearest the exact surface (the CPU collider's signed
// distance, particles and 15 points of each triangle): seen 5.0 mm (the contact thickness) → not inside, and within
// twice the thickness (it lies on the mesh); RMS speed where it touches seen ≤ 2.5 cm/s → 5 cm/s.
const DROPS: [string, Scene][] = [
  ['a cube mesh, scaled, moved up and turned 30° (closed, sharp edges)', drop(0.22, [{ type: 'mesh', mesh: 'cube.obj', scale: 0.2, position: [0, 0.1, 0], rotation: [0, 30, 0] }, floor])],
  ['a terrain mesh (open)', drop(0.22, [{ type: 'mesh', mesh: 'terrain.obj' }])],
];

/**
 * Probes: particles set around mesh colliders, near their vertices, edges and faces, inside and out, then one substep
 * of particle contact alone (no gravity, springs or stretch limit, the whole overlap undone at once, no friction; the
 * cloth's rest edges, 1.2 mm, are too short for triangle contact) on the CPU and on the GPU. A particle within the thickness ends at x + (th − d)·n, so every probe compares the two
 * distances and normals: the nearest triangle by the BVH walk, the sign by the pseudo-normal of a face, an edge or a
 * corner (closed pieces), the shell's side (open ones).
 */
async function probe(scene: Scene, seed: number): Promise<{ before: Float32Array; cpu: Float32Array; gpu: Float32Array; params: SimParams }> {
  const model = modelFor(scene);
  const resolved = resolveParams(model, scene, FRAME_DT, meshes);
  const params: SimParams = {
    ...resolved, substeps: 1, gravity: new Float64Array(3), compliance: new Float32Array(resolved.compliance.length).fill(Infinity),
    stretchFactor: 1e9, thickness: 0.02, depenetrationSpeed: 1e4, friction: 0, staticFriction: 0, damping: 0,
    // no bending stencils either, whatever the scene's bending model (a stencil model's would pull the scattered
    // probes towards their flat grid: 0.9–1.4 m from the CPU's with the Laplacian)
    bending: 'springs',
    // the TypeScript reference reads each cloth's own values (the one cloth's: the scalars above)
    perCloth: { thickness: Float64Array.of(0.02), friction: Float64Array.of(0), staticFriction: Float64Array.of(0), damping: Float64Array.of(0), stretchFactor: Float64Array.of(1e9) },
    springDamping: new Float64Array(resolved.springDamping.length),
  };
  const random = mulberry32(seed);
  const cpu = createState(model), x = cpu.positions;
  for (let i = 0; i < model.particleCount; i++) {
    // a point of a triangle of collider i mod colliders (a corner, an edge or inside it), moved 2–15 mm, in the world
    const shape = params.colliders[i % params.colliders.length], mesh = shape.local as MeshCollider;
    const p = mesh.bvh.positions, t = Math.floor(random() * mesh.triangleCount), tri = mesh.bvh.triangles;
    const kind = random();
    let u = random(), v = random();
    if (kind < 0.3) { u = 1; v = 0; } else if (kind < 0.6) v = 0;
    if (u + v > 1) { u = 1 - u; v = 1 - v; }
    const w = [1 - u - v, u, v], local = [0, 0, 0];
    for (let k = 0; k < 3; k++) for (let j = 0; j < 3; j++) local[j] += w[k] * p[3 * tri[3 * t + k] + j];
    const dir = [random() - 0.5, random() - 0.5, random() - 0.5], l = Math.hypot(...dir), r = 0.002 + 0.013 * random();
    for (let j = 0; j < 3; j++) local[j] += (r * dir[j]) / l;
    const R = shape.R, o = shape.o;
    for (let j = 0; j < 3; j++) x[3 * i + j] = R[3 * j] * local[0] + R[3 * j + 1] * local[1] + R[3 * j + 2] * local[2] + o[j];
  }
  cpu.previousPositions.set(x);
  const before = x.slice(), g = createState(model);
  g.positions.set(x);
  g.previousPositions.set(x);
  const solver = await GpuClothSolver.create(gpu!.device, model);
  try {
    solver.setParams(params);
    solver.upload(g);
    step(model, cpu, params, FRAME_DT);
    solver.step(g, params, FRAME_DT);
    await solver.read(g);
  } finally {
    solver.destroy();
  }
  return { before, cpu: cpu.positions, gpu: g.positions, params };
}

describe.skipIf(!gpu)('the GPU with mesh colliders, as the TypeScript reference', () => {
  it('a mesh\'s signed distance and normal as the CPU\'s, probe by probe: closed and not convex, shared, closed and open in one', async () => {
    const scene = validateScene({
      name: 'probes', cloth: { resolution: 17, width: 0.02, height: 0.02, position: [3, 3, 3] },
      colliders: [
        { type: 'mesh', mesh: 'dented.obj', scale: 0.3, position: [0, 0.2, 0], rotation: [10, 30, 0] },
        { type: 'mesh', mesh: 'dented.obj', scale: 0.3, position: [1, 0.2, 0], rotation: [0, 0, 180] },
        { type: 'mesh', mesh: 'both.obj', position: [-1, 0, 0], rotation: [0, 45, 0] },
      ],
    });
    const { before, cpu, gpu: g, params } = await probe(scene, 7);
    // seen ≤ 1.1e-6 m from the 306 probes 0.5 mm or more from the surface, 3.0e-6 m from those 0.1–0.5 mm from it,
    // 1.7e-5 m from one 11 µm from it (the direction to the closest point is f32 rounding of a 0.3 m mesh, ~3e-8 m,
    // over that distance, turning a push-out of up to 3.5 cm) → 1e-5 m from 0.5 mm on, 1e-4 m nearer
    let far = 0, inside = 0;
    for (let i = 0; i < before.length; i += 3) {
      const d = Math.min(...params.colliders.map((c) => c.signedDistance(before[i], before[i + 1], before[i + 2], n3)));
      const off = Math.hypot(g[i] - cpu[i], g[i + 1] - cpu[i + 1], g[i + 2] - cpu[i + 2]);
      expect(off, `probe ${i / 3}, ${d} m from the surface`).toBeLessThan(Math.abs(d) >= 5e-4 ? 1e-5 : 1e-4);
      // every probe is within the thickness of one: pushed out to it
      expect(Math.hypot(cpu[i] - before[i], cpu[i + 1] - before[i + 1], cpu[i + 2] - before[i + 2])).toBeGreaterThan(0);
      if (Math.abs(d) >= 5e-4) far++;
      if (d < 0) inside++;
    }
    expect(far).toBeGreaterThan(250);
    expect(inside).toBeGreaterThan(30);
  });

  it.each(DROPS)('a cloth dropped on %s comes to rest outside it, as on the CPU: 0.5 mm, centroid 0.05 mm', async (_name, scene) => {
    const { cpu, gpu: g } = await pair(scene);
    const th = scene.cloth.thickness;
    for (let k = 0; k < 2; k++) {
      cpu.advance(12);
      g.advance(12);
      await g.sync();
      expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(5e-4);
      expect(centroidDistance(g.state, cpu.state)).toBeLessThan(5e-5);
      const d = nearest(g);
      expect(d).toBeGreaterThanOrEqual(0);
      expect(d).toBeLessThan(2 * th);
    }
    expect(touchingSpeed(g)).toBeLessThan(0.05);
  });

  // A 0.3 m cloth resting on a 0.5 m cube mesh that moves 0.1 m and turns 20° about its centre in 0.35 s. GPU–CPU seen
  // ≤ 2.6e-6 m (the cloth rides the table: no chaos; the CPU's own spread 3.2e-7 m) → 1e-4 m, as for the moving box.
  it('a cloth lying on a cube mesh that moves and turns (keyframes) rides on it, as on the CPU', async () => {
    const scene = validateScene({
      name: 'mesh table', cloth: { resolution: 8, width: 0.3, height: 0.3, position: [0, 0.51, 0] }, material: cotton, solver: { substeps: 10 },
      colliders: [{ type: 'mesh', mesh: 'cube.obj', scale: 0.5, position: [0, 0.25, 0], motion: { keyframes: [{ time: 0.15 }, { time: 0.5, translation: [0.1, 0, 0], rotation: [0, 20, 0] }] } }],
    });
    const { cpu, gpu: g } = await pair(scene);
    for (const frames of [9, 27]) {
      cpu.advance(frames);
      g.advance(frames);
      await g.sync();
      expect(maxDistance(g.state.positions, cpu.state.positions)).toBeLessThan(1e-4);
    }
    // carried 0.1 m, resting on the moved top at the contact thickness, turned with it: the corner that started at
    // (−0.15, −0.15) in x, z where the turn about the table's centre and the move put it (seen 5 mm off: the cloth
    // slides a little as the table starts)
    const c = centroid(g.state);
    expect(c[0]).toBeCloseTo(0.1, 2);
    expect(Math.abs(c[2])).toBeLessThan(0.005);
    const d = nearest(g);
    expect(d).toBeGreaterThanOrEqual(0);
    expect(d).toBeLessThan(2 * scene.cloth.thickness);
    const turn = (20 * Math.PI) / 180, x = g.state.positions;
    const ex = Math.cos(turn) * -0.15 + Math.sin(turn) * -0.15 + 0.1, ez = -Math.sin(turn) * -0.15 + Math.cos(turn) * -0.15;
    expect(Math.hypot(x[0] - ex, x[2] - ez)).toBeLessThan(0.01);
  });

  // With self-contact the grab goes at most solver.selfContactSpeed (6 m/s: 0.1 m a frame), and each frame's end short
  // of the target is kept out of the colliders as they stand at the frame's end (runFrame; on the GPU grabFrame and
  // grabOutsideMesh, from the last substep's pose records). The grabbed particle is kinematic, so its path depends on
  // nothing but itself and the colliders: the GPU's is the CPU's to f32 rounding (seen ≤ 2.6e-8 m → 1e-5 m), on the
  // cube's surface at the contact thickness at frames 2–3. Before, the GPU kept only the target out: it went straight
  // through the cube, 6.2 cm inside it at frame 3 (6.8 cm from the CPU's).
  it('a grab dragged fast at a moving cube mesh goes round it, as on the CPU', async () => {
    const scene = validateScene({
      name: 'mesh drag', cloth: { resolution: 8, width: 0.4, height: 0.4, position: [0, 0.22, 0] }, material: cotton,
      solver: { substeps: 10, selfContact: true },
      colliders: [{ type: 'mesh', mesh: 'cube.obj', scale: 0.2, position: [0, 0.1, 0], rotation: [0, 30, 0], motion: { keyframes: [{ time: 0 }, { time: 0.5, translation: [0, 0, 0.05] }] } }],
    });
    const { cpu, gpu: g } = await pair(scene);
    // the corner at (−0.2, 0.22, −0.2) m toward a point behind the cube, on a line through it (0.6 m: 6 frames)
    const p = 0, to: [number, number, number] = [0.25, 0.05, 0.15];
    for (const s of [cpu, g]) grab(s.state, p, to);
    const cube = cpu.params.colliders[0], th = scene.cloth.thickness;
    let deepest = Infinity;
    for (let f = 1; f <= 8; f++) {
      cpu.advance(1);
      g.advance(1);
      await g.sync();
      const a = cpu.state.positions, b = g.state.positions;
      expect(Math.hypot(b[3 * p] - a[3 * p], b[3 * p + 1] - a[3 * p + 1], b[3 * p + 2] - a[3 * p + 2]), `frame ${f}`).toBeLessThan(1e-5);
      deepest = Math.min(deepest, cube.signedDistance(b[3 * p], b[3 * p + 1], b[3 * p + 2], n3));
    }
    expect(deepest).toBeGreaterThan(th - 1e-5);
  });
});
