#!/usr/bin/env node
// The numbers of docs/gpu.md "Parity" for mesh colliders, on the scenes of src/gpu/mesh-colliders.test.ts (and an
// icosphere): the probes (particles set around meshes, one substep of particle contact alone on the CPU and on the
// GPU), the largest difference by their distance from the surface; then the drops and the moving table on the WebGPU
// solver and the CPU (TypeScript) solver side by side: over the frames the tests check, the largest particle distance
// and centroid distance, next to the CPU's own spread when its start positions are nudged by 1e-7 (relative), the
// GPU cloth's deepest point inside the mesh (particles and 15 points of each triangle, by the CPU collider's exact
// signed distance) and ms per frame of each.
// Needs `npm run build` (it reads dist/) and a WebGPU adapter (Dawn; SwiftShader from Debian's chromium will do).
//   node scripts/gpu-mesh-parity.mjs
import {
  FRAME_DT, centroid, copyState, createState, modelFor, mulberry32, resolveParams, step, validateScene,
} from '../dist/core/index.js';
import { cubeMesh, icosphereMesh, terrainMesh } from '../dist/core/colliders/mesh-shapes.js';
import { createNodeDevice } from '../dist/gpu/node.js';
import { GpuClothSolver } from '../dist/gpu/solver.js';

const { device, adapter } = await createNodeDevice();
console.log(`adapter: ${adapter}`);
const maxDistance = (p, q) => {
  let m = 0;
  for (let i = 0; i < p.length; i += 3) m = Math.max(m, Math.hypot(p[i] - q[i], p[i + 1] - q[i + 1], p[i + 2] - q[i + 2]));
  return m;
};
const centroidDistance = (a, b) => Math.hypot(...centroid(a).map((v, k) => v - centroid(b)[k]));
const e = (v) => v.toExponential(1);
/** A unit cube with a pyramid-shaped dent 0.4 deep pushed into its top (the test's). */
function dentedCube() {
  const c = cubeMesh();
  const p = [...c.positions, 0, 0.1, 0], top = [2, 6, 7, 3], tri = [];
  for (let k = 0; k < c.triangles.length; k += 3) {
    const f = [c.triangles[k], c.triangles[k + 1], c.triangles[k + 2]];
    if (!f.every((v) => top.includes(v))) tri.push(...f);
  }
  for (let k = 0; k < 4; k++) tri.push(top[k], 8, top[(k + 1) % 4]);
  return { positions: Float32Array.from(p), triangles: Uint32Array.from(tri) };
}
const union = (a, b) => ({ positions: Float32Array.from([...a.positions, ...b.positions]), triangles: Uint32Array.from([...a.triangles, ...[...b.triangles].map((i) => i + a.positions.length / 3)]) });
const bumps = (x, z) => 0.04 * Math.cos(7 * x) * Math.cos(6 * z) + 0.15;
const files = {
  'cube.obj': cubeMesh(),
  'ball.obj': icosphereMesh(2, 0.15, [0, 0.15, 0]),
  'terrain.obj': terrainMesh(12, 0.4, bumps),
  'dented.obj': dentedCube(),
  'both.obj': union(cubeMesh([0.5, 0.1, 0], 0.1), terrainMesh(6, 0.3, bumps)),
};
const n3 = new Float64Array(3);
const cotton = { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 };
const floor = { type: 'floor', height: 0 };
const drop = (y, colliders) => ({ cloth: { resolution: 8, width: 0.4, height: 0.4, position: [0, y, 0] }, material: cotton, solver: { substeps: 10 }, colliders });
// [name, scene, frames, check every]: the tests' (the icosphere only here)
const SCENES = [
  ['cube mesh, scaled, moved up, turned 30°', drop(0.22, [{ type: 'mesh', mesh: 'cube.obj', scale: 0.2, position: [0, 0.1, 0], rotation: [0, 30, 0] }, floor]), 24, 12],
  ['icosphere mesh (closed, curved)', drop(0.32, [{ type: 'mesh', mesh: 'ball.obj' }, floor]), 24, 12],
  ['terrain mesh (open)', drop(0.22, [{ type: 'mesh', mesh: 'terrain.obj' }]), 24, 12],
  ['cube mesh table moving 0.1 m and turning 20° (keyframes)', {
    cloth: { resolution: 8, width: 0.3, height: 0.3, position: [0, 0.51, 0] }, material: cotton, solver: { substeps: 10 },
    colliders: [{ type: 'mesh', mesh: 'cube.obj', scale: 0.5, position: [0, 0.25, 0], motion: { keyframes: [{ time: 0.15 }, { time: 0.5, translation: [0.1, 0, 0], rotation: [0, 20, 0] }] } }],
  }, 36, 9],
];
const meshes = (path) => files[path];

// the probes: as the test sets them (300 and more particles near the meshes' vertices, edges and faces, 2–15 mm off)
{
  const scene = validateScene({
    name: 'probes', cloth: { resolution: 17, width: 0.02, height: 0.02, position: [3, 3, 3] },
    colliders: [
      { type: 'mesh', mesh: 'dented.obj', scale: 0.3, position: [0, 0.2, 0], rotation: [10, 30, 0] },
      { type: 'mesh', mesh: 'dented.obj', scale: 0.3, position: [1, 0.2, 0], rotation: [0, 0, 180] },
      { type: 'mesh', mesh: 'both.obj', position: [-1, 0, 0], rotation: [0, 45, 0] },
    ],
  });
  const model = modelFor(scene), resolved = resolveParams(model, scene, FRAME_DT, meshes);
  const params = {
    ...resolved, substeps: 1, gravity: new Float64Array(3), compliance: new Float32Array(resolved.compliance.length).fill(Infinity),
    stretchFactor: 1e9, thickness: 0.02, depenetrationSpeed: 1e4, friction: 0, staticFriction: 0, damping: 0,
    // no bending stencils either, whatever the scene's bending model, and the reference reads each cloth's own values
    // (as the test sets them)
    bending: 'springs',
    perCloth: { thickness: Float64Array.of(0.02), friction: Float64Array.of(0), staticFriction: Float64Array.of(0), damping: Float64Array.of(0), stretchFactor: Float64Array.of(1e9) },
    springDamping: new Float64Array(resolved.springDamping.length),
  };
  const random = mulberry32(7), cpu = createState(model), x = cpu.positions;
  for (let i = 0; i < model.particleCount; i++) {
    const shape = params.colliders[i % params.colliders.length], mesh = shape.local;
    const p = mesh.bvh.positions, t = Math.floor(random() * mesh.triangleCount), tri = mesh.bvh.triangles;
    const kind = random();
    let u = random(), v = random();
    if (kind < 0.3) { u = 1; v = 0; } else if (kind < 0.6) v = 0;
    if (u + v > 1) { u = 1 - u; v = 1 - v; }
    const w = [1 - u - v, u, v], local = [0, 0, 0];
    for (let k = 0; k < 3; k++) for (let j = 0; j < 3; j++) local[j] += w[k] * p[3 * tri[3 * t + k] + j];
    const dir = [random() - 0.5, random() - 0.5, random() - 0.5], l = Math.hypot(...dir), r = 0.002 + 0.013 * random();
    for (let j = 0; j < 3; j++) local[j] += (r * dir[j]) / l;
    for (let j = 0; j < 3; j++) x[3 * i + j] = shape.R[3 * j] * local[0] + shape.R[3 * j + 1] * local[1] + shape.R[3 * j + 2] * local[2] + shape.o[j];
  }
  cpu.previousPositions.set(x);
  const before = x.slice(), gpu = createState(model);
  gpu.positions.set(x);
  gpu.previousPositions.set(x);
  const solver = await GpuClothSolver.create(device, model);
  solver.setParams(params);
  solver.upload(gpu);
  step(model, cpu, params, FRAME_DT);
  solver.step(gpu, params, FRAME_DT);
  await solver.read(gpu);
  solver.destroy();
  // the largest GPU–CPU difference of the probes by their distance from the surface
  const bands = [[0, 1e-4, 'under 0.1 mm'], [1e-4, 5e-4, '0.1–0.5 mm'], [5e-4, Infinity, '0.5 mm and more']], worst = [0, 0, 0], count = [0, 0, 0];
  let inside = 0;
  for (let i = 0; i < before.length; i += 3) {
    const d = Math.min(...params.colliders.map((c) => c.signedDistance(before[i], before[i + 1], before[i + 2], n3)));
    if (d < 0) inside++;
    const b = bands.findIndex(([lo, hi]) => Math.abs(d) >= lo && Math.abs(d) < hi);
    count[b]++;
    worst[b] = Math.max(worst[b], Math.hypot(gpu.positions[i] - cpu.positions[i], gpu.positions[i + 1] - cpu.positions[i + 1], gpu.positions[i + 2] - cpu.positions[i + 2]));
  }
  console.log(`probes: ${before.length / 3} (${inside} inside); GPU–CPU by distance from the surface: ` +
    bands.map(([, , name], b) => `${name}: ${count[b]} probes, ${e(worst[b])} m`).join('; '));
}

/** deepest point of the cloth inside the mesh collider k [m] (0 if none): particles and 15 points per triangle */
function penetration(model, state, shape) {
  const x = state.positions, t = model.triangles;
  let min = Infinity;
  for (let k = 0; k < t.length; k += 3) {
    const a = 3 * t[k], b = 3 * t[k + 1], c = 3 * t[k + 2];
    for (let i = 0; i <= 4; i++) for (let j = 0; i + j <= 4; j++) {
      const u = i / 4, v = j / 4, w = 1 - u - v;
      min = Math.min(min, shape.signedDistance(w * x[a] + u * x[b] + v * x[c], w * x[a + 1] + u * x[b + 1] + v * x[c + 1], w * x[a + 2] + u * x[b + 2] + v * x[c + 2], n3));
    }
  }
  return Math.max(0, -min);
}
console.log('| scene | frames | GPU–CPU | centroid | CPU\'s own spread | its centroid | penetration (GPU) | ms/frame CPU | ms/frame GPU |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const [name, s, frames, every] of SCENES) {
  const scene = validateScene({ name: 'parity', ...s });
  const model = modelFor(scene), params = resolveParams(model, scene, FRAME_DT, meshes);
  const cpu = createState(model);
  const nudged = createState(model);
  copyState(cpu, nudged);
  for (let i = 0; i < nudged.positions.length; i++) {
    nudged.positions[i] *= 1 + 1e-7 * Math.sin(7 * i);
    nudged.previousPositions[i] = nudged.positions[i];
  }
  const gpu = createState(model);
  copyState(cpu, gpu);
  const solver = await GpuClothSolver.create(device, model);
  solver.setParams(params);
  solver.upload(gpu);
  const mesh = params.colliders[0];
  const worst = [0, 0, 0, 0, 0];
  let cpuMs = 0, gpuMs = 0;
  for (let f = 1; f <= frames; f++) {
    // the three share params: each puts the colliders where they are for its own substeps (moveTo) before use
    let t0 = performance.now();
    step(model, cpu, params, FRAME_DT);
    cpuMs += performance.now() - t0;
    t0 = performance.now();
    solver.step(gpu, params, FRAME_DT);
    await device.queue.onSubmittedWorkDone();
    gpuMs += performance.now() - t0;
    step(model, nudged, params, FRAME_DT);
    if (f % every === 0) {
      await solver.read(gpu);
      // the mesh where the GPU's frame left it (the nudged run moved the shared colliders to its own time, the same)
      const now = [maxDistance(gpu.positions, cpu.positions), centroidDistance(gpu, cpu), maxDistance(nudged.positions, cpu.positions),
        centroidDistance(nudged, cpu), penetration(model, gpu, mesh)];
      now.forEach((v, k) => { worst[k] = Math.max(worst[k], v); });
    }
  }
  console.log(`| ${name} | ${frames} | ${worst.slice(0, 4).map(e).join(' | ')} | ${worst[4] === 0 ? '0' : e(worst[4])} | ${(cpuMs / frames).toFixed(1)} | ${(gpuMs / frames).toFixed(1)} |`);
  solver.destroy();
}
device.destroy();
