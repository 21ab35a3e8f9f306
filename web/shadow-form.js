// The "start a shadow" form and its document (POST /api/v1/shadows): pure, so
// Node tests it. The form's values hold every input as the user typed it (text),
// and whatever the form has no input for (unknown fields) rides along, so
//   docFromValues(valuesFromDoc(doc))  keeps the document, and
//   valuesFromDoc(docFromValues(v))    keeps the form.
// A blank input leaves its key out (the service's default). validateShadow
// checks the document as the service does and names each problem by the path
// the service's 400 would use ("modbus.joints.X.address"), so both are shown at
// the same field.

import { parseUserJson } from "./api-errors.js";
import { prettyJson } from "./format.js";

export const REGISTER_TYPES = ["float32", "int32", "uint32", "int16", "uint16"];
export const WORD_ORDERS = ["abcd", "badc", "cdab", "dcba"];
export const TABLES = ["holding", "input"];
export const JOINT_NAMES = ["X", "Y", "Z", "A", "B", "C", "U", "V", "W"];
// The optional registers, their label and their type when the form adds them.
export const EXTRA_REGISTERS = [
  { key: "tool", label: "Tool number", type: "uint16" },
  { key: "spindle_on", label: "Spindle on", type: "uint16" },
  { key: "line", label: "Program line", type: "uint32" },
];
// The service's defaults for a key left out (what a blank input means).
export const DEFAULTS = { port: 502, unit_id: 1, poll_hz: 50, timeout_ms: 200, table: "holding", word_order: "abcd", scale: 1 };
export const SETTINGS = [
  { key: "host", label: "Controller host", min: null, max: null },
  { key: "port", label: "Port", min: 1, max: 65535, integer: true },
  { key: "unit_id", label: "Unit id", min: 0, max: 255, integer: true },
  { key: "poll_hz", label: "Polls per second", min: 0.1, max: 1000, integer: false },
  { key: "timeout_ms", label: "Timeout (ms)", min: 1, max: 60000, integer: true },
];
const MODBUS_KEYS = ["host", "port", "unit_id", "poll_hz", "timeout_ms", "table", "joints", "tool", "spindle_on", "line", "feed_hold"];
const REGISTER_KEYS = ["address", "type", "word_order", "scale"];
// Top-level keys the form shows in their own sections; the rest is "the cell".
const OWN_KEYS = ["machine", "program", "modbus"];
const MAX_HOST = 253;

export function registerCount(type) {
  return type === "int16" || type === "uint16" ? 1 : 2;
}
export function is32(type) {
  return type === "float32" || type === "int32" || type === "uint32";
}

const isObject = (v) => v !== null && typeof v === "object" && !Array.isArray(v);
const clone = (v) => (v === undefined ? undefined : JSON.parse(JSON.stringify(v)));
const NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

// A value as an input shows it, and back: numbers as numbers, anything else kept
// as it was (so a mistake shows, is flagged, and survives the round trip).
export function textOf(v) {
  if (v === undefined) return "";
  if (typeof v === "string") return v;
  if (typeof v === "number") return String(v);
  return JSON.stringify(v);
}
export function valueOf(text) {
  const s = String(text ?? "").trim();
  if (s === "") return undefined;
  if (NUMBER.test(s)) {
    const n = Number(s);
    if (Number.isFinite(n)) return n;
  }
  if (s === "true" || s === "false" || s === "null") return JSON.parse(s);
  return s;
}

function pick(obj, known) {
  const extra = {};
  if (isObject(obj)) for (const [k, v] of Object.entries(obj)) if (!known.includes(k)) extra[k] = clone(v);
  return extra;
}

// --- form values -------------------------------------------------------------

function registerValues(j, defaultType) {
  const r = isObject(j) ? j : {};
  return {
    address: textOf(r.address),
    type: typeof r.type === "string" ? r.type : r.type === undefined ? defaultType : textOf(r.type),
    word_order: typeof r.word_order === "string" ? r.word_order : DEFAULTS.word_order,
    orderGiven: "word_order" in r,
    scale: textOf(r.scale),
    extra: pick(r, REGISTER_KEYS),
  };
}

function registerJson(e, optional) {
  const out = {};
  const address = valueOf(e.address);
  const scale = valueOf(e.scale);
  const hasExtra = Object.keys(e.extra ?? {}).length > 0;
  if (optional && address === undefined && scale === undefined && !hasExtra && !e.orderGiven) return undefined;
  if (address !== undefined) out.address = address;
  if (e.type !== "") out.type = e.type;
  // A 16-bit type has no word order (the service refuses one): the form drops it.
  if (is32(e.type) && (e.orderGiven || e.word_order !== DEFAULTS.word_order)) out.word_order = e.word_order;
  if (!is32(e.type) && !REGISTER_TYPES.includes(e.type) && e.orderGiven) out.word_order = e.word_order;
  if (scale !== undefined) out.scale = scale;
  return Object.assign(out, clone(e.extra ?? {}));
}

// Default registers for a machine's joints: consecutive float32 pairs from 0,
// then the tool (uint16), spindle on (uint16) and program line (uint32), as the
// service's example and `mdhd modbus-sim` lay them out.
export function defaultRegisters(jointNames) {
  let address = 0;
  const joints = jointNames.map((name) => {
    const e = { name, ...registerValues({ address, type: "float32" }, "float32") };
    address += 2;
    return e;
  });
  const registers = {};
  for (const { key, type } of EXTRA_REGISTERS) {
    registers[key] = registerValues({ address, type }, type);
    address += registerCount(type);
  }
  return { joints, registers };
}

// The form for a new shadow on a machine with these joints.
export function defaultModbusValues(jointNames) {
  return {
    host: "", port: "502", unit_id: "1", poll_hz: "50", timeout_ms: "200",
    table: "holding", tableGiven: true,
    ...defaultRegisters(jointNames),
    feed_hold: { coil: "0", enabled: false, extra: {} },
    extra: {},
  };
}

function modbusValues(m, jointNames) {
  if (!isObject(m)) return defaultModbusValues(jointNames ?? []);
  const v = {
    table: typeof m.table === "string" ? m.table : m.table === undefined ? DEFAULTS.table : textOf(m.table),
    tableGiven: "table" in m,
    joints: [],
    registers: {},
    feed_hold: { coil: textOf(m.feed_hold?.coil), enabled: m.feed_hold?.enabled === true, extra: pick(m.feed_hold, ["coil", "enabled"]) },
    extra: pick(m, MODBUS_KEYS),
  };
  for (const s of SETTINGS) v[s.key] = textOf(m[s.key]);
  if (m.feed_hold !== undefined && !isObject(m.feed_hold)) v.extra.feed_hold = clone(m.feed_hold);
  if (m.joints !== undefined && !isObject(m.joints)) v.extra.joints = clone(m.joints);
  const given = isObject(m.joints) ? m.joints : {};
  // The machine's joints first, in its order, then any the document maps that
  // the machine does not have (validateShadow flags them).
  const names = [...(jointNames ?? []), ...Object.keys(given).filter((n) => !(jointNames ?? []).includes(n))];
  for (const name of names) v.joints.push({ name, ...registerValues(given[name], "float32") });
  for (const { key, type } of EXTRA_REGISTERS) {
    v.registers[key] = registerValues(m[key], type);
    if (m[key] !== undefined && !isObject(m[key])) v.extra[key] = clone(m[key]);
  }
  return v;
}

function modbusJson(v) {
  const out = {};
  const host = String(v.host ?? "").trim();
  if (host !== "") out.host = host;
  for (const s of SETTINGS.slice(1)) {
    const x = valueOf(v[s.key]);
    if (x !== undefined) out[s.key] = x;
  }
  if (v.tableGiven || v.table !== DEFAULTS.table) out.table = v.table;
  out.joints = {};
  for (const j of v.joints) out.joints[j.name] = registerJson(j, false);
  for (const { key } of EXTRA_REGISTERS) {
    const r = v.registers[key] ? registerJson(v.registers[key], true) : undefined;
    if (r !== undefined) out[key] = r;
  }
  const fh = v.feed_hold;
  const coil = valueOf(fh.coil);
  if (coil !== undefined || fh.enabled || Object.keys(fh.extra ?? {}).length) {
    out.feed_hold = {};
    if (coil !== undefined) out.feed_hold.coil = coil;
    out.feed_hold.enabled = fh.enabled === true;
    Object.assign(out.feed_hold, clone(fh.extra ?? {}));
  }
  return Object.assign(out, clone(v.extra ?? {}));
}

// The joint names of a machine: a registered one's from the registry list
// (GET /api/v1/machines: [{name, joints: ["X", ...]}]), an inline one's from its
// joints. null when not known (a name the registry does not hold).
export function machineJointNames(machine, registry = []) {
  if (typeof machine === "string") {
    const m = registry.find((r) => r.name === machine);
    return m && Array.isArray(m.joints) ? m.joints.map(String) : null;
  }
  if (isObject(machine) && Array.isArray(machine.joints)) {
    return machine.joints.map((j) => (isObject(j) && typeof j.name === "string" ? j.name : null)).filter((n) => n !== null);
  }
  return null;
}

// The form's values for a shadow document. `registry` tells a registered
// machine's joints.
export function valuesFromDoc(doc, registry = []) {
  const d = isObject(doc) ? doc : {};
  const cell = {};
  for (const [k, v] of Object.entries(d)) if (!OWN_KEYS.includes(k)) cell[k] = clone(v);
  return {
    machine: d.machine === undefined ? null : clone(d.machine),
    cellText: prettyJson(cell),
    program: typeof d.program === "string" ? d.program : "",
    programExtra: d.program !== undefined && typeof d.program !== "string" ? clone(d.program) : undefined,
    modbus: modbusValues(d.modbus, machineJointNames(d.machine, registry)),
  };
}

// The document the form says, or {problems} when the cell's JSON does not parse.
export function docFromValues(values) {
  let cell;
  try {
    const text = String(values.cellText ?? "").trim();
    cell = text === "" ? {} : parseUserJson(text, "The cell (tools, stock, ...)");
  } catch (err) {
    return { doc: null, problems: [{ field: "cell", message: err.message, line: err.line, column: err.column }] };
  }
  if (!isObject(cell)) {
    return { doc: null, problems: [{ field: "cell", message: "The cell (tools, stock, ...) must be a JSON object: {\"tools\": [...], \"stock\": {...}}" }] };
  }
  const misplaced = OWN_KEYS.filter((k) => k in cell);
  if (misplaced.length) {
    return { doc: null, problems: [{ field: "cell", message: `Set ${misplaced.map((k) => `"${k}"`).join(" and ")} in ${misplaced.length > 1 ? "their" : "its"} own section, not in the cell's JSON.` }] };
  }
  const doc = {};
  if (values.machine !== null && values.machine !== undefined && values.machine !== "") doc.machine = clone(values.machine);
  Object.assign(doc, cell);
  if (values.program !== "") doc.program = values.program;
  else if (values.programExtra !== undefined) doc.program = clone(values.programExtra);
  doc.modbus = modbusJson(values.modbus);
  return { doc, problems: [] };
}

// The joints' registers for another machine. A map still laid out by default is
// laid out again for the new joints; one the user changed keeps every register of
// a joint both machines have, and a new joint gets the next free float32 pair.
export function withJoints(modbus, jointNames) {
  const m = clone(modbus);
  const current = m.joints.map((j) => j.name);
  const layout = defaultRegisters(current);
  if (JSON.stringify({ joints: m.joints, registers: m.registers }) === JSON.stringify(layout)) {
    Object.assign(m, defaultRegisters(jointNames));
    return m;
  }
  const kept = m.joints.filter((j) => jointNames.includes(j.name));
  let next = 0;
  for (const e of [...kept, ...Object.values(m.registers)]) {
    const a = valueOf(e.address);
    if (Number.isInteger(a)) next = Math.max(next, a + registerCount(e.type));
  }
  m.joints = jointNames.map((name) => {
    const have = kept.find((j) => j.name === name);
    if (have) return have;
    const e = { name, ...registerValues({ address: next, type: "float32" }, "float32") };
    next += 2;
    return e;
  });
  return m;
}

// What a loaded job (a file, or a finished job's document) puts in the form:
// its machine, its cell, its program when `takeProgram`, its modbus block if it
// has one. `notes`: what the user must still do (a CLI job names files).
export function applyJob(values, job, { registry = [], takeProgram = true } = {}) {
  const v = clone(values);
  const notes = [];
  const cell = {};
  for (const [k, x] of Object.entries(job)) {
    if (!OWN_KEYS.includes(k) && k !== "machine_file" && k !== "program_file") cell[k] = clone(x);
  }
  v.cellText = prettyJson(cell);
  if (job.machine !== undefined) v.machine = clone(job.machine);
  else if (typeof job.machine_file === "string") notes.push(`The job names its machine file ${job.machine_file}: open it too, or pick a registered machine.`);
  if (takeProgram && typeof job.program === "string") v.program = job.program;
  else if (takeProgram && typeof job.program_file === "string") notes.push(`The job names its program file ${job.program_file}: open it too if the machine runs it (the program is optional).`);
  const names = machineJointNames(v.machine, registry);
  if (isObject(job.modbus)) v.modbus = modbusValues(job.modbus, names);
  else if (names) v.modbus = withJoints(v.modbus, names);
  return { values: v, notes };
}

// --- validation --------------------------------------------------------------

function integerProblem(v, min, max, label) {
  if (v === undefined) return null;
  if (typeof v !== "number" || !Number.isInteger(v) || v < min || v > max) {
    return `${label} must be a whole number from ${min} to ${max}, not ${textOf(v)}.`;
  }
  return null;
}

function registersText(address, type) {
  const n = registerCount(type);
  return n === 1 ? `register ${address}` : `registers ${address}..${address + n - 1}`;
}

// Problems with the document, as [{field, message}], in the form's order. `jointNames`:
// the machine's joints when known (null: not checked against the machine).
export function validateShadow(doc, { jointNames = null } = {}) {
  const problems = [];
  const add = (field, message) => problems.push({ field, message });
  if (!isObject(doc)) {
    add("", "The shadow must be a JSON object.");
    return problems;
  }
  if (doc.machine === undefined || doc.machine === "" || doc.machine === null) add("machine", "Pick a machine.");
  else if (typeof doc.machine !== "string" && !isObject(doc.machine)) add("machine", "The machine is a registered machine's name or a machine object.");
  if (!Array.isArray(doc.tools)) add("tools", "The cell needs its tools (a \"tools\" list): reuse a job's cell or load a job file.");
  if (!isObject(doc.stock)) add("stock", "The cell needs its stock (\"stock\": {\"box\": ...}).");
  if (doc.program !== undefined && typeof doc.program !== "string") add("program", "The program must be text.");

  const m = doc.modbus;
  if (!isObject(m)) {
    add("modbus", "The shadow needs the controller's register map (\"modbus\").");
    return problems;
  }
  const host = m.host;
  if (host === undefined || host === "") add("modbus.host", "Enter the controller's host name or IP address.");
  else if (typeof host !== "string") add("modbus.host", "The host must be text (a name or an IP address).");
  else if (host.length > MAX_HOST) add("modbus.host", `The host is ${host.length} characters long: a host name or address has at most ${MAX_HOST}.`);
  // eslint-disable-next-line no-control-regex
  else if (/[\u0000-\u0020\u007f]/.test(host)) add("modbus.host", "A host name or address has no spaces or control characters.");
  for (const s of SETTINGS.slice(1)) {
    const v = m[s.key];
    if (v === undefined) continue;
    if (s.integer) {
      const p = integerProblem(v, s.min, s.max, s.label);
      if (p) add(`modbus.${s.key}`, p);
    } else if (typeof v !== "number" || !(v >= s.min && v <= s.max)) {
      add(`modbus.${s.key}`, `${s.label} must be a number from ${s.min} to ${s.max}, not ${textOf(v)}.`);
    }
  }
  if (m.table !== undefined && !TABLES.includes(m.table)) add("modbus.table", `The table is holding or input, not ${textOf(m.table)}.`);

  // Each register: address, type, word order, scale; then overlaps between them.
  const placed = [];
  const checkRegister = (path, label, ref, r) => {
    if (!isObject(r)) {
      add(path, `${label}: give its register (address and type).`);
      return;
    }
    const typeOk = REGISTER_TYPES.includes(r.type);
    if (r.type === undefined) add(`${path}.type`, `${label}: choose its type.`);
    else if (!typeOk) add(`${path}.type`, `The type is one of ${REGISTER_TYPES.join(", ")}, not ${textOf(r.type)}.`);
    const a = r.address;
    if (a === undefined) add(`${path}.address`, `${label} needs its register address.`);
    else if (typeof a !== "number" || !Number.isInteger(a) || a < 0 || a > 65535) add(`${path}.address`, `The address must be a whole number from 0 to 65535, not ${textOf(a)}.`);
    else if (typeOk && a + registerCount(r.type) - 1 > 65535) add(`${path}.address`, `A ${r.type} at ${a} needs ${registersText(a, r.type)}: the last register is 65535.`);
    else if (typeOk) placed.push({ path, ref, address: a, type: r.type });
    if (r.word_order !== undefined) {
      if (!WORD_ORDERS.includes(r.word_order)) add(`${path}.word_order`, `The word order is one of ${WORD_ORDERS.join(", ")}, not ${textOf(r.word_order)}.`);
      else if (typeOk && !is32(r.type)) add(`${path}.word_order`, `A word order applies to 32-bit types only, not to ${r.type}.`);
    }
    if (r.scale !== undefined && (typeof r.scale !== "number" || !Number.isFinite(r.scale) || r.scale === 0)) {
      add(`${path}.scale`, `The scale must be a number other than 0, not ${textOf(r.scale)}.`);
    }
  };

  if (!isObject(m.joints)) add("modbus.joints", "Map each of the machine's joints to its register.");
  else {
    const names = Object.keys(m.joints);
    if (names.length === 0) add("modbus.joints", "Map at least one joint.");
    for (const name of names) {
      const path = `modbus.joints.${name}`;
      if (!JOINT_NAMES.includes(name)) add(path, `${name} is not a joint name (${JOINT_NAMES.join(" ")}).`);
      else if (jointNames && !jointNames.includes(name)) add(path, `The machine has no joint ${name} (it has ${jointNames.join(" ")}).`);
      checkRegister(path, `Joint ${name}`, `joint ${name}`, m.joints[name]);
    }
    for (const name of jointNames ?? []) {
      if (!names.includes(name)) add(`modbus.joints.${name}.address`, `Joint ${name} needs its register address: every joint is read for the pose.`);
    }
  }
  for (const { key, label } of EXTRA_REGISTERS) {
    if (m[key] !== undefined) checkRegister(`modbus.${key}`, label, `the ${label.toLowerCase()}`, m[key]);
  }

  const sorted = [...placed].sort((a, b) => a.address - b.address);
  for (let i = 0; i < sorted.length; i++) {
    for (let k = i + 1; k < sorted.length && sorted[k].address < sorted[i].address + registerCount(sorted[i].type); k++) {
      const a = sorted[i], b = sorted[k];
      add(`${b.path}.address`, `${overlapText(b)} ${a.ref} (${registersText(a.address, a.type)}).`);
      add(`${a.path}.address`, `${overlapText(a)} ${b.ref} (${registersText(b.address, b.type)}).`);
    }
  }

  if (m.feed_hold !== undefined) {
    const fh = m.feed_hold;
    if (!isObject(fh)) add("modbus.feed_hold", "Feed hold is {\"coil\": N, \"enabled\": true|false}.");
    else {
      if (fh.coil === undefined) add("modbus.feed_hold.coil", "Give the feed-hold coil's address.");
      else {
        const p = integerProblem(fh.coil, 0, 65535, "The coil");
        if (p) add("modbus.feed_hold.coil", p);
      }
      if (fh.enabled !== undefined && typeof fh.enabled !== "boolean") add("modbus.feed_hold.enabled", "Enabled is true or false.");
    }
  }
  return problems;
}

function overlapText(r) {
  const text = registersText(r.address, r.type);
  return `${text.charAt(0).toUpperCase()}${text.slice(1)} ${registerCount(r.type) === 1 ? "overlaps" : "overlap"}`;
}

// The field of the form a problem's path belongs to: the longest of `known`
// that is the path or a prefix of it ("tools[0].diameter" -> "tools",
// "modbus.extra" -> "modbus"); null when none is.
export function fieldFor(path, known) {
  let p = String(path ?? "");
  for (;;) {
    if (known.includes(p)) return p;
    const cut = Math.max(p.lastIndexOf("."), p.lastIndexOf("["));
    if (cut <= 0) return null;
    p = p.slice(0, cut);
  }
}
