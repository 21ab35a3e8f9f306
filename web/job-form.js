// From what the New check form holds to the job document the service takes:
// pure, so Node tests it. The form keeps the machine and the program apart from
// the rest of the job (tools, stock, fixtures, work offsets, options), because
// that is what a machinist changes: a registered machine or a loaded file, a
// program file or pasted text.

import { InputError, parseUserJson } from "./api-errors.js";
import { prettyJson } from "./format.js";

const PROGRAM_EXTENSIONS = /\.(ngc|nc|tap|gcode|gc|cnc|txt|iso|mpf|eia)$/i;

// What a loaded file is: {kind: "job" | "machine" | "program", value}.
export function classifyFile(name, text) {
  if (PROGRAM_EXTENSIONS.test(name)) return { kind: "program", value: text };
  if (/\.json$/i.test(name) || /^\s*[{[]/.test(text)) {
    const value = parseUserJson(text, name);
    if (!value || typeof value !== "object" || Array.isArray(value)) {
      throw new InputError(`${name} is not a JSON object`);
    }
    if ("tools" in value || "stock" in value || "program" in value || "program_file" in value) {
      return { kind: "job", value };
    }
    if ("joints" in value && ("tool_chain" in value || "workpiece_chain" in value)) {
      return { kind: "machine", value };
    }
    throw new InputError(`${name} is neither a job (it has no tools or stock) nor a machine (no joints and chains)`);
  }
  return { kind: "program", value: text };
}

// Splits a job document into the form's parts. `machine` is a name (string), an
// object, or null; `needs` names the files a command-line job refers to.
export function splitJob(job) {
  const rest = { ...job };
  const machine = rest.machine ?? null;
  const program = typeof rest.program === "string" ? rest.program : null;
  const needs = {};
  if (typeof rest.machine_file === "string") needs.machine_file = rest.machine_file;
  if (typeof rest.program_file === "string") needs.program_file = rest.program_file;
  delete rest.machine;
  delete rest.machine_file;
  delete rest.program;
  delete rest.program_file;
  const options = rest.options && typeof rest.options === "object" ? { ...rest.options } : {};
  return { machine, program, rest, options, needs };
}

// The job to POST. `form`: {jobText, machineMode: "registered" | "json",
// machineName, machineText, programText, density, steps, tolerance} (numbers as
// the inputs' strings; blank keeps the job's value or the service's default).
export function buildJob(form) {
  const jobText = String(form.jobText ?? "").trim();
  const base = jobText === "" ? {} : parseUserJson(jobText, "The job (tools, stock, ...)");
  if (!base || typeof base !== "object" || Array.isArray(base)) {
    throw new InputError("The job (tools, stock, ...) must be a JSON object");
  }
  const { rest, options } = splitJob(base);
  const job = { ...rest };

  if (form.machineMode === "registered") {
    const name = String(form.machineName ?? "").trim();
    if (!name) throw new InputError("Pick a registered machine, or paste the machine's JSON.", { input: "machine" });
    job.machine = name;
  } else {
    const text = String(form.machineText ?? "").trim();
    if (!text) throw new InputError("Paste or load the machine's JSON, or pick a registered machine.", { input: "machine" });
    const machine = parseUserJson(text, "The machine");
    if (!machine || typeof machine !== "object" || Array.isArray(machine)) {
      throw new InputError("The machine must be a JSON object", { input: "machine" });
    }
    job.machine = machine;
  }

  const program = String(form.programText ?? "");
  if (program.trim() === "") throw new InputError("Load or paste the G-code program.", { input: "program" });
  job.program = program;

  const density = numberField(form.density, "Density (points per mm)", (v) => v > 0 && v <= 1000, "a number above 0 and at most 1000");
  const steps = numberField(form.steps, "Steps per move", (v) => Number.isInteger(v) && v >= 0 && v <= 100000, "a whole number from 0 to 100000");
  const tolerance = numberField(form.tolerance, "Tolerance (mm)", (v) => v > 0, "a number above 0");
  if (density !== null) options.density = density;
  if (steps !== null) options.steps = steps;
  if (tolerance !== null) options.tolerance = tolerance;
  if (Object.keys(options).length) job.options = options;
  else delete job.options;

  if (!Array.isArray(job.tools)) throw new InputError("The job needs its tools (a \"tools\" list): load a job file or paste it.", { input: "job" });
  if (!job.stock) throw new InputError("The job needs its stock (\"stock\": {\"box\": ...}): load a job file or paste it.", { input: "job" });
  return job;
}

function numberField(text, label, ok, expected) {
  const s = String(text ?? "").trim();
  if (s === "") return null;
  const v = Number(s);
  if (!Number.isFinite(v) || !ok(v)) throw new InputError(`${label} must be ${expected}, not "${s}".`, { input: label });
  return v;
}

// The form fields a job fills, for the user to see and change.
export function formFromJob(job) {
  const { machine, program, rest, options, needs } = splitJob(job);
  const shown = { ...rest };
  delete shown.options;
  const extra = { ...options };
  delete extra.density;
  delete extra.steps;
  delete extra.tolerance;
  if (Object.keys(extra).length) shown.options = extra;
  return {
    jobText: prettyJson(shown),
    machine,
    program,
    density: options.density ?? "",
    steps: options.steps ?? "",
    tolerance: options.tolerance ?? "",
    needs,
  };
}
