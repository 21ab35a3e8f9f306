import { test } from "node:test";
import assert from "node:assert/strict";
import { parseHash, hashFor, sectionOf } from "../router.js";

test("an empty hash and #/ are the jobs list", () => {
  for (const h of ["", "#", "#/", "#/jobs", "#/jobs/"]) assert.equal(parseHash(h).name, "jobs", h);
});

test("each page and its parameters", () => {
  assert.deepEqual(parseHash("#/jobs/60cbcf9c").params, { id: "60cbcf9c" });
  assert.equal(parseHash("#/jobs/60cbcf9c").name, "job");
  assert.equal(parseHash("#/new").name, "new");
  assert.equal(parseHash("#/shadows").name, "shadows");
  assert.deepEqual(parseHash("#/shadows/sh-1a2b"), { name: "shadow", params: { id: "sh-1a2b" }, query: {} });
  assert.equal(parseHash("#/machines").name, "machines");
  assert.deepEqual(parseHash("#/machines/ac-trunnion").params, { name: "ac-trunnion" });
  assert.equal(parseHash("#/new-machine").name, "new-machine");
});

test("segments are URL-decoded and the query is parsed", () => {
  const r = parseHash("#/machines/my%20mill?from=3axis-mill&x");
  assert.equal(r.params.name, "my mill");
  assert.deepEqual(r.query, { from: "3axis-mill", x: "" });
});

test("unknown and malformed hashes are not_found", () => {
  assert.equal(parseHash("#/nope").name, "not_found");
  assert.equal(parseHash("#/jobs/a/b").name, "not_found");
  assert.equal(parseHash("#/machines/%E0%A4%A").name, "not_found");
});

test("hashFor builds what parseHash reads back", () => {
  assert.equal(hashFor("job", { id: "abc" }), "#/jobs/abc");
  assert.equal(hashFor("machine", { name: "a/b c" }), "#/machines/a%2Fb%20c");
  assert.deepEqual(parseHash(hashFor("machine", { name: "a/b c" })).params, { name: "a/b c" });
  assert.equal(hashFor("jobs"), "#/jobs");
  assert.throws(() => hashFor("job", {}), /needs id/);
  assert.throws(() => hashFor("bogus"), /no route/);
});

test("sectionOf marks the header tab of each page", () => {
  assert.equal(sectionOf(parseHash("#/jobs/x")), "jobs");
  assert.equal(sectionOf(parseHash("#/new")), "new");
  assert.equal(sectionOf(parseHash("#/shadows/x")), "shadows");
  assert.equal(sectionOf(parseHash("#/new-machine")), "machines");
  assert.equal(sectionOf(parseHash("#/zzz")), "");
});
