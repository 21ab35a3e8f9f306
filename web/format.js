// Turning jobs and reports into the words and numbers the pages show: pure, so
// Node tests it.

const COLLISION_LABELS = {
  rapid_into_stock: "Rapid into stock",
  shank_contact: "Shank contact",
  holder_contact: "Holder contact",
  fixture_contact: "Fixture contact",
  spindle_off_cut: "Cut with spindle off",
  axis_limit: "Axis limit",
};

export function collisionLabel(type) {
  return COLLISION_LABELS[type] ?? String(type ?? "unknown").replace(/_/g, " ");
}

const STATUS_LABELS = {
  queued: "Queued", running: "Running", done: "Done", failed: "Failed", cancelled: "Cancelled",
  connecting: "Connecting", live: "Live", stale: "Stale", stopped: "Stopped",
};

export function statusLabel(status) {
  return STATUS_LABELS[status] ?? String(status ?? "unknown");
}

// 1234.5678 -> "1,234.568" (digits after the point, thousands grouped).
export function formatNumber(value, digits = 3) {
  if (typeof value !== "number" || !Number.isFinite(value)) return "–";
  const fixed = Math.abs(value).toFixed(digits);
  const [whole, frac] = fixed.split(".");
  const grouped = whole.replace(/\B(?=(\d{3})+(?!\d))/g, ",");
  const sign = value < 0 && Number(fixed) !== 0 ? "-" : "";
  return sign + grouped + (frac ? "." + frac : "");
}

export function formatMm(value, digits = 3) {
  return typeof value === "number" && Number.isFinite(value) ? `${formatNumber(value, digits)} mm` : "–";
}

// Seconds as "0.43 s", "12.9 s", "3 min 12 s", "2 h 05 min".
export function formatDuration(seconds) {
  if (typeof seconds !== "number" || !Number.isFinite(seconds) || seconds < 0) return "–";
  if (seconds < 10) return `${seconds.toFixed(2)} s`;
  if (seconds < 60) return `${seconds.toFixed(1)} s`;
  const total = Math.round(seconds);
  if (total < 3600) return `${Math.floor(total / 60)} min ${String(total % 60).padStart(2, "0")} s`;
  const minutes = Math.floor(total / 60);
  return `${Math.floor(minutes / 60)} h ${String(minutes % 60).padStart(2, "0")} min`;
}

export function formatBytes(bytes) {
  if (typeof bytes !== "number" || !Number.isFinite(bytes) || bytes < 0) return "–";
  if (bytes < 1024) return `${bytes} B`;
  const units = ["KiB", "MiB", "GiB", "TiB"];
  let v = bytes / 1024, i = 0;
  while (v >= 1024 && i < units.length - 1) {
    v /= 1024;
    i++;
  }
  return `${v.toFixed(v < 10 ? 2 : 1)} ${units[i]}`;
}

// [x, y, z] -> "X 20.000 Y 20.000 Z -0.101".
export function formatPosition(p, digits = 3) {
  if (!Array.isArray(p) || p.length < 3) return "–";
  return ["X", "Y", "Z"].map((a, i) => `${a} ${formatNumber(p[i], digits)}`).join(" ");
}

// {X: 1, B: -30} -> "X 1.000 B -30.000" in the object's order.
export function formatJoints(joints, digits = 3) {
  if (!joints || typeof joints !== "object") return "–";
  const parts = Object.entries(joints).map(([k, v]) => `${k} ${formatNumber(v, digits)}`);
  return parts.length ? parts.join(" ") : "–";
}

// ISO time -> local "YYYY-MM-DD HH:MM:SS".
export function formatTimestamp(iso) {
  if (typeof iso !== "string" || iso === "") return "–";
  const d = new Date(iso);
  if (Number.isNaN(d.getTime())) return "–";
  const p = (n) => String(n).padStart(2, "0");
  return `${d.getFullYear()}-${p(d.getMonth() + 1)}-${p(d.getDate())} ${p(d.getHours())}:${p(d.getMinutes())}:${p(d.getSeconds())}`;
}

export function shortId(id) {
  return typeof id === "string" ? id.slice(0, 8) : "";
}

export function percent(progress) {
  const v = typeof progress === "number" && Number.isFinite(progress) ? progress : 0;
  return Math.round(Math.min(1, Math.max(0, v)) * 100);
}

// Lines of a collision: "11" or "11–14" when its episode lasted past its first line.
export function lineSpan(c) {
  if (!Number.isInteger(c?.line)) return "–";
  return Number.isInteger(c.last_line) && c.last_line !== c.line ? `${c.line}–${c.last_line}` : String(c.line);
}

// The rows of the collisions table.
export function collisionRows(report) {
  const list = Array.isArray(report?.collisions) ? report.collisions : [];
  return list.map((c, index) => ({
    index,
    type: c.type,
    label: collisionLabel(c.type),
    line: Number.isInteger(c.line) ? c.line : null,
    lines: lineSpan(c),
    block: typeof c.block === "string" ? c.block : "",
    tool: c.tool ?? "–",
    part: typeof c.part === "string" ? c.part : "",
    position: formatPosition(c.position),
    point: Array.isArray(c.position) && c.position.length >= 3 ? c.position.slice(0, 3) : null,
    depth: formatMm(c.depth),
  }));
}

// The banner of a job: {kind, title, detail}; kind is the CSS modifier.
export function verdict(job) {
  const status = job?.status;
  const report = job?.report;
  if (status === "queued") return { kind: "busy", title: "Queued", detail: "Waiting for a free worker." };
  if (status === "running") {
    return { kind: "busy", title: `Running: ${percent(job.progress)} %`, detail: "Simulating the program." };
  }
  if (status === "cancelled") return { kind: "neutral", title: "Cancelled", detail: "The job was cancelled before it finished." };
  if (report?.status === "clean") {
    return { kind: "clean", title: "Clean", detail: "The program ran without collisions or limit violations." };
  }
  if (report?.status === "collisions") {
    const rows = collisionRows(report);
    const n = rows.length;
    const parts = rows.slice(0, 4).map((r) => `${r.label.toLowerCase()} at line ${r.lines}`);
    const more = n > 4 ? ` and ${n - 4} more` : "";
    return {
      kind: "collisions",
      title: `${n} collision${n === 1 ? "" : "s"}`,
      detail: n ? `${parts.join(", ")}${more}.` : "The report lists collisions.",
    };
  }
  if (report?.status === "error" || status === "failed") {
    return { kind: "error", title: "Error", detail: reportErrorText(report?.error) };
  }
  return { kind: "neutral", title: statusLabel(status), detail: "" };
}

// A listed job's result in a word or two, from the listing's `verdict` ({status,
// collisions}); {kind, text}, kind as in verdict(). Null while it has none.
export function listVerdict(job) {
  const v = job?.verdict;
  if (!v) return null;
  if (v.status === "clean") return { kind: "clean", text: "Clean" };
  if (v.status === "collisions") {
    const n = Number(v.collisions) || 0;
    return { kind: "collisions", text: `${n} collision${n === 1 ? "" : "s"}` };
  }
  if (v.status === "error") return { kind: "error", text: "Error" };
  return null;
}

// A report's error as one sentence: where (line and column, or field) and what.
export function reportErrorText(error) {
  if (!error || typeof error !== "object") return "The job failed without a report.";
  const msg = typeof error.message === "string" ? error.message : "unknown error";
  if (Number.isInteger(error.line) && error.line > 0) {
    const col = Number.isInteger(error.column) && error.column > 0 ? `, column ${error.column}` : "";
    const file = typeof error.file === "string" ? ` of ${error.file}` : "";
    return /line \d+/.test(msg) ? msg : `Line ${error.line}${col}${file}: ${msg}`;
  }
  if (typeof error.field === "string" && error.field && !msg.startsWith(error.field)) return `${error.field}: ${msg}`;
  return msg;
}

// Label/value pairs of a report's stats, mdh, overhang and timing blocks.
export function reportFacts(report) {
  const s = report?.stats ?? {};
  const m = report?.mdh ?? {};
  const o = report?.overhang ?? {};
  const t = report?.timing ?? {};
  const vol = (v) => (typeof v === "number" ? `${formatNumber(v, 1)} mm³` : "–");
  const directions = m.directions && typeof m.directions === "object"
    ? Object.entries(m.directions).filter(([, n]) => n > 0).map(([d, n]) => `${d} ${n}`).join(", ") || "–"
    : "–";
  return {
    stats: [
      ["Blocks", count(s.blocks)],
      ["Moves", count(s.moves)],
      ["Path length", formatMm(s.path_length, 1)],
      ["Cycle time", formatDuration(s.cycle_time_s)],
      ["Stock volume", vol(s.stock_volume_mm3)],
      ["Removed volume", vol(s.removed_volume_mm3)],
      ["Final volume", vol(s.final_volume_mm3)],
    ],
    mdh: [
      ["Cells", count(m.cells)],
      ["Leaves", count(m.leaves)],
      ["Grid spacing", formatMm(m.grid_spacing_mm, 3)],
      ["Splits", m.splits ? `direct ${count(m.splits.direct)}, indirect ${count(m.splits.indirect)}, sign conflict ${count(m.splits.sign_conflict)}` : "–"],
      ["Directions", directions],
      ["Memory", formatBytes(m.memory_bytes)],
      ["Of a pointer grid", typeof m.pointer_grid_percent === "number" ? `${formatNumber(m.pointer_grid_percent, 2)} %` : "–"],
    ],
    overhang: [
      ["Events", count(o.events)],
      ["First line", Number.isInteger(o.first_line) ? String(o.first_line) : "–"],
      ["Cells not +z", count(o.cells_not_plus_z)],
      ["Area", typeof o.area_mm2 === "number" ? `${formatNumber(o.area_mm2, 1)} mm²` : "–"],
    ],
    timing: Object.entries(t)
      .filter(([, v]) => typeof v === "number")
      .map(([k, v]) => [k.replace(/_ms$/, "").replace(/_/g, " "), `${formatNumber(v, 1)} ms`]),
  };
}

function count(v) {
  return typeof v === "number" && Number.isFinite(v) ? formatNumber(v, 0) : "–";
}

// JSON for people to edit: two-space indents, but lists of numbers and small
// flat objects on one line ({"address": 0, "type": "float32"}, [0, 0, -40]).
export function prettyJson(value, indent = "") {
  const scalar = (v) => v === null || typeof v !== "object";
  const flat = (v) => scalar(v) || (Array.isArray(v) && v.every(scalar));
  if (Array.isArray(value)) {
    if (value.every(scalar)) return `[${value.map((x) => JSON.stringify(x) ?? "null").join(", ")}]`;
    const inner = indent + "  ";
    return `[\n${value.map((x) => inner + prettyJson(x, inner)).join(",\n")}\n${indent}]`;
  }
  if (value && typeof value === "object") {
    const entries = Object.entries(value).filter(([, v]) => v !== undefined && typeof v !== "function");
    if (entries.length === 0) return "{}";
    if (entries.every(([, v]) => flat(v))) {
      const line = `{${entries.map(([k, v]) => `${JSON.stringify(k)}: ${prettyJson(v)}`).join(", ")}}`;
      if (indent.length + line.length <= 88) return line;
    }
    const inner = indent + "  ";
    return `{\n${entries.map(([k, v]) => `${inner}${JSON.stringify(k)}: ${prettyJson(v, inner)}`).join(",\n")}\n${indent}}`;
  }
  return JSON.stringify(value) ?? "null";
}
