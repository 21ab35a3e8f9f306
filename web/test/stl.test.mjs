import { test } from "node:test";
import assert from "node:assert/strict";
import { parseStl, writeStl, StlError, faceNormal } from "../stl.js";

const cube = () => {
  // Two triangles of a unit square in z = 0 (counter-clockwise seen from +z) and
  // one in x = 0 facing -x.
  return [
    [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
    [[0, 0, 0], [1, 1, 0], [0, 1, 0]],
    [[0, 0, 0], [0, 0, 2], [0, 1, 0]],
  ];
};

test("a good binary STL gives its triangles, positions, face normals and bounds", () => {
  const mesh = parseStl(writeStl(cube()));
  assert.equal(mesh.triangles, 3);
  assert.equal(mesh.positions.length, 27);
  assert.deepEqual(Array.from(mesh.positions.slice(0, 9)), [0, 0, 0, 1, 0, 0, 1, 1, 0]);
  assert.deepEqual(Array.from(mesh.normals.slice(0, 3)), [0, 0, 127]);
  assert.deepEqual(Array.from(mesh.normals.slice(4, 7)), [0, 0, 127], "every vertex of a face has its normal");
  assert.deepEqual(Array.from(mesh.normals.slice(24, 27)), [-127, 0, 0]);
  assert.deepEqual(mesh.min, [0, 0, 0]);
  assert.deepEqual(mesh.max, [1, 1, 2]);
});

test("the stored normal is ignored: a wrong one does not change the face normal", () => {
  const buf = writeStl([[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]);
  new DataView(buf).setFloat32(84, 1, true);  // stored normal says +x
  assert.deepEqual(Array.from(parseStl(buf).normals.slice(0, 3)), [0, 0, 127]);
});

test("an empty STL (0 triangles) is valid", () => {
  const mesh = parseStl(writeStl([]));
  assert.equal(mesh.triangles, 0);
  assert.deepEqual(mesh.min, [0, 0, 0]);
});

test("fewer bytes than a header is refused with the size", () => {
  assert.throws(() => parseStl(new ArrayBuffer(50)), (e) => e instanceof StlError && /50 bytes/.test(e.message) && /84/.test(e.message));
});

test("a truncated STL is refused: size against count", () => {
  const buf = writeStl(cube()).slice(0, 84 + 50 * 2 + 20);
  assert.throws(() => parseStl(buf), (e) => e instanceof StlError &&
    /says it holds 3 triangles \(234 bytes\) but has 204 bytes/.test(e.message) && /room for 2 and a partial one/.test(e.message));
});

test("a wrong triangle count is refused", () => {
  const buf = writeStl(cube());
  new DataView(buf).setUint32(80, 7, true);
  assert.throws(() => parseStl(buf), (e) => e instanceof StlError && /holds 7 triangles/.test(e.message) && /room for 3\)/.test(e.message));
  new DataView(buf).setUint32(80, 2, true);
  assert.throws(() => parseStl(buf), /holds 2 triangles \(184 bytes\) but has 234 bytes/);
});

test("a NaN or infinite coordinate is refused naming its triangle", () => {
  const buf = writeStl(cube());
  new DataView(buf).setFloat32(84 + 50 + 12 + 4 * 4, NaN, true);
  assert.throws(() => parseStl(buf), (e) => e instanceof StlError && /triangle 2 of 3/.test(e.message) && /NaN/.test(e.message));
  const inf = writeStl(cube());
  new DataView(inf).setFloat32(84 + 100 + 12, Infinity, true);
  assert.throws(() => parseStl(inf), /triangle 3 of 3 .*Infinity/);
});

test("not an ArrayBuffer is refused", () => {
  assert.throws(() => parseStl("solid ascii"), StlError);
});

test("a degenerate face has a zero normal", () => {
  assert.deepEqual(faceNormal([0, 0, 0, 1, 1, 1, 2, 2, 2]), [0, 0, 0]);
});
