// The token dialog: asked for by api.js on a 401/403, and from the header button.
import { getToken, setToken } from "./token-store.js";

let pending = null;  // one dialog for every request that needs it at once

export function askForToken(reason) {
  if (pending) return pending;
  const dialog = document.getElementById("token-dialog");
  const input = document.getElementById("token-input");
  const show = document.getElementById("token-show");
  document.getElementById("token-reason").textContent = reason;
  input.value = getToken();
  show.checked = false;
  input.type = "password";
  show.onchange = () => {
    input.type = show.checked ? "text" : "password";
  };
  pending = new Promise((resolve) => {
    dialog.addEventListener("close", () => {
      pending = null;
      const action = dialog.returnValue;
      if (action === "save" && input.value.trim()) {
        setToken(input.value.trim());
        resolve(input.value.trim());
      } else {
        if (action === "clear") setToken("");
        resolve(null);
      }
      updateTokenButton();
    }, { once: true });
  });
  dialog.returnValue = "";
  dialog.showModal();
  input.focus();
  return pending;
}

export function updateTokenButton() {
  const button = document.getElementById("token-button");
  if (!button) return;
  const has = Boolean(getToken());
  button.textContent = has ? "Token ✓" : "Token";
  button.setAttribute("aria-label", has ? "Access token (set)" : "Access token (none)");
}
