import { describe, expect, it } from 'vitest';
import { builtinScene, setScenePath } from '../core/index.js';
import { MAX_PARTICLES, MAX_RESOLUTION, capResolution, fitSideBySide, importSizeProblem, particlesOf } from './limits.js';

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

  it('a scene file over 32 MiB is not read', () => {
    expect(importSizeProblem(1000)).toBe('');
    expect(importSizeProblem(32 * 2 ** 20)).toBe('');
    expect(importSizeProblem(2 ** 30)).toBe('1024.0 MiB, more than the 32 MiB a scene file may be');
  });
});
