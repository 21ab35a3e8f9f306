import { test } from "node:test";
import assert from "node:assert/strict";
import {
  applyJob, defaultModbusValues, docFromValues, fieldFor, machineJointNames,
  textOf, validateShadow, valueOf, valuesFromDoc, withJoints,
} from "../shadow-form.js";

// The service contract's example (service.md), with a cell.
const SPEC_MODBUS = {
  host: "127.0.0.1", port: 502, unit_id: 1,
  poll_hz: 50, timeout_ms: 200,
  table: "holding",
  joints: {
    X: { address: 0, type: "float32", word_order: "abcd", scale: 1.0 },
    Y: { address: 2, type: "float32" },
    Z: { address: 4, type: "float32" },
    A: { address: 6, type: "float32" },
    C: { address: 8, type: "float32" },
  },
  tool: { address: 10, type: "uint16" },
  spindle_on: { address: 11, type: "uint16" },
  line: { address: 12, type: "uint32" },
  feed_hold: { coil: 0, enabled: false },
};
const CELL = {
  tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 15, length: 50 }],
  stock: { box: { min: [0, 0, -40], max: [100, 80, 0] } },
  options: { density: 5 },
};
const REGISTRY = [
  { name: "3axis-mill", joints: ["X", "Y", "Z"] },
  { name: "ac-trunnion", joints: ["X", "Y", "Z", "A", "C"] },
];
const AC = ["X", "Y", "Z", "A", "C"];
const MACHINE_3 = {
  name: "3-axis vertical mill",
  joints: [{ name: "X", type: "linear", axis: [1, 0, 0] }, { name: "Y", type: "linear", axis: [0, 1, 0] }, { name: "Z", type: "linear", axis: [0, 0, 1] }],
  tool_chain: ["X", "Y", "Z"], workpiece_chain: [],
};
const spec = () => ({ machine: "ac-trunnion", ...structuredClone(CELL), modbus: structuredClone(SPEC_MODBUS) });
const roundTrip = (doc, registry = REGISTRY) => docFromValues(valuesFromDoc(doc, registry)).doc;

test("the contract's example goes JSON -> form -> JSON unchanged and is valid", () => {
  const doc = spec();
  assert.deepEqual(roundTrip(doc), doc);
  assert.deepEqual(validateShadow(doc, { jointNames: AC }), []);
  const v = valuesFromDoc(doc, REGISTRY);
  assert.deepEqual(v.modbus.joints.map((j) => [j.name, j.address, j.type]), [["X", "0", "float32"], ["Y", "2", "float32"], ["Z", "4", "float32"], ["A", "6", "float32"], ["C", "8", "float32"]]);
  assert.equal(v.modbus.registers.line.type, "uint32");
  assert.equal(v.modbus.host, "127.0.0.1");
  assert.equal(v.modbus.feed_hold.coil, "0");
  assert.equal(v.machine, "ac-trunnion");
});

test("unknown fields at every level survive the form", () => {
  const doc = spec();
  doc.vendor_note = { a: [1, 2] };
  doc.options.chain_tolerance = 0.002;
  doc.fixtures = [{ box: { min: [0, 0, -50], max: [10, 10, -40] } }];
  doc.work_offsets = { G54: [0, 0, 0] };
  doc.modbus.vendor = "fanuc";
  doc.modbus.joints.X.comment = "X axis";
  doc.modbus.tool.bits = 16;
  doc.modbus.feed_hold.pulse_ms = 100;
  doc.program = "G0 X1\nM30\n";
  const back = roundTrip(doc);
  assert.deepEqual(back, doc);
  // And a second time through (form -> JSON -> form -> JSON).
  assert.deepEqual(roundTrip(back), doc);
});

test("form -> JSON -> form keeps every input, mistakes and blanks included", () => {
  const v = valuesFromDoc(spec(), REGISTRY);
  v.modbus.host = "cnc-7.shop";
  v.modbus.port = "";                 // blank: the service's default
  v.modbus.unit_id = "12x";           // a mistake stays as typed
  v.modbus.poll_hz = "12.5";
  v.modbus.table = "input";
  v.modbus.joints[1].word_order = "cdab";
  v.modbus.joints[1].orderGiven = true;
  v.modbus.joints[2].scale = "0.001";
  v.modbus.joints[3].address = "";    // a joint without its address
  v.modbus.registers.tool.address = ""; // not read
  v.modbus.feed_hold = { coil: "3", enabled: true, extra: {} };
  v.program = "G1 X5\n";
  const { doc, problems } = docFromValues(v);
  assert.deepEqual(problems, []);
  assert.equal(doc.modbus.host, "cnc-7.shop");
  assert.ok(!("port" in doc.modbus), "a blank port is left to the service");
  assert.equal(doc.modbus.unit_id, "12x");
  assert.equal(doc.modbus.poll_hz, 12.5);
  assert.equal(doc.modbus.table, "input");
  assert.deepEqual(doc.modbus.joints.Y, { address: 2, type: "float32", word_order: "cdab" });
  assert.deepEqual(doc.modbus.joints.Z, { address: 4, type: "float32", scale: 0.001 });
  assert.deepEqual(doc.modbus.joints.A, { type: "float32" });
  assert.ok(!("tool" in doc.modbus), "a register with a blank address is not read");
  assert.deepEqual(doc.modbus.feed_hold, { coil: 3, enabled: true });
  assert.equal(doc.program, "G1 X5\n");
  const again = valuesFromDoc(doc, REGISTRY);
  for (const k of ["host", "port", "unit_id", "poll_hz", "timeout_ms", "table"]) assert.equal(again.modbus[k], v.modbus[k], k);
  assert.deepEqual(again.modbus.joints.map((j) => [j.name, j.address, j.type, j.word_order, j.scale]),
    v.modbus.joints.map((j) => [j.name, j.address, j.type, j.word_order, j.scale]));
  assert.deepEqual(again.modbus.feed_hold, v.modbus.feed_hold);
  assert.equal(again.modbus.registers.tool.address, "");
  assert.equal(again.program, v.program);
  assert.deepEqual(docFromValues(again).doc, doc);
  // The mistake is flagged at its field, the missing joint address at its row.
  const problems2 = validateShadow(doc, { jointNames: AC });
  assert.deepEqual(problems2.map((p) => p.field), ["modbus.unit_id", "modbus.joints.A.address"]);
  assert.match(problems2[0].message, /Unit id must be a whole number from 0 to 255, not 12x/);
  assert.match(problems2[1].message, /Joint A needs its register address/);
});

test("a 16-bit type has no word order; defaults are left out unless given", () => {
  const v = valuesFromDoc(spec(), REGISTRY);
  v.modbus.joints[0].type = "int16";
  const { doc } = docFromValues(v);
  assert.deepEqual(doc.modbus.joints.X, { address: 0, type: "int16", scale: 1 });
  const w = valuesFromDoc({ machine: "3axis-mill", ...CELL, modbus: { host: "h", joints: { X: { address: 0, type: "float32" } } } }, REGISTRY);
  assert.equal(w.modbus.table, "holding");
  assert.equal(w.modbus.joints[0].word_order, "abcd");
  const back = docFromValues(w).doc.modbus;
  assert.ok(!("table" in back) && !("word_order" in back.joints.X), "no defaults added");
  assert.ok(!("feed_hold" in back), "no feed hold added");
  // The machine's joints the document does not map get rows (blank addresses).
  assert.deepEqual(w.modbus.joints.map((j) => [j.name, j.address]), [["X", "0"], ["Y", ""], ["Z", ""]]);
});

test("text <-> value: numbers become numbers, anything else is kept", () => {
  assert.equal(valueOf(" 12 "), 12);
  assert.equal(valueOf("-1.5e2"), -150);
  assert.equal(valueOf(""), undefined);
  assert.equal(valueOf("0x10"), "0x10");
  assert.equal(valueOf("true"), true);
  assert.equal(textOf(0.1), "0.1");
  assert.equal(textOf(undefined), "");
  assert.equal(textOf(null), "null");
  for (const n of [0, 1, 65535, 0.001, 1e-7, -2.5, 123456789.123]) assert.equal(valueOf(textOf(n)), n);
});

test("a new form: consecutive float32 pairs, then tool, spindle, line, as in the contract", () => {
  const values = { machine: "ac-trunnion", cellText: JSON.stringify(CELL), program: "", modbus: defaultModbusValues(AC) };
  values.modbus.host = "127.0.0.1";
  const { doc } = docFromValues(values);
  assert.deepEqual(doc.modbus, { ...SPEC_MODBUS, joints: { ...SPEC_MODBUS.joints, X: { address: 0, type: "float32" } } });
  assert.ok(!("program" in doc), "no program: none sent");
  assert.deepEqual(validateShadow(doc, { jointNames: AC }), []);
  // Without a host it is refused at the host.
  values.modbus.host = "  ";
  assert.deepEqual(validateShadow(docFromValues(values).doc, { jointNames: AC }).map((p) => p.field), ["modbus.host"]);
});

test("another machine: a default layout is laid out again, a changed one keeps its registers", () => {
  const three = defaultModbusValues(["X", "Y", "Z"]);
  const five = withJoints(three, AC);
  assert.deepEqual(five.joints.map((j) => [j.name, j.address]), [["X", "0"], ["Y", "2"], ["Z", "4"], ["A", "6"], ["C", "8"]]);
  assert.deepEqual(Object.entries(five.registers).map(([k, r]) => [k, r.address]), [["tool", "10"], ["spindle_on", "11"], ["line", "12"]]);
  const custom = defaultModbusValues(["X", "Y", "Z"]);
  custom.joints[2].address = "100";
  custom.joints[2].type = "int32";
  custom.joints[2].word_order = "dcba";
  const moved = withJoints(custom, ["X", "Z", "B"]);
  assert.deepEqual(moved.joints.map((j) => [j.name, j.address, j.type, j.word_order]),
    [["X", "0", "float32", "abcd"], ["Z", "100", "int32", "dcba"], ["B", "102", "float32", "abcd"]]);
  assert.equal(moved.registers.line.address, "8", "the other registers stay");
});

test("the machine's joints: the registry's for a name, the object's own", () => {
  assert.deepEqual(machineJointNames("ac-trunnion", REGISTRY), AC);
  assert.equal(machineJointNames("unknown", REGISTRY), null);
  assert.deepEqual(machineJointNames(MACHINE_3), ["X", "Y", "Z"]);
  assert.equal(machineJointNames(null), null);
});

test("a finished job's cell: its machine, tools, stock and program; the registers follow its joints", () => {
  const form = valuesFromDoc({ machine: "ac-trunnion", ...CELL, modbus: { ...SPEC_MODBUS, host: "10.0.0.5" } }, REGISTRY);
  const job = { machine: MACHINE_3, ...CELL, fixtures: [], program: "G0 X1\nM30\n" };
  const { values, notes } = applyJob(form, job, { registry: REGISTRY });
  assert.deepEqual(notes, []);
  assert.deepEqual(values.machine, MACHINE_3);
  assert.equal(values.program, job.program);
  assert.deepEqual(JSON.parse(values.cellText), { ...CELL, fixtures: [] });
  assert.deepEqual(values.modbus.joints.map((j) => [j.name, j.address]), [["X", "0"], ["Y", "2"], ["Z", "4"]], "the changed joints keep their registers");
  assert.equal(values.modbus.host, "10.0.0.5", "the controller stays");
  const doc = docFromValues(values).doc;
  assert.deepEqual(validateShadow(doc, { jointNames: machineJointNames(doc.machine) }), []);
  // Without its program.
  assert.equal(applyJob(form, job, { registry: REGISTRY, takeProgram: false }).values.program, "");
  // A command-line job names files: they are not sent, the user is told.
  const cli = applyJob(form, { machine_file: "machine-3axis.json", program_file: "crash.ngc", ...CELL }, { registry: REGISTRY });
  assert.equal(cli.values.machine, "ac-trunnion");
  assert.deepEqual(cli.notes.length, 2);
  assert.match(cli.notes[0], /machine-3axis\.json/);
  assert.ok(!/machine_file|program_file/.test(cli.values.cellText));
  // A job file with its own modbus block brings it.
  const withMap = applyJob(form, { machine: "3axis-mill", ...CELL, modbus: { host: "sim", port: 5020, joints: { X: { address: 20, type: "int32" } } } }, { registry: REGISTRY });
  assert.equal(withMap.values.modbus.host, "sim");
  assert.deepEqual(withMap.values.modbus.joints.map((j) => [j.name, j.address]), [["X", "20"], ["Y", ""], ["Z", ""]]);
});

test("the cell's JSON: a mistake is placed; the machine, program or map in it are refused", () => {
  const base = { machine: "3axis-mill", program: "", modbus: defaultModbusValues(["X", "Y", "Z"]) };
  const bad = docFromValues({ ...base, cellText: "{\n  \"tools\": [\n  oops\n}" });
  assert.equal(bad.doc, null);
  assert.equal(bad.problems[0].field, "cell");
  assert.equal(bad.problems[0].line, 3);
  assert.match(bad.problems[0].message, /not valid JSON at line 3, column 3/);
  assert.match(docFromValues({ ...base, cellText: "[1]" }).problems[0].message, /must be a JSON object/);
  assert.match(docFromValues({ ...base, cellText: "{\"modbus\": {}}" }).problems[0].message, /Set "modbus" in its own section/);
  assert.deepEqual(docFromValues({ ...base, cellText: "" }).doc.machine, "3axis-mill");
});

// One problem in an otherwise valid document: [path, message pattern].
function problemsOf(change, jointNames = AC) {
  const doc = spec();
  change(doc);
  return validateShadow(doc, { jointNames }).map((p) => [p.field, p.message]);
}

test("validation: every setting's range, named by the service's path", () => {
  const cases = [
    [(d) => { d.modbus.port = 0; }, "modbus.port", /Port must be a whole number from 1 to 65535, not 0/],
    [(d) => { d.modbus.port = 65536; }, "modbus.port", /not 65536/],
    [(d) => { d.modbus.port = 502.5; }, "modbus.port", /whole number/],
    [(d) => { d.modbus.unit_id = 256; }, "modbus.unit_id", /0 to 255/],
    [(d) => { d.modbus.poll_hz = 0.05; }, "modbus.poll_hz", /from 0.1 to 1000, not 0.05/],
    [(d) => { d.modbus.poll_hz = 1001; }, "modbus.poll_hz", /not 1001/],
    [(d) => { d.modbus.timeout_ms = 0; }, "modbus.timeout_ms", /1 to 60000/],
    [(d) => { d.modbus.host = ""; }, "modbus.host", /Enter the controller's host/],
    [(d) => { d.modbus.host = "cnc 7"; }, "modbus.host", /no spaces/],
    [(d) => { d.modbus.host = "h".repeat(254); }, "modbus.host", /254 characters long/],
    [(d) => { d.modbus.table = "coils"; }, "modbus.table", /holding or input, not coils/],
    [(d) => { d.modbus.feed_hold = { enabled: true }; }, "modbus.feed_hold.coil", /feed-hold coil/],
    [(d) => { d.modbus.feed_hold.coil = 70000; }, "modbus.feed_hold.coil", /0 to 65535, not 70000/],
    [(d) => { d.modbus.feed_hold.enabled = "yes"; }, "modbus.feed_hold.enabled", /true or false/],
    [(d) => { delete d.machine; }, "machine", /Pick a machine/],
    [(d) => { delete d.tools; }, "tools", /needs its tools/],
    [(d) => { d.program = 5; }, "program", /must be text/],
  ];
  for (const [change, field, pattern] of cases) {
    const found = problemsOf(change);
    assert.equal(found.length, 1, `${field}: ${JSON.stringify(found)}`);
    assert.equal(found[0][0], field);
    assert.match(found[0][1], pattern);
  }
  assert.deepEqual(validateShadow({ machine: "m", ...CELL }).map((p) => p.field), ["modbus"]);
});

test("validation: registers (address 0..65535, type, word order, scale) and joints against the machine", () => {
  const cases = [
    [(d) => { d.modbus.joints.Y.address = -1; }, "modbus.joints.Y.address", /whole number from 0 to 65535, not -1/],
    [(d) => { d.modbus.joints.Y.address = 65536; }, "modbus.joints.Y.address", /not 65536/],
    [(d) => { d.modbus.joints.Y.address = 2.5; }, "modbus.joints.Y.address", /not 2.5/],
    [(d) => { d.modbus.joints.Y.address = "2x"; }, "modbus.joints.Y.address", /not 2x/],
    [(d) => { d.modbus.joints.C.address = 65535; }, "modbus.joints.C.address", /A float32 at 65535 needs registers 65535..65536: the last register is 65535/],
    [(d) => { delete d.modbus.joints.Y.address; }, "modbus.joints.Y.address", /Joint Y needs its register address/],
    [(d) => { d.modbus.joints.Y.type = "float64"; }, "modbus.joints.Y.type", /one of float32, int32, uint32, int16, uint16, not float64/],
    [(d) => { d.modbus.joints.Y.word_order = "abdc"; }, "modbus.joints.Y.word_order", /one of abcd, badc, cdab, dcba/],
    [(d) => { d.modbus.tool.word_order = "abcd"; }, "modbus.tool.word_order", /32-bit types only, not to uint16/],
    [(d) => { d.modbus.joints.Y.scale = 0; }, "modbus.joints.Y.scale", /other than 0/],
    [(d) => { delete d.modbus.joints.C; }, "modbus.joints.C.address", /Joint C needs its register address: every joint is read/],
    [(d) => { d.modbus.joints.B = { address: 20, type: "float32" }; }, "modbus.joints.B", /The machine has no joint B \(it has X Y Z A C\)/],
    [(d) => { d.modbus.joints.Q = { address: 20, type: "float32" }; }, "modbus.joints.Q", /Q is not a joint name/],
    [(d) => { d.modbus.tool = 7; }, "modbus.tool", /Tool number: give its register/],
  ];
  for (const [change, field, pattern] of cases) {
    const found = problemsOf(change);
    assert.equal(found.length, 1, `${field}: ${JSON.stringify(found)}`);
    assert.equal(found[0][0], field);
    assert.match(found[0][1], pattern);
  }
  // An unknown machine (a name the registry lacks): its joints are not checked.
  const doc = spec();
  doc.modbus.joints.B = { address: 20, type: "float32" };
  assert.deepEqual(validateShadow(doc, { jointNames: null }), []);
});

test("validation: overlapping registers are named at both fields, 32-bit spans counted", () => {
  // Y (a float32 at 1) takes registers 1..2; X holds 0..1.
  const y = problemsOf((d) => { d.modbus.joints.Y.address = 1; });
  assert.deepEqual(y, [
    ["modbus.joints.Y.address", "Registers 1..2 overlap joint X (registers 0..1)."],
    ["modbus.joints.X.address", "Registers 0..1 overlap joint Y (registers 1..2)."],
  ]);
  // The line (uint32 at 12, 12..13) against the tool moved to 13.
  const t = problemsOf((d) => { d.modbus.tool.address = 13; });
  assert.deepEqual(t.map((p) => p[0]), ["modbus.tool.address", "modbus.line.address"]);
  assert.match(t[0][1], /Register 13 overlaps the program line \(registers 12..13\)/);
  // Three on one register: every pair.
  const three = problemsOf((d) => { d.modbus.tool.address = 11; d.modbus.line.type = "uint16"; d.modbus.line.address = 11; delete d.modbus.line.word_order; });
  assert.equal(three.length, 6);
  // Touching is not overlapping: a float32 at 0 and a uint16 at 2.
  assert.deepEqual(problemsOf((d) => { d.modbus.joints.Y.type = "uint16"; }), []);
  // Problems at several fields are all reported: Y at 3..4 overlaps Z at 4..5 (two), and the tool's scale.
  assert.equal(problemsOf((d) => { d.modbus.joints.Y.address = 3; d.modbus.tool.scale = 0; }).length, 3);
});

test("a problem's path finds its field: itself or the nearest enclosing one", () => {
  const known = ["cell", "tools", "machine", "modbus", "modbus.joints", "modbus.joints.X", "modbus.joints.X.address", "modbus.host"];
  assert.equal(fieldFor("modbus.joints.X.address", known), "modbus.joints.X.address");
  assert.equal(fieldFor("modbus.joints.X", known), "modbus.joints.X");
  assert.equal(fieldFor("modbus.joints.Y.address", known), "modbus.joints");
  assert.equal(fieldFor("tools[0].diameter", known), "tools");
  assert.equal(fieldFor("tools[0].holder[1].length", known), "tools");
  assert.equal(fieldFor("modbus.extra", known), "modbus");
  assert.equal(fieldFor("stock.box", known), null);
  assert.equal(fieldFor("", known), null);
});
