// The single page: routes the hash to a page, keeps the header's tabs current,
// wires the token dialog, and turns any stray failure into a calm message.
import { parseHash, sectionOf } from "./router.js";
import { setTokenPrompt } from "./api.js";
import { askForToken, updateTokenButton } from "./token-dialog.js";
import { h, fill } from "./dom.js";
import { renderJobs } from "./view-jobs.js";
import { renderJob } from "./view-job.js";
import { renderNewCheck } from "./view-new-check.js";
import { renderShadows } from "./view-shadows.js";
import { renderShadow } from "./view-shadow.js";
import { renderMachines } from "./view-machines.js";
import { renderMachine } from "./view-machine.js";

const PAGES = {
  jobs: renderJobs,
  job: renderJob,
  new: renderNewCheck,
  shadows: renderShadows,
  shadow: renderShadow,
  machines: renderMachines,
  machine: renderMachine,
  "new-machine": renderMachine,
};

let leave = null;  // AbortController of the page shown

function show() {
  leave?.abort();
  leave = new AbortController();
  const route = parseHash(location.hash);
  const main = document.getElementById("main");
  document.getElementById("page-error").hidden = true;
  for (const a of document.querySelectorAll("[data-section]")) {
    if (a.dataset.section === sectionOf(route)) a.setAttribute("aria-current", "page");
    else a.removeAttribute("aria-current");
  }
  const page = PAGES[route.name];
  fill(main);
  if (!page) {
    document.title = "Not found · mdhd";
    fill(main, h("h1", {}, "Nothing here"), h("p", {}, "This address is not a page of mdhd. ", h("a", { href: "#/jobs" }, "Go to the jobs.")));
    return;
  }
  page(main, route, leave.signal);
  // Move focus to the new page's heading for screen readers and keyboards,
  // without scrolling a tablet's view away from where the finger is.
  const heading = main.querySelector("h1");
  if (heading && document.activeElement !== document.body && !main.contains(document.activeElement)) {
    heading.focus({ preventScroll: true });
  }
}

function pageError(message) {
  const box = document.getElementById("page-error");
  box.textContent = message;
  box.hidden = false;
}

window.addEventListener("error", (e) => {
  console.error(e.error ?? e.message);
  pageError("Something unexpected went wrong in the page. Reload it if it stops responding (details are in the browser console).");
});
window.addEventListener("unhandledrejection", (e) => {
  if (e.reason?.name === "AbortError") return;
  console.error(e.reason);
  pageError("Something unexpected went wrong in the page. Reload it if it stops responding (details are in the browser console).");
});

setTokenPrompt(askForToken);
document.getElementById("token-button").addEventListener("click", () => askForToken("The access token this browser sends to the service."));
updateTokenButton();
window.addEventListener("hashchange", show);
show();
