import { describe, expect, it } from 'vitest';
import { plainText } from './text.js';

describe('plainText', () => {
  it('keeps ordinary text, including non-Latin scripts and emoji', () => {
    expect(plainText('Silk drape — 絹 ✓ 🧵')).toBe('Silk drape — 絹 ✓ 🧵');
  });
  it('replaces line breaks, terminal escapes and bidi overrides', () => {
    expect(plainText('a\nv 1 2 3\r\nmtllib x')).toBe('a\ufffdv 1 2 3\ufffd\ufffdmtllib x');
    expect(plainText('\u001b[31mred\u001b[0m\u0007')).toBe('\ufffd[31mred\ufffd[0m\ufffd');
    expect(plainText('\u009b2J \u202eevil\u2066 \u2028')).toBe('\ufffd2J \ufffdevil\ufffd \ufffd');
  });
  it('cuts long text', () => {
    expect(plainText('x'.repeat(500), 10)).toBe('xxxxxxxxx…');
  });
});
