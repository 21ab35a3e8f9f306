// The 3D viewer: a canvas with the mesh, markers at report positions, an axis
// triad (X red, Y green, Z blue) at the part's lower corner, orbit
// (drag), pan (right drag, shift drag or two fingers), zoom (wheel or pinch),
// fit (double click, F or the button) and the keyboard (arrows, +/-).
// The canvas carries data-state ("empty", "drawn", "error") and, once a mesh is
// drawn, data-triangles: the triangles of the last frame.
import { h } from "./dom.js";
import { OrbitCamera, normalize, sub } from "./camera.js";
import { GlScene } from "./viewer-gl.js";

const MARKER_COLOR = [0.95, 0.2, 0.15];
const MARKER_HIGHLIGHT = [1.0, 0.85, 0.1];

export class MeshViewer {
  constructor({ label = "3D view of the part" } = {}) {
    this.canvas = h("canvas", { class: "viewer-canvas", tabindex: "0", role: "img", "aria-label": label, dataset: { state: "empty" } });
    this.status = h("p", { class: "viewer-status", role: "status" });
    const button = (text, title, fn) => h("button", { type: "button", class: "ghost small", title, onclick: fn }, text);
    this.toolbar = h("div", { class: "viewer-tools" },
      button("Fit", "Fit the part in view (F)", () => this.fit()),
      button("Top", "Look down Z", () => this.view(-Math.PI / 2, Math.PI / 2)),
      button("Front", "Look along +Y", () => this.view(-Math.PI / 2, 0.0)),
      button("Iso", "Isometric view", () => this.view(-Math.PI / 4, Math.atan(1 / Math.SQRT2))));
    this.el = h("figure", { class: "viewer" }, this.canvas, this.toolbar, this.status,
      h("figcaption", { class: "hint" }, "Drag to turn, right-drag or two fingers to move, wheel or pinch to zoom, double-click to fit."));
    this.camera = new OrbitCamera();
    this.bounds = null;
    this.markers = [];
    this.highlightIndex = -1;
    this.extraMarkers = [];
    this.lines = [];
    this.frame = 0;
    this.pointers = new Map();
    this.gl = this.canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: false });
    if (!this.gl) {
      this.canvas.dataset.state = "error";
      this.say("This browser cannot show 3D (WebGL is off or unsupported). The report above is complete without it.");
      return;
    }
    try {
      this.scene = new GlScene(this.gl);
    } catch (err) {
      console.error(err);
      this.gl = null;
      this.canvas.dataset.state = "error";
      this.say("The 3D view could not start on this device.");
      return;
    }
    this.canvas.addEventListener("webglcontextlost", (e) => {
      e.preventDefault();
      this.say("The 3D view lost its graphics context; reload the page to see it again.");
    });
    this.observer = new ResizeObserver(() => this.redraw());
    this.observer.observe(this.canvas);
    this.bindInput();
  }

  say(text) {
    this.status.textContent = text;
  }

  // mesh: the result of parseStl.
  setMesh(mesh) {
    if (!this.scene) return;
    this.scene.setMesh(mesh.positions, mesh.normals);
    this.triangles = mesh.triangles;
    const first = !this.bounds;
    this.bounds = { min: mesh.min, max: mesh.max };
    this.uploadLines();
    if (first) this.fit();
    else this.redraw();
    this.say("");
  }

  // points: [[x,y,z] or null, ...] (collision positions, in order).
  setMarkers(points) {
    this.markers = points;
    this.uploadMarkers();
  }

  // Other marks: [{point, color: [r,g,b], size}] and line vertices in pairs.
  setExtras(marks, lines = []) {
    this.extraMarkers = marks;
    this.lines = lines;
    this.uploadLines();
    this.uploadMarkers();
  }

  // The caller's lines and an axis triad at the part's lower corner (X red, Y green,
  // Z blue, a fifth of the part's size), so the machine's directions are never in doubt.
  uploadLines() {
    if (!this.scene) return;
    const all = [...this.lines];
    if (this.bounds) {
      const { min, max } = this.bounds;
      const size = Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2], 1) * 0.2;
      const colors = [[0.95, 0.3, 0.3], [0.3, 0.85, 0.35], [0.35, 0.55, 1.0]];
      for (let a = 0; a < 3; a++) {
        const end = [...min];
        end[a] += size;
        all.push({ point: [...min], color: colors[a] }, { point: end, color: colors[a] });
      }
    }
    this.scene.setLines(all);
  }

  highlight(index) {
    this.highlightIndex = index;
    this.uploadMarkers();
  }

  uploadMarkers() {
    if (!this.scene) return;
    const list = [];
    this.markers.forEach((p, i) => {
      if (p && i !== this.highlightIndex) list.push({ point: p, color: MARKER_COLOR, size: 14 });
    });
    list.push(...this.extraMarkers);
    const hp = this.markers[this.highlightIndex];
    if (hp) list.push({ point: hp, color: MARKER_HIGHLIGHT, size: 24 });
    this.scene.setMarkers(list);
    this.canvas.dataset.highlight = String(this.highlightIndex);
    this.redraw();
  }

  fit() {
    const b = this.bounds ?? this.markerBounds();
    if (!b) return;
    this.camera.fit(b.min, b.max, this.aspect());
    this.redraw();
  }

  markerBounds() {
    const pts = [...this.markers.filter(Boolean), ...this.extraMarkers.map((m) => m.point)];
    if (!pts.length) return null;
    const min = [0, 1, 2].map((i) => Math.min(...pts.map((p) => p[i])) - 10);
    const max = [0, 1, 2].map((i) => Math.max(...pts.map((p) => p[i])) + 10);
    return { min, max };
  }

  view(yaw, pitch) {
    this.camera.yaw = yaw;
    this.camera.pitch = Math.max(-Math.PI / 2 + 0.01, Math.min(Math.PI / 2 - 0.01, pitch));
    this.fit();
  }

  // Turns the camera's target to a point (a collision) without changing the distance.
  centerOn(point) {
    if (!point) return;
    this.camera.target = [...point];
    this.redraw();
  }

  aspect() {
    const w = this.canvas.clientWidth || 1, hgt = this.canvas.clientHeight || 1;
    return w / hgt;
  }

  redraw() {
    if (!this.scene || this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.draw();
    });
  }

  draw() {
    const gl = this.gl;
    if (!gl || gl.isContextLost()) return;
    const ratio = Math.min(window.devicePixelRatio || 1, 2);
    const w = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
    const hgt = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
    if (this.canvas.width !== w || this.canvas.height !== hgt) {
      this.canvas.width = w;
      this.canvas.height = hgt;
    }
    const mvp = this.camera.viewProjection(w / hgt);
    const toEye = normalize(sub(this.camera.eye(), this.camera.target));
    const light = normalize([toEye[0] + 0.3, toEye[1] + 0.2, toEye[2] + 0.6]);
    const drawn = this.scene.draw(w, hgt, mvp, light, ratio);
    const error = gl.getError();
    if (error !== gl.NO_ERROR) this.canvas.dataset.glError = String(error);
    if (this.triangles !== undefined) {
      this.canvas.dataset.triangles = String(drawn);
      this.canvas.dataset.state = "drawn";
    }
  }

  bindInput() {
    const c = this.canvas;
    c.addEventListener("contextmenu", (e) => e.preventDefault());
    c.addEventListener("pointerdown", (e) => {
      c.setPointerCapture(e.pointerId);
      this.pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, button: e.button, shift: e.shiftKey || e.ctrlKey });
    });
    const end = (e) => this.pointers.delete(e.pointerId);
    c.addEventListener("pointerup", end);
    c.addEventListener("pointercancel", end);
    c.addEventListener("pointermove", (e) => {
      const p = this.pointers.get(e.pointerId);
      if (!p) return;
      if (this.pointers.size === 1) {
        const dx = e.clientX - p.x, dy = e.clientY - p.y;
        if (p.button === 2 || p.button === 1 || p.shift) this.camera.pan(dx, dy, c.clientHeight);
        else this.camera.orbit(dx, dy);
      } else if (this.pointers.size === 2) {
        const [a, b] = [...this.pointers.values()];
        const before = { d: Math.hypot(a.x - b.x, a.y - b.y), mx: (a.x + b.x) / 2, my: (a.y + b.y) / 2 };
        const moved = { ...p, x: e.clientX, y: e.clientY };
        const [a2, b2] = [...this.pointers.entries()].map(([id, q]) => (id === e.pointerId ? moved : q));
        const after = { d: Math.hypot(a2.x - b2.x, a2.y - b2.y), mx: (a2.x + b2.x) / 2, my: (a2.y + b2.y) / 2 };
        if (before.d > 0 && after.d > 0) this.camera.zoom(before.d / after.d);
        this.camera.pan(after.mx - before.mx, after.my - before.my, c.clientHeight);
      }
      p.x = e.clientX;
      p.y = e.clientY;
      this.redraw();
    });
    c.addEventListener("wheel", (e) => {
      e.preventDefault();
      const unit = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? 400 : 1;
      this.camera.zoom(Math.exp(e.deltaY * unit * 0.0015));
      this.redraw();
    }, { passive: false });
    c.addEventListener("dblclick", () => this.fit());
    c.addEventListener("keydown", (e) => {
      const step = 20;
      const keys = {
        ArrowLeft: () => (e.shiftKey ? this.camera.pan(-step, 0, c.clientHeight) : this.camera.orbit(-step, 0)),
        ArrowRight: () => (e.shiftKey ? this.camera.pan(step, 0, c.clientHeight) : this.camera.orbit(step, 0)),
        ArrowUp: () => (e.shiftKey ? this.camera.pan(0, -step, c.clientHeight) : this.camera.orbit(0, -step)),
        ArrowDown: () => (e.shiftKey ? this.camera.pan(0, step, c.clientHeight) : this.camera.orbit(0, step)),
        "+": () => this.camera.zoom(0.8),
        "=": () => this.camera.zoom(0.8),
        "-": () => this.camera.zoom(1.25),
        f: () => this.fit(),
        F: () => this.fit(),
        Home: () => this.fit(),
      };
      const fn = keys[e.key];
      if (!fn) return;
      e.preventDefault();
      fn();
      this.redraw();
    });
  }

  destroy() {
    this.observer?.disconnect();
    if (this.frame) cancelAnimationFrame(this.frame);
    this.scene?.dispose();
    this.gl?.getExtension("WEBGL_lose_context")?.loseContext();
  }
}
