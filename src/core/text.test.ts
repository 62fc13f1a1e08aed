import { describe, expect, it } from 'vitest';
import { plainText, safeJson, shownValue } from './text.js';

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

describe('safeJson', () => {
  it('is the same JSON value with every unsafe character escaped', () => {
    const value = { name: 'a\u001b[2J\u009b\u2028\u202eb', n: [1, 2] };
    const text = safeJson(value);
    expect(text).not.toMatch(/[\u0000-\u001f\u007f-\u009f\u2028\u2029\u202a-\u202e\u2066-\u2069]/);
    expect(JSON.parse(text)).toEqual(value);
    expect(safeJson({ a: 1 }, 2)).toBe('{\n  "a": 1\n}');
  });
});

describe('shownValue', () => {
  it('quotes a string, cuts it and makes it safe; shows anything else as String does', () => {
    expect(shownValue('2')).toBe('"2"');
    expect(shownValue(2.5)).toBe('2.5');
    expect(shownValue(NaN)).toBe('NaN');
    expect(shownValue(undefined)).toBe('undefined');
    expect(shownValue('a\u001b[2Jb')).toBe('"a\ufffd[2Jb"');
    expect(shownValue('x'.repeat(100))).toBe(`"${'x'.repeat(39)}…"`);
  });
});
