// Small pieces every page uses: notices, error boxes, status badges, progress.
import { h } from "./dom.js";
import { describeError } from "./api-errors.js";
import { statusLabel, percent } from "./format.js";

export function notice(kind, ...content) {
  return h("div", { class: `notice ${kind}`, role: kind === "error" ? "alert" : "status" }, ...content);
}

// An error as the user should read it: the service's message, its field and
// problems (400), its line and column (422). Never a stack.
export function errorBox(err, title = "That did not work") {
  if (err?.name !== "ApiError" && err?.name !== "InputError" && err?.name !== "StlError") {
    console.error(err);  // the details stay in the console
  }
  const extra = [];
  if (err?.name === "ApiError") {
    if (Number.isInteger(err.line) && err.line > 0) {
      extra.push(h("p", { class: "where" }, `Program line ${err.line}` + (Number.isInteger(err.column) && err.column > 0 ? `, column ${err.column}` : "")));
    }
    if (err.problems?.length > 1 || (err.problems?.length === 1 && !err.message.includes(err.problems[0].message))) {
      extra.push(h("ul", { class: "problems" }, err.problems.map((p) => h("li", {}, p.field ? [h("code", {}, p.field), ": ", p.message] : p.message))));
    } else if (err.field && !err.message.includes(err.field)) {
      extra.push(h("p", { class: "where" }, "Field ", h("code", {}, err.field)));
    }
    if (err.status) extra.push(h("p", { class: "code" }, `HTTP ${err.status}${err.code ? ` · ${err.code}` : ""}`));
  }
  return notice("error", h("strong", {}, title), h("p", { class: "message" }, describeError(err)), ...extra);
}

export function statusBadge(status) {
  return h("span", { class: `badge status-${status}`, dataset: { status } }, statusLabel(status));
}

export function progressBar(progress, label = "Progress") {
  const p = percent(progress);
  const bar = h("progress", { max: 100, value: p, "aria-label": label }, `${p} %`);
  return h("span", { class: "progress" }, bar, h("span", { class: "pct" }, `${p} %`));
}

export function pageHead(title, ...actions) {
  return h("div", { class: "page-head" }, h("h1", { tabindex: "-1" }, title), h("div", { class: "actions" }, ...actions));
}

// Runs an async action from a button: disabled and marked busy meanwhile; an
// error goes into `errorSlot` (replacing what was there).
export async function busy(button, errorSlot, action) {
  button.disabled = true;
  button.setAttribute("aria-busy", "true");
  if (errorSlot) errorSlot.replaceChildren();
  try {
    return await action();
  } catch (err) {
    if (errorSlot) errorSlot.replaceChildren(errorBox(err));
    return undefined;
  } finally {
    button.disabled = false;
    button.removeAttribute("aria-busy");
  }
}

// A sleep that ends early (without error) when the page is left.
export function pause(ms, signal) {
  return new Promise((resolve) => {
    const t = setTimeout(resolve, ms);
    signal?.addEventListener("abort", () => {
      clearTimeout(t);
      resolve();
    }, { once: true });
  });
}

export function isAbort(err, signal) {
  return signal?.aborted || err?.name === "AbortError";
}
