// One job: progress while it runs, cancel; the verdict; the collisions (a click
// shows the line in the program and the point in 3D); stats, mdh, overhang,
// timing; downloads; delete.
import { h, fill, facts, download } from "./dom.js";
import { apiJson, apiFetch, apiBytes, enc } from "./api.js";
import { hashFor } from "./router.js";
import { collisionRows, reportFacts, verdict, formatTimestamp, shortId, formatBytes } from "./format.js";
import { errorBox, notice, statusBadge, progressBar, pageHead, pause, isAbort, busy } from "./ui.js";
import { ProgramView } from "./program-view.js";
import { MeshViewer } from "./viewer.js";
import { parseStl } from "./stl.js";

const POLL_MS = 700;

export function renderJob(main, route, signal) {
  const id = route.params.id;
  document.title = `Job ${shortId(id)} · mdhd`;
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const banner = h("div", { class: "verdict neutral", role: "status", "aria-live": "polite" }, "Loading the job…");
  const meta = h("div", { class: "meta" });
  const actions = h("div", { class: "actions" });
  const results = h("div", { class: "results" });
  fill(main, h("div", { class: "page-head" }, h("h1", { tabindex: "-1" }, "Job ", h("code", { title: id }, shortId(id))), actions),
    errors, banner, meta, results);

  let job = null;
  let shown = false;       // the finished results are drawn
  let meshBytes = null;
  let viewer = null;
  let program = null;
  signal.addEventListener("abort", () => {
    viewer?.destroy();
    program?.destroy();
  });

  const drawHead = () => {
    const v = verdict(job);
    banner.className = `verdict ${v.kind}`;
    banner.dataset.verdict = job.report?.status ?? job.status;
    fill(banner, h("strong", { class: "verdict-title" }, v.title), v.detail ? h("span", { class: "verdict-detail" }, v.detail) : null,
      job.status === "running" || job.status === "queued" ? progressBar(job.progress, "Job progress") : null);
    fill(meta, facts([
      ["Status", statusBadge(job.status)],
      ["Job id", h("code", {}, job.id)],
      ["Machine", typeof job.machine === "string" ? job.machine : "inline"],
      ["Submitted", formatTimestamp(job.created_at)],
      ["Started", formatTimestamp(job.started_at)],
      ["Finished", formatTimestamp(job.finished_at)],
      ...(job.attempts > 1 || job.interrupted ? [["Attempts", `${job.attempts} (${job.interrupted} interrupted)`]] : []),
    ], "facts inline"));
    drawActions();
  };

  const drawActions = () => {
    const running = job.status === "queued" || job.status === "running";
    const list = [];
    if (running) {
      const cancel = h("button", { type: "button", class: "danger" }, "Cancel job");
      cancel.addEventListener("click", () => busy(cancel, errors, async () => {
        await apiFetch(`/api/v1/jobs/${enc(id)}`, { method: "DELETE", signal });
        await refresh();
      }));
      list.push(cancel);
    } else {
      if (job.report) {
        list.push(h("button", { type: "button", onclick: () => download(`mdhd-${shortId(id)}-report.json`,
          new Blob([JSON.stringify(job.report, null, 2) + "\n"], { type: "application/json" })) }, "Download report"));
      }
      if (job.mesh) {
        const stl = h("button", { type: "button" }, "Download STL");
        stl.addEventListener("click", () => busy(stl, errors, async () => {
          const bytes = meshBytes ?? await apiBytes(`/api/v1/jobs/${enc(id)}/mesh`, { signal });
          download(`mdhd-${shortId(id)}.stl`, new Blob([bytes], { type: "model/stl" }));
        }));
        list.push(stl);
      }
      const del = h("button", { type: "button", class: "danger" }, "Delete");
      del.addEventListener("click", () => {
        if (!confirm(`Delete job ${shortId(id)} with its report and mesh?`)) return;
        busy(del, errors, async () => {
          await apiFetch(`/api/v1/jobs/${enc(id)}`, { method: "DELETE", signal });
          location.hash = hashFor("jobs");
        });
      });
      list.push(del);
    }
    fill(actions, list);
  };

  const refresh = async () => {
    job = await apiJson(`/api/v1/jobs/${enc(id)}`, { signal });
    drawHead();
  };

  const showResults = async () => {
    shown = true;
    const report = job.report;
    const rows = collisionRows(report);
    const programSlot = h("div", { class: "program-slot" }, h("p", { class: "hint" }, "Loading the program…"));
    const viewerSlot = h("div", { class: "viewer-slot" });
    const collisionsSlot = h("section", { class: "card collisions", "aria-labelledby": "collisions-h" });
    const f = reportFacts(report);
    fill(results,
      collisionsSlot,
      h("div", { class: "columns" },
        h("section", { class: "card", "aria-labelledby": "program-h" }, h("h2", { id: "program-h" }, "Program"), programSlot),
        h("section", { class: "card", "aria-labelledby": "part-h" }, h("h2", { id: "part-h" }, "Final part"), viewerSlot)),
      report ? h("section", { class: "card", "aria-labelledby": "facts-h" }, h("h2", { id: "facts-h" }, "Report"),
        h("div", { class: "fact-groups" },
          h("div", {}, h("h3", {}, "Stats"), facts(f.stats)),
          h("div", {}, h("h3", {}, "mdh-map"), facts(f.mdh)),
          h("div", {}, h("h3", {}, "Overhang"), facts(f.overhang)),
          f.timing.length ? h("div", {}, h("h3", {}, "Timing"), facts(f.timing)) : null)) : null);

    // Collisions.
    const select = (i) => {
      const r = rows[i];
      for (const tr of collisionsSlot.querySelectorAll("tr[data-index]")) {
        tr.setAttribute("aria-selected", String(Number(tr.dataset.index) === i));
      }
      if (program && r.line) {
        program.highlight(r.line);
        // On a tablet the listing is below the table: bring it up (a desk shows both already).
        program.el.scrollIntoView({ block: "nearest", behavior: "smooth" });
      }
      if (viewer) {
        viewer.highlight(i);
        viewer.centerOn(r.point);
      }
    };
    if (rows.length) {
      const body = h("tbody", {}, rows.map((r) => {
        const tr = h("tr", { class: "clickable", tabindex: "0", "aria-selected": "false", dataset: { index: String(r.index), type: r.type, line: String(r.line ?? "") } },
          h("td", {}, h("span", { class: `ctype ${r.type}` }, r.label)),
          h("td", { class: "num" }, r.lines),
          h("td", {}, h("code", {}, r.block)),
          h("td", { class: "num" }, String(r.tool)),
          h("td", { class: "num" }, r.position),
          h("td", { class: "num" }, r.depth));
        tr.addEventListener("click", () => select(r.index));
        tr.addEventListener("keydown", (e) => {
          if (e.key === "Enter" || e.key === " ") {
            e.preventDefault();
            select(r.index);
          }
        });
        return tr;
      }));
      fill(collisionsSlot, h("h2", { id: "collisions-h" }, `Collisions (${rows.length})`),
        h("p", { class: "hint" }, "Select a row to see its line in the program and its point in the 3D view."),
        h("div", { class: "table-wrap" }, h("table", { class: "grid collisions-table" },
          h("thead", {}, h("tr", {}, ["Type", "Line", "Block", "Tool", "Position (mm)", "Depth"].map((t) => h("th", { scope: "col" }, t)))),
          body)));
    } else {
      fill(collisionsSlot, h("h2", { id: "collisions-h" }, "Collisions"),
        h("p", {}, report?.status === "clean" ? "None: the program ran clean." : "None reported."));
    }

    // Program (the job as accepted).
    try {
      const doc = await apiJson(`/api/v1/jobs/${enc(id)}/job`, { signal });
      program = new ProgramView(doc?.program ?? "", { label: "Program" });
      // A line with a collision selects it, as its row does.
      program.onLineClick = (n) => {
        const i = rows.findIndex((r) => r.line === n);
        if (i >= 0) select(i);
      };
      fill(programSlot, program.el);
      const err = report?.error;
      if (Number.isInteger(err?.line) && err.line > 0) program.highlight(err.line, err.column ?? 0);
    } catch (err) {
      if (isAbort(err, signal)) return;
      fill(programSlot, errorBox(err, "Could not load the program"));
    }

    // The part.
    if (!job.mesh) {
      const me = job.mesh_error;
      fill(viewerSlot, notice("info", me?.message ? `No mesh: ${me.message}` : job.status === "done" ? "This job has no mesh." : "A failed job has no mesh."));
      return;
    }
    viewer = new MeshViewer({ label: `Final part of job ${shortId(id)}` });
    viewer.setMarkers(rows.map((r) => r.point));
    fill(viewerSlot, viewer.el);
    viewer.say("Loading the part…");
    try {
      meshBytes = await apiBytes(`/api/v1/jobs/${enc(id)}/mesh`, { signal });
      viewer.say(`Reading ${formatBytes(meshBytes.byteLength)}…`);
      await pause(0, signal);
      const mesh = parseStl(meshBytes);
      viewer.setMesh(mesh);
      viewer.say(`${mesh.triangles.toLocaleString("en")} triangles, ${formatBytes(meshBytes.byteLength)}`);
    } catch (err) {
      if (isAbort(err, signal)) return;
      viewer.canvas.dataset.state = "error";
      viewerSlot.append(errorBox(err, "Cannot show the part"));
    }
  };

  (async () => {
    while (!signal.aborted) {
      try {
        await refresh();
        errors.replaceChildren();
      } catch (err) {
        if (isAbort(err, signal)) return;
        errors.replaceChildren(errorBox(err, err?.status === 404 ? "No such job" : "Could not load the job"));
        if (err?.status === 404) {
          fill(banner, "This job does not exist (it may have been deleted). ", h("a", { href: hashFor("jobs") }, "Back to the jobs."));
          banner.className = "verdict neutral";
          return;
        }
      }
      if (job && job.status !== "queued" && job.status !== "running") {
        if (!shown) await showResults();
        return;
      }
      await pause(POLL_MS, signal);
    }
  })();
}
