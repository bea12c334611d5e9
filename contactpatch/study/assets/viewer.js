/* Interactive 3D view of the deformed tire: a small WebGL 1 viewer, no libraries,
   no network. Reads the meshes from <script type="application/json" id="viewer-data">:
   {cases: [{label, positions, indices, values, outline, grid, lo, hi, focus, span}]}
   where positions/values/outline/grid are base64 little-endian Float32 arrays and
   indices base64 Uint16 (Uint32 when index_bits is 32). Drag to turn, wheel or pinch to zoom, buttons to switch. */
(function () {
  "use strict";
  var root = document.getElementById("tire3d");
  var dataEl = document.getElementById("viewer-data");
  if (!root || !dataEl) return;
  var canvas = root.querySelector("canvas");
  var note = root.querySelector(".viewer-note");
  var data = JSON.parse(dataEl.textContent);
  var VIRIDIS = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
    [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];

  function b64(s, Type) {
    var bin = atob(s), n = bin.length, buf = new ArrayBuffer(n), u8 = new Uint8Array(buf);
    for (var i = 0; i < n; i++) u8[i] = bin.charCodeAt(i);
    return new Type(buf);
  }
  function colour(t) {
    t = Math.min(1, Math.max(0, t)) * (VIRIDIS.length - 1);
    var i = Math.min(VIRIDIS.length - 2, Math.floor(t)), f = t - i, a = VIRIDIS[i], b = VIRIDIS[i + 1];
    return [0, 1, 2].map(function (k) { return (a[k] + f * (b[k] - a[k])) / 255; });
  }
  function normals(p, idx) {
    var n = new Float32Array(p.length);
    for (var f = 0; f < idx.length; f += 3) {
      var a = 3 * idx[f], b = 3 * idx[f + 1], c = 3 * idx[f + 2];
      var ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
      var vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
      var nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      [a, b, c].forEach(function (v) { n[v] += nx; n[v + 1] += ny; n[v + 2] += nz; });
    }
    for (var i = 0; i < n.length; i += 3) {
      var l = Math.hypot(n[i], n[i + 1], n[i + 2]) || 1;
      n[i] /= l; n[i + 1] /= l; n[i + 2] /= l;
    }
    return n;
  }

  var gl = null;
  try {
    gl = canvas.getContext("webgl", { antialias: true }) ||
      canvas.getContext("experimental-webgl");
  } catch (e) { gl = null; }
  if (!gl) {
    note.textContent = "This browser cannot show WebGL: the renders above show the same model.";
    return;
  }
  var uintOK = !!gl.getExtension("OES_element_index_uint");

  var VS = "attribute vec3 p; attribute vec3 n; attribute vec3 c; uniform mat4 m;" +
    "varying vec3 vn; varying vec3 vc; void main(){ gl_Position = m * vec4(p, 1.0);" +
    " vn = n; vc = c; gl_PointSize = 1.0; }";
  var FS = "precision mediump float; varying vec3 vn; varying vec3 vc; uniform vec3 l;" +
    " uniform float lit; void main(){ float k = 1.0; if (lit > 0.5) {" +
    " vec3 nn = normalize(vn); k = 0.35 + 0.65 * abs(dot(nn, l)); }" +
    " gl_FragColor = vec4(vc * k, 1.0); }";
  function shader(type, src) {
    var s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    return s;
  }
  var prog = gl.createProgram();
  gl.attachShader(prog, shader(gl.VERTEX_SHADER, VS));
  gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, FS));
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) {
    note.textContent = "WebGL could not compile the viewer's shaders.";
    return;
  }
  gl.useProgram(prog);
  var loc = { p: gl.getAttribLocation(prog, "p"), n: gl.getAttribLocation(prog, "n"),
    c: gl.getAttribLocation(prog, "c"), m: gl.getUniformLocation(prog, "m"),
    l: gl.getUniformLocation(prog, "l"), lit: gl.getUniformLocation(prog, "lit") };

  function buffer(arr, target) {
    var b = gl.createBuffer();
    gl.bindBuffer(target || gl.ARRAY_BUFFER, b);
    gl.bufferData(target || gl.ARRAY_BUFFER, arr, gl.STATIC_DRAW);
    return b;
  }
  function lines(flat, rgb) {
    var cols = new Float32Array(flat.length);
    for (var i = 0; i < flat.length; i += 3) { cols[i] = rgb[0]; cols[i + 1] = rgb[1]; cols[i + 2] = rgb[2]; }
    return { p: buffer(flat), n: buffer(new Float32Array(flat.length)), c: buffer(cols), count: flat.length / 3 };
  }
  function prepare(cs) {
    var wide = cs.index_bits === 32;
    var p = b64(cs.positions, Float32Array), idx = b64(cs.indices, wide ? Uint32Array : Uint16Array);
    var v = b64(cs.values, Float32Array), cols = new Float32Array(p.length);
    for (var i = 0; i < v.length; i++) {
      var rgb = colour((v[i] - cs.lo) / (cs.hi - cs.lo || 1));
      cols[3 * i] = rgb[0]; cols[3 * i + 1] = rgb[1]; cols[3 * i + 2] = rgb[2];
    }
    if (wide && !uintOK) return null;  /* a mesh too big for this WebGL */
    return { p: buffer(p), n: buffer(normals(p, idx)), c: buffer(cols),
      i: buffer(idx, gl.ELEMENT_ARRAY_BUFFER), count: idx.length,
      type: wide ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT,
      outline: lines(b64(cs.outline, Float32Array), [0.85, 0.1, 0.1]),
      grid: lines(b64(cs.grid, Float32Array), [0.55, 0.55, 0.55]), cs: cs };
  }
  var meshes = data.cases.map(prepare).filter(Boolean);
  if (!meshes.length) {
    note.textContent = "This browser's WebGL cannot draw meshes this large.";
    return;
  }
  var view = { az: -0.7, el: -0.35, dist: 1, k: 0 };

  function mat(cs) {
    var w = canvas.width, h = canvas.height, f = 1 / Math.tan(0.35);
    var ce = Math.cos(view.el), eye = [cs.focus[0] + view.dist * ce * Math.cos(view.az),
      cs.focus[1] + view.dist * ce * Math.sin(view.az), cs.focus[2] + view.dist * Math.sin(view.el)];
    var z = [0, 1, 2].map(function (k) { return (eye[k] - cs.focus[k]) / view.dist; });
    var up = [0, 0, 1], x = [up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]];
    var lx = Math.hypot(x[0], x[1], x[2]) || 1; x = x.map(function (a) { return a / lx; });
    var y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]];
    var near = view.dist / 50, far = view.dist * 50, a = w / h;
    var P = [f / a, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
    var V = [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
    return { m: mul(P, V), light: z };
  }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function mul(a, b) {
    var o = new Float32Array(16);
    for (var c = 0; c < 4; c++) for (var r = 0; r < 4; r++) {
      var s = 0;
      for (var k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
      o[c * 4 + r] = s;
    }
    return o;
  }
  function bind(obj) {
    [["p", obj.p], ["n", obj.n], ["c", obj.c]].forEach(function (e) {
      gl.bindBuffer(gl.ARRAY_BUFFER, e[1]);
      gl.enableVertexAttribArray(loc[e[0]]);
      gl.vertexAttribPointer(loc[e[0]], 3, gl.FLOAT, false, 0, 0);
    });
  }
  function draw() {
    var r = window.devicePixelRatio || 1, w = Math.round(canvas.clientWidth * r),
      h = Math.round(canvas.clientHeight * r);
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    var mesh = meshes[view.k], M = mat(mesh.cs);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.uniformMatrix4fv(loc.m, false, M.m);
    gl.uniform3fv(loc.l, M.light);
    gl.uniform1f(loc.lit, 1);
    bind(mesh);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, mesh.i);
    gl.drawElements(gl.TRIANGLES, mesh.count, mesh.type, 0);
    gl.uniform1f(loc.lit, 0);
    bind(mesh.grid);
    gl.drawArrays(gl.LINES, 0, mesh.grid.count);
    gl.disable(gl.DEPTH_TEST);
    bind(mesh.outline);
    gl.drawArrays(gl.LINE_STRIP, 0, mesh.outline.count);
  }
  var pending = false;
  function redraw() {
    if (pending) return;
    pending = true;
    window.requestAnimationFrame(function () { pending = false; draw(); });
  }
  function show(k) {
    view.k = k;
    view.dist = 2.2 * meshes[k].cs.span;
    root.querySelectorAll("button[data-case]").forEach(function (b) {
      b.setAttribute("aria-pressed", String(+b.dataset.case === k));
    });
    var cs = meshes[k].cs;
    root.querySelector(".viewer-lo").textContent = cs.lo_text;
    root.querySelector(".viewer-hi").textContent = cs.hi_text;
    root.querySelector(".viewer-title").textContent = cs.label;
    redraw();
  }
  root.querySelectorAll("button[data-case]").forEach(function (b) {
    b.addEventListener("click", function () { show(+b.dataset.case); });
  });
  root.querySelectorAll("button[data-view]").forEach(function (b) {
    b.addEventListener("click", function () {
      var v = b.dataset.view.split(",");
      view.az = +v[0]; view.el = +v[1];
      redraw();
    });
  });
  var drag = null;
  canvas.addEventListener("pointerdown", function (e) {
    drag = { x: e.clientX, y: e.clientY, az: view.az, el: view.el };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) return;
    view.az = drag.az - (e.clientX - drag.x) * 0.01;
    view.el = Math.max(-1.55, Math.min(1.55, drag.el + (e.clientY - drag.y) * 0.01));
    redraw();
  });
  canvas.addEventListener("pointerup", function () { drag = null; });
  canvas.addEventListener("pointercancel", function () { drag = null; });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    var s = meshes[view.k].cs.span;
    view.dist = Math.max(0.3 * s, Math.min(40 * s, view.dist * Math.exp(e.deltaY * 0.001)));
    redraw();
  }, { passive: false });
  window.addEventListener("resize", redraw);
  root.dataset.ready = "1";
  show(0);
})();
