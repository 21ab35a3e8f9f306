// End-to-end test of the browser UI: a real `mdhd serve` (MDHD_BIN), Debian's
// chromium driven by playwright-core. Exit status 0 when every step passed.
//
//   MDHD_BIN=build/bin/mdhd node web/e2e/e2e.mjs
//
// Environment: MDHD_BIN (required), CHROMIUM (default /usr/bin/chromium),
// MDHD_EXAMPLES (default ../shared/examples beside the repository),
// E2E_HEADED=1 to watch, E2E_SKIP_SHADOW=1 to leave out the shadow step,
// E2E_SCREENSHOTS=DIR to save a screenshot of each page as the test sees it.
import { spawn } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const webDir = path.resolve(here, "..");
const examples = process.env.MDHD_EXAMPLES ?? path.resolve(webDir, "../../shared/examples");
const chromiumPath = process.env.CHROMIUM ?? "/usr/bin/chromium";
const TOKEN = "e2e-token-0123456789abcdef";
const started = Date.now();

function die(message) {
  console.error(`web_e2e: ${message}`);
  process.exit(1);
}

// Prerequisites: fail (not skip) saying what is missing.
const mdhdBin = process.env.MDHD_BIN;
if (!mdhdBin) die("MDHD_BIN is not set: point it at the mdhd executable (ctest sets it).");
if (!existsSync(mdhdBin)) die(`MDHD_BIN=${mdhdBin} does not exist: build the mdhd target first.`);
if (!existsSync(chromiumPath)) die(`no chromium at ${chromiumPath}: install Debian's package (apt-get install chromium, scripts/install-deps.sh does) or set CHROMIUM.`);
if (!existsSync(path.join(examples, "crash-3axis.json"))) die(`no example jobs in ${examples}: set MDHD_EXAMPLES.`);
let chromium;
try {
  ({ chromium } = await import(path.join(webDir, "node_modules/playwright-core/index.mjs")));
} catch {
  die("playwright-core is not installed in web/node_modules: run `npm ci --prefix web` (scripts/test.sh does).");
}

const axePath = path.join(webDir, "node_modules/axe-core/axe.min.js");
if (!existsSync(axePath)) die("axe-core is not installed in web/node_modules: run `npm ci --prefix web` (scripts/test.sh does).");

const children = [];
const temps = [];
function cleanup() {
  for (const c of children) if (c.exitCode === null && c.signalCode === null) c.kill("SIGKILL");
  for (const t of temps) rmSync(t, { recursive: true, force: true });
}
process.on("exit", cleanup);
for (const sig of ["SIGINT", "SIGTERM"]) process.on(sig, () => process.exit(1));

// Starts a process and resolves with the first stdout line matching `pattern`.
function startProcess(args, pattern, what) {
  return new Promise((resolve, reject) => {
    const child = spawn(mdhdBin, args, { stdio: ["ignore", "pipe", "pipe"] });
    children.push(child);
    let out = "", err = "";
    const timer = setTimeout(() => reject(new Error(`${what} did not start in 10 s: ${out}${err}`)), 10000);
    child.stdout.on("data", (d) => {
      out += d;
      const m = pattern.exec(out);
      if (m) {
        clearTimeout(timer);
        resolve({ child, match: m });
      }
    });
    child.stderr.on("data", (d) => { err += d; });
    child.on("exit", (code) => {
      clearTimeout(timer);
      reject(new Error(`${what} exited with ${code}: ${err.trim().slice(-500)}`));
    });
  });
}

async function startService(extra = []) {
  const dir = mkdtempSync(path.join(tmpdir(), "mdhd-e2e-"));
  temps.push(dir);
  const { child, match } = await startProcess(["serve", "--port", "0", "--data-dir", dir, "--workers", "2", ...extra],
    /listening on ([0-9.]+):([0-9]+)/, "mdhd serve");
  return { child, base: `http://${match[1]}:${match[2]}` };
}

let passed = 0;
const failures = [];
async function step(name, fn) {
  const t0 = Date.now();
  try {
    await fn();
    passed++;
    console.log(`ok - ${name} (${Date.now() - t0} ms)`);
  } catch (err) {
    failures.push(name);
    console.log(`not ok - ${name} (${Date.now() - t0} ms)\n  ${String(err?.stack ?? err).split("\n").slice(0, 6).join("\n  ")}`);
  }
}
function assert(cond, message) {
  if (!cond) throw new Error(message);
}
function equal(actual, expected, message) {
  const a = JSON.stringify(actual), e = JSON.stringify(expected);
  if (a !== e) throw new Error(`${message}: got ${a}, expected ${e}`);
}

// A page that fails the test on any script error or Content-Security-Policy violation.
async function newPage(browser, options = {}) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, ...options });
  const page = await context.newPage();
  page.problems = [];
  page.on("pageerror", (e) => page.problems.push(`page error: ${e.message}`));
  page.on("console", (m) => {
    if (m.type() === "error" && !/Failed to load resource/.test(m.text())) page.problems.push(`console error: ${m.text()}`);
    if (/Content Security Policy/i.test(m.text())) page.problems.push(`CSP: ${m.text()}`);
  });
  page.on("dialog", (d) => d.accept());
  page.setDefaultTimeout(15000);
  return page;
}
async function shot(page, name) {
  if (process.env.E2E_SCREENSHOTS) await page.screenshot({ path: path.join(process.env.E2E_SCREENSHOTS, `${name}.png`), fullPage: true });
}
// Script errors, CSP violations, and the page's own fault banner (#page-error), which
// also catches window "error" events no console message marks as an error.
async function noProblems(page) {
  assert(page.problems.length === 0, page.problems.join("\n"));
  const banner = page.locator("#page-error");
  if ((await banner.count()) > 0 && (await banner.isVisible())) {
    throw new Error(`the page shows a fault: ${await banner.textContent()}`);
  }
}

const service = await startService();
const browser = await chromium.launch({
  executablePath: chromiumPath,
  headless: !process.env.E2E_HEADED,
  args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox"],
});

try {
  const page = await newPage(browser);
  let jobId = null;

  await step("New check: the crash example's job, machine and program files submitted through the form", async () => {
    await page.goto(`${service.base}/#/new`);
    await page.setInputFiles("#files", ["crash-3axis.json", "machine-3axis.json", "crash-3axis.ngc"].map((f) => path.join(examples, f)));
    await page.waitForSelector(".loaded li >> nth=2");
    const loaded = await page.locator(".loaded li").allTextContents();
    equal(loaded, ["Job: crash-3axis.json", "Machine: machine-3axis.json", "Program: crash-3axis.ngc"], "loaded files");
    assert(await page.isChecked("#mode-json"), "an opened machine file selects Machine JSON");
    equal(await page.inputValue("#density"), "5", "density from the job's options");
    assert((await page.inputValue("#program")).includes("G1 Z-25 F200"), "program text loaded");
    await page.click("#submit-check");
    await page.waitForURL(/#\/jobs\/[0-9a-f]{32}$/);
    jobId = page.url().split("/").pop();
    await noProblems(page);
  });

  await step("Job detail: verdict and collisions table as the example's README says", async () => {
    await page.waitForSelector('.verdict[data-verdict="collisions"]', { timeout: 30000 });
    const title = await page.textContent(".verdict-title");
    const rows = await page.$$eval(".collisions-table tbody tr", (trs) => trs.map((tr) => [tr.dataset.type, tr.dataset.line, tr.cells[0].textContent, tr.cells[1].textContent]));
    equal(rows.map((r) => [r[0], r[1]]), [["rapid_into_stock", "7"], ["holder_contact", "11"], ["shank_contact", "12"]], "collision types and lines");
    equal(rows.map((r) => r[2]), ["Rapid into stock", "Holder contact", "Shank contact"], "type labels shown");
    assert(rows[1][3].startsWith("11"), `the holder line cell shows 11: ${rows[1][3]}`);
    equal(title, "3 collisions", "verdict title");
    const stats = await page.textContent(".fact-groups");
    assert(/Blocks\s*17/.test(stats), `stats show the blocks: ${stats.slice(0, 200)}`);
    await noProblems(page);
  });

  await step("3D view: data-triangles equals the STL's triangle count, drawn without GL errors", async () => {
    const stl = await (await page.request.get(`${service.base}/api/v1/jobs/${jobId}/mesh`)).body();
    const count = stl.readUInt32LE(80);
    assert(count > 1000 && stl.length === 84 + 50 * count, `a whole STL (${count} triangles, ${stl.length} bytes)`);
    await page.waitForSelector('canvas.viewer-canvas[data-state="drawn"]', { timeout: 20000 });
    const canvas = page.locator("canvas.viewer-canvas");
    equal(Number(await canvas.getAttribute("data-triangles")), count, "triangles drawn");
    equal(await canvas.getAttribute("data-gl-error"), null, "GL error");
    // Turn and zoom it with the mouse: still drawn, no errors.
    const box = await canvas.boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 80, box.y + box.height / 2 + 30, { steps: 4 });
    await page.mouse.up();
    await page.mouse.wheel(0, -200);
    await page.waitForTimeout(100);
    equal(Number(await canvas.getAttribute("data-triangles")), count, "triangles drawn after orbit and zoom");
    await noProblems(page);
  });

  await step("Clicking a collision highlights its program line and its marker", async () => {
    await page.click('.collisions-table tr[data-type="holder_contact"]');
    await page.waitForSelector('.program .pl.hl[data-line="11"]');
    assert((await page.textContent(".program .pl.hl")).includes("G1 Z-25 F200"), "line 11's text highlighted");
    equal(await page.locator(".program .pl.hl").count(), 1, "one highlighted line");
    equal(await page.getAttribute('.collisions-table tr[data-type="holder_contact"]', "aria-selected"), "true", "row selected");
    equal(await page.getAttribute("canvas.viewer-canvas", "data-highlight"), "1", "marker highlighted");
    // The keyboard does the same.
    await page.focus('.collisions-table tr[data-type="rapid_into_stock"]');
    await page.keyboard.press("Enter");
    await page.waitForSelector('.program .pl.hl[data-line="7"]');
    assert((await page.textContent(".program .pl.hl")).includes("G0 Z-1"), "line 7's text highlighted");
    equal(await page.getAttribute("canvas.viewer-canvas", "data-highlight"), "0", "marker 0 highlighted");
    await shot(page, "job");
    assert(await page.locator(".program .pl.hl").isVisible(), "the highlighted line is scrolled into view");
    // A program line with a collision selects it, as its row does.
    await page.click('.program .pl[data-line="12"]');
    equal(await page.getAttribute('.collisions-table tr[data-type="shank_contact"]', "aria-selected"), "true", "line 12 selects the shank row");
    equal(await page.getAttribute("canvas.viewer-canvas", "data-highlight"), "2", "marker 2 highlighted");
    await noProblems(page);
  });

  await step("The job's page opened directly by its address (a shared link): whole, no fault", async () => {
    const direct = await newPage(browser);
    await direct.goto(`${service.base}/#/jobs/${jobId}`);
    await direct.waitForSelector('.verdict[data-verdict="collisions"]');
    await direct.waitForSelector('canvas.viewer-canvas[data-state="drawn"]', { timeout: 20000 });
    await direct.waitForSelector(".program .pl");
    await direct.waitForTimeout(300);
    await noProblems(direct);
    await direct.context().close();
  });

  await step("Jobs list shows the job as done with its verdict, newest first", async () => {
    await page.click('nav a[data-section="jobs"]');
    await page.waitForSelector(`table.jobs tr[data-id="${jobId}"]`);
    equal(await page.getAttribute(`table.jobs tr[data-id="${jobId}"] .badge`, "data-status"), "done", "status");
    const result = page.locator(`table.jobs tr[data-id="${jobId}"] [data-verdict]`);
    equal(await result.getAttribute("data-verdict"), "collisions", "verdict kind");
    equal(await result.textContent(), "3 collisions", "verdict text");
    equal(await page.getAttribute('a[data-section="jobs"]', "aria-current"), "page", "the Jobs tab is current");
    await noProblems(page);
  });

  await step("A long job: progress shown while it runs, cancelled from its page", async () => {
    const job = JSON.parse(readFileSync(path.join(examples, "contour-3axis.json"), "utf8"));
    job.machine = JSON.parse(readFileSync(path.join(examples, job.machine_file), "utf8"));
    job.program = readFileSync(path.join(examples, job.program_file), "utf8");
    delete job.machine_file;
    delete job.program_file;
    job.options = { ...job.options, density: 80 };
    const reply = await page.request.post(`${service.base}/api/v1/jobs`, { data: job });
    equal(reply.status(), 202, "long job accepted");
    const id = (await reply.json()).id;
    await page.goto(`${service.base}/#/jobs/${id}`);
    await page.waitForSelector('.verdict.busy progress');
    await page.click('button:text("Cancel job")');
    await page.waitForSelector('.verdict[data-verdict="cancelled"]', { timeout: 10000 });
    assert(!(await page.isVisible('button:text("Cancel job")')), "no Cancel once cancelled");
    await noProblems(page);
  });

  await step("A job that fails while it runs: error banner with the line, that line highlighted; deleted", async () => {
    const reply = await page.request.post(`${service.base}/api/v1/jobs`, { data: {
      machine: "3axis-mill",
      tools: [{ number: 1, shape: "flat", diameter: 0.1, flute_length: 20, length: 50 }],
      stock: { box: { min: [0, 0, -20], max: [50, 50, 0] } },
      program: "G21 G90\nT1 M6\nG43 H1\nM3 S1000\nG0 X10 Y10 Z5\nG1 Z-1 F100\nM30\n",
      options: { density: 5 } } });
    equal(reply.status(), 202, "accepted");
    await page.goto(`${service.base}/#/jobs/${(await reply.json()).id}`);
    await page.waitForSelector('.verdict[data-verdict="error"]', { timeout: 15000 });
    const detail = await page.textContent(".verdict-detail");
    assert(/^Line 5, column 1: tool 1's cutter/.test(detail), `error detail: ${detail}`);
    await page.waitForSelector('.program .pl.hl[data-line="5"] mark.column');
    assert(/failed job has no mesh/.test(await page.textContent(".viewer-slot")), "no mesh said");
    // Delete it (the confirmation is accepted): back to the list, gone from the API.
    const failedId = page.url().split("/").pop();
    await page.click('.page-head button:text("Delete")');
    await page.waitForURL(/#\/jobs$/);
    equal((await page.request.get(`${service.base}/api/v1/jobs/${failedId}`)).status(), 404, "deleted job");
    await noProblems(page);
  });

  await step("Jobs list pages with next_cursor: 20 first, older ones on request", async () => {
    const tiny = { machine: "3axis-mill", tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 20, length: 50 }],
      stock: { box: { min: [0, 0, -5], max: [10, 10, 0] } }, program: "M30\n", options: { density: 2 } };
    const before = (await (await page.request.get(`${service.base}/api/v1/jobs?limit=100`)).json()).jobs.length;
    for (let i = before; i < 23; i++) equal((await page.request.post(`${service.base}/api/v1/jobs`, { data: tiny })).status(), 202, "tiny job");
    const all = (await (await page.request.get(`${service.base}/api/v1/jobs?limit=100`)).json()).jobs.map((j) => j.id);
    assert(all.length > 20, `more than a page of jobs (${all.length})`);
    await page.goto(`${service.base}/#/jobs`);
    await page.reload();  // the delete above left the page on #/jobs already
    await page.waitForSelector("table.jobs tbody tr[data-id]");
    equal(await page.locator("table.jobs tbody tr[data-id]").count(), 20, "first page");
    equal(await page.getAttribute("table.jobs tbody tr[data-id] >> nth=0", "data-id"), all[0], "newest first");
    await page.click('button:text("Show older jobs")');
    await page.waitForFunction((n) => document.querySelectorAll("table.jobs tbody tr[data-id]").length === n, all.length);
    const shown = await page.$$eval("table.jobs tbody tr[data-id]", (trs) => trs.map((t) => t.dataset.id));
    equal(shown, all, "every job once, in order");
    assert(await page.isHidden('button:text("Show older jobs")'), "no more pages");
    await noProblems(page);
  });

  await step("A program that does not interpret: 422 shown with its line and column highlighted", async () => {
    await page.goto(`${service.base}/#/new`);
    await page.check("#mode-registered");
    await page.waitForSelector('#machine-select option[value="3axis-mill"]', { state: "attached" });
    await page.selectOption("#machine-select", "3axis-mill");
    await page.fill("#program", "G21 G90\nT1 M6\nG1 X10 Q\nM30\n");
    await page.fill("#job-json", JSON.stringify({ tools: [{ number: 1, shape: "flat", diameter: 6, flute_length: 20, length: 50 }], stock: { box: { min: [0, 0, -20], max: [50, 50, 0] } } }));
    await page.fill("#density", "5");
    await page.click("#submit-check");
    await page.waitForSelector(".submit-result .notice.error");
    const text = await page.textContent(".submit-result .notice.error");
    assert(/does not interpret/.test(text) && /Program line 3, column 9/.test(text) && /HTTP 422/.test(text), `error box: ${text}`);
    await page.waitForSelector('.program-error .pl.hl[data-line="3"]');
    // Column 9 is just past "G1 X10 Q" (the value Q lacks): the mark sits after the Q.
    equal(await page.getAttribute(".program-error .pl.hl mark.column", "title"), "column 9", "column 9 marked");
    equal(await page.evaluate(() => document.querySelector(".program-error .pl.hl mark.column").previousSibling.textContent), "G1 X10 Q", "text before the mark");
    assert(/#\/new$/.test(page.url()), "stays on the form");
    await shot(page, "program-error");
    await noProblems(page);
  });

  await step("A bad field: 400 shown with the service's message and field", async () => {
    await page.fill("#program", "M30\n");
    await page.fill("#job-json", JSON.stringify({ tools: [{ number: 1, shape: "flat", diameter: "x", flute_length: 20, length: 50 }], stock: { box: { min: [0, 0, -20], max: [50, 50, 0] } } }));
    await page.click("#submit-check");
    await page.waitForFunction(() => /tools\[0\]\.diameter/.test(document.querySelector(".submit-result")?.textContent ?? ""));
    const text = await page.textContent(".submit-result .notice.error");
    assert(/expected a number/.test(text) && /HTTP 400/.test(text), `error box: ${text}`);
    await page.fill("#job-json", "{\n  \"tools\": [],\n  oops\n}");
    await page.click("#submit-check");
    await page.waitForFunction(() => /not valid JSON at line 3, column 3/.test(document.querySelector(".submit-result")?.textContent ?? ""));
    await noProblems(page);
  });

  await step("Machines: the presets listed; one copied, registered by PUT, and deleted", async () => {
    await page.goto(`${service.base}/#/machines`);
    await page.waitForSelector("table.machines tr[data-name]");
    const names = await page.$$eval("table.machines tr[data-name]", (trs) => trs.map((t) => t.dataset.name));
    for (const preset of ["3axis-mill", "ac-trunnion", "bc-trunnion", "bc-head-table", "ab-head-head", "bc-head-head", "nutating-b45"]) {
      assert(names.includes(preset), `preset ${preset} listed in ${names}`);
    }
    await shot(page, "machines");
    await page.click('table.machines a:text-is("ac-trunnion")');
    await page.waitForFunction(() => document.querySelector("#machine-editor")?.value.includes("workpiece_chain"));
    await page.click('a:text("Copy as a new machine")');
    await page.waitForFunction(() => document.querySelector("#machine-name")?.value === "ac-trunnion-copy");
    await page.waitForFunction(() => document.querySelector("#machine-editor")?.value.includes("workpiece_chain"));
    await page.fill("#machine-name", "e2e-mill");
    await page.click('button:text("Register")');
    await page.waitForURL(/#\/machines\/e2e-mill$/);
    const put = await (await page.request.get(`${service.base}/api/v1/machines/e2e-mill`)).json();
    assert(Array.isArray(put.joints) && put.joints.length === 5, "registered with its 5 joints");
    // A broken edit is refused locally with its place.
    await page.waitForFunction(() => document.querySelector("#machine-editor")?.value.includes("workpiece_chain"));
    await page.fill("#machine-editor", "{\n  \"joints\": [,]\n}");
    await page.click('button:text("Save changes")');
    await page.waitForFunction(() => /not valid JSON at line 2, column 14/.test(document.querySelector(".errors")?.textContent ?? ""));
    await page.click('button:text("Delete")');
    await page.waitForURL(/#\/machines$/);
    await page.waitForSelector('table.machines tr[data-name="3axis-mill"]');
    equal(await page.locator('table.machines tr[data-name="e2e-mill"]').count(), 0, "deleted machine gone");
    await noProblems(page);
  });

  await step("Accessibility: axe-core finds no violations on any page", async () => {
    // axe is injected as an inline script, which the page's own CSP forbids: a context
    // that bypasses CSP for this step only.
    const a11y = await newPage(browser, { bypassCSP: true });
    const axe = readFileSync(axePath, "utf8");
    const found = [];
    for (const hash of ["#/jobs", "#/new", `#/jobs/${jobId}`, "#/shadows", "#/machines", "#/machines/3axis-mill"]) {
      await a11y.goto(`${service.base}/${hash}`);
      await a11y.waitForSelector("main h1");
      await a11y.waitForTimeout(300);
      await a11y.addScriptTag({ content: axe });
      const r = await a11y.evaluate(async () => await window.axe.run(document, { resultTypes: ["violations"] }));
      assert(r.passes.length > 10, `axe checked ${r.passes.length} rules on ${hash}`);
      for (const v of r.violations) found.push(`${hash}: ${v.id} (${v.impact}) ${v.help}, e.g. ${v.nodes[0]?.target.join(" ")}`);
    }
    // The shadow form with refusals at its fields, and its JSON view.
    await a11y.goto(`${service.base}/#/shadows`);
    await a11y.waitForSelector("#reg-X-address");
    if (!(await a11y.evaluate(() => Boolean(window.axe)))) await a11y.addScriptTag({ content: axe });
    await a11y.fill("#reg-Y-address", "1");
    await a11y.click("#shadow-start");
    await a11y.waitForSelector("#reg-Y-address-error:not([hidden])");
    for (const what of ["shadow form with errors", "shadow JSON"]) {
      if (what === "shadow JSON") {
        await a11y.click("#shadow-as-json");
        await a11y.waitForSelector("#shadow-json");
      }
      const r = await a11y.evaluate(async () => await window.axe.run(document, { resultTypes: ["violations"] }));
      for (const v of r.violations) found.push(`${what}: ${v.id} (${v.impact}) ${v.help}, e.g. ${v.nodes[0]?.target.join(" ")}`);
    }
    assert(found.length === 0, found.join("\n"));
    await a11y.context().close();
  });

  await step("Tablet: big touch targets and one column", async () => {
    const tablet = await newPage(browser, { viewport: { width: 820, height: 1180 }, hasTouch: true, isMobile: true });
    await tablet.goto(`${service.base}/#/jobs/${jobId}`);
    await tablet.waitForSelector('canvas.viewer-canvas[data-state="drawn"]', { timeout: 20000 });
    for (const sel of ['nav a[data-section="new"]', ".collisions-table tbody tr", "#token-button", ".viewer-tools button"]) {
      const b = await tablet.locator(sel).first().boundingBox();
      assert(b && b.height >= 40, `${sel} is ${b?.height} px tall`);
    }
    const program = await tablet.locator(".program").boundingBox();
    const viewer = await tablet.locator("canvas.viewer-canvas").boundingBox();
    assert(viewer.y > program.y + program.height - 1, "program and 3D view stacked");
    await tablet.tap('.collisions-table tr[data-type="shank_contact"]');
    await tablet.waitForSelector('.program .pl.hl[data-line="12"]');
    await shot(tablet, "tablet-job");
    // The shadow form: its register rows fit the width, their controls big enough.
    await tablet.goto(`${service.base}/#/shadows`);
    await tablet.waitForSelector("#reg-Z-scale");
    equal(await tablet.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), true, "no sideways scrolling");
    for (const sel of ["#reg-X-address", "#reg-X-type", "#reg-X-word_order", "#reg-X-scale", "#mb-host", "label[for=fh-enabled]", "#shadow-start"]) {
      const b = await tablet.locator(sel).first().boundingBox();
      assert(b && b.height >= 40, `${sel} is ${b?.height} px tall`);
    }
    const z = await tablet.locator("#reg-Z-scale").boundingBox();
    assert(z.x + z.width <= 820, `the Z row fits: ends at ${z.x + z.width}`);
    await shot(tablet, "tablet-shadow-form");
    await noProblems(tablet);
    await tablet.context().close();
  });

  await step("A service with a token: the UI asks for it (a wrong one again), then works and keeps it", async () => {
    const guarded = await startService(["--token", TOKEN]);
    const p = await newPage(browser);
    await p.goto(`${guarded.base}/#/machines`);
    await p.waitForSelector("#token-dialog[open]");
    await shot(p, "token");
    assert(/needs an access token/.test(await p.textContent("#token-reason")), "the dialog says why");
    await p.fill("#token-input", "wrong-token-0123456789");
    await p.click('#token-form button[value="save"]');
    await p.waitForFunction(() => document.querySelector("#token-dialog")?.open && /not accepted/.test(document.querySelector("#token-reason").textContent));
    await p.fill("#token-input", TOKEN);
    await p.click('#token-form button[value="save"]');
    await p.waitForSelector('table.machines tr[data-name="3axis-mill"]');
    equal(await p.evaluate(() => localStorage.getItem("mdhd.token")), TOKEN, "token kept");
    await p.reload();
    await p.waitForSelector('table.machines tr[data-name="3axis-mill"]');
    assert(!(await p.evaluate(() => document.querySelector("#token-dialog").open)), "no dialog once the token is kept");
    // Cancelling leaves the service's 401 message on the page.
    await p.evaluate(() => localStorage.clear());
    await p.goto(`${guarded.base}/#/jobs`);
    await p.reload();
    await p.waitForSelector("#token-dialog[open]");
    await p.click('#token-form button[value="cancel"]');
    await p.waitForSelector(".errors .notice.error");
    assert(/HTTP 401/.test(await p.textContent(".errors .notice.error")), "the 401 is shown");
    await noProblems(p);
    await p.context().close();
    guarded.child.kill("SIGTERM");
  });

  // The "start a shadow" form: the crash job's cell reused (machine, tools, stock,
  // program), the default register map (what modbus-sim serves), client-side
  // refusals at their fields, the JSON view both ways, the service's 400 at its field.
  async function startShadowThroughForm(page, simPort) {
    await page.goto(`${service.base}/#/shadows`);
    await page.waitForSelector(`#shadow-job option[value="${jobId}"]`, { state: "attached" });
    await page.waitForSelector('#shadow-machine option[value="3axis-mill"]', { state: "attached" });
    await page.selectOption("#shadow-job", jobId);
    await page.click("#shadow-use-job");
    await page.waitForFunction(() => document.querySelector("#shadow-program")?.value.includes("G1 Z-25 F200"));
    equal(await page.inputValue("#shadow-machine"), "(inline)", "the job's own machine chosen");
    assert(/3-axis/.test(await page.textContent('#shadow-machine option[value="(inline)"]')), "the job's machine named");
    const rows = await page.$$eval(".reg-row", (rs) => rs.map((r) => [r.querySelector(".reg-name span").textContent, r.querySelector("input").value, r.querySelector("select").value]));
    equal(rows, [["X", "0", "float32"], ["Y", "2", "float32"], ["Z", "4", "float32"], ["Tool number", "6", "uint16"], ["Spindle on", "7", "uint16"], ["Program line", "8", "uint32"]], "one row per joint, default registers");
    assert(await page.isDisabled("#reg-tool-word_order") && !(await page.isDisabled("#reg-line-word_order")), "word order for 32-bit types only");
    const cell = JSON.parse(await page.inputValue("#shadow-cell"));
    equal([cell.stock?.box?.min, cell.stock?.box?.max, cell.tools?.[0]?.holder?.length], [[0, 0, -40], [100, 80, 0], 1], "the job's stock and tool");
    equal(Object.keys(cell).includes("machine") || Object.keys(cell).includes("program"), false, "machine and program apart from the cell");
    cell.options = { ...cell.options, density: 2 };
    await page.fill("#shadow-cell", JSON.stringify(cell, null, 2));
    // Feed hold: off, and a warning that turning it on writes to the controller.
    assert(!(await page.isChecked("#fh-enabled")), "feed hold off by default");
    await page.check("#fh-enabled");
    await page.waitForSelector('#fh-warning[data-armed="true"]');
    assert(/writes to the controller/.test(await page.textContent("#fh-warning")), "feed hold warning");
    await page.uncheck("#fh-enabled");
    // Refused before sending, at the fields: no host, Y overlapping X.
    await page.fill("#reg-Y-address", "1");
    await page.click("#shadow-start");
    await page.waitForSelector("#reg-Y-address-error:not([hidden])");
    assert(/Registers 1\.\.2 overlap joint X/.test(await page.textContent("#reg-Y-address-error")), "overlap at Y");
    assert(/overlap joint Y/.test(await page.textContent("#reg-X-address-error")), "overlap at X");
    assert(/host name or IP address/.test(await page.textContent("#mb-host-error")), "host needed");
    equal(await page.getAttribute("#reg-Y-address", "aria-invalid"), "true", "Y marked invalid");
    equal(await page.evaluate(() => document.activeElement.id), "mb-host", "the first problem focused");
    assert(/#\/shadows$/.test(page.url()), "nothing sent");
    await page.fill("#reg-Y-address", "2");
    await page.fill("#mb-host", "127.0.0.1");
    await page.fill("#mb-port", String(simPort));
    await page.fill("#mb-timeout_ms", "500");
    // Edit as JSON: the form's document, changed there, read back into the form.
    await page.click("#shadow-as-json");
    const doc = JSON.parse(await page.inputValue("#shadow-json"));
    equal(doc.modbus.port, simPort, "port in the JSON");
    equal(doc.modbus.joints, { X: { address: 0, type: "float32" }, Y: { address: 2, type: "float32" }, Z: { address: 4, type: "float32" } }, "joints in the JSON");
    equal([doc.machine.name, doc.options.density, doc.program.includes("G1 Z-25 F200")], ["3-axis vertical mill", 2, true], "the cell in the JSON");
    doc.modbus.timeout_ms = 600;
    doc.modbus.line.scale = 1;
    doc.modbus.joints.B = { address: 30, type: "int32", word_order: "cdab" };  // the machine has no B
    await page.fill("#shadow-json", JSON.stringify(doc, null, 2));
    await page.click("#shadow-as-json");
    await page.waitForSelector("#mb-timeout_ms");
    equal([await page.inputValue("#mb-timeout_ms"), await page.inputValue("#reg-line-scale"), await page.inputValue("#mb-port")], ["600", "1", String(simPort)], "JSON edits in the form");
    equal([await page.inputValue("#reg-B-address"), await page.inputValue("#reg-B-type"), await page.inputValue("#reg-B-word_order")], ["30", "int32", "cdab"], "a joint the form did not have");
    await page.click("#reg-B-remove");
    await page.waitForSelector("#reg-B-address", { state: "detached" });
    delete doc.modbus.joints.B;
    await page.click("#shadow-as-json");
    equal(JSON.parse(await page.inputValue("#shadow-json")), doc, "form -> JSON -> form -> JSON unchanged");
    await page.click("#shadow-as-json");
    await page.waitForSelector("#mb-host");
    // The service's 400 shown at the field its path names (the cell's tools).
    const bad = structuredClone(cell);
    bad.tools[0].diameter = "x";
    await page.fill("#shadow-cell", JSON.stringify(bad, null, 2));
    await page.click("#shadow-start");
    await page.waitForSelector("#shadow-cell-error:not([hidden])");
    assert(/expected a number/.test(await page.textContent("#shadow-cell-error")), "the 400 at the cell");
    assert(/HTTP 400/.test(await page.textContent("#shadow-result")) && /tools\[0\]\.diameter/.test(await page.textContent("#shadow-result")), "the 400 in full");
    await page.fill("#shadow-cell", JSON.stringify(cell, null, 2));
    // A program that does not interpret: the 422's line and column at the program.
    const program = await page.inputValue("#shadow-program");
    await page.fill("#shadow-program", "G21 G90\nG1 X10 Q\nM30\n");
    await page.click("#shadow-start");
    await page.waitForSelector("#shadow-program-error:not([hidden])");
    assert(/^Program line 2, column 9: /.test(await page.textContent("#shadow-program-error")), `422 at the program: ${await page.textContent("#shadow-program-error")}`);
    equal(await page.evaluate(() => document.activeElement.id), "shadow-program", "the program focused at the line");
    assert(await page.isHidden("#shadow-cell-error"), "the cell's earlier refusal cleared");
    await page.fill("#shadow-program", program);
    await noProblems(page);
    await page.click("#shadow-start");
    await page.waitForURL(/#\/shadows\/sh-[0-9a-f]+$/);
  }

  if (!process.env.E2E_SKIP_SHADOW) {
    await step("Shadow against mdhd modbus-sim: live state, joints, alarms, live mesh, stop", async () => {
      const sim = await startProcess(["modbus-sim", path.join(examples, "crash-3axis.json"), "--port", "0", "--speed", "20", "--loop"],
        /listening on [0-9.]+:([0-9]+)/, "mdhd modbus-sim");
      const simPort = Number(sim.match[1]);
      await startShadowThroughForm(page, simPort);
      const t0 = Date.now();
      const mark = (what) => console.log(`  ${what} after ${Date.now() - t0} ms`);
      await page.waitForSelector('.shadow-state[data-state="live"]', { timeout: 10000 });
      mark("live");
      await page.waitForSelector(".stream-note:text('live events')");
      // Joints move with the events.
      const z1 = await page.textContent('.joint[data-axis="Z"]');
      await page.waitForFunction((z) => document.querySelector('.joint[data-axis="Z"]')?.textContent !== z, z1, { timeout: 10000 });
      // The crash raises alarms live.
      mark("joints moving");
      // A collision alarm (at speed 20 a poll may straddle the 1 ms rapid, so any of the
      // crash's three; the holder contact lasts long enough to be seen every time).
      await page.waitForSelector("table.alarms tr.collision[data-type]", { timeout: 20000 });
      const types = await page.$$eval("table.alarms tr.collision[data-type]", (trs) => trs.map((t) => t.dataset.type));
      assert(types.every((t) => ["rapid_into_stock", "holder_contact", "shank_contact"].includes(t)), `alarm types ${types}`);
      // Alarms keep coming (the simulator loops) and each new one goes on top, moving
      // the rows: a click that waits for a row to stand still can wait for ever on a
      // loaded machine. The click event itself is what the page acts on.
      const alarmId = await page.getAttribute("table.alarms tr.collision[data-type] >> nth=0", "data-id");
      await page.locator(`table.alarms tr[data-id="${alarmId}"]`).dispatchEvent("click");
      // Its row selected and its marker (collision alarms by id, oldest first) highlighted.
      await page.waitForFunction((id) => {
        const ids = [...document.querySelectorAll("table.alarms tr.collision[data-id]")].map((t) => Number(t.dataset.id)).sort((x, y) => x - y);
        const row = document.querySelector(`table.alarms tr[data-id="${id}"]`);
        return row?.getAttribute("aria-selected") === "true" && ids.includes(Number(id)) &&
          document.querySelector("canvas.viewer-canvas")?.dataset.highlight === String(ids.indexOf(Number(id)));
      }, alarmId, { timeout: 5000 });
      mark("alarm");
      await page.waitForSelector('canvas.viewer-canvas[data-state="drawn"]', { timeout: 10000 });
      assert(Number(await page.getAttribute("canvas.viewer-canvas", "data-triangles")) > 0, "live mesh drawn");
      mark("mesh");
      await shot(page, "shadow");
      await page.click('button:text("Stop shadowing")');
      await page.waitForSelector('.shadow-state[data-state="stopped"]');
      mark("stopped");
      await page.click('a:text("All shadows")');
      await page.waitForSelector('table.shadows tr[data-state="stopped"]');
      await noProblems(page);
      sim.child.kill("SIGTERM");
    });
  }
} finally {
  await browser.close().catch(() => {});
  cleanup();
}

const seconds = ((Date.now() - started) / 1000).toFixed(1);
console.log(`web_e2e: ${passed} passed, ${failures.length} failed in ${seconds} s`);
if (failures.length) {
  console.log(`failed: ${failures.join("; ")}`);
  process.exit(1);
}
