// The 3D viewer's camera math: 4x4 matrices (column-major, as WebGL takes them)
// and an orbit camera around a target with +Z up (the machine's convention).
// Pure, so Node tests it.

export function identity() {
  const m = new Float32Array(16);
  m[0] = m[5] = m[10] = m[15] = 1;
  return m;
}

// a * b (apply b first).
export function multiply(a, b) {
  const out = new Float32Array(16);
  for (let c = 0; c < 4; c++) {
    for (let r = 0; r < 4; r++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = s;
    }
  }
  return out;
}

export function perspective(fovY, aspect, near, far) {
  const f = 1 / Math.tan(fovY / 2);
  const m = new Float32Array(16);
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (far + near) / (near - far);
  m[11] = -1;
  m[14] = (2 * far * near) / (near - far);
  return m;
}

export function lookAt(eye, target, up) {
  const z = normalize(sub(eye, target));
  let x = cross(up, z);
  if (length(x) < 1e-9) x = cross([0, 1, 0], z);  // looking along up
  x = normalize(x);
  const y = cross(z, x);
  const m = identity();
  m[0] = x[0]; m[4] = x[1]; m[8] = x[2];
  m[1] = y[0]; m[5] = y[1]; m[9] = y[2];
  m[2] = z[0]; m[6] = z[1]; m[10] = z[2];
  m[12] = -dot(x, eye);
  m[13] = -dot(y, eye);
  m[14] = -dot(z, eye);
  return m;
}

// m * [x, y, z, 1] -> [x, y, z, w].
export function transform(m, p) {
  const [x, y, z] = p;
  return [
    m[0] * x + m[4] * y + m[8] * z + m[12],
    m[1] * x + m[5] * y + m[9] * z + m[13],
    m[2] * x + m[6] * y + m[10] * z + m[14],
    m[3] * x + m[7] * y + m[11] * z + m[15],
  ];
}

const MIN_PITCH = -Math.PI / 2 + 0.01;
const MAX_PITCH = Math.PI / 2 - 0.01;

export class OrbitCamera {
  constructor() {
    this.target = [0, 0, 0];
    this.yaw = -Math.PI / 3;     // around +Z, from +X
    this.pitch = Math.PI / 6;    // above the XY plane
    this.distance = 100;
    this.fovY = (45 * Math.PI) / 180;
    this.radius = 50;            // of the model: sets near and far
  }

  eye() {
    const c = Math.cos(this.pitch);
    return [
      this.target[0] + this.distance * c * Math.cos(this.yaw),
      this.target[1] + this.distance * c * Math.sin(this.yaw),
      this.target[2] + this.distance * Math.sin(this.pitch),
    ];
  }

  // Drag by (dx, dy) pixels: left/right turns around Z, up/down tilts.
  orbit(dx, dy, radiansPerPixel = 0.01) {
    this.yaw -= dx * radiansPerPixel;
    this.pitch = clamp(this.pitch + dy * radiansPerPixel, MIN_PITCH, MAX_PITCH);
  }

  // factor < 1 comes closer.
  zoom(factor) {
    if (!(factor > 0) || !Number.isFinite(factor)) return;
    const min = Math.max(this.radius * 1e-3, 1e-3);
    const max = Math.max(this.radius * 100, 1);
    this.distance = clamp(this.distance * factor, min, max);
  }

  // Drag by (dx, dy) pixels in a viewport `height` pixels tall: the model follows the pointer.
  pan(dx, dy, height) {
    const perPixel = (2 * this.distance * Math.tan(this.fovY / 2)) / Math.max(1, height);
    const { right, up } = this.axes();
    for (let i = 0; i < 3; i++) this.target[i] += (-dx * right[i] + dy * up[i]) * perPixel;
  }

  // The camera's right and up directions in the world.
  axes() {
    const forward = normalize(sub(this.target, this.eye()));
    let right = cross(forward, [0, 0, 1]);
    if (length(right) < 1e-9) right = [1, 0, 0];
    right = normalize(right);
    const up = cross(right, forward);
    return { right, up };
  }

  // Frames the box [min, max] whole in a viewport of this aspect (width/height).
  fit(min, max, aspect = 1) {
    this.target = [0, 1, 2].map((i) => (min[i] + max[i]) / 2);
    const r = Math.max(1e-3, 0.5 * Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]));
    this.radius = r;
    const fovX = 2 * Math.atan(Math.tan(this.fovY / 2) * aspect);
    const fov = Math.min(this.fovY, fovX);
    this.distance = (r / Math.sin(fov / 2)) * 1.05;
  }

  view() {
    return lookAt(this.eye(), this.target, [0, 0, 1]);
  }

  projection(aspect) {
    const near = Math.max(this.distance - this.radius * 2, this.distance * 1e-3, 1e-3);
    const far = this.distance + this.radius * 2 + 1;
    return perspective(this.fovY, aspect, near, far);
  }

  viewProjection(aspect) {
    return multiply(this.projection(aspect), this.view());
  }

  // A world point on a width x height canvas: {x, y} pixels from the top left,
  // `inside` when it lies in the view volume.
  project(point, width, height) {
    const clip = transform(this.viewProjection(width / height), point);
    const w = clip[3];
    const nx = clip[0] / w, ny = clip[1] / w, nz = clip[2] / w;
    return {
      x: (nx + 1) * 0.5 * width,
      y: (1 - ny) * 0.5 * height,
      inside: w > 0 && Math.abs(nx) <= 1 && Math.abs(ny) <= 1 && Math.abs(nz) <= 1,
    };
  }
}

export function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
export function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
export function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}
export function length(a) { return Math.hypot(a[0], a[1], a[2]); }
export function normalize(a) {
  const l = length(a);
  return l > 0 ? [a[0] / l, a[1] / l, a[2] / l] : [0, 0, 0];
}
function clamp(v, lo, hi) { return Math.min(hi, Math.max(lo, v)); }
