// Server-Sent Events parsing (the WHATWG event-stream format): pure, so Node
// tests it. EventSource cannot send an Authorization header, so the UI reads the
// stream with fetch and feeds the bytes here, chunk by chunk, wherever the
// network cut them (inside a line, a CR LF pair or a UTF-8 character).

export class SseParser {
  constructor() {
    this.decoder = new TextDecoder("utf-8");
    this.buffer = "";          // text of an unfinished line
    this.skipLf = false;       // the last chunk ended in CR: a leading LF belongs to it
    this.started = false;      // a BOM is dropped at the very start only
    this.data = [];
    this.type = "";
    this.lastEventId = "";
    this.retry = null;
  }

  // Feeds a chunk (Uint8Array or string); returns the events it completed, each
  // {type, data, id}.
  push(chunk) {
    let text = typeof chunk === "string" ? chunk : this.decoder.decode(chunk, { stream: true });
    if (!this.started && text.length > 0) {
      this.started = true;
      if (text.charCodeAt(0) === 0xfeff) text = text.slice(1);
    }
    const events = [];
    let i = 0;
    if (this.skipLf && text.length > 0) {
      if (text[0] === "\n") i = 1;
      this.skipLf = false;
    }
    let start = i;
    for (; i < text.length; i++) {
      const c = text[i];
      if (c !== "\n" && c !== "\r") continue;
      const line = this.buffer + text.slice(start, i);
      this.buffer = "";
      if (c === "\r") {
        if (i + 1 < text.length) {
          if (text[i + 1] === "\n") i++;
        } else {
          this.skipLf = true;
        }
      }
      start = i + 1;
      const event = this.line(line);
      if (event) events.push(event);
    }
    this.buffer += text.slice(start);
    return events;
  }

  // The end of the stream: an unfinished event is dropped (as the standard says).
  end() {
    this.buffer = "";
    this.data = [];
    this.type = "";
    return [];
  }

  line(line) {
    if (line === "") return this.dispatch();
    if (line[0] === ":") return null;  // a comment (keep-alive)
    const colon = line.indexOf(":");
    let field = line, value = "";
    if (colon >= 0) {
      field = line.slice(0, colon);
      value = line.slice(colon + 1);
      if (value[0] === " ") value = value.slice(1);
    }
    switch (field) {
      case "event": this.type = value; break;
      case "data": this.data.push(value); break;
      case "id": if (!value.includes("\0")) this.lastEventId = value; break;
      case "retry": if (/^[0-9]+$/.test(value)) this.retry = Number(value); break;
      default: break;  // unknown fields are ignored
    }
    return null;
  }

  dispatch() {
    const type = this.type || "message";
    this.type = "";
    if (this.data.length === 0) return null;
    const data = this.data.join("\n");
    this.data = [];
    return { type, data, id: this.lastEventId };
  }
}

// Parses an event's data as JSON; a malformed one gives null (not an exception).
export function eventJson(event) {
  try {
    return JSON.parse(event.data);
  } catch {
    return null;
  }
}
