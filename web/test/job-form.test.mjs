import { test } from "node:test";
import assert from "node:assert/strict";
import { classifyFile, splitJob, buildJob, formFromJob } from "../job-form.js";
import { InputError } from "../api-errors.js";

const JOB = {
  machine_file: "machine-3axis.json",
  tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 15, length: 50 }],
  stock: { box: { min: [0, 0, -40], max: [100, 80, 0] } },
  program_file: "crash-3axis.ngc",
  options: { density: 5, chain_tolerance: 0.002 },
};
const MACHINE = { name: "m", joints: [{ name: "X", type: "linear", axis: [1, 0, 0] }], tool_chain: ["X"], workpiece_chain: [] };

test("loaded files are told apart: job, machine, program", () => {
  assert.equal(classifyFile("crash-3axis.json", JSON.stringify(JOB)).kind, "job");
  assert.equal(classifyFile("machine-3axis.json", JSON.stringify(MACHINE)).kind, "machine");
  assert.deepEqual(classifyFile("crash-3axis.ngc", "G0 X1\n"), { kind: "program", value: "G0 X1\n" });
  assert.equal(classifyFile("PART.NC", "{ not json").kind, "program");
  assert.equal(classifyFile("program", "G0 X1").kind, "program");
  assert.throws(() => classifyFile("x.json", "{\"a\": 1}"), (e) => e instanceof InputError && /neither a job/.test(e.message));
  assert.throws(() => classifyFile("x.json", "[1]"), /not a JSON object/);
  assert.throws(() => classifyFile("x.json", "{\n\"a\": }"), (e) => e.line === 2 && /x.json is not valid JSON at line 2/.test(e.message));
});

test("splitJob takes machine and program apart and names the files a CLI job needs", () => {
  const s = splitJob(JOB);
  assert.equal(s.machine, null);
  assert.equal(s.program, null);
  assert.deepEqual(s.needs, { machine_file: "machine-3axis.json", program_file: "crash-3axis.ngc" });
  assert.ok(!("machine_file" in s.rest) && !("program_file" in s.rest));
  assert.deepEqual(s.options, { density: 5, chain_tolerance: 0.002 });
});

test("formFromJob fills the option inputs and keeps the other options in the job text", () => {
  const form = formFromJob({ ...JOB, machine: "3axis-mill", program: "M30\n" });
  assert.equal(form.density, 5);
  assert.equal(form.steps, "");
  assert.equal(form.machine, "3axis-mill");
  assert.equal(form.program, "M30\n");
  const shown = JSON.parse(form.jobText);
  assert.deepEqual(shown.options, { chain_tolerance: 0.002 });
  assert.ok(!("program_file" in shown) && !("machine" in shown));
});

test("buildJob: a registered machine, the program, and the options merged", () => {
  const form = formFromJob(JOB);
  const job = buildJob({ jobText: form.jobText, machineMode: "registered", machineName: "3axis-mill", programText: "M30\n",
    density: "10", steps: "", tolerance: "0.02" });
  assert.equal(job.machine, "3axis-mill");
  assert.equal(job.program, "M30\n");
  assert.deepEqual(job.options, { chain_tolerance: 0.002, density: 10, tolerance: 0.02 });
  assert.deepEqual(job.tools, JOB.tools);
  assert.ok(!("machine_file" in job) && !("program_file" in job));
});

test("buildJob: an inline machine; no options at all leaves none", () => {
  const job = buildJob({ jobText: JSON.stringify({ tools: [], stock: { box: {} } }), machineMode: "json",
    machineText: JSON.stringify(MACHINE), programText: "M30" });
  assert.deepEqual(job.machine, MACHINE);
  assert.ok(!("options" in job));
});

test("buildJob refuses what cannot be sent, saying what to do", () => {
  const base = { jobText: JSON.stringify({ tools: [], stock: { box: {} } }), machineMode: "registered", machineName: "m", programText: "M30" };
  assert.throws(() => buildJob({ ...base, machineName: " " }), /Pick a registered machine/);
  assert.throws(() => buildJob({ ...base, machineMode: "json", machineText: "" }), /Paste or load the machine/);
  assert.throws(() => buildJob({ ...base, machineMode: "json", machineText: "{oops" }), /The machine is not valid JSON at line 1/);
  assert.throws(() => buildJob({ ...base, machineMode: "json", machineText: "[]" }), /must be a JSON object/);
  assert.throws(() => buildJob({ ...base, programText: "  \n" }), /Load or paste the G-code program/);
  assert.throws(() => buildJob({ ...base, jobText: "[1]" }), /must be a JSON object/);
  assert.throws(() => buildJob({ ...base, jobText: "{\"stock\": {}}" }), /needs its tools/);
  assert.throws(() => buildJob({ ...base, jobText: "{\"tools\": []}" }), /needs its stock/);
  assert.throws(() => buildJob({ ...base, density: "0" }), /Density \(points per mm\) must be a number above 0/);
  assert.throws(() => buildJob({ ...base, density: "abc" }), /not "abc"/);
  assert.throws(() => buildJob({ ...base, steps: "1.5" }), /Steps per move must be a whole number/);
  assert.throws(() => buildJob({ ...base, tolerance: "-1" }), /Tolerance \(mm\) must be a number above 0/);
});
