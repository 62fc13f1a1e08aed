import { describe, expect, it } from 'vitest';
import { fabricFor } from './looks.js';

describe("a cloth's look", () => {
  it("is its fabric's, except the scenes that are about one thing; without a fabric, its scene's name says", () => {
    expect(['cotton', 'silk', 'leather', 'rubber', 'denim', 'wool'].map((f) => fabricFor('layers', f))).toEqual(['cotton', 'silk', 'leather', 'rubber', 'cotton', 'cotton']);
    // a one-cloth scene whose fabric changed looks like the new fabric
    expect(fabricFor('cotton-basic', 'silk')).toBe('silk');
    expect(fabricFor('wind', 'silk')).toBe('flag');
    expect(fabricFor('pins', 'cotton')).toBe('hammock');
    expect(fabricFor('resolution', 'leather')).toBe('checker');
    expect(fabricFor('silk-drape', undefined)).toBe('silk');
    expect(fabricFor('leather-stiff', 'rubber')).toBe('rubber');
    expect(fabricFor('imported', undefined)).toBe('cotton');
  });
});
