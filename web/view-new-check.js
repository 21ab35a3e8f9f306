// New check: a registered machine or machine JSON; job, machine and program files
// (or pasted text); density, steps, tolerance; submit. Every refusal is shown
// with what the service said, a program error with its line and column marked.
import { h, fill } from "./dom.js";
import { apiJson } from "./api.js";
import { hashFor } from "./router.js";
import { buildJob, classifyFile, formFromJob } from "./job-form.js";
import { InputError } from "./api-errors.js";
import { errorBox, notice, pageHead, busy } from "./ui.js";
import { ProgramView } from "./program-view.js";
import { selectLine } from "./text-select.js";
import { prettyJson } from "./format.js";

// The form's contents outlive a visit to another page (a machinist checks the
// jobs list and comes back to fix the program).
const kept = { jobText: "", machineMode: "registered", machineName: "", machineText: "", programText: "", density: "", steps: "", tolerance: "" };

let uid = 0;
function field(label, control, hint) {
  const id = control.id || (control.id = `f${++uid}`);
  return h("div", { class: "field" }, h("label", { for: id }, label), control, hint ? h("p", { class: "hint", id: `${id}-hint` }, hint) : null);
}

export function renderNewCheck(main, route, signal) {
  document.title = "New check · mdhd";
  const loaded = h("ul", { class: "loaded", "aria-live": "polite" });
  const fileInput = h("input", { type: "file", id: "files", multiple: true, accept: ".json,.ngc,.nc,.tap,.gcode,.txt,.cnc" });
  const dropZone = h("div", { class: "drop" },
    h("label", { for: "files", class: "button" }, "Open files…"), fileInput,
    h("p", { class: "hint" }, "A job (.json), its machine (.json) and its program (.ngc): one, some or all at once. You can also drop them here."));

  const modeRegistered = h("input", { type: "radio", name: "machine-mode", value: "registered", id: "mode-registered" });
  const modeJson = h("input", { type: "radio", name: "machine-mode", value: "json", id: "mode-json" });
  const machineSelect = h("select", { id: "machine-select" }, h("option", { value: "" }, "Loading machines…"));
  const machineText = h("textarea", { id: "machine-json", rows: 8, spellcheck: "false", class: "code-input", placeholder: "{\"joints\": [...], \"tool_chain\": [...], ...}" });
  const machineErrors = h("div", { class: "errors" });
  const registeredBlock = h("div", { class: "sub" }, field("Registered machine", machineSelect));
  const jsonBlock = h("div", { class: "sub" }, field("Machine JSON", machineText, "Paste the machine object of the job format, or open its file above."));

  const programText = h("textarea", { id: "program", rows: 14, spellcheck: "false", class: "code-input", placeholder: "G21 G90 G54\nT1 M6\n…" });
  const programFile = h("input", { type: "file", id: "program-file", accept: ".ngc,.nc,.tap,.gcode,.txt,.cnc" });
  const programInfo = h("p", { class: "hint", "aria-live": "polite" });
  const jobText = h("textarea", { id: "job-json", rows: 10, spellcheck: "false", class: "code-input", placeholder: "{\"tools\": [...], \"stock\": {\"box\": {...}}}" });
  const density = h("input", { id: "density", type: "number", inputmode: "decimal", min: "0", step: "any", placeholder: "10" });
  const steps = h("input", { id: "steps", type: "number", inputmode: "numeric", min: "0", step: "1", placeholder: "0 (adaptive)" });
  const tolerance = h("input", { id: "tolerance", type: "number", inputmode: "decimal", min: "0", step: "any", placeholder: "0.01" });
  const submit = h("button", { type: "submit", class: "primary big", id: "submit-check" }, "Check the program");
  const result = h("div", { class: "submit-result", "aria-live": "polite" });

  const form = h("form", { class: "check-form", novalidate: true },
    h("section", { class: "card" }, h("h2", {}, "1. Files"), dropZone, loaded),
    h("section", { class: "card" }, h("h2", {}, "2. Machine"),
      h("fieldset", { class: "choice" }, h("legend", { class: "visually-hidden" }, "Machine source"),
        h("label", { for: "mode-registered", class: "radio" }, modeRegistered, " A registered machine"),
        h("label", { for: "mode-json", class: "radio" }, modeJson, " Machine JSON")),
      registeredBlock, jsonBlock, machineErrors),
    h("section", { class: "card" }, h("h2", {}, "3. Program"),
      field("G-code", programText), h("div", { class: "row" }, h("label", { for: "program-file", class: "button ghost" }, "Open a program file…"), programFile, programInfo)),
    h("section", { class: "card" }, h("h2", {}, "4. Tools, stock, fixtures"),
      field("Job JSON (everything but the machine and the program)", jobText, "tools, stock, fixtures, work_offsets and any other options.")),
    h("section", { class: "card" }, h("h2", {}, "5. Options"),
      h("div", { class: "options" },
        field("Density (points per mm)", density, "Blank: the job's value or 10."),
        field("Steps per move", steps, "0 or blank: adaptive."),
        field("Tolerance (mm)", tolerance, "Blank: 0.01 mm."))),
    h("div", { class: "submit-bar" }, submit),
    result);

  fill(main, pageHead("New check"), form);

  // Restore and keep the fields.
  const inputs = { jobText, machineText, programText, density, steps, tolerance };
  for (const [k, el] of Object.entries(inputs)) {
    el.value = kept[k];
    el.addEventListener("input", () => {
      kept[k] = el.value;
      if (el === programText) countLines();
    });
  }
  const setMode = (mode) => {
    kept.machineMode = mode;
    modeRegistered.checked = mode === "registered";
    modeJson.checked = mode === "json";
    registeredBlock.hidden = mode !== "registered";
    jsonBlock.hidden = mode !== "json";
  };
  modeRegistered.addEventListener("change", () => setMode("registered"));
  modeJson.addEventListener("change", () => setMode("json"));
  machineSelect.addEventListener("change", () => { kept.machineName = machineSelect.value; });
  setMode(kept.machineMode);
  const countLines = () => {
    const n = programText.value === "" ? 0 : programText.value.replace(/\r?\n$/, "").split(/\r\n|\n/).length;
    programInfo.textContent = n ? `${n} lines` : "";
  };
  countLines();

  // Registered machines.
  (async () => {
    try {
      const { machines } = await apiJson("/api/v1/machines", { signal });
      fill(machineSelect, h("option", { value: "" }, machines.length ? "Choose a machine…" : "No machines registered"),
        machines.map((m) => h("option", { value: m.name }, `${m.name}${m.description ? ` · ${m.description}` : ""} (${(m.joints ?? []).join(" ")})`)));
      machineSelect.value = kept.machineName;
      machineErrors.replaceChildren();
    } catch (err) {
      if (signal.aborted) return;
      fill(machineSelect, h("option", { value: "" }, "Machines not available"));
      machineErrors.replaceChildren(errorBox(err, "Could not list the machines"));
    }
  })();

  // Files.
  const takeFiles = async (files, forceKind = null) => {
    const items = [];
    let job = null;
    const found = {};
    try {
      for (const file of files) {
        const text = await file.text();
        const c = forceKind ? { kind: forceKind, value: text } : classifyFile(file.name, text);
        found[file.name] = c;
        if (c.kind === "job") job = { name: file.name, value: c.value };
      }
    } catch (err) {
      loaded.replaceChildren(h("li", {}, errorBox(err, "Could not use a file")));
      return;
    }
    if (job) {
      const f = formFromJob(job.value);
      jobText.value = kept.jobText = f.jobText;
      density.value = kept.density = String(f.density);
      steps.value = kept.steps = String(f.steps);
      tolerance.value = kept.tolerance = String(f.tolerance);
      if (typeof f.machine === "string") {
        setMode("registered");
        machineSelect.value = kept.machineName = f.machine;
      } else if (f.machine) {
        setMode("json");
        machineText.value = kept.machineText = prettyJson(f.machine);
      }
      if (f.program !== null) programText.value = kept.programText = f.program;
      const needs = Object.values(f.needs).filter((n) => !(n in found));
      items.push(h("li", {}, `Job: ${job.name}`, needs.length
        ? h("span", { class: "warn" }, ` — it names ${needs.join(" and ")}: open ${needs.length > 1 ? "them" : "it"} too${f.needs.machine_file && !(f.needs.machine_file in found) ? ", or pick a registered machine" : ""}.`)
        : null));
    }
    for (const [name, c] of Object.entries(found)) {
      if (c.kind === "machine") {
        setMode("json");
        machineText.value = kept.machineText = prettyJson(c.value);
        items.push(h("li", {}, `Machine: ${name}`));
      } else if (c.kind === "program") {
        programText.value = kept.programText = c.value;
        items.push(h("li", {}, `Program: ${name}`));
      }
    }
    countLines();
    loaded.replaceChildren(...items);
    result.replaceChildren();
  };
  fileInput.addEventListener("change", () => takeFiles([...fileInput.files]));
  programFile.addEventListener("change", () => takeFiles([...programFile.files], "program"));
  dropZone.addEventListener("dragover", (e) => {
    e.preventDefault();
    dropZone.classList.add("over");
  });
  dropZone.addEventListener("dragleave", () => dropZone.classList.remove("over"));
  dropZone.addEventListener("drop", (e) => {
    e.preventDefault();
    dropZone.classList.remove("over");
    takeFiles([...e.dataTransfer.files]);
  });

  // Submit.
  form.addEventListener("submit", (e) => {
    e.preventDefault();
    busy(submit, null, async () => {
      result.replaceChildren(notice("info", "Sending the job…"));
      let job;
      try {
        job = buildJob({ ...kept, machineName: machineSelect.value });
      } catch (err) {
        result.replaceChildren(errorBox(err, "The job is not complete"));
        focusInput(err);
        return;
      }
      try {
        const reply = await apiJson("/api/v1/jobs", { method: "POST", json: job, signal });
        location.hash = hashFor("job", { id: reply.id });
      } catch (err) {
        if (signal.aborted) return;
        const box = errorBox(err, err?.status === 422 ? "The program does not interpret" : "The service refused the job");
        result.replaceChildren(box);
        if (err?.status === 422 && Number.isInteger(err.line) && err.line > 0) showProgramError(err, job.program);
        result.scrollIntoView({ block: "nearest" });
      }
    });
  });

  const focusInput = (err) => {
    if (!(err instanceof InputError)) return;
    const target = { machine: kept.machineMode === "json" ? machineText : machineSelect, program: programText, job: jobText }[err.input];
    if (err.line && /machine/i.test(err.message)) selectLine(machineText, err.line);
    else if (err.line && /job/i.test(err.message)) selectLine(jobText, err.line);
    else target?.focus();
  };

  const showProgramError = (err, text) => {
    const view = new ProgramView(text, { label: "Program with the error" });
    const goto = h("button", { type: "button", class: "ghost" }, `Go to line ${err.line} in the editor`);
    goto.addEventListener("click", () => selectLine(programText, err.line, err.column));
    result.append(h("div", { class: "card program-error" }, h("h3", {}, `Line ${err.line}${err.column ? `, column ${err.column}` : ""}`), view.el, goto));
    view.highlight(err.line, err.column ?? 0);
    signal.addEventListener("abort", () => view.destroy());
  };
}
