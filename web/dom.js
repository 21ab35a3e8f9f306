// Building DOM without innerHTML (the page's Content-Security-Policy forbids
// inline styles and scripts; text is always text, never markup).

// h("a", {href: "#/x", class: "btn", onclick: fn, dataset: {k: v}}, "text", child, [more])
export function h(tag, props = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(props ?? {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key === "class") el.className = value;
    else if (key === "dataset") Object.assign(el.dataset, value);
    else if (key.startsWith("on") && typeof value === "function") el.addEventListener(key.slice(2), value);
    else if (key in el && typeof value !== "string") el[key] = value;
    else el.setAttribute(key, value === true ? "" : String(value));
  }
  append(el, children);
  return el;
}

export function append(el, children) {
  for (const child of children.flat(Infinity)) {
    if (child === undefined || child === null || child === false) continue;
    el.append(child instanceof Node ? child : String(child));
  }
  return el;
}

export function clear(el) {
  while (el.firstChild) el.firstChild.remove();
  return el;
}

// Replaces el's children.
export function fill(el, ...children) {
  clear(el);
  return append(el, children);
}

// A table from column headers and rows of cells (strings or nodes).
export function table(caption, headers, rows, { className = "grid" } = {}) {
  return h("div", { class: "table-wrap" },
    h("table", { class: className },
      caption ? h("caption", {}, caption) : null,
      h("thead", {}, h("tr", {}, headers.map((t) => h("th", { scope: "col" }, t)))),
      h("tbody", {}, rows)));
}

// A definition list of [label, value] pairs.
export function facts(pairs, className = "facts") {
  return h("dl", { class: className }, pairs.map(([k, v]) => [h("dt", {}, k), h("dd", {}, v)]));
}

// Saves bytes as a file the user downloads.
export function download(name, blob) {
  const url = URL.createObjectURL(blob);
  const a = h("a", { href: url, download: name, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}
