import { describe, expect, it } from 'vitest';
import { BoxTree } from './box-tree.js';
import { mulberry32 } from './random.js';

/** n random boxes (sides up to `size`) in the unit cube, and their centres */
function randomBoxes(n: number, size: number, seed: number): { boxes: Float64Array; centres: Float64Array } {
  const rand = mulberry32(seed), boxes = new Float64Array(6 * n), centres = new Float64Array(3 * n);
  for (let i = 0; i < n; i++) {
    for (let c = 0; c < 3; c++) {
      const lo = rand(), side = size * rand();
      boxes[6 * i + c] = lo; boxes[6 * i + 3 + c] = lo + side;
      centres[3 * i + c] = lo + side / 2;
    }
  }
  return { boxes, centres };
}

const meets = (a: Float64Array, i: number, b: Float64Array, j: number) =>
  [0, 1, 2].every((c) => a[6 * i + c] <= b[6 * j + 3 + c] && b[6 * j + c] <= a[6 * i + 3 + c]);

describe('BoxTree', () => {
  it('finds exactly the pairs whose boxes meet, each once, between two trees and within one', () => {
    // built from other centres than the boxes are at: the pairs do not depend on how good the tree is
    const a = randomBoxes(300, 0.3, 1), b = randomBoxes(217, 0.2, 2);
    const ta = new BoxTree(randomBoxes(300, 0.1, 3).centres, 300), tb = new BoxTree(b.centres, 217);
    expect(ta.refit(a.boxes) && tb.refit(b.boxes)).toBe(true);
    const cross: string[] = [];
    ta.pairsWith(tb, a.boxes, b.boxes, (i, j) => cross.push(`${i},${j}`));
    const want: string[] = [];
    for (let i = 0; i < 300; i++) for (let j = 0; j < 217; j++) if (meets(a.boxes, i, b.boxes, j)) want.push(`${i},${j}`);
    expect(want.length).toBeGreaterThan(300);
    expect(cross.sort()).toEqual(want.sort());

    const within: string[] = [];
    ta.pairsWithin(a.boxes, (i, j) => { expect(i).toBeLessThan(j); within.push(`${i},${j}`); });
    const wantWithin: string[] = [];
    for (let i = 0; i < 300; i++) for (let j = i + 1; j < 300; j++) if (meets(a.boxes, i, a.boxes, j)) wantWithin.push(`${i},${j}`);
    expect(within.sort()).toEqual(wantWithin.sort());
  });

  it('finds exactly the primitives whose boxes meet one box', () => {
    const a = randomBoxes(300, 0.3, 1), q = randomBoxes(40, 0.25, 4);
    const t = new BoxTree(randomBoxes(300, 0.1, 3).centres, 300);
    expect(t.refit(a.boxes)).toBe(true);
    let found = 0;
    for (let k = 0; k < 40; k++) {
      const got: number[] = [];
      t.query(q.boxes, 6 * k, a.boxes, k, (id, j) => { expect(id).toBe(k); got.push(j); });
      const want: number[] = [];
      for (let j = 0; j < 300; j++) if (meets(a.boxes, j, q.boxes, k)) want.push(j);
      expect(got.sort((x, y) => x - y)).toEqual(want);
      found += want.length;
    }
    expect(found).toBeGreaterThan(40);
  });

  it('refuses a box that is not finite', () => {
    const a = randomBoxes(50, 0.1, 4), t = new BoxTree(a.centres, 50);
    expect(t.refit(a.boxes)).toBe(true);
    a.boxes[6 * 17 + 4] = NaN;
    expect(t.refit(a.boxes)).toBe(false);
    a.boxes[6 * 17 + 4] = Infinity;
    expect(t.refit(a.boxes)).toBe(false);
  });
});
