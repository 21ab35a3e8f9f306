// What a failed request means to the user: pure, so Node tests it.

import { findJsonError } from "./json-errors.js";
// The service answers errors as {"error": {"code", "message", ...}} (400 adds
// `field` and `problems`, 422 `line`, `column` and `block`, 429 a Retry-After).

export class ApiError extends Error {
  constructor(info) {
    super(info.message);
    this.name = "ApiError";
    Object.assign(this, info);
  }
}

const STATUS_TEXT = {
  400: "the request was refused",
  401: "a token is needed",
  403: "the token was not accepted",
  404: "not found",
  405: "method not allowed",
  409: "not available in this state",
  413: "too large",
  415: "unsupported media type",
  422: "the program does not interpret",
  429: "the service is busy",
  500: "the service failed",
  502: "bad gateway",
  503: "the service is unavailable",
  504: "gateway timeout",
};

// The error of a reply with HTTP status `status` and body text `text`.
export function errorFromReply(status, text, retryAfter = null) {
  let body = null;
  try {
    body = JSON.parse(text);
  } catch {
    body = null;
  }
  const e = body && typeof body === "object" && body.error && typeof body.error === "object" ? body.error : null;
  const info = {
    status,
    code: typeof e?.code === "string" ? e.code : `http_${status}`,
    message: "",
    line: Number.isInteger(e?.line) ? e.line : null,
    column: Number.isInteger(e?.column) ? e.column : null,
    block: typeof e?.block === "string" ? e.block : null,
    field: typeof e?.field === "string" ? e.field : null,
    problems: Array.isArray(e?.problems)
      ? e.problems.filter((p) => p && typeof p === "object").map((p) => ({
          field: typeof p.field === "string" ? p.field : "",
          message: typeof p.message === "string" ? p.message : String(p.message ?? ""),
        }))
      : [],
    retryAfter: retryAfter !== null && /^[0-9]+$/.test(String(retryAfter)) ? Number(retryAfter) : null,
  };
  if (typeof e?.message === "string" && e.message.trim() !== "") {
    info.message = e.message;
  } else {
    const plain = typeof text === "string" && text.length < 300 && !/[<>]/.test(text) ? text.trim() : "";
    info.message = `HTTP ${status}: ${STATUS_TEXT[status] ?? "unexpected reply"}` + (plain ? ` (${plain})` : "");
  }
  if (info.retryAfter !== null && !/retry/i.test(info.message)) {
    info.message += ` Try again in ${info.retryAfter} s.`;
  }
  return new ApiError(info);
}

// One sentence for the user, whatever was thrown: never a stack or an internal name.
export function describeError(err) {
  if (err instanceof ApiError || err?.name === "ApiError") return err.message;
  if (err?.name === "StlError" || err?.name === "InputError") return err.message;
  if (err?.name === "AbortError") return "The request was cancelled.";
  if (err instanceof TypeError && /fetch|network|load failed/i.test(String(err.message))) {
    return "Cannot reach the mdhd service: check that it is running and that this device is on its network.";
  }
  return "Something unexpected went wrong in the page (details are in the browser console).";
}

// A mistake in text the user typed or loaded, shown as is.
export class InputError extends Error {
  constructor(message, where = {}) {
    super(message);
    this.name = "InputError";
    Object.assign(this, where);
  }
}

// Parses JSON typed by the user; throws InputError naming `what` and the line and
// column of the mistake.
export function parseUserJson(text, what) {
  try {
    return JSON.parse(text);
  } catch {
    const found = findJsonError(String(text));
    if (!found) throw new InputError(`${what} is not valid JSON`);
    const where = placeOf(String(text), found.offset);
    throw new InputError(`${what} is not valid JSON at line ${where.line}, column ${where.column}: ${found.reason}`, where);
  }
}

// The 1-based line and column of character `offset` in `text`.
export function placeOf(text, offset) {
  let line = 1, lineStart = 0;
  for (let i = 0; i < Math.min(offset, text.length); i++) {
    if (text[i] === "\n") {
      line++;
      lineStart = i + 1;
    }
  }
  return { line, column: offset - lineStart + 1 };
}
