import { test } from "node:test";
import assert from "node:assert/strict";
import { OrbitCamera, multiply, identity, perspective, lookAt, transform, normalize } from "../camera.js";

const near = (a, b, eps = 1e-4) => Math.abs(a - b) <= eps;
const nearVec = (a, b, eps = 1e-4) => a.every((v, i) => near(v, b[i], eps));

test("identity and multiply", () => {
  const m = lookAt([1, 2, 3], [0, 0, 0], [0, 0, 1]);
  assert.ok(nearVec(Array.from(multiply(identity(), m)), Array.from(m)));
  assert.ok(nearVec(Array.from(multiply(m, identity())), Array.from(m)));
});

test("lookAt puts the target straight ahead on -Z at its distance", () => {
  const v = lookAt([0, -10, 0], [0, 0, 0], [0, 0, 1]);
  assert.ok(nearVec(transform(v, [0, 0, 0]), [0, 0, -10, 1]));
  assert.ok(nearVec(transform(v, [0, 0, 1]), [0, 1, -10, 1]), "world up is screen up");
  assert.ok(nearVec(transform(v, [1, 0, 0]), [1, 0, -10, 1]), "world +x is screen right seen from -y");
  const straightDown = lookAt([0, 0, 10], [0, 0, 0], [0, 0, 1]);
  assert.ok(transform(straightDown, [0, 0, 0]).every(Number.isFinite), "looking along up stays finite");
});

test("perspective maps near to -1 and far to +1", () => {
  const p = perspective(Math.PI / 2, 1, 1, 100);
  const n = transform(p, [0, 0, -1]);
  const f = transform(p, [0, 0, -100]);
  assert.ok(near(n[2] / n[3], -1));
  assert.ok(near(f[2] / f[3], 1));
  const edge = transform(p, [1, 0, -1]);
  assert.ok(near(edge[0] / edge[3], 1), "90 degrees: x = z at the edge");
});

test("fit frames the whole box: every corner projects inside the canvas", () => {
  const cam = new OrbitCamera();
  const min = [0, 0, -40], max = [100, 80, 0];
  for (const aspect of [0.5, 1, 2.5]) {
    for (const [yaw, pitch] of [[0, 0], [1, 0.5], [-2, -1.2], [3, 1.5]]) {
      cam.yaw = yaw;
      cam.pitch = pitch;
      cam.fit(min, max, aspect);
      assert.deepEqual(cam.target, [50, 40, -20]);
      const h = 600, w = h * aspect;
      for (let c = 0; c < 8; c++) {
        const p = [c & 1 ? max[0] : min[0], c & 2 ? max[1] : min[1], c & 4 ? max[2] : min[2]];
        const s = cam.project(p, w, h);
        assert.ok(s.inside, `corner ${p} at aspect ${aspect}, yaw ${yaw}, pitch ${pitch}: ${JSON.stringify(s)}`);
      }
      const centre = cam.project(cam.target, w, h);
      assert.ok(near(centre.x, w / 2, 1e-2) && near(centre.y, h / 2, 1e-2), "the target is the centre");
    }
  }
});

test("orbit turns around Z and clamps the tilt below the poles", () => {
  const cam = new OrbitCamera();
  cam.fit([-1, -1, -1], [1, 1, 1]);
  const d = cam.distance;
  cam.orbit(100, 0);
  assert.ok(near(Math.hypot(...cam.eye().map((v, i) => v - cam.target[i])), d), "orbit keeps the distance");
  cam.orbit(0, 10000);
  assert.ok(cam.pitch < Math.PI / 2 && cam.pitch > 1.5);
  cam.orbit(0, -20000);
  assert.ok(cam.pitch > -Math.PI / 2 && cam.pitch < -1.5);
  assert.ok(cam.view().every(Number.isFinite));
});

test("zoom scales the distance within bounds and ignores bad factors", () => {
  const cam = new OrbitCamera();
  cam.fit([0, 0, 0], [10, 10, 10]);
  const d = cam.distance;
  cam.zoom(0.5);
  assert.ok(near(cam.distance, d / 2));
  cam.zoom(NaN);
  cam.zoom(-1);
  assert.ok(near(cam.distance, d / 2));
  for (let i = 0; i < 100; i++) cam.zoom(0.1);
  assert.ok(cam.distance > 0);
  for (let i = 0; i < 100; i++) cam.zoom(10);
  assert.ok(cam.distance <= cam.radius * 100 + 1e-6);
});

test("pan moves the model with the pointer: a point under it stays under it", () => {
  const cam = new OrbitCamera();
  cam.fit([0, 0, 0], [100, 80, 40], 4 / 3);
  const w = 800, h = 600;
  const before = cam.project(cam.target, w, h);
  const point = [...cam.target];
  cam.pan(120, -45, h);
  const after = cam.project(point, w, h);
  assert.ok(near(after.x - before.x, 120, 0.5), `x moved ${after.x - before.x}`);
  assert.ok(near(after.y - before.y, -45, 0.5), `y moved ${after.y - before.y}`);
});

test("axes are unit and perpendicular, right is horizontal", () => {
  const cam = new OrbitCamera();
  cam.yaw = 0.7;
  cam.pitch = 0.4;
  const { right, up } = cam.axes();
  assert.ok(near(Math.hypot(...right), 1) && near(Math.hypot(...up), 1));
  assert.ok(near(right[0] * up[0] + right[1] * up[1] + right[2] * up[2], 0));
  assert.ok(near(right[2], 0));
  assert.deepEqual(normalize([0, 0, 0]), [0, 0, 0]);
});
