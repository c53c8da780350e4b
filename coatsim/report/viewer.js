/* coatsim report: interactive view of the coated part (thickness colours, tool path).
   A canvas-2D renderer (orthographic, painter's algorithm, flat-shaded triangles): no WebGL, no
   network, so it runs in any browser with or without a GPU. Data: the JSON block
   #coatsim-viewer-data written by coatsim/report/viewer.py. */
(function () {
  "use strict";
  var root = document.getElementById("coatsim-viewer");
  var source = document.getElementById("coatsim-viewer-data");
  if (!root || !source) { return; }
  var data = JSON.parse(source.textContent);

  function bytes(b64) {
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) { out[i] = s.charCodeAt(i); }
    return out;
  }
  function floats(b64) { return new Float32Array(bytes(b64).buffer); }

  var P = floats(data.positions);
  var faceBytes = bytes(data.faces);
  var F = data.index === "u16" ? new Uint16Array(faceBytes.buffer) : new Uint32Array(faceBytes.buffer);
  var nV = P.length / 3, nF = F.length / 3;
  var variants = data.variants.map(function (v) {
    return { name: v.name, colours: bytes(v.colours), paths: v.paths.map(floats) };
  });
  var radius = 1e-9;
  for (var i = 0; i < nV; i++) {
    radius = Math.max(radius, Math.hypot(P[3 * i], P[3 * i + 1], P[3 * i + 2]));
  }

  // a rotation taking the part's mean normal ("up") to +z, so the default view looks down on it
  function align(up) {
    var n = Math.hypot(up[0], up[1], up[2]) || 1, u = [up[0] / n, up[1] / n, up[2] / n];
    var c = u[2], ax = [u[1], -u[0], 0], s = Math.hypot(ax[0], ax[1]);
    if (s < 1e-9) { return c > 0 ? [1, 0, 0, 0, 1, 0, 0, 0, 1] : [1, 0, 0, 0, -1, 0, 0, 0, -1]; }
    var x = ax[0] / s, y = ax[1] / s, t = 1 - c;
    return [t * x * x + c, t * x * y, y * s, t * x * y, t * y * y + c, -x * s, -y * s, x * s, c];
  }
  function mul(a, b) {
    var out = new Array(9);
    for (var r = 0; r < 3; r++) {
      for (var k = 0; k < 3; k++) {
        out[3 * r + k] = a[3 * r] * b[k] + a[3 * r + 1] * b[3 + k] + a[3 * r + 2] * b[6 + k];
      }
    }
    return out;
  }
  var base = align(data.up);
  var initial = { yaw: -0.5, pitch: -0.85, zoom: 1, panX: 0, panY: 0 };
  var view = Object.assign({}, initial);
  var state = { variant: 0, path: true };

  var canvas = document.getElementById("coatsim-canvas");
  var g = canvas.getContext("2d");
  var X = new Float32Array(nV), Y = new Float32Array(nV), Z = new Float32Array(nV);
  var order = new Uint32Array(nF), depth = new Float32Array(nF);
  for (i = 0; i < nF; i++) { order[i] = i; }

  function rotation() {
    var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw), cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
    var yaw = [cy, -sy, 0, sy, cy, 0, 0, 0, 1], pitch = [1, 0, 0, 0, cp, -sp, 0, sp, cp];
    return mul(pitch, mul(yaw, base));
  }

  function draw() {
    var w = canvas.width, h = canvas.height, R = rotation();
    var scale = view.zoom * 0.42 * Math.min(w, h) / radius, cx = w / 2 + view.panX, cy = h / 2 + view.panY;
    g.fillStyle = "#ffffff";
    g.fillRect(0, 0, w, h);
    for (var v = 0; v < nV; v++) {
      var x = P[3 * v], y = P[3 * v + 1], z = P[3 * v + 2];
      X[v] = cx + scale * (R[0] * x + R[1] * y + R[2] * z);
      Y[v] = cy - scale * (R[3] * x + R[4] * y + R[5] * z);
      Z[v] = scale * (R[6] * x + R[7] * y + R[8] * z);
    }
    for (var f = 0; f < nF; f++) { depth[f] = Z[F[3 * f]] + Z[F[3 * f + 1]] + Z[F[3 * f + 2]]; }
    order.sort(function (a, b) { return depth[a] - depth[b]; });
    var col = variants[state.variant].colours;
    g.lineWidth = 0.6;
    for (var k = 0; k < nF; k++) {
      var t = order[k], a = F[3 * t], b = F[3 * t + 1], c = F[3 * t + 2];
      var ux = X[b] - X[a], uy = Y[b] - Y[a], vx = X[c] - X[a], vy = Y[c] - Y[a];
      var area = Math.abs(ux * vy - uy * vx);
      var wz = Z[b] - Z[a], vz = Z[c] - Z[a];
      var nx = uy * vz - wz * vy, ny = wz * vx - ux * vz, len = Math.hypot(nx, ny, area) || 1;
      var shade = 0.62 + 0.38 * area / len;
      var r = (col[3 * a] + col[3 * b] + col[3 * c]) / 3 * shade;
      var gg = (col[3 * a + 1] + col[3 * b + 1] + col[3 * c + 1]) / 3 * shade;
      var bl = (col[3 * a + 2] + col[3 * b + 2] + col[3 * c + 2]) / 3 * shade;
      var style = "rgb(" + (r | 0) + "," + (gg | 0) + "," + (bl | 0) + ")";
      g.fillStyle = style;
      g.strokeStyle = style;
      g.beginPath();
      g.moveTo(X[a], Y[a]);
      g.lineTo(X[b], Y[b]);
      g.lineTo(X[c], Y[c]);
      g.closePath();
      g.fill();
      g.stroke();
    }
    if (state.path) {
      g.strokeStyle = "#e0301e";
      g.lineWidth = 1.4;
      variants[state.variant].paths.forEach(function (p) {
        g.beginPath();
        for (var q = 0; q < p.length / 3; q++) {
          var x = p[3 * q], y = p[3 * q + 1], z = p[3 * q + 2];
          var sx = cx + scale * (R[0] * x + R[1] * y + R[2] * z), syy = cy - scale * (R[3] * x + R[4] * y + R[5] * z);
          if (q === 0) { g.moveTo(sx, syy); } else { g.lineTo(sx, syy); }
        }
        g.stroke();
      });
    }
    legend(w, h);
    root.setAttribute("data-viewer", "ready");
  }

  function legend(w, h) {
    var x = w - 34, top = 30, height = h - 80, bar = data.bar;
    var gradient = g.createLinearGradient(0, top + height, 0, top);
    bar.forEach(function (c, k) { gradient.addColorStop(k / (bar.length - 1), c); });
    g.fillStyle = gradient;
    g.fillRect(x, top, 14, height);
    g.strokeStyle = "#444444";
    g.lineWidth = 0.8;
    g.strokeRect(x, top, 14, height);
    g.fillStyle = "#222222";
    g.font = "11px sans-serif";
    g.textAlign = "right";
    g.fillText(data.scale[1].toPrecision(3) + " µm", x + 14, top - 8);
    g.fillText(data.scale[0].toPrecision(3) + " µm", x + 14, top + height + 16);
    g.textAlign = "left";
    g.fillText(variants[state.variant].name, 10, 18);
  }

  var pending = false;
  function redraw() {
    if (pending) { return; }
    pending = true;
    window.requestAnimationFrame(function () { pending = false; draw(); });
  }

  var drag = null;
  canvas.addEventListener("pointerdown", function (e) {
    drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) { return; }
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.pan) {
      view.panX += dx;
      view.panY += dy;
    } else {
      view.yaw += 0.01 * dx;
      view.pitch = Math.max(-Math.PI, Math.min(Math.PI, view.pitch + 0.01 * dy));
    }
    redraw();
  });
  canvas.addEventListener("pointerup", function () { drag = null; });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    view.zoom = Math.max(0.2, Math.min(20, view.zoom * Math.exp(-0.0015 * e.deltaY)));
    redraw();
  }, { passive: false });
  root.querySelectorAll('input[name="coatsim-variant"]').forEach(function (input) {
    input.addEventListener("change", function () { state.variant = Number(input.value); redraw(); });
  });
  document.getElementById("coatsim-path").addEventListener("change", function (e) {
    state.path = e.target.checked;
    redraw();
  });
  document.getElementById("coatsim-reset").addEventListener("click", function () {
    view = Object.assign({}, initial);
    redraw();
  });
  draw();
}());
