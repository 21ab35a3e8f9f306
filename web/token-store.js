// The API token, kept in this browser's local storage.
const KEY = "mdhd.token";

export function getToken() {
  try {
    return localStorage.getItem(KEY) ?? "";
  } catch {
    return "";  // storage disabled: no token
  }
}

export function setToken(token) {
  try {
    if (token) localStorage.setItem(KEY, token);
    else localStorage.removeItem(KEY);
  } catch {
    // storage disabled: the token lasts until the page is reloaded
  }
  memory = token;
}

let memory = "";
export function tokenInMemory() {
  return memory;
}
