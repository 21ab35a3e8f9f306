// A G-code listing with line numbers that shows only the lines in view (a
// program may have a million lines), scrolls to a line and highlights it (and a
// column in it).
import { h, clear } from "./dom.js";

const LINE_PX = 24;
const OVERSCAN = 20;

export class ProgramView {
  constructor(text, { label = "Program" } = {}) {
    this.lines = String(text ?? "").split(/\r\n|\n/);
    if (this.lines.length > 1 && this.lines[this.lines.length - 1] === "") this.lines.pop();
    this.highlighted = null;   // {line, column}
    this.onLineClick = null;
    this.spacer = h("div", { class: "program-spacer" });
    this.spacer.style.height = `${this.lines.length * LINE_PX}px`;
    this.el = h("div", { class: "program", role: "region", tabindex: "0", "aria-label": `${label}, ${this.lines.length} lines` }, this.spacer);
    // A short program gets a box its size, not a screenful of blank lines.
    this.el.style.maxHeight = `${this.lines.length * LINE_PX + 20}px`;  // + a scroll bar
    this.digits = String(this.lines.length).length;
    this.el.style.setProperty("--digits", String(this.digits));
    this.el.addEventListener("scroll", () => this.schedule());
    this.frame = 0;
    // Render once attached and sized: in the next frame, because rendering here would
    // resize the box inside its own observer's callback (the browser then reports a
    // "ResizeObserver loop" error, which the page shows as a fault).
    this.resize = new ResizeObserver(() => this.schedule());
    this.resize.observe(this.el);
  }

  schedule() {
    if (this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.render();
    });
  }

  render() {
    const height = this.el.clientHeight || 400;
    const first = Math.max(0, Math.floor(this.el.scrollTop / LINE_PX) - OVERSCAN);
    const last = Math.min(this.lines.length, Math.ceil((this.el.scrollTop + height) / LINE_PX) + OVERSCAN);
    clear(this.spacer);
    for (let i = first; i < last; i++) this.spacer.append(this.lineElement(i + 1));
  }

  lineElement(n) {
    const text = this.lines[n - 1];
    const hl = this.highlighted && this.highlighted.line === n;
    let code;
    if (hl && this.highlighted.column > 0) {
      const c = Math.min(this.highlighted.column - 1, text.length);
      code = h("span", { class: "code" }, text.slice(0, c), h("mark", { class: "column", title: `column ${this.highlighted.column}` }, text.slice(c, c + 1) || " "), text.slice(c + 1));
    } else {
      code = h("span", { class: "code" }, text);
    }
    const el = h("div", { class: hl ? "pl hl" : "pl", dataset: { line: String(n) } }, h("span", { class: "ln", "aria-hidden": "true" }, String(n)), code);
    if (hl) el.setAttribute("aria-current", "true");
    el.style.top = `${(n - 1) * LINE_PX}px`;
    if (this.onLineClick) el.addEventListener("click", () => this.onLineClick(n));
    return el;
  }

  // Highlights line n (1-based; column 0 or absent: the whole line) and scrolls it to the middle.
  highlight(line, column = 0) {
    if (!Number.isInteger(line) || line < 1 || line > this.lines.length) {
      this.highlighted = null;
      this.render();
      return false;
    }
    this.highlighted = { line, column };
    const height = this.el.clientHeight || 400;
    this.el.scrollTop = Math.max(0, (line - 1) * LINE_PX - height / 2 + LINE_PX / 2);
    this.render();
    return true;
  }

  lineText(n) {
    return this.lines[n - 1] ?? "";
  }

  destroy() {
    this.resize.disconnect();
    if (this.frame) cancelAnimationFrame(this.frame);
  }
}
