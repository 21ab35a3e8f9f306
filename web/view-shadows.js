// Shadows: the running and stopped shadows, and a form to start one: the cell
// (a registered machine, a finished job's cell or a loaded job file; the program
// if the machine runs one), the controller and its registers, feed hold. "Edit as
// JSON" shows the same document as text (shadow-form.js keeps both in step).
import { h, fill } from "./dom.js";
import { apiJson, enc } from "./api.js";
import { hashFor } from "./router.js";
import { errorBox, notice, pageHead, statusBadge, busy, pause, isAbort } from "./ui.js";
import { selectLine } from "./text-select.js";
import { formatNumber, formatTimestamp, listVerdict, prettyJson, shortId, statusLabel } from "./format.js";
import { parseUserJson } from "./api-errors.js";
import { classifyFile } from "./job-form.js";
import {
  EXTRA_REGISTERS, REGISTER_TYPES, SETTINGS, TABLES, WORD_ORDERS, DEFAULTS,
  applyJob, defaultModbusValues, docFromValues, fieldFor, is32, machineJointNames,
  validateShadow, valuesFromDoc, withJoints,
} from "./shadow-form.js";

const TEMPLATE_CELL = {
  tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 15, length: 50, shank_diameter: 6, holder: [{ diameter: 30, length: 30 }] }],
  stock: { box: { min: [0, 0, -40], max: [100, 80, 0] } },
  options: { density: 5 },
};

// The form outlives a visit to another page.
const kept = {
  values: { machine: "3axis-mill", cellText: prettyJson(TEMPLATE_CELL), program: "", modbus: defaultModbusValues(["X", "Y", "Z"]) },
  jsonMode: false,
  jsonText: "",
};

const TABLE_LABELS = { holding: "holding (function 3)", input: "input (function 4)" };
const CELL_PATHS = ["cell", "tools", "stock", "fixtures", "work_offsets", "options"];

export function renderShadows(main, route, signal) {
  document.title = "Shadows · mdhd";
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const body = h("tbody", {}, h("tr", {}, h("td", { colspan: "4" }, "Loading…")));
  let registry = [];
  let registryError = false;
  let jobs = null;  // finished jobs, once listed
  let jobsError = null;

  const formBody = h("div", { class: "shadow-form-body" });
  const jsonToggle = h("button", { type: "button", class: "ghost", id: "shadow-as-json", "aria-pressed": "false" }, "Edit as JSON");
  const start = h("button", { type: "submit", class: "primary big", id: "shadow-start" }, "Start shadowing");
  const summary = h("div", { class: "submit-result", id: "shadow-result", "aria-live": "polite" });
  const form = h("form", { class: "shadow-form", novalidate: true, "aria-labelledby": "shadow-form-title" },
    h("div", { class: "card form-head" },
      h("h2", { id: "shadow-form-title" }, "Start a shadow"),
      h("p", { class: "hint" }, "The service polls the machine's controller over Modbus TCP, moves a virtual machine with it, cuts a live stock and raises an alarm at each collision."),
      h("div", { class: "row" }, jsonToggle)),
    formBody,
    h("div", { class: "submit-bar" }, start),
    summary);

  fill(main, pageHead("Shadows"), errors,
    h("div", { class: "table-wrap" }, h("table", { class: "grid shadows" },
      h("thead", {}, h("tr", {}, ["Shadow", "State", "Controller", "Samples"].map((t) => h("th", { scope: "col" }, t)))),
      body)),
    form);

  // ---- the form ----------------------------------------------------------------
  let fields = new Map();  // problem path -> {control, slot}
  let uid = 0;

  const field = (label, control, { paths = [], hint = null, className = "field" } = {}) => {
    const id = control.id || (control.id = `sf${++uid}`);
    const slot = h("p", { class: "field-error", id: `${id}-error`, hidden: true });
    const hintEl = hint ? h("p", { class: "hint", id: `${id}-hint` }, hint) : null;
    control.setAttribute("aria-describedby", [hintEl ? `${id}-hint` : null, `${id}-error`].filter(Boolean).join(" "));
    const rec = { control, slot };
    for (const p of paths) fields.set(p, rec);
    return h("div", { class: className }, h("label", { for: id }, label), control, hintEl, slot);
  };
  const textInput = (id, value, onInput, props = {}) => {
    const el = h("input", { type: "text", id, autocomplete: "off", spellcheck: "false", ...props });
    el.value = value;
    el.addEventListener("input", () => onInput(el.value));
    return el;
  };
  // A select that also shows a value it does not offer (from JSON), so nothing is lost.
  const select = (id, options, value, onChange) => {
    const list = options.some(([v]) => v === value) ? options : [...options, [value, `${value || "(none)"} (not valid)`]];
    const el = h("select", { id }, list.map(([v, text]) => h("option", { value: v }, text)));
    el.value = value;
    el.addEventListener("change", () => onChange(el.value));
    return el;
  };

  const values = () => kept.values;
  const jointNames = () => machineJointNames(values().machine, registry);

  const redraw = () => {
    const focused = document.activeElement?.id;
    fields = new Map();
    if (kept.jsonMode) fill(formBody, jsonSection());
    else fill(formBody, cellSection(), programSection(), controllerSection(), registersSection(), feedHoldSection());
    jsonToggle.setAttribute("aria-pressed", String(kept.jsonMode));
    if (focused) document.getElementById(focused)?.focus({ preventScroll: true });
  };

  // The machine changed: its joints get their registers.
  const setMachine = (machine) => {
    values().machine = machine;
    const names = jointNames();
    if (names) values().modbus = withJoints(values().modbus, names);
    redraw();
  };

  // What a loaded file or job did, and what is left to do.
  const notes = h("div", { class: "notes", id: "shadow-notes", "aria-live": "polite" });
  const setNotes = (...items) => notes.replaceChildren(h("ul", { class: "loaded" },
    items.map((t) => (Array.isArray(t) ? h("li", { class: t[0] }, t[1]) : h("li", {}, t)))));
  const jobOptions = () => {
    const list = [h("option", { value: "" }, jobs === null ? (jobsError ? "Jobs not available" : "Loading jobs…") : jobs.length ? "Choose a finished job…" : "No finished jobs")];
    for (const j of jobs ?? []) {
      const verdict = listVerdict(j);
      list.push(h("option", { value: j.id }, `${shortId(j.id)} · ${typeof j.machine === "string" ? j.machine : "inline machine"} · ${verdict ? verdict.text : statusLabel(j.status)} · ${formatTimestamp(j.finished_at ?? j.created_at)}`));
    }
    return list;
  };

  const cellSection = () => {
    const v = values();
    const options = [["", registry.length ? "Choose a machine…" : registryError ? "Machines not available" : "Loading machines…"]];
    for (const m of registry) options.push([m.name, `${m.name}${m.description ? ` · ${m.description}` : ""} (${(m.joints ?? []).join(" ")})`]);
    let current = typeof v.machine === "string" ? v.machine : "";
    if (v.machine && typeof v.machine === "object") {
      const names = machineJointNames(v.machine) ?? [];
      options.push(["(inline)", `${v.machine.name ?? "Machine"} from the job (${names.join(" ")})`]);
      current = "(inline)";
    } else if (current && !registry.some((m) => m.name === current)) {
      options.push([current, registry.length ? `${current} (not registered)` : current]);
    }
    const machineSelect = select("shadow-machine", options, current, (name) => {
      if (name !== "(inline)") setMachine(name === "" ? null : name);
    });

    const jobSelect = h("select", { id: "shadow-job" }, jobOptions());
    const withProgram = h("input", { type: "checkbox", id: "shadow-job-program", checked: true });
    const useJob = h("button", { type: "button", class: "ghost", id: "shadow-use-job" }, "Use this job's cell");
    useJob.addEventListener("click", () => {
      const id = jobSelect.value;
      if (!id) {
        setNotes(["warn", "Choose a finished job first."]);
        jobSelect.focus();
        return;
      }
      busy(useJob, notes, async () => {
        const job = await apiJson(`/api/v1/jobs/${enc(id)}/job`, { signal });
        const r = applyJob(values(), job, { registry, takeProgram: withProgram.checked });
        kept.values = r.values;
        redraw();
        setNotes(`Cell of job ${shortId(id)}: its machine, tools, stock${withProgram.checked && typeof job.program === "string" ? " and program" : ""}.`,
          ...r.notes.map((n) => ["warn", n]));
      });
    });

    const files = h("input", { type: "file", id: "shadow-files", multiple: true, accept: ".json,.ngc,.nc,.tap,.gcode,.txt,.cnc" });
    files.addEventListener("change", () => takeFiles([...files.files]));
    const cell = h("textarea", { id: "shadow-cell", rows: 10, spellcheck: "false", class: "code-input" });
    cell.value = v.cellText;
    cell.addEventListener("input", () => { values().cellText = cell.value; });

    return h("section", { class: "card", "aria-labelledby": "shadow-cell-title" },
      h("h3", { id: "shadow-cell-title", class: "section-title" }, "1. The cell"),
      h("div", { class: "options" },
        field("Machine", machineSelect, { paths: ["machine"], hint: "A registered machine, or the machine of a job's cell." }),
        h("div", { class: "field" },
          h("label", { for: "shadow-job" }, "Reuse a finished job's cell"),
          jobSelect,
          h("div", { class: "row" },
            h("label", { for: "shadow-job-program", class: "check" }, withProgram, "With its program"),
            useJob))),
      h("div", { class: "row" },
        h("label", { for: "shadow-files", class: "button ghost" }, "Open a job, machine or program file…"), files),
      notes,
      field("Tools, stock, fixtures, work offsets and options (JSON)", cell,
        { paths: CELL_PATHS, hint: "Everything of the job but the machine and the program. A job's cell or file fills it." }));
  };

  const programSection = () => {
    const v = values();
    const program = h("textarea", { id: "shadow-program", rows: 6, spellcheck: "false", class: "code-input", placeholder: "(no program: the shadow follows the machine without looking ahead)" });
    program.value = v.program;
    const info = h("p", { class: "hint", "aria-live": "polite" });
    const count = () => {
      const n = program.value === "" ? 0 : program.value.replace(/\r?\n$/, "").split(/\r\n|\n/).length;
      info.textContent = n ? `${n} lines` : "No program.";
    };
    program.addEventListener("input", () => {
      values().program = program.value;
      values().programExtra = undefined;
      count();
    });
    count();
    const file = h("input", { type: "file", id: "shadow-program-file", accept: ".ngc,.nc,.tap,.gcode,.txt,.cnc" });
    file.addEventListener("change", async () => {
      if (!file.files[0]) return;
      values().program = await file.files[0].text();
      redraw();
    });
    const clear = h("button", { type: "button", class: "ghost", id: "shadow-program-clear" }, "No program");
    clear.addEventListener("click", () => {
      values().program = "";
      values().programExtra = undefined;
      program.value = "";
      count();
    });
    return h("section", { class: "card", "aria-labelledby": "shadow-program-title" },
      h("h3", { id: "shadow-program-title", class: "section-title" }, "2. The program (optional)"),
      field("G-code the machine runs", program, { paths: ["program"], hint: "With it the service reports the program line and predicts collisions ahead of the tool." }),
      h("div", { class: "row" }, h("label", { for: "shadow-program-file", class: "button ghost" }, "Open a program file…"), file, clear, info));
  };

  const controllerSection = () => {
    const m = values().modbus;
    const settings = SETTINGS.map((s) => {
      const input = textInput(`mb-${s.key}`, m[s.key], (x) => { m[s.key] = x; },
        s.key === "host" ? { placeholder: "e.g. 192.168.0.20", autocapitalize: "off" } : { inputmode: s.integer ? "numeric" : "decimal", placeholder: String(DEFAULTS[s.key]) });
      const hint = s.key === "host" ? "The controller's name or IP address." : `${s.min} to ${s.max}; blank: ${DEFAULTS[s.key]}.`;
      return field(s.label, input, { paths: [`modbus.${s.key}`], hint });
    });
    const table = select("mb-table", TABLES.map((t) => [t, TABLE_LABELS[t]]), m.table, (t) => {
      m.table = t;
      m.tableGiven = true;
    });
    return h("section", { class: "card", "aria-labelledby": "shadow-controller-title" },
      h("h3", { id: "shadow-controller-title", class: "section-title" }, "3. The controller (Modbus TCP)"),
      h("div", { class: "options" }, settings, field("Register table", table, { paths: ["modbus.table"] })));
  };

  const registerRow = (path, title, entry, idBase, remove = null) => {
    const address = textInput(`${idBase}-address`, entry.address, (x) => { entry.address = x; },
      { inputmode: "numeric", placeholder: path.startsWith("modbus.joints.") ? "" : "not read" });
    const order = select(`${idBase}-word_order`, WORD_ORDERS.map((o) => [o, o]), entry.word_order, (o) => {
      entry.word_order = o;
      entry.orderGiven = true;
    });
    const type = select(`${idBase}-type`, REGISTER_TYPES.map((t) => [t, t]), entry.type, (t) => {
      entry.type = t;
      if (!is32(t)) entry.orderGiven = false;
      order.disabled = !is32(t);
    });
    order.disabled = !is32(entry.type) && REGISTER_TYPES.includes(entry.type);
    const scale = textInput(`${idBase}-scale`, entry.scale, (x) => { entry.scale = x; }, { inputmode: "decimal", placeholder: "1" });
    const nameId = `${idBase}-name`;
    const row = h("div", { class: "reg-row", role: "group", "aria-labelledby": nameId, dataset: { path } },
      h("div", { class: "reg-name" }, h("span", { id: nameId }, title),
        remove ? h("button", { type: "button", class: "ghost small", id: `${idBase}-remove`, "aria-label": `Remove joint ${title}`, onclick: remove }, "Remove") : null),
      field("Address", address, { paths: [path, `${path}.address`], className: "field reg-field" }),
      field("Type", type, { paths: [`${path}.type`], className: "field reg-field" }),
      field("Word order", order, { paths: [`${path}.word_order`], className: "field reg-field" }),
      field("Scale", scale, { paths: [`${path}.scale`], className: "field reg-field" }));
    return row;
  };

  const registersSection = () => {
    const m = values().modbus;
    const jointsSlot = h("p", { class: "field-error", id: "reg-joints-error", hidden: true });
    const modbusSlot = h("p", { class: "field-error", id: "reg-modbus-error", hidden: true });
    const section = h("section", { class: "card", "aria-labelledby": "shadow-registers-title", id: "shadow-registers", tabindex: "-1" },
      h("h3", { id: "shadow-registers-title", class: "section-title" }, "4. Registers"),
      h("p", { class: "hint" }, "Where the controller publishes each value. A 32-bit type takes two registers (its word order says which comes first); each value read is multiplied by its scale. Joints in mm and degrees."),
      modbusSlot,
      h("h4", { class: "sub-title", id: "reg-joints-title" }, "Joints"),
      jointsSlot,
      m.joints.length ? m.joints.map((j) => registerRow(`modbus.joints.${j.name}`, j.name, j, `reg-${j.name}`,
        // A joint the machine does not have (from JSON or a file) can go.
        jointNames() && !jointNames().includes(j.name) ? () => {
          m.joints = m.joints.filter((x) => x !== j);
          redraw();
        } : null))
        : h("p", { class: "hint" }, "Pick a machine: each of its joints gets a row."),
      h("h4", { class: "sub-title" }, "Tool, spindle and program line (optional: blank address, not read)"),
      EXTRA_REGISTERS.map(({ key, label }) => registerRow(`modbus.${key}`, label, m.registers[key], `reg-${key}`)));
    fields.set("modbus.joints", { control: section, slot: jointsSlot });
    fields.set("modbus", { control: section, slot: modbusSlot });
    return section;
  };

  const feedHoldSection = () => {
    const fh = values().modbus.feed_hold;
    const warning = h("div", { class: `notice ${fh.enabled ? "danger" : "warn"}`, id: "fh-warning", dataset: { armed: String(fh.enabled) } });
    const say = () => {
      const coil = String(fh.coil ?? "").trim() || "?";
      warning.className = `notice ${fh.enabled ? "danger" : "warn"}`;
      warning.dataset.armed = String(fh.enabled);
      fill(warning, h("strong", {}, fh.enabled ? "Feed hold is ON: this shadow writes to the controller." : "Feed hold writes to the controller."),
        h("p", {}, `When enabled, the service writes 1 to coil ${coil} of the controller at every collision alarm (and at a predicted one when it follows the program), which holds the machine's feed. Enable it only if that coil is the controller's feed hold and the machine's operator knows.`));
    };
    const enabled = h("input", { type: "checkbox", id: "fh-enabled", checked: fh.enabled });
    const coil = textInput("fh-coil", fh.coil, (x) => { fh.coil = x; say(); }, { inputmode: "numeric", placeholder: "0" });
    enabled.addEventListener("change", () => {
      fh.enabled = enabled.checked;
      say();
    });
    say();
    const enabledSlot = h("p", { class: "field-error", id: "fh-enabled-error", hidden: true });
    enabled.setAttribute("aria-describedby", "fh-warning fh-enabled-error");
    fields.set("modbus.feed_hold.enabled", { control: enabled, slot: enabledSlot });
    return h("section", { class: "card", "aria-labelledby": "shadow-fh-title" },
      h("h3", { id: "shadow-fh-title", class: "section-title" }, "5. Feed hold"),
      warning,
      h("div", { class: "options" },
        h("div", { class: "field" },
          h("label", { for: "fh-enabled", class: "check" }, enabled, "Write feed hold to the controller on a collision alarm"),
          enabledSlot),
        field("Feed-hold coil", coil, { paths: ["modbus.feed_hold", "modbus.feed_hold.coil"], hint: "0 to 65535." })));
  };

  const jsonSection = () => {
    const editor = h("textarea", { id: "shadow-json", rows: 28, spellcheck: "false", class: "code-input" });
    editor.value = kept.jsonText;
    editor.addEventListener("input", () => { kept.jsonText = editor.value; });
    return h("section", { class: "card" }, field("Shadow JSON", editor, { paths: [""], hint: "The document POST /api/v1/shadows takes. \"Edit as JSON\" again reads it back into the form, fields the form has no input for included." }));
  };

  // ---- files, JSON mode, problems, submit -----------------------------------
  const takeFiles = async (list) => {
    const items = [];
    try {
      const found = [];
      for (const file of list) found.push({ name: file.name, ...classifyFile(file.name, await file.text()) });
      const job = found.find((f) => f.kind === "job");
      let v = values();
      if (job) {
        const r = applyJob(v, job.value, { registry });
        v = r.values;
        items.push(`Job: ${job.name}`);
        const opened = found.map((f) => f.name);
        for (const n of r.notes) if (!opened.some((o) => n.includes(o))) items.push(["warn", n]);
      }
      for (const f of found) {
        if (f.kind === "machine") {
          v.machine = f.value;
          items.push(`Machine: ${f.name}`);
        } else if (f.kind === "program") {
          v.program = f.value;
          items.push(`Program: ${f.name}`);
        }
      }
      kept.values = v;
      const names = jointNames();
      if (names && !(job && job.value.modbus)) kept.values.modbus = withJoints(kept.values.modbus, names);
      redraw();
      setNotes(...items);
    } catch (err) {
      notes.replaceChildren(errorBox(err, "Could not use a file"));
    }
  };

  const clearProblems = () => {
    for (const el of form.querySelectorAll("[aria-invalid]")) el.removeAttribute("aria-invalid");
    for (const el of form.querySelectorAll(".field-error")) {
      el.textContent = "";
      el.hidden = true;
    }
  };

  // Shows each problem at its field; the rest, and a list of all, above the button.
  const showProblems = (problems, title, box = null) => {
    clearProblems();
    const known = [...fields.keys()];
    const unplaced = [];
    let first = null;
    for (const p of problems) {
      let path = fieldFor(p.field, known);
      if (path === null && !kept.jsonMode && p.field && !/^(machine|program|modbus)\b/.test(p.field)) path = "cell";
      const rec = path === null ? null : fields.get(path);
      if (!rec) {
        unplaced.push(p);
        continue;
      }
      const text = p.message.startsWith(`${p.field}: `) ? p.message.slice(p.field.length + 2) : p.message;
      rec.slot.append(h("span", {}, text));
      rec.slot.hidden = false;
      if (rec.control.matches?.("input, select, textarea")) rec.control.setAttribute("aria-invalid", "true");
      p.control = rec.control;
      p.where = [rec.control.closest?.(".reg-row")?.querySelector(".reg-name span")?.textContent,
        form.querySelector(`label[for="${rec.control.id}"]`)?.textContent].filter(Boolean).join(" · ");
      first ??= p;
    }
    const list = h("ul", { class: "problems" }, problems.map((p) => h("li", {},
      p.control
        ? h("button", { type: "button", class: "link", onclick: () => p.control.focus() }, p.where ? `${p.where}: ${p.message}` : p.message)
        : [p.field ? [h("code", {}, p.field), ": "] : null, p.message])));
    summary.replaceChildren(box ?? notice("error", h("strong", {}, title), list));
    return { first, unplaced };
  };

  const currentDoc = () => {
    if (kept.jsonMode) {
      try {
        return parseUserJson(kept.jsonText, "The shadow JSON");
      } catch (err) {
        showProblems([{ field: "", message: err.message }], "The JSON does not parse");
        if (err.line) selectLine(document.getElementById("shadow-json"), err.line, err.column);
        return null;
      }
    }
    const { doc, problems } = docFromValues(values());
    if (!doc) {
      showProblems(problems, "The cell's JSON does not parse");
      const cell = document.getElementById("shadow-cell");
      if (problems[0].line) selectLine(cell, problems[0].line, problems[0].column);
      else cell.focus();
      return null;
    }
    return doc;
  };

  jsonToggle.addEventListener("click", () => {
    summary.replaceChildren();
    if (!kept.jsonMode) {
      const doc = currentDoc();
      if (!doc) return;
      kept.jsonText = prettyJson(doc);
      kept.jsonMode = true;
    } else {
      const doc = currentDoc();
      if (!doc) return;
      if (!doc || typeof doc !== "object" || Array.isArray(doc)) {
        showProblems([{ field: "", message: "The shadow must be a JSON object ({...})." }], "The JSON is not a shadow");
        return;
      }
      kept.values = valuesFromDoc(doc, registry);
      kept.jsonMode = false;
    }
    redraw();
    jsonToggle.focus();
  });

  form.addEventListener("submit", (e) => {
    e.preventDefault();
    busy(start, null, async () => {
      summary.replaceChildren();
      clearProblems();
      const doc = currentDoc();
      if (!doc) return;
      const problems = validateShadow(doc, { jointNames: machineJointNames(doc.machine, registry) });
      if (problems.length) {
        const { first } = showProblems(problems, `Fix ${problems.length === 1 ? "this" : `these ${problems.length}`} before starting`);
        first?.control?.focus();
        return;
      }
      summary.replaceChildren(notice("info", "Starting the shadow…"));
      try {
        const reply = await apiJson("/api/v1/shadows", { method: "POST", json: doc, signal });
        location.hash = hashFor("shadow", { id: reply.id });
      } catch (err) {
        if (isAbort(err, signal)) return;
        // The service's refusal at its field (400 names the path, 422 the program's
        // line), and in full above the button.
        let problems = [];
        if (err?.name === "ApiError" && err.status === 422 && Number.isInteger(err.line)) {
          problems = [{ field: "program", message: `Program line ${err.line}${err.column ? `, column ${err.column}` : ""}: ${err.message.replace(/^program line \d+(, column \d+)?: /i, "")}` }];
        } else if (err?.name === "ApiError" && err.problems?.length) {
          problems = err.problems.map((p) => ({ field: p.field, message: p.message }));
        } else if (err?.name === "ApiError" && err.field) {
          problems = [{ field: err.field, message: err.message }];
        }
        if (problems.length && !kept.jsonMode) {
          const { first } = showProblems(problems, "", errorBox(err, "The service refused the shadow"));
          if (err.status === 422 && Number.isInteger(err.line)) selectLine(document.getElementById("shadow-program"), err.line, err.column ?? 0);
          else first?.control?.focus();
        } else {
          summary.replaceChildren(errorBox(err, "The service refused the shadow"));
        }
      }
    });
  });

  redraw();

  // Registered machines: the machine list, and the joints of a registered machine.
  (async () => {
    try {
      ({ machines: registry } = await apiJson("/api/v1/machines", { signal }));
      const names = jointNames();
      if (names && !kept.jsonMode) values().modbus = withJoints(values().modbus, names);
    } catch (err) {
      if (isAbort(err, signal)) return;
      registryError = true;
      notes.replaceChildren(errorBox(err, "Could not list the machines"));
    }
    if (!signal.aborted) redraw();
  })();
  // Finished jobs whose cell can be reused.
  (async () => {
    try {
      const reply = await apiJson("/api/v1/jobs?limit=50", { signal });
      jobs = reply.jobs.filter((j) => j.status === "done" || j.status === "failed");
    } catch (err) {
      if (isAbort(err, signal)) return;
      jobsError = err;
    }
    // Only the job list changes: what the user is typing stays as it is.
    if (!signal.aborted) document.getElementById("shadow-job")?.replaceChildren(...jobOptions());
  })();

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
