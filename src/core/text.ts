/**
 * Strings that came from a scene, a link or a file, made safe to print or to write into a file: control characters
 * (C0, DEL, C1, which carry terminal escapes and line breaks), line and paragraph separators and bidirectional
 * overrides (which reorder what a reader sees) each become U+FFFD, and the text is cut to `maxLength` characters.
 */
const UNSAFE = /[\u0000-\u001f\u007f-\u009f\u2028\u2029\u202a-\u202e\u2066-\u2069]/g;

export function plainText(text: string, maxLength = 200): string {
  const s = String(text).replace(UNSAFE, '\ufffd');
  return s.length > maxLength ? `${s.slice(0, maxLength - 1)}…` : s;
}
