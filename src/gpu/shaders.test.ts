/** GPU-free checks of the GPU backend: generated shaders up to date, layouts, mesh tables. */
import { readFileSync } from 'node:fs';
import { describe, expect, test } from 'vitest';
import { buildGridModel, builtinScene, modelFor } from '../core/index.js';
import { GENERATED_FILE, generateShaderModule } from './gen-shaders.mjs';
import { BUFFERS, CARRY, COLLIDER, GLOBALS, KERNELS, PASS, RECORD_STRIDE, SUBSTEP, wgslFloat, type KernelName, type KernelSpec } from './layout.js';
import { kernelSource } from './shaders.js';
import { WGSL_SOURCES } from './shaders.generated.js';
import { triangleAdjacency } from './topology.js';

describe('shaders', () => {
  test("the table's f32 constants are WGSL float literals, whole or not", () => {
    expect(wgslFloat(2)).toBe('2.0');
    expect(wgslFloat(2 ** 26)).toBe('67108864.0');
    expect(wgslFloat(1.82)).toBe('1.82');
    expect(wgslFloat(1e-7)).toBe('1e-7');
    expect(() => wgslFloat(NaN)).toThrow(/not a finite number/);
  });

  test('shaders.generated.ts matches src/gpu/shaders/*.wgsl (else run: node src/gpu/gen-shaders.mjs)', () => {
    expect(readFileSync(GENERATED_FILE, 'utf8')).toBe(generateShaderModule());
  });

  test('every kernel has its .wgsl, at most 8 storage buffers, and declares what it binds', () => {
    for (const kernel of Object.keys(KERNELS) as KernelName[]) {
      const spec: KernelSpec = KERNELS[kernel];
      const file = spec.file ?? kernel;
      expect(WGSL_SOURCES[file], kernel).toBeTypeOf('string');
      expect(spec.bindings.length).toBeLessThanOrEqual(8);
      const src = kernelSource(kernel);
      // one workgroup per solve: a factor's triangular solves, the coarse correction's factor and solves (one per cloth)
      // and its check (one)
      const whole = ['factorSolve', 'coarseFactor', 'coarseSolve', 'coarseCheck'].includes(file);
      expect(src).toMatch(whole ? /@compute @workgroup_size\(FACTOR_WORKGROUP\)\s*fn main/ : /@compute @workgroup_size\(WG\)\s*fn main/);
      // each bound buffer is used by the kernel body (or a library it includes)
      const body = src.slice(src.indexOf(`// ---- bindings of ${kernel} ----`));
      for (const [name] of spec.bindings) {
        expect(body.split(`${name}[`).length - 1, `${kernel} uses ${name}`).toBeGreaterThan(0);
      }
      // and uses no storage buffer it does not bind
      for (const name of Object.keys(BUFFERS)) {
        if (spec.bindings.some(([b]) => b === name)) continue;
        expect(WGSL_SOURCES[file].includes(`${name}[`), `${kernel} does not bind ${name}`).toBe(false);
      }
    }
  });

  test('uniform layouts fit their records', () => {
    expect(SUBSTEP.size).toBeLessThanOrEqual(RECORD_STRIDE);
    expect(PASS.size).toBeLessThanOrEqual(RECORD_STRIDE);
    expect(GLOBALS.size % 16).toBe(0);
    expect(GLOBALS.grabTarget % 16).toBe(0);
  });

  test('storage structs: records as long as their WGSL array stride, vec4 rows where the kernels expect them', () => {
    expect(BUFFERS.colliders.bytes).toBe(COLLIDER.size);
    expect(COLLIDER.size).toBe(128);
    expect([COLLIDER.pose0, COLLIDER.pose1, COLLIDER.pose2, COLLIDER.motion0, COLLIDER.motion1, COLLIDER.motion2, COLLIDER.shape]).toEqual([0, 16, 32, 48, 64, 80, 96]);
    expect(BUFFERS.carried.bytes).toBe(CARRY.size);
    expect([CARRY.local, CARRY.particle, CARRY.collider, CARRY.size]).toEqual([0, 12, 16, 32]);
  });
});

describe('mesh tables', () => {
  const model = buildGridModel({
    resolution: 5, width: 1, height: 1, orientation: 'horizontal', position: [0, 0, 0], rotation: [0, 0, 0], scaleWithResolution: true,
  });

  test('adjacency lists each triangle under each of its vertices', () => {
    const adj = triangleAdjacency(model);
    const n = model.particleCount;
    expect(adj[0]).toBe(n + 1);
    expect(adj[n]).toBe(adj.length);
    for (let i = 0; i < n; i++) {
      for (let k = adj[i]; k < adj[i + 1]; k++) {
        const t = adj[k];
        expect([model.triangles[3 * t], model.triangles[3 * t + 1], model.triangles[3 * t + 2]]).toContain(i);
      }
    }
  });
});
