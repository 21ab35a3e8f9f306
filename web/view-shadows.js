// Shadows: the running and stopped shadows, and a form to start one.
import { h, fill } from "./dom.js";
import { apiJson } from "./api.js";
import { hashFor } from "./router.js";
import { parseUserJson } from "./api-errors.js";
import { errorBox, notice, pageHead, statusBadge, busy, pause, isAbort } from "./ui.js";
import { selectLine } from "./text-select.js";
import { formatNumber, prettyJson } from "./format.js";

const TEMPLATE = {
  machine: "3axis-mill",
  tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 15, length: 50, shank_diameter: 6, holder: [{ diameter: 30, length: 30 }] }],
  stock: { box: { min: [0, 0, -40], max: [100, 80, 0] } },
  options: { density: 5 },
  modbus: {
    host: "127.0.0.1", port: 5020, unit_id: 1, poll_hz: 50, timeout_ms: 200, table: "holding",
    joints: { X: { address: 0, type: "float32" }, Y: { address: 2, type: "float32" }, Z: { address: 4, type: "float32" } },
    tool: { address: 6, type: "uint16" },
    spindle_on: { address: 7, type: "uint16" },
    line: { address: 8, type: "uint32" },
    feed_hold: { coil: 0, enabled: false },
  },
};

let keptText = null;

export function renderShadows(main, route, signal) {
  document.title = "Shadows · mdhd";
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const body = h("tbody", {}, h("tr", {}, h("td", { colspan: "4" }, "Loading…")));
  const editor = h("textarea", { id: "shadow-json", rows: 22, spellcheck: "false", class: "code-input", "aria-describedby": "shadow-json-hint" });
  editor.value = keptText ?? prettyJson(TEMPLATE);
  editor.addEventListener("input", () => { keptText = editor.value; });
  const jobFile = h("input", { type: "file", id: "shadow-job-file", accept: ".json" });
  const programFile = h("input", { type: "file", id: "shadow-program-file", accept: ".ngc,.nc,.tap,.gcode,.txt,.cnc" });
  const start = h("button", { type: "submit", class: "primary" }, "Start shadowing");
  const formErrors = h("div", { class: "errors", "aria-live": "polite" });
  const form = h("form", { class: "card", novalidate: true },
    h("h2", {}, "Start a shadow"),
    h("p", { class: "hint" }, "The cell (machine, tools, stock, fixtures, optionally the program the machine runs) and the controller's Modbus register map. The service polls the controller and cuts a live stock."),
    h("div", { class: "row" },
      h("label", { for: "shadow-job-file", class: "button ghost" }, "Take the cell from a job file…"), jobFile,
      h("label", { for: "shadow-program-file", class: "button ghost" }, "Add the program…"), programFile),
    h("div", { class: "field" }, h("label", { for: "shadow-json" }, "Shadow JSON"), editor,
      h("p", { class: "hint", id: "shadow-json-hint" }, "modbus.host and modbus.port name the controller; each machine joint needs a register.")),
    h("div", { class: "buttons" }, start),
    formErrors);

  fill(main, pageHead("Shadows"), errors,
    h("div", { class: "table-wrap" }, h("table", { class: "grid shadows" },
      h("thead", {}, h("tr", {}, ["Shadow", "State", "Controller", "Samples"].map((t) => h("th", { scope: "col" }, t)))),
      body)),
    form);

  const current = () => {
    try {
      return parseUserJson(editor.value, "The shadow");
    } catch (err) {
      if (err.line) selectLine(editor, err.line);
      throw err;
    }
  };

  jobFile.addEventListener("change", async () => {
    formErrors.replaceChildren();
    try {
      const job = parseUserJson(await jobFile.files[0].text(), jobFile.files[0].name);
      const doc = current();
      for (const k of ["machine", "tools", "stock", "fixtures", "work_offsets", "options", "program"]) {
        if (k in job) doc[k] = job[k];
      }
      if (job.modbus) doc.modbus = job.modbus;
      const missing = ["machine_file", "program_file"].filter((k) => k in job).map((k) => job[k]);
      editor.value = keptText = prettyJson(doc);
      if (missing.length) formErrors.replaceChildren(notice("info", `The job names ${missing.join(" and ")}: the service takes only inline machines and programs. Set "machine" to a registered machine's name, and add the program with the button.`));
    } catch (err) {
      formErrors.replaceChildren(errorBox(err, "Could not use the file"));
    }
  });
  programFile.addEventListener("change", async () => {
    formErrors.replaceChildren();
    try {
      const doc = current();
      doc.program = await programFile.files[0].text();
      editor.value = keptText = prettyJson(doc);
    } catch (err) {
      formErrors.replaceChildren(errorBox(err, "Could not add the program"));
    }
  });

  form.addEventListener("submit", (e) => {
    e.preventDefault();
    busy(start, formErrors, async () => {
      const doc = current();
      const reply = await apiJson("/api/v1/shadows", { method: "POST", json: doc, signal });
      location.hash = hashFor("shadow", { id: reply.id });
    });
  });

  (async () => {
    while (!signal.aborted) {
      try {
        const { shadows } = await apiJson("/api/v1/shadows", { signal });
        fill(body, shadows.length
          ? shadows.map((s) => h("tr", { dataset: { id: s.id, state: s.state } },
              h("td", {}, h("a", { href: hashFor("shadow", { id: s.id }) }, h("code", {}, s.id))),
              h("td", {}, statusBadge(s.state)),
              h("td", {}, `${s.host ?? "?"}:${s.port ?? "?"}`),
              h("td", { class: "num" }, formatNumber(s.samples, 0))))
          : h("tr", {}, h("td", { colspan: "4" }, "No shadows. Start one below.")));
        errors.replaceChildren();
      } catch (err) {
        if (isAbort(err, signal)) return;
        errors.replaceChildren(errorBox(err, "Could not list the shadows"));
      }
      await pause(3000, signal);
    }
  })();
}
