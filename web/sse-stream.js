// Reads a Server-Sent Events stream with fetch (so the Authorization header
// goes along, which EventSource cannot do), parses it with SseParser, and
// reconnects with Last-Event-ID when the connection drops.
import { apiFetch } from "./api.js";
import { SseParser } from "./sse.js";
import { pause } from "./ui.js";

// onEvent({type, data, id}); onStatus("open" | "reconnecting" | "ended", error?).
// Resolves when the server ends the stream for good (it ended with no error)
// or the signal aborts.
export async function followEvents(path, { signal, onEvent, onStatus = () => {}, shouldReconnect = () => true }) {
  let lastId = "";
  let delay = 500;
  while (!signal.aborted) {
    let failure = null;
    try {
      const headers = { Accept: "text/event-stream" };
      if (lastId) headers["Last-Event-ID"] = lastId;
      const res = await apiFetch(path, { headers, signal });
      onStatus("open");
      delay = 500;
      const parser = new SseParser();
      const reader = res.body.getReader();
      signal.addEventListener("abort", () => reader.cancel().catch(() => {}), { once: true });
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        for (const event of parser.push(value)) {
          if (event.id) lastId = event.id;
          onEvent(event);
        }
      }
    } catch (err) {
      if (signal.aborted) return;
      failure = err;
      // A 404 (the shadow is gone) or a refused token will not get better by retrying.
      if (err?.status === 404 || err?.status === 401 || err?.status === 403) {
        onStatus("ended", err);
        return;
      }
    }
    if (signal.aborted) return;
    if (!failure && !shouldReconnect()) {
      onStatus("ended");
      return;
    }
    onStatus("reconnecting", failure);
    await pause(delay, signal);
    delay = Math.min(delay * 2, 5000);
  }
}
