// One machine: its JSON in an editor, saved by PUT (register or replace), or
// deleted. #/new-machine registers a new one (?from=NAME starts from a copy).
import { h, fill } from "./dom.js";
import { apiJson, apiFetch, enc } from "./api.js";
import { hashFor } from "./router.js";
import { parseUserJson, InputError } from "./api-errors.js";
import { selectLine } from "./text-select.js";
import { prettyJson } from "./format.js";
import { errorBox, notice, pageHead, busy, isAbort } from "./ui.js";

const NAME_RULE = /^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$/;

const TEMPLATE = {
  name: "3-axis vertical mill",
  joints: [
    { name: "X", type: "linear", axis: [1, 0, 0], limits: [-400, 400] },
    { name: "Y", type: "linear", axis: [0, 1, 0], limits: [-300, 300] },
    { name: "Z", type: "linear", axis: [0, 0, 1], limits: [-200, 400] },
  ],
  tool_chain: ["X", "Y", "Z"],
  workpiece_chain: [],
  spindle_axis: [0, 0, 1],
  home: { X: 0, Y: 0, Z: 300 },
  rapid_feed: 20000,
  max_feed: 10000,
};

export function renderMachine(main, route, signal) {
  const creating = route.name === "new-machine";
  const existing = creating ? null : route.params.name;
  const from = creating ? route.query.from ?? null : null;
  document.title = `${creating ? "Register a machine" : existing} · mdhd`;

  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const nameInput = h("input", { id: "machine-name", type: "text", required: true, maxlength: "64", autocomplete: "off", spellcheck: "false",
    pattern: "[A-Za-z0-9][A-Za-z0-9._\\-]{0,63}", "aria-describedby": "machine-name-hint" });
  const editor = h("textarea", { id: "machine-editor", rows: 24, spellcheck: "false", class: "code-input", "aria-describedby": "machine-editor-hint" });
  const save = h("button", { type: "submit", class: "primary" }, creating ? "Register" : "Save changes");
  const format = h("button", { type: "button", class: "ghost" }, "Tidy the JSON");
  const del = h("button", { type: "button", class: "danger" }, "Delete");
  const copy = h("a", { class: "button ghost", href: `${hashFor("new-machine")}?from=${enc(existing ?? "")}` }, "Copy as a new machine");
  const form = h("form", { class: "card machine-form", novalidate: true },
    creating
      ? h("div", { class: "field" }, h("label", { for: "machine-name" }, "Name"), nameInput,
        h("p", { class: "hint", id: "machine-name-hint" }, "1-64 letters, digits, '.', '_' or '-', starting with a letter or digit. Jobs name the machine by it."))
      : null,
    h("div", { class: "field" }, h("label", { for: "machine-editor" }, "Machine JSON"), editor,
      h("p", { class: "hint", id: "machine-editor-hint" }, "The machine object of the job format (joints, tool_chain, workpiece_chain, ...). The service checks it when you save.")),
    h("div", { class: "buttons" }, save, format, creating ? null : copy, creating ? null : del));

  fill(main, pageHead(creating ? "Register a machine" : h("span", {}, "Machine ", h("code", {}, existing)),
    h("a", { class: "button ghost", href: hashFor("machines") }, "All machines")), errors, form);

  const load = async (name) => {
    const machine = await apiJson(`/api/v1/machines/${enc(name)}`, { signal });
    editor.value = prettyJson(machine);
  };
  (async () => {
    try {
      if (existing) await load(existing);
      else if (from) {
        await load(from);
        nameInput.value = `${from}-copy`;
      } else editor.value = prettyJson(TEMPLATE);
    } catch (err) {
      if (isAbort(err, signal)) return;
      errors.replaceChildren(errorBox(err, err?.status === 404 ? "No such machine" : "Could not load the machine"));
      if (existing) form.hidden = true;
    }
  })();

  const parsed = () => {
    try {
      return parseUserJson(editor.value, "The machine");
    } catch (err) {
      if (err.line) selectLine(editor, err.line);
      throw err;
    }
  };

  format.addEventListener("click", () => {
    errors.replaceChildren();
    try {
      editor.value = prettyJson(parsed());
    } catch (err) {
      errors.replaceChildren(errorBox(err, "Cannot tidy it"));
    }
  });

  form.addEventListener("submit", (e) => {
    e.preventDefault();
    busy(save, errors, async () => {
      const name = creating ? nameInput.value.trim() : existing;
      if (!NAME_RULE.test(name)) {
        nameInput.focus();
        throw new InputError("The name must be 1-64 letters, digits, '.', '_' or '-', starting with a letter or digit.");
      }
      const machine = parsed();
      if (creating) {
        let taken = false;
        try {
          await apiJson(`/api/v1/machines/${enc(name)}`, { signal });
          taken = true;
        } catch (err) {
          if (err?.status !== 404) throw err;
        }
        if (taken && !confirm(`A machine named ${name} is registered. Replace it?`)) return;
      }
      const res = await apiFetch(`/api/v1/machines/${enc(name)}`, { method: "PUT", json: machine, signal });
      errors.replaceChildren(notice("ok", res.status === 201 ? `Registered ${name}.` : `Saved ${name}.`));
      if (creating) location.hash = hashFor("machine", { name });
    });
  });

  del.addEventListener("click", () => {
    if (!confirm(`Delete the machine ${existing}? Jobs already accepted keep their copy.`)) return;
    busy(del, errors, async () => {
      await apiFetch(`/api/v1/machines/${enc(existing)}`, { method: "DELETE", signal });
      location.hash = hashFor("machines");
    });
  });
}
