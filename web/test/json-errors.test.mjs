import { test } from "node:test";
import assert from "node:assert/strict";
import { findJsonError } from "../json-errors.js";

test("valid JSON has no error", () => {
  for (const t of ["{}", "[]", " 1 ", "-0.5e+3", "\"a\\u00e9\\n\"", "{\"a\": [1, true, false, null, {\"b\": \"c\"}]}", "\n{\r\n\t\"x\": 1\n}\n"]) {
    assert.equal(findJsonError(t), null, t);
    JSON.parse(t);
  }
});

test("each kind of mistake is found at its place with a reason", () => {
  const cases = [
    ["{\"a\": 1,}", 8, /expected a name in quotes, found "}"/],
    ["{\"a\" 1}", 5, /expected ':'/],
    ["{\"a\": 1 \"b\": 2}", 8, /expected ',' or '}'/],
    ["[1 2]", 3, /expected ',' or ']'/],
    ["[1,]", 3, /expected a value, found "]"/],
    ["{\"a\": tru}", 6, /expected a value/],
    ["{\"a\": 01}", 7, /expected ',' or '}'/],
    ["\"abc", 4, /not closed/],
    ["\"a\nb\"", 2, /line break/],
    ["\"\\x\"", 1, /unknown escape/],
    ["\"\\u12\"", 1, /4 hex digits/],
    ["{} x", 3, /after the end/],
    ["", 0, /expected a value, the text ends/],
    ["{\"a\": ", 6, /the text ends/],
  ];
  for (const [text, offset, reason] of cases) {
    const e = findJsonError(text);
    assert.ok(e, `${JSON.stringify(text)} is an error`);
    assert.equal(e.offset, offset, JSON.stringify(text));
    assert.match(e.reason, reason, JSON.stringify(text));
    assert.throws(() => JSON.parse(text), SyntaxError, "JSON.parse agrees");
  }
});

test("deep nesting is refused, not a stack overflow", () => {
  assert.match(findJsonError("[".repeat(100000)).reason, /nested too deeply/);
});
