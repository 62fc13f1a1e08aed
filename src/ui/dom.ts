/**
 * Building page content without parsing HTML: every string becomes a text node (never markup), so a scene name,
 * a link or a file name can never turn into elements or script. Nothing in the app parses markup.
 */

export type Child = Node | string | number | null | undefined | false;

/** A number for the screen with `digits` decimals: never 'NaN' or 'Infinity' ('—' for a value that is not finite). */
export function finite(v: number, digits: number): string {
  return Number.isFinite(v) ? v.toFixed(digits) : '—';
}

export interface Props {
  className?: string;
  /** data-testid */
  testid?: string;
  title?: string;
}

/** An element with the given class and children (strings are text). */
export function h<K extends keyof HTMLElementTagNameMap>(tag: K, props: Props | string | null, ...children: Child[]): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  const p: Props = typeof props === 'string' ? { className: props } : props ?? {};
  if (p.className) e.className = p.className;
  if (p.testid) e.dataset.testid = p.testid;
  if (p.title) e.title = p.title;
  append(e, children);
  return e;
}

/** Appends children to a node; strings and numbers as text. */
export function append(parent: Node, children: Child[]): void {
  for (const c of children) {
    if (c === null || c === undefined || c === false) continue;
    parent.appendChild(typeof c === 'string' || typeof c === 'number' ? document.createTextNode(String(c)) : c);
  }
}

/** Lines of content separated by <br>, replacing what `parent` held. */
export function setLines(parent: HTMLElement, lines: Child[][]): void {
  const out: Child[] = [];
  lines.forEach((line, k) => {
    if (k > 0) out.push(document.createElement('br'));
    out.push(...line);
  });
  parent.replaceChildren();
  append(parent, out);
}
