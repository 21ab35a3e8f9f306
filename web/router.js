// Hash routes of the single page: pure, so Node tests it.
// #/jobs, #/jobs/<id>, #/new, #/shadows, #/shadows/<id>, #/machines,
// #/machines/<name>, #/new-machine. An empty hash is the jobs list.

const ROUTES = [
  { name: "jobs", pattern: ["jobs"] },
  { name: "job", pattern: ["jobs", ":id"] },
  { name: "new", pattern: ["new"] },
  { name: "shadows", pattern: ["shadows"] },
  { name: "shadow", pattern: ["shadows", ":id"] },
  { name: "machines", pattern: ["machines"] },
  { name: "machine", pattern: ["machines", ":name"] },
  { name: "new-machine", pattern: ["new-machine"] },
];

// "#/jobs/abc?x=1" -> {name: "job", params: {id: "abc"}, query: {x: "1"}}.
// Unknown or malformed hashes give {name: "not_found", path}.
export function parseHash(hash) {
  let text = String(hash ?? "");
  if (text.startsWith("#")) text = text.slice(1);
  let queryText = "";
  const q = text.indexOf("?");
  if (q >= 0) {
    queryText = text.slice(q + 1);
    text = text.slice(0, q);
  }
  const query = {};
  for (const pair of queryText.split("&")) {
    if (!pair) continue;
    const eq = pair.indexOf("=");
    const key = safeDecode(eq >= 0 ? pair.slice(0, eq) : pair);
    const value = safeDecode(eq >= 0 ? pair.slice(eq + 1) : "");
    if (key !== null && value !== null) query[key] = value;
  }
  const segments = text.split("/").filter((s) => s !== "");
  if (segments.length === 0) return { name: "jobs", params: {}, query };
  const decoded = segments.map(safeDecode);
  if (decoded.includes(null)) return { name: "not_found", params: {}, query, path: text };
  for (const route of ROUTES) {
    if (route.pattern.length !== decoded.length) continue;
    const params = {};
    let ok = true;
    route.pattern.forEach((part, i) => {
      if (part.startsWith(":")) params[part.slice(1)] = decoded[i];
      else if (part !== decoded[i]) ok = false;
    });
    if (ok) return { name: route.name, params, query };
  }
  return { name: "not_found", params: {}, query, path: text };
}

// The hash of a route: hashFor("job", {id}) -> "#/jobs/<id>".
export function hashFor(name, params = {}) {
  const route = ROUTES.find((r) => r.name === name);
  if (!route) throw new Error(`no route ${name}`);
  const parts = route.pattern.map((part) => {
    if (!part.startsWith(":")) return part;
    const value = params[part.slice(1)];
    if (value === undefined || value === "") throw new Error(`route ${name} needs ${part.slice(1)}`);
    return encodeURIComponent(value);
  });
  return "#/" + parts.join("/");
}

// The navigation tab a route belongs to (for aria-current in the header).
export function sectionOf(route) {
  switch (route.name) {
    case "jobs": case "job": return "jobs";
    case "new": return "new";
    case "shadows": case "shadow": return "shadows";
    case "machines": case "machine": case "new-machine": return "machines";
    default: return "";
  }
}

function safeDecode(s) {
  try {
    return decodeURIComponent(s);
  } catch {
    return null;
  }
}
