import { test } from "node:test";
import assert from "node:assert/strict";
import { SseParser, eventJson } from "../sse.js";

const STREAM =
  "\uFEFF: hello\n" +
  "id: 1\nevent: state\ndata: {\"state\":\"live\"}\n\n" +
  "id: 2\r\nevent: pose\r\ndata: {\"joints\":{\"X\":1.5},\"label\":\"Ø ü 😀\"}\r\n\r\n" +
  ": keep-alive\r\r" +
  "id: 3\revent: alarm\rdata: line one\rdata:line two\r\r" +
  "data: no type\n\n" +
  "event: empty\n\n" +
  "retry: 3000\nid\ndata\n\n" +
  "event: cut\ndata: never finished";

const EXPECTED = [
  { type: "state", data: "{\"state\":\"live\"}", id: "1" },
  { type: "pose", data: "{\"joints\":{\"X\":1.5},\"label\":\"Ø ü 😀\"}", id: "2" },
  { type: "alarm", data: "line one\nline two", id: "3" },
  { type: "message", data: "no type", id: "3" },
  { type: "message", data: "", id: "" },
];

function run(chunks) {
  const p = new SseParser();
  const events = [];
  for (const c of chunks) events.push(...p.push(c));
  events.push(...p.end());
  return { events, parser: p };
}

test("a whole stream in one chunk: types, ids, multi-line data, comments, CR/LF/CRLF, BOM", () => {
  const bytes = new TextEncoder().encode(STREAM);
  const { events, parser } = run([bytes]);
  assert.deepEqual(events, EXPECTED);
  assert.equal(parser.retry, 3000);
});

test("the same events however the bytes are cut: every split point, two and three chunks", () => {
  const bytes = new TextEncoder().encode(STREAM);
  for (let i = 0; i <= bytes.length; i++) {
    const { events } = run([bytes.slice(0, i), bytes.slice(i)]);
    assert.deepEqual(events, EXPECTED, `split at byte ${i}`);
  }
  for (let i = 0; i < bytes.length; i += 3) {
    for (let j = i; j <= bytes.length; j += 7) {
      const { events } = run([bytes.slice(0, i), bytes.slice(i, j), bytes.slice(j)]);
      assert.deepEqual(events, EXPECTED, `split at ${i} and ${j}`);
    }
  }
});

test("one byte at a time (UTF-8 characters cut inside)", () => {
  const bytes = new TextEncoder().encode(STREAM);
  const chunks = Array.from(bytes, (b) => Uint8Array.of(b));
  assert.deepEqual(run(chunks).events, EXPECTED);
});

test("a CR at the end of a chunk and the LF at the start of the next are one line end", () => {
  const p = new SseParser();
  assert.deepEqual(p.push("data: a\r"), []);
  assert.deepEqual(p.push("\n"), [], "CR LF is one line end, not a line and an empty line");
  assert.deepEqual(p.push("\r"), [{ type: "message", data: "a", id: "" }]);
  assert.deepEqual(p.push("\ndata: b\n\n"), [{ type: "message", data: "b", id: "" }]);
});

test("a CR LF split across chunks does not end an event early", () => {
  const p = new SseParser();
  const events = [...p.push("data: a\r"), ...p.push("\ndata: b\r"), ...p.push("\n\r"), ...p.push("\n")];
  assert.deepEqual(events, [{ type: "message", data: "a\nb", id: "" }]);
});

test("eventJson parses data and gives null for malformed JSON", () => {
  assert.deepEqual(eventJson({ data: "{\"a\":1}" }), { a: 1 });
  assert.equal(eventJson({ data: "{oops" }), null);
});
