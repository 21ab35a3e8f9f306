// Requests to the service's API: the bearer token, and on 401/403 the token
// dialog, then the same request again. Every failure is an ApiError whose message
// is the service's own (see api-errors.js).

import { ApiError, errorFromReply } from "./api-errors.js";
import { getToken, tokenInMemory } from "./token-store.js";

let askToken = null;  // async (reason) => token | null

// The page registers how to ask for a token (the dialog).
export function setTokenPrompt(fn) {
  askToken = fn;
}

// fetch with the token; resolves to the Response when it is 2xx, else throws.
export async function apiFetch(path, { method = "GET", json, headers = {}, signal } = {}) {
  for (let attempt = 0; ; attempt++) {
    const head = { ...headers };
    const token = getToken() || tokenInMemory();
    if (token) head.Authorization = `Bearer ${token}`;
    let body;
    if (json !== undefined) {
      body = JSON.stringify(json);
      head["Content-Type"] = "application/json";
    }
    const res = await fetch(path, { method, headers: head, body, signal, cache: "no-store" });
    if ((res.status === 401 || res.status === 403) && askToken && attempt < 5) {
      const err = errorFromReply(res.status, await res.text());
      const reason = res.status === 401
        ? "This service needs an access token."
        : `The token was not accepted (${err.message}). Enter another one.`;
      const next = await askToken(reason);
      if (!next) throw err;
      continue;
    }
    if (!res.ok) throw errorFromReply(res.status, await res.text(), res.headers.get("Retry-After"));
    return res;
  }
}

// The reply's JSON (null for 204).
export async function apiJson(path, options) {
  const res = await apiFetch(path, options);
  if (res.status === 204) return null;
  const text = await res.text();
  try {
    return text === "" ? null : JSON.parse(text);
  } catch {
    throw new ApiError({ status: res.status, code: "bad_reply", message: `The service's reply to ${path} was not JSON.` });
  }
}

export async function apiBytes(path, options) {
  const res = await apiFetch(path, options);
  return res.arrayBuffer();
}

export const enc = encodeURIComponent;
