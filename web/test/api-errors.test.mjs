import { test } from "node:test";
import assert from "node:assert/strict";
import { errorFromReply, describeError, ApiError, parseUserJson, InputError, placeOf } from "../api-errors.js";

test("a 422 program error keeps line, column, block and the message", () => {
  const e = errorFromReply(422, JSON.stringify({ error: { block: "G1 X10 Q", code: "program_error", column: 9, line: 3,
    message: "program line 3, column 9: No characters found in reading real value" } }));
  assert.ok(e instanceof ApiError);
  assert.equal(e.status, 422);
  assert.equal(e.code, "program_error");
  assert.equal(e.line, 3);
  assert.equal(e.column, 9);
  assert.equal(e.block, "G1 X10 Q");
  assert.match(e.message, /column 9/);
  assert.equal(describeError(e), e.message);
});

test("a 400 keeps the field and every problem", () => {
  const e = errorFromReply(400, JSON.stringify({ error: { code: "bad_field", field: "tools[0].diameter", message: "tools[0].diameter: expected a number",
    problems: [{ field: "tools[0].diameter", message: "expected a number" }, { field: "stock", message: "missing" }, "junk"] } }));
  assert.equal(e.field, "tools[0].diameter");
  assert.deepEqual(e.problems, [{ field: "tools[0].diameter", message: "expected a number" }, { field: "stock", message: "missing" }]);
  assert.equal(e.line, null);
});

test("a reply that is not the service's JSON still says what happened", () => {
  const html = errorFromReply(502, "<html><body>Bad Gateway</body></html>");
  assert.equal(html.message, "HTTP 502: bad gateway");
  assert.equal(html.code, "http_502");
  assert.equal(errorFromReply(500, "").message, "HTTP 500: the service failed");
  assert.equal(errorFromReply(418, "short and plain").message, "HTTP 418: unexpected reply (short and plain)");
  assert.equal(errorFromReply(400, JSON.stringify({ error: "flat string" })).message, "HTTP 400: the request was refused (" + JSON.stringify({ error: "flat string" }) + ")");
  assert.equal(errorFromReply(404, JSON.stringify({ error: { code: "not_found", message: "" } })).message, "HTTP 404: not found ({\"error\":{\"code\":\"not_found\",\"message\":\"\"}})");
});

test("Retry-After is kept and said", () => {
  const e = errorFromReply(429, JSON.stringify({ error: { code: "queue_full", message: "the queue is full" } }), "5");
  assert.equal(e.retryAfter, 5);
  assert.equal(e.message, "the queue is full Try again in 5 s.");
  assert.equal(errorFromReply(429, "{}", "soon").retryAfter, null);
});

test("describeError never shows a raw exception", () => {
  assert.match(describeError(new TypeError("Failed to fetch")), /Cannot reach the mdhd service/);
  assert.equal(describeError(new TypeError("x is undefined")), "Something unexpected went wrong in the page (details are in the browser console).");
  assert.equal(describeError(new RangeError("boom")), "Something unexpected went wrong in the page (details are in the browser console).");
  assert.equal(describeError(undefined), "Something unexpected went wrong in the page (details are in the browser console).");
  assert.equal(describeError(new InputError("Load the program.")), "Load the program.");
  const abort = new Error("aborted");
  abort.name = "AbortError";
  assert.equal(describeError(abort), "The request was cancelled.");
});

test("JSON typed by the user: its mistakes are placed by line and column", () => {
  assert.deepEqual(parseUserJson("{\"a\": 1}", "x"), { a: 1 });
  assert.throws(() => parseUserJson("{\n  \"a\": 1,\n  oops\n}", "The machine"),
    (e) => e instanceof InputError && e.line === 3 && e.column === 3 &&
      e.message === "The machine is not valid JSON at line 3, column 3: expected a name in quotes, found \"o\"");
  assert.throws(() => parseUserJson("{\"a\": ", "The job"), (e) => e.line === 1 && e.column === 7 && /The job is not valid JSON at line 1, column 7: expected a value, the text ends/.test(e.message));
});

test("placeOf", () => {
  assert.deepEqual(placeOf("ab\ncd\nef", 4), { line: 2, column: 2 });
  assert.deepEqual(placeOf("abc", 0), { line: 1, column: 1 });
  assert.deepEqual(placeOf("ab", 2), { line: 1, column: 3 });
});
