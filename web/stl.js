// Binary STL reading: pure (no DOM), so Node's test runner checks it.
// A binary STL is an 80-byte header, a uint32 triangle count, then 50 bytes per
// triangle (normal, three vertices as float32 little-endian, a uint16 attribute).
// The stored normals are ignored: each face's normal is computed from its
// vertices (outward for the counter-clockwise order STL prescribes).

export const STL_HEADER_BYTES = 84;
export const STL_TRIANGLE_BYTES = 50;

export class StlError extends Error {
  constructor(message) {
    super(message);
    this.name = "StlError";
  }
}

// Returns {triangles, positions: Float32Array(9 per triangle), normals:
// Int8Array(12 per triangle: x y z and a pad byte per vertex, for WebGL's
// normalized BYTE attribute), min: [x,y,z], max: [x,y,z]}.
// Throws StlError when the bytes are not a usable binary STL.
export function parseStl(buffer) {
  const bytes = buffer instanceof ArrayBuffer ? buffer : null;
  if (!bytes) throw new StlError("the mesh is not binary data");
  if (bytes.byteLength < STL_HEADER_BYTES) {
    throw new StlError(`the mesh has ${bytes.byteLength} bytes, fewer than the ${STL_HEADER_BYTES} of a binary STL header`);
  }
  const view = new DataView(bytes);
  const count = view.getUint32(80, true);
  const expected = STL_HEADER_BYTES + count * STL_TRIANGLE_BYTES;
  if (bytes.byteLength !== expected) {
    const whole = Math.floor((bytes.byteLength - STL_HEADER_BYTES) / STL_TRIANGLE_BYTES);
    throw new StlError(
      `the mesh says it holds ${count} triangles (${expected} bytes) but has ${bytes.byteLength} bytes` +
        ` (room for ${whole}${(bytes.byteLength - STL_HEADER_BYTES) % STL_TRIANGLE_BYTES ? " and a partial one" : ""})`);
  }
  const positions = new Float32Array(count * 9);
  const normals = new Int8Array(count * 12);
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let t = 0; t < count; t++) {
    const base = STL_HEADER_BYTES + t * STL_TRIANGLE_BYTES + 12;
    for (let k = 0; k < 9; k++) {
      const v = view.getFloat32(base + 4 * k, true);
      if (!Number.isFinite(v)) {
        throw new StlError(`triangle ${t + 1} of ${count} has a coordinate that is not a finite number (${v})`);
      }
      positions[t * 9 + k] = v;
      const axis = k % 3;
      if (v < min[axis]) min[axis] = v;
      if (v > max[axis]) max[axis] = v;
    }
    const n = faceNormal(positions, t * 9);
    for (let c = 0; c < 3; c++) {
      const o = t * 12 + c * 4;
      normals[o] = Math.round(n[0] * 127);
      normals[o + 1] = Math.round(n[1] * 127);
      normals[o + 2] = Math.round(n[2] * 127);
    }
  }
  if (count === 0) {
    min.fill(0);
    max.fill(0);
  }
  return { triangles: count, positions, normals, min, max };
}

// The unit normal of the triangle whose 9 coordinates start at p[o]; a
// degenerate triangle gets (0, 0, 0), which the shader lights as ambient only.
export function faceNormal(p, o = 0) {
  const ux = p[o + 3] - p[o], uy = p[o + 4] - p[o + 1], uz = p[o + 5] - p[o + 2];
  const vx = p[o + 6] - p[o], vy = p[o + 7] - p[o + 1], vz = p[o + 8] - p[o + 2];
  const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const len = Math.hypot(nx, ny, nz);
  return len > 0 ? [nx / len, ny / len, nz / len] : [0, 0, 0];
}

// Builds a binary STL from triangles [[x,y,z] x3, ...] (for tests and samples).
export function writeStl(triangles) {
  const out = new ArrayBuffer(STL_HEADER_BYTES + triangles.length * STL_TRIANGLE_BYTES);
  const view = new DataView(out);
  view.setUint32(80, triangles.length, true);
  triangles.forEach((tri, t) => {
    const base = STL_HEADER_BYTES + t * STL_TRIANGLE_BYTES + 12;
    tri.flat().forEach((v, k) => view.setFloat32(base + 4 * k, v, true));
  });
  return out;
}
