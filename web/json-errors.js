// Where and why JSON text is malformed, the same in every browser (engines word
// JSON.parse's errors differently and some give no position): a small
// recursive-descent scan of RFC 8259. Pure, so Node tests it.

// Returns null for valid JSON, else {offset, reason}.
export function findJsonError(text) {
  let i = 0;
  const fail = (reason, at = i) => {
    throw { offset: at, reason };
  };
  const ws = () => {
    while (i < text.length && (text[i] === " " || text[i] === "\t" || text[i] === "\n" || text[i] === "\r")) i++;
  };
  const describe = () => (i >= text.length ? "the text ends" : `found ${JSON.stringify(text[i])}`);
  const literal = (word) => {
    if (text.startsWith(word, i)) i += word.length;
    else fail(`expected a value, ${describe()}`);
  };
  const string = () => {
    i++;  // opening quote
    for (;;) {
      if (i >= text.length) fail("a string is not closed", i);
      const c = text.charCodeAt(i);
      if (c === 0x22) { i++; return; }
      if (c < 0x20) fail("a string holds a line break or control character (write \\n)");
      if (c === 0x5c) {
        const e = text[i + 1];
        if (e === "u") {
          if (!/^[0-9a-fA-F]{4}$/.test(text.slice(i + 2, i + 6))) fail("a \\u escape needs 4 hex digits");
          i += 6;
        } else if (e !== undefined && "\"\\/bfnrt".includes(e)) {
          i += 2;
        } else {
          fail("an unknown escape in a string");
        }
      } else {
        i++;
      }
    }
  };
  const number = () => {
    const m = /^-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?/.exec(text.slice(i, i + 400));
    if (!m || m[0] === "" || m[0] === "-") fail(`expected a value, ${describe()}`);
    i += m[0].length;
  };
  const value = (depth) => {
    if (depth > 512) fail("nested too deeply");
    ws();
    const c = text[i];
    if (c === "{") {
      i++;
      ws();
      if (text[i] === "}") { i++; return; }
      for (;;) {
        ws();
        if (text[i] !== "\"") fail(`expected a name in quotes, ${describe()}`);
        string();
        ws();
        if (text[i] !== ":") fail(`expected ':' after a name, ${describe()}`);
        i++;
        value(depth + 1);
        ws();
        if (text[i] === ",") { i++; continue; }
        if (text[i] === "}") { i++; return; }
        fail(`expected ',' or '}', ${describe()}`);
      }
    } else if (c === "[") {
      i++;
      ws();
      if (text[i] === "]") { i++; return; }
      for (;;) {
        value(depth + 1);
        ws();
        if (text[i] === ",") { i++; continue; }
        if (text[i] === "]") { i++; return; }
        fail(`expected ',' or ']', ${describe()}`);
      }
    } else if (c === "\"") {
      string();
    } else if (c === "t") {
      literal("true");
    } else if (c === "f") {
      literal("false");
    } else if (c === "n") {
      literal("null");
    } else {
      number();
    }
  };
  try {
    value(0);
    ws();
    if (i < text.length) fail(`unexpected text after the end, ${describe()}`);
    return null;
  } catch (e) {
    if (e && typeof e.offset === "number") return e;
    throw e;
  }
}
