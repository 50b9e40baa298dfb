//! The page's elements, the status line, and the state the page exposes to tests on `<body>`
//! (`data-ready`, `data-frames`, `data-depth-m`, `data-poses`, `data-state`, ...).

/** The element with this id (of this class, when given); a missing or mistyped id is a bug in
 * index.html, reported at once. */
export function $(id: string): HTMLElement;
export function $<T extends HTMLElement>(id: string, type: new () => T): T;
export function $<T extends HTMLElement>(id: string, type?: new () => T): HTMLElement {
  const el = document.getElementById(id);
  if (!el) throw new Error(`index.html has no element #${id}`);
  if (type && !(el instanceof type)) throw new Error(`#${id} is a <${el.tagName.toLowerCase()}>, not a ${type.name}`);
  return el;
}

/** Shows a one-line message (errors, progress) under the tissue view. */
export function status(msg: string): void {
  $("status").textContent = msg;
}

/** Sets `data-<key>` on `<body>` (the page's state, for tests). */
export function publish(key: string, value: string | number): void {
  document.body.dataset[key] = String(value);
}
