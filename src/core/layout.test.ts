import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { AS_FILE, CONTROL, TS_FILE, generateLayoutModules, layoutControl } from './gen-layout.mjs';
import { CTRL, CTRL_BYTES } from './layout.generated.js';

describe('the one table of shared constants and the kernel control block', () => {
  it('layout.generated.ts and wasm/layout.generated.as.ts are what gen-layout.mjs writes (else run: npm run gen)', () => {
    const { ts, as } = generateLayoutModules();
    expect(readFileSync(TS_FILE, 'utf8')).toBe(ts);
    expect(readFileSync(AS_FILE, 'utf8')).toBe(as);
  });

  it('control block fields are aligned, do not overlap, and the words threads write sit on their own lines', () => {
    const { offsets, bytes } = layoutControl();
    expect(bytes).toBe(CTRL_BYTES);
    const size = { i32: 4, i64: 8, f64: 8 };
    let end = 0;
    for (const [name, type, count, , line] of CONTROL) {
      const at = offsets[name];
      expect(at % size[type], name).toBe(0);
      expect(at, `${name} after the field before it`).toBeGreaterThanOrEqual(end);
      if (line) expect(at % 64, `${name} on its own line`).toBe(0);
      end = at + size[type] * count;
      expect(CTRL[name as keyof typeof CTRL]).toBe(at);
    }
    expect(end).toBeLessThanOrEqual(CTRL_BYTES);
  });
});
