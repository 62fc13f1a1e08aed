/**
 * Strings that came from a scene, a link or a file, made safe to print or to write into a file: control characters
 * (C0, DEL, C1, which carry terminal escapes and line breaks), line and paragraph separators and bidirectional
 * overrides (which reorder what a reader sees).
 */
const UNSAFE = /[\u0000-\u001f\u007f-\u009f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

/** `text` with every unsafe character replaced by U+FFFD, cut to `maxLength` characters. */
export function plainText(text: string, maxLength = 200): string {
  const s = String(text).replace(UNSAFE, '\ufffd');
  return s.length > maxLength ? `${s.slice(0, maxLength - 1)}…` : s;
}

/** What JSON.stringify leaves unescaped of UNSAFE (it escapes C0 itself): only ever inside strings. */
const UNSAFE_IN_JSON = /[\u007f-\u009f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

/**
 * JSON of `value` (as JSON.stringify) in which every unsafe character is a \u escape: the same JSON value, but
 * nothing in it can move a terminal's cursor or reorder text when printed or opened.
 */
export function safeJson(value: unknown, space?: number): string {
  return JSON.stringify(value, null, space).replace(UNSAFE_IN_JSON, (c) => `\\u${c.charCodeAt(0).toString(16).padStart(4, '0')}`);
}

/**
 * A value a caller passed, as an error message shows it after "got": a string quoted (so that "got 2" cannot read as
 * if the number 2 were refused) and cut to 40 characters, anything else as String() gives it; both made safe to print.
 */
export function shownValue(value: unknown): string {
  return typeof value === 'string' ? safeJson(plainText(value, 40)) : plainText(String(value), 40);
}
