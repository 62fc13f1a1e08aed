import { describe, expect, it } from 'vitest';
import { pngSize } from './file-export.js';

describe('pngSize: a screenshot\'s size', () => {
  it('a fixed size is what it says, whatever the window', () => {
    expect(pngSize('1920x1080', 390, 844, 3)).toEqual([1920, 1080]);
    expect(pngSize('3840x2160', 390, 844, 1)).toEqual([3840, 2160]);
  });

  it('"view" is the window less the panel, at the screen\'s pixel ratio', () => {
    // 960 px wide with a 300 px panel: the free 660 × 600, at ratio 2
    expect(pngSize('view', 660, 600, 2)).toEqual([1320, 1200]);
  });

  it('never NaN, zero or huge: a size out of range is clamped', () => {
    expect(pngSize('view', NaN, 0, NaN)).toEqual([16, 16]);
    expect(pngSize('99999x5', 1, 1, 1)).toEqual([4096, 16]);
    expect(pngSize('<b>x</b>', 100, 50, 1)).toEqual([100, 50]);
  });
});
