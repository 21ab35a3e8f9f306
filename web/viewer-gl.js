// WebGL drawing of the viewer: a lit mesh with per-face normals, and markers
// (round points drawn over everything) and lines. Plain WebGL 1.

const MESH_VS = `
attribute vec3 aPos;
attribute vec3 aNormal;
uniform mat4 uMvp;
varying vec3 vNormal;
void main() {
  vNormal = aNormal;
  gl_Position = uMvp * vec4(aPos, 1.0);
}`;

const MESH_FS = `
precision mediump float;
varying vec3 vNormal;
uniform vec3 uLight;
uniform vec3 uColor;
uniform vec3 uBackColor;
void main() {
  float len = length(vNormal);
  vec3 n = len > 0.0 ? vNormal / len : vec3(0.0);
  vec3 base = gl_FrontFacing ? uColor : uBackColor;
  if (!gl_FrontFacing) n = -n;
  float diffuse = max(dot(n, uLight), 0.0);
  float fill = max(dot(n, vec3(0.0, 0.0, 1.0)), 0.0) * 0.15;
  gl_FragColor = vec4(base * (0.28 + 0.62 * diffuse + fill), 1.0);
}`;

const MARK_VS = `
attribute vec3 aPos;
attribute vec4 aColor;
uniform mat4 uMvp;
uniform float uScale;
varying vec4 vColor;
void main() {
  vColor = aColor;
  gl_Position = uMvp * vec4(aPos, 1.0);
  gl_PointSize = aColor.a * uScale;
}`;

const MARK_FS = `
precision mediump float;
varying vec4 vColor;
uniform float uRound;
void main() {
  if (uRound > 0.5) {
    vec2 d = gl_PointCoord - vec2(0.5);
    float r = length(d);
    if (r > 0.5) discard;
    if (r > 0.36) { gl_FragColor = vec4(0.05, 0.05, 0.05, 1.0); return; }
  }
  gl_FragColor = vec4(vColor.rgb, 1.0);
}`;

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    const log = gl.getShaderInfoLog(shader);
    gl.deleteShader(shader);
    throw new Error(`shader: ${log}`);
  }
  return shader;
}

function link(gl, vs, fs) {
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vs));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fs));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`program: ${gl.getProgramInfoLog(program)}`);
  const loc = (name) => gl.getUniformLocation(program, name);
  const attr = (name) => gl.getAttribLocation(program, name);
  return { program, loc, attr };
}

export class GlScene {
  constructor(gl) {
    this.gl = gl;
    this.mesh = link(gl, MESH_VS, MESH_FS);
    this.mark = link(gl, MARK_VS, MARK_FS);
    this.meshPos = gl.createBuffer();
    this.meshNormal = gl.createBuffer();
    this.markBuf = gl.createBuffer();
    this.lineBuf = gl.createBuffer();
    this.vertices = 0;
    this.markCount = 0;
    this.lineCount = 0;
  }

  setMesh(positions, normals) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.meshPos);
    gl.bufferData(gl.ARRAY_BUFFER, positions, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.meshNormal);
    gl.bufferData(gl.ARRAY_BUFFER, normals, gl.STATIC_DRAW);
    this.vertices = positions.length / 3;
  }

  // points: [{point: [x,y,z], color: [r,g,b], size: px}]
  setMarkers(points) {
    this.markCount = this.upload(this.markBuf, points);
  }

  // segments: [{point, color}, {point, color}, ...] in pairs
  setLines(vertices) {
    this.lineCount = this.upload(this.lineBuf, vertices.map((v) => ({ ...v, size: 1 })));
  }

  upload(buffer, items) {
    const gl = this.gl;
    const data = new Float32Array(items.length * 7);
    items.forEach((m, i) => data.set([...m.point, ...m.color, m.size ?? 1], i * 7));
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    return items.length;
  }

  // Draws everything; returns the triangles drawn.
  draw(width, height, mvp, light, pixelRatio) {
    const gl = this.gl;
    gl.viewport(0, 0, width, height);
    gl.clearColor(0.13, 0.15, 0.18, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    let drawn = 0;
    if (this.vertices > 0) {
      const m = this.mesh;
      gl.useProgram(m.program);
      gl.enable(gl.DEPTH_TEST);
      gl.depthFunc(gl.LEQUAL);
      gl.uniformMatrix4fv(m.loc("uMvp"), false, mvp);
      gl.uniform3fv(m.loc("uLight"), light);
      gl.uniform3fv(m.loc("uColor"), [0.72, 0.76, 0.82]);
      gl.uniform3fv(m.loc("uBackColor"), [0.85, 0.45, 0.2]);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.meshPos);
      gl.enableVertexAttribArray(m.attr("aPos"));
      gl.vertexAttribPointer(m.attr("aPos"), 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.meshNormal);
      gl.enableVertexAttribArray(m.attr("aNormal"));
      gl.vertexAttribPointer(m.attr("aNormal"), 3, gl.BYTE, true, 4, 0);
      gl.drawArrays(gl.TRIANGLES, 0, this.vertices);
      gl.disableVertexAttribArray(m.attr("aNormal"));
      drawn = this.vertices / 3;
    }
    if (this.lineCount > 0 || this.markCount > 0) {
      const k = this.mark;
      gl.useProgram(k.program);
      gl.disable(gl.DEPTH_TEST);  // markers show through the material they sit in
      gl.uniformMatrix4fv(k.loc("uMvp"), false, mvp);
      gl.uniform1f(k.loc("uScale"), pixelRatio);
      const bind = (buffer) => {
        gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
        gl.enableVertexAttribArray(k.attr("aPos"));
        gl.vertexAttribPointer(k.attr("aPos"), 3, gl.FLOAT, false, 28, 0);
        gl.enableVertexAttribArray(k.attr("aColor"));
        gl.vertexAttribPointer(k.attr("aColor"), 4, gl.FLOAT, false, 28, 12);
      };
      if (this.lineCount > 0) {
        bind(this.lineBuf);
        gl.uniform1f(k.loc("uRound"), 0);
        gl.drawArrays(gl.LINES, 0, this.lineCount);
      }
      if (this.markCount > 0) {
        bind(this.markBuf);
        gl.uniform1f(k.loc("uRound"), 1);
        gl.drawArrays(gl.POINTS, 0, this.markCount);
      }
      gl.disableVertexAttribArray(k.attr("aColor"));
    }
    return drawn;
  }

  dispose() {
    const gl = this.gl;
    for (const b of [this.meshPos, this.meshNormal, this.markBuf, this.lineBuf]) gl.deleteBuffer(b);
    gl.deleteProgram(this.mesh.program);
    gl.deleteProgram(this.mark.program);
  }
}
