// One shadow, live: state, joints, tool pose, alarms from the event stream; the
// live stock in 3D, refreshed while it runs; stop and delete.
import { h, fill, facts } from "./dom.js";
import { apiJson, apiFetch, apiBytes, enc } from "./api.js";
import { hashFor } from "./router.js";
import { eventJson } from "./sse.js";
import { describeError } from "./api-errors.js";
import { followEvents } from "./sse-stream.js";
import { collisionLabel, formatNumber, formatPosition, formatMm, lineSpan } from "./format.js";
import { errorBox, notice, statusBadge, busy, pause, isAbort } from "./ui.js";
import { MeshViewer } from "./viewer.js";
import { parseStl } from "./stl.js";

const MESH_REFRESH_MS = 3000;
const STATE_REFRESH_MS = 2000;

export function renderShadow(main, route, signal) {
  const id = route.params.id;
  document.title = `Shadow ${id} · mdhd`;
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const stateSlot = h("span", { class: "shadow-state", "aria-live": "polite" });
  const streamNote = h("span", { class: "hint stream-note" });
  const actions = h("div", { class: "actions" });
  const pose = h("div", { class: "pose" });
  const alarmsBody = h("tbody");
  const alarmsNote = h("p", { class: "hint" });
  const health = h("div", { class: "health" });
  const autoMesh = h("input", { type: "checkbox", id: "auto-mesh", checked: true });
  const refreshMesh = h("button", { type: "button", class: "ghost small" }, "Refresh now");
  const viewer = new MeshViewer({ label: "Live stock of the shadow" });
  signal.addEventListener("abort", () => viewer.destroy());

  fill(main,
    h("div", { class: "page-head" }, h("h1", { tabindex: "-1" }, "Shadow ", h("code", {}, id)), actions),
    h("p", { class: "state-line" }, stateSlot, " ", streamNote),
    errors,
    h("div", { class: "columns" },
      h("div", { class: "col" },
        h("section", { class: "card", "aria-labelledby": "pose-h" }, h("h2", { id: "pose-h" }, "Machine"), pose),
        h("section", { class: "card", "aria-labelledby": "alarms-h" }, h("h2", { id: "alarms-h" }, "Alarms"), alarmsNote,
          h("div", { class: "table-wrap" }, h("table", { class: "grid alarms" },
            h("thead", {}, h("tr", {}, ["#", "Kind", "Type", "Line", "Position (mm)", "Depth"].map((t) => h("th", { scope: "col" }, t)))),
            alarmsBody))),
        h("section", { class: "card", "aria-labelledby": "health-h" }, h("h2", { id: "health-h" }, "Polling and carving"), health)),
      h("div", { class: "col" },
        h("section", { class: "card", "aria-labelledby": "stock-h" }, h("h2", { id: "stock-h" }, "Live stock"),
          h("div", { class: "row" }, h("label", { class: "check", for: "auto-mesh" }, autoMesh, " Refresh while live"), refreshMesh),
          viewer.el))));

  const s = { state: null, alarms: new Map(), dropped: 0, markerIds: [], selected: null };

  const drawState = (state, reason) => {
    s.state = state;
    fill(stateSlot, statusBadge(state), reason ? h("span", { class: "reason" }, ` ${reason}`) : null);
    stateSlot.dataset.state = state;
    drawActions();
  };

  const drawPose = (p) => {
    fill(pose, facts([
      ["Joints", h("span", { class: "joints" }, Object.entries(p.joints ?? {}).map(([k, v]) => h("span", { class: "joint", dataset: { axis: k } }, h("b", {}, k), " ", formatNumber(v, 3))))],
      ["Tool tip", formatPosition(p.tool_pose?.tip)],
      ["Tool axis", Array.isArray(p.tool_pose?.axis) ? p.tool_pose.axis.map((v) => formatNumber(v, 3)).join(", ") : "–"],
      ["Tool", p.tool === 0 ? "none (empty spindle)" : p.tool ?? "–"],
      ["Line", p.line ?? "–"],
      ["Spindle", p.spindle_on === true ? "on" : p.spindle_on === false ? "off" : "–"],
      ["Samples", formatNumber(p.samples, 0)],
    ], "facts pose-facts"));
    const tip = p.tool_pose?.tip;
    const axis = p.tool_pose?.axis;
    if (Array.isArray(tip) && tip.length === 3) {
      const marks = [{ point: tip, color: [0.2, 0.8, 1.0], size: 16 }];
      const lines = Array.isArray(axis) && axis.length === 3
        ? [{ point: tip, color: [0.2, 0.8, 1.0] }, { point: tip.map((v, i) => v + axis[i] * 50), color: [0.2, 0.8, 1.0] }]
        : [];
      viewer.setExtras(marks, lines);
    }
  };

  // Rows are kept per alarm and rebuilt only when that alarm changed, so a row stays
  // put under a finger while new alarms arrive; drawing waits for the next frame.
  const rowCache = new Map();  // id -> {key, tr}
  let alarmFrame = 0;
  const drawAlarms = () => {
    if (!alarmFrame) alarmFrame = requestAnimationFrame(drawAlarmsNow);
  };
  const alarmRow = (a) => h("tr", {
      class: a.kind === "predicted" ? "predicted" : "collision clickable",
      tabindex: a.kind === "predicted" ? null : "0",
      "aria-selected": a.kind === "predicted" ? null : String(a.id === s.selected),
      dataset: { id: String(a.id), type: a.type },
      onclick: () => showAlarm(a),
      onkeydown: (e) => { if (e.key === "Enter" || e.key === " ") { e.preventDefault(); showAlarm(a); } },
    },
    h("td", { class: "num" }, String(a.id ?? "")),
    h("td", {}, a.kind === "predicted" ? `predicted${typeof a.time_to_contact_s === "number" ? ` in ${formatNumber(a.time_to_contact_s, 1)} s` : ""}` : "collision"),
    h("td", {}, h("span", { class: `ctype ${a.type}` }, collisionLabel(a.type))),
    h("td", { class: "num" }, lineSpan(a)),
    h("td", { class: "num" }, formatPosition(a.position)),
    h("td", { class: "num" }, `${formatMm(a.depth)}${a.depth_measured === false ? " (so far)" : ""}`));
  const drawAlarmsNow = () => {
    alarmFrame = 0;
    // Like the service, keep the first 100 and the latest 200 of a long session.
    const ids = [...s.alarms.keys()].sort((a, b) => a - b);
    if (ids.length > 300) for (const id of ids.slice(100, ids.length - 200)) s.alarms.delete(id);
    const list = [...s.alarms.values()].sort((a, b) => (a.id ?? 0) - (b.id ?? 0));
    const rows = [];
    const seen = new Set();
    // Newest first: the alarm that matters at the machine is the latest.
    for (const a of [...list].reverse()) {
      const key = JSON.stringify(a);
      let cached = rowCache.get(a.id);
      if (!cached || cached.key !== key) {
        cached = { key, tr: alarmRow(a) };
        rowCache.set(a.id, cached);
      }
      seen.add(a.id);
      rows.push(cached.tr);
    }
    for (const id of [...rowCache.keys()]) if (!seen.has(id)) rowCache.delete(id);
    alarmsBody.replaceChildren(...(rows.length ? rows : [h("tr", {}, h("td", { colspan: "6" }, "No alarms."))]));
    alarmsNote.textContent = s.dropped ? `${s.dropped} alarms in the middle were dropped from the list (the first and last 100 are kept).` : "";
    s.markerIds = list.filter((a) => a.kind !== "predicted").map((a) => a.id);
    viewer.setMarkers(list.filter((a) => a.kind !== "predicted").map((a) => (Array.isArray(a.position) ? a.position : null)));
    viewer.highlight(s.markerIds.indexOf(s.selected));
  };
  signal.addEventListener("abort", () => cancelAnimationFrame(alarmFrame));

  // A collision alarm's row shows its point in the live stock.
  const showAlarm = (a) => {
    if (a.kind === "predicted") return;
    s.selected = a.id;
    for (const tr of alarmsBody.querySelectorAll("tr[data-id]")) tr.setAttribute("aria-selected", String(tr.dataset.id === String(a.id)));
    viewer.highlight(s.markerIds.indexOf(a.id));
    if (Array.isArray(a.position)) viewer.centerOn(a.position);
  };

  const drawHealth = (doc) => {
    const p = doc.polls ?? {}, c = doc.carving ?? {};
    fill(health, facts([
      ["Polls", `${formatNumber(p.ok, 0)} ok, ${formatNumber(p.failed, 0)} failed${p.poll_hz ? ` at ${formatNumber(p.poll_hz, 0)} Hz` : ""}`],
      ["Last error", p.last_error ?? "none"],
      ["Carving", `${formatNumber(c.motions, 0)} motions, lag ${formatNumber(c.lag_ms, 1)} ms, backlog ${formatNumber(c.backlog, 0)}`],
      ["Report", doc.report?.status ? `${doc.report.status}${typeof doc.report_age_ms === "number" ? ` (${formatNumber(doc.report_age_ms / 1000, 1)} s old)` : ""}` : "–"],
      ["Feed hold", doc.feed_hold?.enabled ? `on coil ${doc.feed_hold.coil}, ${doc.feed_hold.writes} written${doc.feed_hold.error ? `, error: ${doc.feed_hold.error}` : ""}` : "off"],
    ]));
  };

  const drawActions = () => {
    const list = [h("a", { class: "button ghost", href: hashFor("shadows") }, "All shadows")];
    if (s.state && s.state !== "stopped") {
      const stop = h("button", { type: "button", class: "danger" }, "Stop shadowing");
      stop.addEventListener("click", () => busy(stop, errors, async () => {
        const doc = await apiJson(`/api/v1/shadows/${enc(id)}`, { method: "DELETE", signal });
        if (doc) apply(doc);
      }));
      list.push(stop);
    } else if (s.state === "stopped") {
      const del = h("button", { type: "button", class: "danger" }, "Delete");
      del.addEventListener("click", () => {
        if (!confirm(`Delete shadow ${id} with its live stock?`)) return;
        busy(del, errors, async () => {
          await apiFetch(`/api/v1/shadows/${enc(id)}`, { method: "DELETE", signal });
          location.hash = hashFor("shadows");
        });
      });
      list.push(del);
    }
    fill(actions, list);
  };

  const apply = (doc) => {
    drawState(doc.state, doc.state === "stale" ? doc.polls?.last_error ?? "" : "");
    drawPose(doc);
    s.alarms = new Map((doc.alarms ?? []).map((a, i) => [a.id ?? i, a]));
    s.dropped = doc.alarms_dropped ?? 0;
    drawAlarms();
    drawHealth(doc);
  };

  let meshBusy = false;
  const loadMesh = async () => {
    if (meshBusy) return;
    meshBusy = true;
    try {
      const bytes = await apiBytes(`/api/v1/shadows/${enc(id)}/mesh`, { signal });
      viewer.setMesh(parseStl(bytes));
      viewer.say(`Live stock at ${new Date().toLocaleTimeString()}`);
    } catch (err) {
      if (!isAbort(err, signal)) viewer.say(`The live stock could not be shown: ${describeError(err)}`);
    } finally {
      meshBusy = false;
    }
  };
  refreshMesh.addEventListener("click", loadMesh);

  (async () => {
    try {
      apply(await apiJson(`/api/v1/shadows/${enc(id)}`, { signal }));
    } catch (err) {
      if (isAbort(err, signal)) return;
      errors.replaceChildren(errorBox(err, err?.status === 404 ? "No such shadow" : "Could not load the shadow"));
      return;
    }
    loadMesh();
    // Events: live state, pose and alarms.
    followEvents(`/api/v1/shadows/${enc(id)}/events`, {
      signal,
      shouldReconnect: () => s.state !== "stopped",
      onStatus: (status, err) => {
        streamNote.textContent = status === "open" ? "· live events" : status === "reconnecting" ? "· reconnecting to the events…" : "· events ended";
        if (err && err.status !== 404) errors.replaceChildren(errorBox(err, "The event stream failed"));
      },
      onEvent: (event) => {
        const data = eventJson(event);
        if (!data) return;
        if (event.type === "state") drawState(data.state, data.reason ?? "");
        else if (event.type === "pose") drawPose(data);
        else if (event.type === "alarm" || event.type === "alarm_update") {
          s.alarms.set(data.id ?? s.alarms.size, data);
          drawAlarms();
        } else if (event.type === "feed_hold" && data.ok === false) {
          errors.replaceChildren(notice("error", `Feed hold failed: ${data.error ?? "unknown error"}`));
        }
      },
    });
    // The rest of the state (polls, carving, report) and the live stock.
    let lastMesh = Date.now();
    while (!signal.aborted) {
      await pause(STATE_REFRESH_MS, signal);
      if (signal.aborted) return;
      try {
        const doc = await apiJson(`/api/v1/shadows/${enc(id)}`, { signal });
        drawHealth(doc);
        if (doc.state !== s.state) drawState(doc.state, doc.state === "stale" ? doc.polls?.last_error ?? "" : "");
        s.dropped = doc.alarms_dropped ?? 0;
        // Alarms raised between the first GET and the stream's start come in here.
        let added = false;
        for (const a of doc.alarms ?? []) {
          if (a.id !== undefined && !s.alarms.has(a.id)) {
            s.alarms.set(a.id, a);
            added = true;
          }
        }
        if (added) drawAlarms();
        if (doc.state === "stopped") {
          apply(doc);
          await loadMesh();
          return;
        }
      } catch (err) {
        if (isAbort(err, signal)) return;
        errors.replaceChildren(errorBox(err, err?.status === 404 ? "The shadow is gone" : "Could not refresh the shadow"));
        if (err?.status === 404) return;
      }
      if (autoMesh.checked && s.state === "live" && Date.now() - lastMesh >= MESH_REFRESH_MS) {
        lastMesh = Date.now();
        loadMesh();
      }
    }
  })();
}
