import { test } from "node:test";
import assert from "node:assert/strict";
import * as f from "../format.js";

// The crash example's report as the service gave it (trimmed).
const CRASH = {
  status: "collisions", error: null,
  collisions: [
    { type: "rapid_into_stock", line: 7, last_line: 7, block: "G0 Z-1", tool: 1, part: "cutter", position: [20, 20, -0.100585938], depth: 1.0 },
    { type: "holder_contact", line: 11, last_line: 14, block: "G1 Z-25 F200", tool: 1, part: "holder", position: [50, 40, -20.100097656], depth: 5.0 },
    { type: "shank_contact", line: 12, last_line: 13, block: "G1 X60 F500", tool: 1, part: "shank", position: [50.007324219, 40, -25], depth: 2.333333333 },
  ],
  stats: { blocks: 17, moves: 9, path_length: 376.682761857, cycle_time_s: 12.872, stock_volume_mm3: 320000, removed_volume_mm3: 1658.461287532, final_volume_mm3: 318341.538712468 },
  mdh: { cells: 210, leaves: 209, grid_spacing_mm: 0.2, splits: { direct: 1, indirect: 0, sign_conflict: 0 },
    directions: { "+x": 0, "+y": 1, "+z": 5, "-x": 4, "-y": 0, "-z": 1, empty: 0, solid: 198 }, memory_bytes: 335508, pointer_grid_percent: 0.10344143 },
  overhang: { events: 6, first_line: 12, cells_not_plus_z: 6, area_mm2: 65.79707344 },
  timing: { total_ms: 431.25, simulate_ms: 300.5 },
};

test("numbers: grouping, digits, sign, not-a-number", () => {
  assert.equal(f.formatNumber(1234567.891, 2), "1,234,567.89");
  assert.equal(f.formatNumber(-0.100585938), "-0.101");
  assert.equal(f.formatNumber(-0.0001), "0.000");
  assert.equal(f.formatNumber(999, 0), "999");
  assert.equal(f.formatNumber(NaN), "–");
  assert.equal(f.formatNumber("7"), "–");
  assert.equal(f.formatMm(2.333333333), "2.333 mm");
  assert.equal(f.formatMm(null), "–");
});

test("durations, bytes, percent, ids", () => {
  assert.equal(f.formatDuration(0.431), "0.43 s");
  assert.equal(f.formatDuration(12.872), "12.9 s");
  assert.equal(f.formatDuration(192), "3 min 12 s");
  assert.equal(f.formatDuration(7500), "2 h 05 min");
  assert.equal(f.formatDuration(-1), "–");
  assert.equal(f.formatBytes(512), "512 B");
  assert.equal(f.formatBytes(335508), "327.6 KiB");
  assert.equal(f.formatBytes(7156184), "6.82 MiB");
  assert.equal(f.percent(0.456), 46);
  assert.equal(f.percent(2), 100);
  assert.equal(f.percent(undefined), 0);
  assert.equal(f.shortId("60cbcf9c1d85e3b055a8d683573a28e5"), "60cbcf9c");
});

test("positions and joints", () => {
  assert.equal(f.formatPosition([20, 20, -0.100585938]), "X 20.000 Y 20.000 Z -0.101");
  assert.equal(f.formatPosition(null), "–");
  assert.equal(f.formatJoints({ X: 1, B: -30.5 }, 1), "X 1.0 B -30.5");
  assert.equal(f.formatJoints({}), "–");
});

test("timestamps are local and whole", () => {
  process.env.TZ = "UTC";
  assert.equal(f.formatTimestamp("2026-11-29T12:39:59.274Z"), "2026-11-29 12:39:59");
  assert.equal(f.formatTimestamp("garbage"), "–");
  assert.equal(f.formatTimestamp(null), "–");
});

test("collision rows of the crash example: types, lines, blocks, positions, depths", () => {
  const rows = f.collisionRows(CRASH);
  assert.deepEqual(rows.map((r) => [r.type, r.label, r.line, r.lines]), [
    ["rapid_into_stock", "Rapid into stock", 7, "7"],
    ["holder_contact", "Holder contact", 11, "11–14"],
    ["shank_contact", "Shank contact", 12, "12–13"],
  ]);
  assert.equal(rows[1].position, "X 50.000 Y 40.000 Z -20.100");
  assert.deepEqual(rows[1].point, [50, 40, -20.100097656]);
  assert.equal(rows[2].depth, "2.333 mm");
  assert.equal(rows[0].block, "G0 Z-1");
  assert.equal(rows[0].part, "cutter");
  assert.deepEqual(f.collisionRows({}), []);
  assert.equal(f.collisionLabel("new_kind_of_thing"), "new kind of thing");
});

test("verdicts: clean, collisions, error, running, queued, cancelled", () => {
  const v = f.verdict({ status: "done", report: CRASH });
  assert.equal(v.kind, "collisions");
  assert.equal(v.title, "3 collisions");
  assert.equal(v.detail, "rapid into stock at line 7, holder contact at line 11–14, shank contact at line 12–13.");
  assert.deepEqual(f.verdict({ status: "done", report: { status: "clean", collisions: [] } }).kind, "clean");
  const err = f.verdict({ status: "failed", report: { status: "error", error: { message: "Unknown tool 7", line: 4, column: 1, block: "T7 M6" } } });
  assert.equal(err.kind, "error");
  assert.equal(err.detail, "Line 4, column 1: Unknown tool 7");
  assert.equal(f.verdict({ status: "failed", report: { status: "error", error: { message: "program line 3, column 9: bad", line: 3, column: 9 } } }).detail,
    "program line 3, column 9: bad");
  assert.equal(f.verdict({ status: "failed", report: { status: "error", error: { field: "(limits)", message: "ran too long" } } }).detail, "(limits): ran too long");
  assert.equal(f.verdict({ status: "failed" }).detail, "The job failed without a report.");
  assert.equal(f.verdict({ status: "running", progress: 0.42 }).title, "Running: 42 %");
  assert.equal(f.verdict({ status: "queued" }).kind, "busy");
  assert.equal(f.verdict({ status: "cancelled" }).title, "Cancelled");
  const many = { status: "collisions", collisions: Array.from({ length: 6 }, (_, i) => ({ type: "axis_limit", line: i + 1 })) };
  assert.match(f.verdict({ status: "done", report: many }).detail, /and 2 more\.$/);
  assert.equal(f.verdict({ status: "done", report: { status: "collisions", collisions: [{ type: "axis_limit", line: 2 }] } }).title, "1 collision");
});

test("report facts: stats, mdh, overhang, timing", () => {
  const facts = f.reportFacts(CRASH);
  const get = (list, label) => list.find(([l]) => l === label)?.[1];
  assert.equal(get(facts.stats, "Blocks"), "17");
  assert.equal(get(facts.stats, "Cycle time"), "12.9 s");
  assert.equal(get(facts.stats, "Removed volume"), "1,658.5 mm³");
  assert.equal(get(facts.mdh, "Grid spacing"), "0.200 mm");
  assert.equal(get(facts.mdh, "Directions"), "+y 1, +z 5, -x 4, -z 1, solid 198");
  assert.equal(get(facts.mdh, "Splits"), "direct 1, indirect 0, sign conflict 0");
  assert.equal(get(facts.overhang, "First line"), "12");
  assert.equal(get(facts.overhang, "Area"), "65.8 mm²");
  assert.deepEqual(facts.timing, [["total", "431.3 ms"], ["simulate", "300.5 ms"]]);
  const empty = f.reportFacts(null);
  assert.equal(get(empty.stats, "Blocks"), "–");
  assert.deepEqual(empty.timing, []);
});

test("prettyJson: readable, and the same value back", () => {
  const value = {
    machine: "3axis-mill",
    tools: [{ number: 1, shape: "flat", holder: [{ diameter: 30, length: 30 }] }],
    stock: { box: { min: [0, 0, -40], max: [100, 80, 0] } },
    empty: {}, list: [], nested: [[1, 2], [3]], text: "a \"quoted\"\nline", skip: undefined,
  };
  const text = f.prettyJson(value);
  assert.deepEqual(JSON.parse(text), JSON.parse(JSON.stringify(value)));
  assert.match(text, /^ {6}"holder": \[\n {8}\{"diameter": 30, "length": 30\}\n {6}\]/m);
  assert.match(text, /"box": \{"min": \[0, 0, -40\], "max": \[100, 80, 0\]\}/);
  assert.match(text, /"empty": \{\},\n {2}"list": \[\]/);
  assert.ok(!text.includes("skip"));
  const long = { a: "x".repeat(100), b: 1 };
  assert.equal(f.prettyJson(long), `{\n  "a": "${"x".repeat(100)}",\n  "b": 1\n}`);
  assert.equal(f.prettyJson(null), "null");
  assert.equal(f.prettyJson([1, null, "a"]), "[1, null, \"a\"]");
});

test("listVerdict: the listing's verdict in a word or two", () => {
  assert.deepEqual(f.listVerdict({ verdict: { status: "clean", collisions: 0 } }), { kind: "clean", text: "Clean" });
  assert.deepEqual(f.listVerdict({ verdict: { status: "collisions", collisions: 3 } }), { kind: "collisions", text: "3 collisions" });
  assert.deepEqual(f.listVerdict({ verdict: { status: "collisions", collisions: 1 } }), { kind: "collisions", text: "1 collision" });
  assert.deepEqual(f.listVerdict({ verdict: { status: "error", collisions: 0 } }), { kind: "error", text: "Error" });
  assert.equal(f.listVerdict({ status: "running" }), null);
  assert.equal(f.listVerdict({ verdict: null }), null);
});
