import { describe, expect, it } from 'vitest';
import { SceneError, builtinScene, clothEntries, modelFor, setScenePath } from '../core/index.js';
import {
  MAX_PARTICLES, MAX_RESOLUTION, capCloth, capResolution, fitSideBySide, importSizeProblem, particlesOf, shapeParticles,
} from './limits.js';

const noMesh = (): number => { throw new Error('no mesh here'); };

describe('backend size caps', () => {
  it('the CPU takes 256 faces per side and the GPU 1024, as documented', () => {
    expect(MAX_RESOLUTION).toEqual({ cpu: 256, gpu: 1024 });
  });

  it('a cloth over the CPU cap is clamped to 256, with a note; the GPU keeps 1024', () => {
    const big = setScenePath(builtinScene('cotton-basic'), 'cloth.resolution', 1024);
    const cpu = capResolution(big, 'cpu');
    expect(cpu.scene.cloth.resolution).toBe(256);
    expect(cpu.note).toMatch(/resolution 1024 faces per side: more than the CPU backend takes, clamped to 256/);
    expect(big.cloth.resolution).toBe(1024); // the input is not changed
    const gpu = capResolution(big, 'gpu');
    expect(gpu.scene).toBe(big);
    expect(gpu.note).toBe('');
    const small = builtinScene('cotton-basic');
    expect(capResolution(small, 'cpu')).toEqual({ scene: small, note: '' });
  });

  it('a clamped cloth keeps its presets and regions, not its pins on particle numbers (which name other particles now)', () => {
    const region = { min: [-1, 0, -1] as [number, number, number], max: [1, 2, 0] as [number, number, number] };
    const big = setScenePath(setScenePath(builtinScene('cotton-basic'), 'cloth.resolution', 512), 'pins', ['top-left', 70000, region]);
    const cpu = capResolution(big, 'cpu');
    expect(cpu.scene.pins).toEqual(['top-left', region]);
    expect(cpu.note).toBe('resolution 512 faces per side: more than the CPU backend takes, clamped to 256; the pins on particle numbers are dropped; the GPU backend goes to 1024');
  });

  it('a disc clamped to the CPU drops its pins on particle numbers too', () => {
    const disc = setScenePath(setScenePath(setScenePath(builtinScene('cotton-basic'), 'cloth.shape', 'disc'), 'cloth.resolution', 1024), 'pins', ['center', 70000]);
    const cpu = capCloth(disc, 'cpu', () => 0);
    expect(cpu.scene.pins).toEqual(['center']);
    expect(cpu.note).toMatch(/^disc of resolution 1024: .* clamped to resolution \d+ \(.* particles\); the pins on particle numbers are dropped; the GPU backend takes/);
  });

  it('sweep resolutions over the cap are clamped too (once each)', () => {
    const s = setScenePath(builtinScene('resolution'), 'resolutionSweep', [64, 512, 1024, 128]);
    const cpu = capResolution(s, 'cpu');
    expect(cpu.scene.resolutionSweep).toEqual([64, 256, 128]);
    expect(cpu.note).toContain('sweep resolutions 512, 1024');
  });

  it('side by side keeps the cloths that fit in one cloth\'s worth of particles', () => {
    expect(fitSideBySide([1, 2, 4, 8, 16, 32, 64], 'cpu')).toEqual({ list: [1, 2, 4, 8, 16, 32, 64], note: '' });
    const many = Array.from({ length: 16 }, () => 256);
    const cpu = fitSideBySide(many, 'cpu');
    expect(cpu.list).toEqual([256]);
    expect(cpu.note).toContain('1 of 16 cloths');
    const gpu = fitSideBySide(many, 'gpu');
    expect(gpu.list.length).toBe(15);
    expect(gpu.list.reduce((a, r) => a + particlesOf(r), 0)).toBeLessThanOrEqual(MAX_PARTICLES.gpu);
  });

  it('a scene or mesh file over 32 MiB is not read', () => {
    expect(importSizeProblem(1000)).toBe('');
    expect(importSizeProblem(32 * 2 ** 20)).toBe('');
    expect(importSizeProblem(2 ** 30)).toBe('1024.0 MiB, more than the 32 MiB a scene file may be');
    expect(importSizeProblem(33 * 2 ** 20, 'mesh file')).toBe('33.0 MiB, more than the 32 MiB a mesh file may be');
  });
});

describe('caps by particles: discs, tubes and mesh files', () => {
  const shaped = (shape: string, resolution: number, width = 1, height = 1) =>
    setScenePath(setScenePath(setScenePath(setScenePath(builtinScene('cotton-basic'), 'cloth.shape', shape), 'cloth.resolution', resolution), 'cloth.width', width), 'cloth.height', height);

  it('counts the particles of a generated cloth as the model builds it', () => {
    for (const [shape, r, w, h] of [
      ['rectangle', 16, 1, 1], ['disc', 1, 1, 1], ['disc', 32, 1, 1], ['disc', 33, 2, 1], ['tube', 32, 1, 1],
      ['tube', 7, 0.2, 3], ['tube', 40, 3, 0.5], ['tube', 1, 1, 1],
    ] as const) {
      const s = shaped(shape, r, w, h);
      expect(shapeParticles(s.cloth), `${shape} ${r} ${w}×${h}`).toBe(modelFor(s).particleCount);
    }
    expect(shapeParticles(shaped('disc', 32).cloth)).toBe(817); // 1 + 3K(K + 1), K = 16
    for (const r of [1, 4, 33, 48]) {
      const woven = setScenePath(shaped('disc', r, 0.3, 1), 'cloth.lattice', 'weave');
      expect(shapeParticles(woven.cloth), `woven disc ${r}`).toBe(modelFor(woven).particleCount);
    }
    // a woven disc clamped as a disc of rings is, by its own count
    const woven = capCloth(setScenePath(shaped('disc', 1024), 'cloth.lattice', 'weave'), 'cpu', noMesh);
    expect(shapeParticles(woven.scene.cloth)).toBeLessThanOrEqual(MAX_PARTICLES.cpu);
    expect(shapeParticles(woven.scene.cloth, woven.scene.cloth.resolution + 1)).toBeGreaterThan(MAX_PARTICLES.cpu);
  });

  it('a disc or tube over the backend\'s particles is clamped to the largest resolution that fits, with a note', () => {
    const disc = shaped('disc', 1024);
    const cpu = capCloth(disc, 'cpu', noMesh);
    const r = cpu.scene.cloth.resolution;
    expect(shapeParticles(cpu.scene.cloth)).toBeLessThanOrEqual(MAX_PARTICLES.cpu);
    expect(shapeParticles(cpu.scene.cloth, r + 1)).toBeGreaterThan(MAX_PARTICLES.cpu);
    expect(r).toBe(294); // K = 147: 65,269 particles
    expect(cpu.note).toBe('disc of resolution 1024: 787,969 particles, more than the CPU backend takes (66,049), clamped to resolution 294 (65,269 particles); the GPU backend takes 1,050,625');
    expect(disc.cloth.resolution).toBe(1024);
    expect(capCloth(disc, 'gpu', noMesh)).toEqual({ scene: disc, note: '' });
    // within the cap: the same scene (a disc of 256 faces across has fewer particles than the 256² grid)
    const d256 = shaped('disc', 256);
    expect(capCloth(d256, 'cpu', noMesh).scene).toBe(d256);
    const tube = shaped('tube', 1024, 10, 10);
    const t = capCloth(tube, 'cpu', noMesh);
    expect(shapeParticles(t.scene.cloth)).toBeLessThanOrEqual(MAX_PARTICLES.cpu);
    expect(t.note).toMatch(/^tube of resolution 1024: [\d,]+ particles, more than the CPU backend takes \(66,049\), clamped to resolution \d+/);
  });

  it('a rectangle is still capped by its resolution (and its sweep)', () => {
    const big = setScenePath(builtinScene('cotton-basic'), 'cloth.resolution', 1024);
    expect(capCloth(big, 'cpu', noMesh)).toEqual(capResolution(big, 'cpu'));
  });

  it('a mesh file is refused, not clamped, when it has more particles than the backend takes', () => {
    const mesh = setScenePath(builtinScene('cotton-basic'), 'cloth.mesh', 'big.obj');
    const count = (n: number) => (path: string) => { expect(path).toBe('big.obj'); return n; };
    expect(capCloth(mesh, 'cpu', count(1258))).toEqual({ scene: mesh, note: '' });
    expect(capCloth(mesh, 'cpu', count(257 ** 2))).toEqual({ scene: mesh, note: '' });
    expect(() => capCloth(mesh, 'cpu', count(70_000))).toThrow(SceneError);
    expect(() => capCloth(mesh, 'cpu', count(70_000)))
      .toThrow('big.obj: 70,000 particles, more than the CPU backend takes (66,049); the GPU backend takes 1,050,625');
    expect(capCloth(mesh, 'gpu', count(70_000)).note).toBe('');
  });
});

describe('backend size caps, several cloths', () => {
  const layers = builtinScene('layers');
  const big = [0, 1, 2].reduce((s, k) => setScenePath(s, `cloths[${k}].cloth.resolution`, 256), layers);

  it('share the cap: each generated cloth over its share lowered, with a note naming them; the GPU keeps them', () => {
    expect(capCloth(layers, 'cpu', noMesh)).toEqual({ scene: layers, note: '' });
    const cpu = capCloth(setScenePath(big, 'cloths[0].pins', ['top-left', 7]), 'cpu', noMesh);
    // 22,016 particles each at most: (147 + 1)² = 21,904
    expect(clothEntries(cpu.scene).map((e) => e.cloth.resolution)).toEqual([147, 147, 147]);
    expect(clothEntries(cpu.scene).map((e) => e.name)).toEqual(['leather', 'cotton', 'silk']);
    // particle numbers belong to the old resolution; presets stay
    expect(cpu.scene.cloths![0].pins).toEqual(['top-left']);
    expect(cpu.note).toBe('3 cloths of 198,147 particles together: more than the CPU backend takes (66,049), clamped: ' +
      'cloths[0] (leather) resolution 256 → 147, cloths[1] (cotton) resolution 256 → 147, cloths[2] (silk) resolution 256 → 147; ' +
      'the GPU backend takes 1,050,625');
    expect(capCloth(big, 'gpu', noMesh)).toEqual({ scene: big, note: '' });
    // a small cloth under its share keeps its resolution
    const mixed = capCloth(setScenePath(big, 'cloths[1].cloth.resolution', 20), 'cpu', noMesh);
    expect(clothEntries(mixed.scene).map((e) => e.cloth.resolution)).toEqual([147, 20, 147]);
  });

  it("a mesh file keeps its particles; mesh files over the cap together are refused", () => {
    const mesh = setScenePath(big, 'cloths[1].cloth.mesh', 'shirt.obj');
    const cpu = capCloth(mesh, 'cpu', () => 30_000);
    // the rest, 36,049, shared by the two rectangles: 18,024 each, (133 + 1)² = 17,956
    expect(clothEntries(cpu.scene).map((e) => e.cloth.resolution)).toEqual([133, 256, 133]);
    expect(() => capCloth(mesh, 'cpu', () => 70_000)).toThrow(new SceneError(
      "the cloths' mesh files: 70,000 particles together, more than the CPU backend takes (66,049); the GPU backend takes 1,050,625"));
  });
});
