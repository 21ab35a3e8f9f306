// Jobs: newest first, paged with next_cursor, refreshed while any is queued or running.
import { h, fill, table } from "./dom.js";
import { apiJson } from "./api.js";
import { hashFor } from "./router.js";
import { formatTimestamp, listVerdict, shortId } from "./format.js";
import { errorBox, statusBadge, progressBar, pageHead, pause, isAbort } from "./ui.js";

const PAGE = 20;
const REFRESH_MS = 1500;
const IDLE_REFRESH_MS = 5000;

// Clean / N collisions / Error at a glance: which programs are safe to run.
function resultBadge(job) {
  const v = listVerdict(job);
  if (!v) return "–";
  return h("span", { class: `badge verdict-${v.kind}`, dataset: { verdict: v.kind } }, v.text);
}

export function renderJobs(main, route, signal) {
  document.title = "Jobs · mdhd";
  const body = h("tbody");
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const more = h("button", { type: "button", class: "ghost", hidden: true }, "Show older jobs");
  const empty = h("p", { class: "empty", hidden: true }, "No jobs yet. ", h("a", { href: hashFor("new") }, "Check a program"), " to start one.");
  const live = h("p", { class: "hint live-note", "aria-live": "polite" });
  let jobs = [];
  let cursor = null;

  fill(main,
    pageHead("Jobs", h("a", { class: "button primary", href: hashFor("new") }, "New check")),
    errors,
    h("div", { class: "table-wrap" },
      h("table", { class: "grid jobs" },
        h("thead", {}, h("tr", {}, ["Job", "Status", "Result", "Progress", "Machine", "Submitted", "Finished"].map((t) => h("th", { scope: "col" }, t)))),
        body)),
    empty, live, h("div", { class: "buttons" }, more));

  const row = (job) => h("tr", { dataset: { id: job.id, status: job.status } },
    h("td", {}, h("a", { href: hashFor("job", { id: job.id }), class: "job-link", title: job.id }, h("code", {}, shortId(job.id)))),
    h("td", {}, statusBadge(job.status)),
    h("td", {}, resultBadge(job)),
    h("td", {}, job.status === "running" || job.status === "queued" ? progressBar(job.progress) : "–"),
    h("td", {}, typeof job.machine === "string" ? job.machine : "inline"),
    h("td", {}, formatTimestamp(job.created_at)),
    h("td", {}, formatTimestamp(job.finished_at)));

  const draw = () => {
    fill(body, jobs.map(row));
    empty.hidden = jobs.length > 0;
    more.hidden = !cursor;
  };

  // A refresh still in flight when older jobs are asked for would undo them: each
  // load has a number, and only the latest one's answer is drawn.
  let generation = 0;
  let loadingMore = false;
  const load = async (append) => {
    const mine = ++generation;
    const q = new URLSearchParams({ limit: String(append ? PAGE : Math.min(100, Math.max(PAGE, jobs.length))) });
    if (append && cursor) q.set("cursor", cursor);
    const page = await apiJson(`/api/v1/jobs?${q}`, { signal });
    if (mine !== generation) return;
    if (append) {
      const seen = new Set(jobs.map((j) => j.id));
      jobs = jobs.concat(page.jobs.filter((j) => !seen.has(j.id)));
    } else {
      jobs = page.jobs;
    }
    cursor = page.next_cursor ?? null;
    draw();
  };

  more.addEventListener("click", async () => {
    more.disabled = true;
    loadingMore = true;
    try {
      await load(true);
      errors.replaceChildren();
    } catch (err) {
      if (!isAbort(err, signal)) errors.replaceChildren(errorBox(err, "Could not load older jobs"));
    } finally {
      more.disabled = false;
      loadingMore = false;
    }
  });

  (async () => {
    let first = true;
    while (!signal.aborted) {
      try {
        // The first load pages from the start; refreshes keep as many rows as shown.
        if (!loadingMore) {
          await load(first);
          first = false;
        }
        errors.replaceChildren();
      } catch (err) {
        if (isAbort(err, signal)) return;
        errors.replaceChildren(errorBox(err, "Could not load the jobs"));
      }
      const active = jobs.some((j) => j.status === "queued" || j.status === "running");
      live.textContent = active ? "Refreshing while jobs run…" : "";
      // Jobs come from other clients too (CAM, MES): look again now and then when idle.
      await pause(active || first ? REFRESH_MS : IDLE_REFRESH_MS, signal);
    }
  })();
}
