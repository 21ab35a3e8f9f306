// Machines: the registry, with links to each machine and to register a new one.
import { h, fill } from "./dom.js";
import { apiJson } from "./api.js";
import { hashFor } from "./router.js";
import { formatTimestamp } from "./format.js";
import { errorBox, pageHead } from "./ui.js";

export function renderMachines(main, route, signal) {
  document.title = "Machines · mdhd";
  const errors = h("div", { class: "errors", "aria-live": "polite" });
  const body = h("tbody", {}, h("tr", {}, h("td", { colspan: "4" }, "Loading…")));
  fill(main,
    pageHead("Machines", h("a", { class: "button primary", href: hashFor("new-machine") }, "Register a machine")),
    errors,
    h("div", { class: "table-wrap" }, h("table", { class: "grid machines" },
      h("thead", {}, h("tr", {}, ["Name", "Description", "Joints", "Updated"].map((t) => h("th", { scope: "col" }, t)))),
      body)));
  (async () => {
    try {
      const { machines } = await apiJson("/api/v1/machines", { signal });
      fill(body, machines.length
        ? machines.map((m) => h("tr", { dataset: { name: m.name } },
            h("td", {}, h("a", { href: hashFor("machine", { name: m.name }) }, m.name)),
            h("td", {}, m.description ?? ""),
            h("td", {}, (m.joints ?? []).join(" ")),
            h("td", {}, formatTimestamp(m.updated_at))))
        : h("tr", {}, h("td", { colspan: "4" }, "No machines are registered. Register one, or send jobs with the machine inline.")));
    } catch (err) {
      if (signal.aborted) return;
      fill(body);
      errors.replaceChildren(errorBox(err, "Could not list the machines"));
    }
  })();
}
