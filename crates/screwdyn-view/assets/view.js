// screwdyn view: draws the robot the Rust library described in the JSON of #data.
// Every pose (H_i^0 of each body, per run sample) was computed by the library; this script
// only multiplies the 4x4 matrices it is given, draws triangles and lines with WebGL 2, and
// plots the run. Sections: errors, data, math, scene (GL), geometry, camera, animation, plot.
"use strict";

// ---------------------------------------------------------------- errors
// Any error is shown on the page (#errors) so a user, and the browser tests, see it.
function reportError(text) {
  const box = document.getElementById("errors");
  if (box) box.textContent += text + "\n";
}
window.onerror = function (msg, src, line, col) {
  reportError("JavaScript error: " + msg + " (line " + line + ":" + col + ")");
};
window.addEventListener("unhandledrejection", function (e) {
  reportError("JavaScript error: " + e.reason);
});

(function main() {
  // -------------------------------------------------------------- data
  const D = JSON.parse(document.getElementById("data").textContent);
  function bytes(b64) {
    const s = atob(b64), out = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
    return out;
  }
  const f32 = (b64) => new Float32Array(bytes(b64).buffer);
  const u32 = (b64) => new Uint32Array(bytes(b64).buffer);
  const run = D.run;
  const nb = D.bodies.length, nq = D.joints.length;
  const pose0 = f32(D.pose0);
  const runPoses = run ? f32(run.poses) : null;
  const runT = run ? f32(run.t) : null;
  const runQ = run ? f32(run.q) : null;
  const runTau = run && run.tau ? f32(run.tau) : null;
  const runFlags = run ? bytes(run.flags) : null;
  const PAST_LIMIT = 1, PAST_EFFORT = 2;

  // -------------------------------------------------------------- math
  // 4x4 matrices are Float32Array(16), column-major as WebGL wants them.
  function fromRows34(a, o) { // 3x4 row-major at a[o..o+12] -> 4x4 column-major
    return new Float32Array([a[o], a[o + 4], a[o + 8], 0, a[o + 1], a[o + 5], a[o + 9], 0,
      a[o + 2], a[o + 6], a[o + 10], 0, a[o + 3], a[o + 7], a[o + 11], 1]);
  }
  const IDENTITY = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  function mul(a, b) {
    const r = new Float32Array(16);
    for (let c = 0; c < 4; c++)
      for (let k = 0; k < 4; k++) {
        const s = b[4 * c + k];
        for (let i = 0; i < 4; i++) r[4 * c + i] += a[4 * k + i] * s;
      }
    return r;
  }
  function apply(m, p) { // m · (p, 1)
    return [0, 1, 2].map((i) => m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i]);
  }
  function applyDir(m, d) {
    return [0, 1, 2].map((i) => m[i] * d[0] + m[4 + i] * d[1] + m[8 + i] * d[2]);
  }
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const normalize = (a) => scale(a, 1 / Math.hypot(a[0], a[1], a[2]));
  function lookAt(eye, target, up) {
    const z = normalize(sub(eye, target)), x = normalize(cross(up, z)), y = cross(z, x);
    return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
  }
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1,
      0, 0, 2 * far * near * nf, 0]);
  }

  // -------------------------------------------------------------- scene (GL)
  const canvas = document.getElementById("view");
  const gl = canvas.getContext("webgl2", { antialias: true, preserveDrawingBuffer: true });
  if (!gl) throw new Error("this browser has no WebGL 2: the robot cannot be drawn");
  const BACKGROUND = [0.929, 0.945, 0.965];
  function program(vs, fs) {
    const p = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(p, s);
    }
    gl.bindAttribLocation(p, 0, "p"); // positions at 0, colours at 1 in every vertex array
    gl.bindAttribLocation(p, 1, "c");
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    return p;
  }
  // Triangles: flat shading from the screen-space derivatives of the world position (no
  // normals need to be embedded), lit by a head light.
  const meshProg = program(
    "#version 300 es\nin vec3 p; uniform mat4 M, VP; out vec3 w;\n" +
    "void main() { vec4 x = M * vec4(p, 1.0); w = x.xyz; gl_Position = VP * x; }",
    "#version 300 es\nprecision highp float; in vec3 w; uniform vec4 color; uniform vec3 eye;\n" +
    "out vec4 o; void main() { vec3 n = normalize(cross(dFdx(w), dFdy(w)));\n" +
    "float d = abs(dot(n, normalize(eye - w))); o = vec4(color.rgb * (0.3 + 0.7 * d), color.a); }");
  // Lines: one colour per vertex.
  const lineProg = program(
    "#version 300 es\nin vec3 p; in vec3 c; uniform mat4 VP; out vec3 k;\n" +
    "void main() { k = c; gl_Position = VP * vec4(p, 1.0); }",
    "#version 300 es\nprecision highp float; in vec3 k; out vec4 o; void main() { o = vec4(k, 1.0); }");
  const U = {
    M: gl.getUniformLocation(meshProg, "M"), VP: gl.getUniformLocation(meshProg, "VP"),
    color: gl.getUniformLocation(meshProg, "color"), eye: gl.getUniformLocation(meshProg, "eye"),
    lineVP: gl.getUniformLocation(lineProg, "VP"),
  };

  // -------------------------------------------------------------- geometry
  // Meshes: one vertex array per mesh, shared by the parts that place it.
  const meshes = D.meshes.map(function (m) {
    const pos = f32(m.p), idx = u32(m.i);
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    const vb = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, vb);
    gl.bufferData(gl.ARRAY_BUFFER, pos, gl.STATIC_DRAW);
    gl.enableVertexAttribArray(0);
    gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
    const ib = gl.createBuffer();
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, idx, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    return { vao: vao, count: idx.length, pos: pos };
  });
  const parts = D.parts.map((p) => ({ b: p.b, mesh: p.m, t: fromRows34(p.t, 0), c: p.c, g: p.g }));

  // Body poses H_i^0 of the shown sample (the base is the identity).
  function bodyPoses(k) {
    const src = k === null ? pose0 : runPoses, o = k === null ? 0 : k * nb * 12;
    const out = [];
    for (let i = 0; i < nb; i++) out.push(fromRows34(src, o + 12 * i));
    return out;
  }
  const poseOf = (poses, b) => (b < 0 ? IDENTITY : poses[b]);

  // Line buffers (rebuilt when the pose changes): positions and colours.
  const lineVao = gl.createVertexArray(), lineBuf = gl.createBuffer(), colBuf = gl.createBuffer();
  gl.bindVertexArray(lineVao);
  gl.bindBuffer(gl.ARRAY_BUFFER, lineBuf);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
  gl.bindBuffer(gl.ARRAY_BUFFER, colBuf);
  gl.enableVertexAttribArray(1);
  gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 0, 0);
  gl.bindVertexArray(null);

  const up = D.up, size = D.size;
  // Two unit vectors spanning the floor (perpendicular to "up" = −gravity).
  const e1 = normalize(cross(Math.abs(up[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0], up));
  const e2 = cross(up, e1);

  // Floor level: the lowest of the base and the robot (at rest and along the run).
  let floor = 0;
  (function () {
    const poses = bodyPoses(null);
    for (const p of parts) {
      if (p.g !== "robot") continue;
      const m = mul(poseOf(poses, p.b), p.t), pos = meshes[p.mesh].pos;
      for (let v = 0; v < pos.length; v += 3 * Math.max(1, Math.floor(pos.length / 3000)))
        floor = Math.min(floor, dot(apply(m, [pos[v], pos[v + 1], pos[v + 2]]), up));
    }
    if (run) for (let k = 0; k < run.n; k++) for (let i = 0; i < nb; i++) {
      const o = (k * nb + i) * 12;
      floor = Math.min(floor, dot([runPoses[o + 3], runPoses[o + 7], runPoses[o + 11]], up) - 0.05 * size);
    }
  })();

  // Grid spacing: 1, 2 or 5 × 10^k, about a quarter of the robot.
  const spacing = (function () {
    const raw = size / 4, p = Math.pow(10, Math.floor(Math.log10(raw)));
    return raw / p < 2 ? p : raw / p < 5 ? 2 * p : 5 * p;
  })();

  function triad(lines, m, len, dim) {
    const o = apply(m, [0, 0, 0]);
    const colors = dim ? [[0.9, 0.4, 0.4], [0.4, 0.8, 0.4], [0.4, 0.5, 0.95]]
      : [[0.85, 0.1, 0.1], [0.1, 0.6, 0.1], [0.1, 0.2, 0.9]];
    for (let a = 0; a < 3; a++) {
      const d = [0, 0, 0]; d[a] = len;
      lines.push([o, apply(m, d), colors[a]]);
    }
  }

  // The overlay lines of the shown pose: grid, base frame, link frames, joint axes, path.
  function overlayLines(poses, k) {
    const lines = [];
    if (show.grid) {
      const n = Math.ceil((1.25 * size) / spacing), f = scale(up, floor);
      for (let i = -n; i <= n; i++) {
        const c = i === 0 ? [0.55, 0.58, 0.62] : [0.78, 0.8, 0.83];
        lines.push([add(f, add(scale(e1, i * spacing), scale(e2, -n * spacing))),
          add(f, add(scale(e1, i * spacing), scale(e2, n * spacing))), c]);
        lines.push([add(f, add(scale(e2, i * spacing), scale(e1, -n * spacing))),
          add(f, add(scale(e2, i * spacing), scale(e1, n * spacing))), c]);
      }
      triad(lines, IDENTITY, 0.3 * size, false);
    }
    if (show.frames)
      for (const f of D.frames)
        if (f.b >= 0) triad(lines, mul(poses[f.b], fromRows34(f.t, 0)), 0.12 * size, true);
    if (show.axes)
      for (const a of D.axes) {
        const m = poses[a.b], p = apply(m, a.p), d = applyDir(m, a.d), L = 0.35 * size;
        const past = k !== null && runFlags[k * nq + a.b];
        lines.push([add(p, scale(d, -L)), add(p, scale(d, L)),
          past ? [0.9, 0, 0] : a.kind === "prismatic" ? [0.6, 0.2, 0.8] : [0.95, 0.55, 0.05]]);
      }
    if (show.path && run)
      for (const path of paths)
        for (let s = 1; s < run.n; s++) {
          const a = [path[3 * s - 3], path[3 * s - 2], path[3 * s - 1]];
          const b = [path[3 * s], path[3 * s + 1], path[3 * s + 2]];
          lines.push([a, b, k !== null && s <= k ? [0.55, 0.1, 0.6] : [0.8, 0.65, 0.85]]);
        }
    return lines;
  }
  const paths = run ? run.paths.map((p) => f32(p.p)) : [];

  // -------------------------------------------------------------- camera
  // Orbit camera about `target`: azimuth and elevation measured in the floor's (e1, e2) plane.
  const cam = { target: [0, 0, 0], dist: 1, az: 0, el: 0.35, fovy: 0.8 };
  function fitCamera() {
    const poses = bodyPoses(null);
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    const grow = (x) => { for (let i = 0; i < 3; i++) { lo[i] = Math.min(lo[i], x[i]); hi[i] = Math.max(hi[i], x[i]); } };
    grow([0, 0, 0]);
    for (const p of parts) {
      const m = mul(poseOf(poses, p.b), p.t), pos = meshes[p.mesh].pos;
      const step = 3 * Math.max(1, Math.floor(pos.length / 3000));
      for (let v = 0; v < pos.length; v += step) grow(apply(m, [pos[v], pos[v + 1], pos[v + 2]]));
    }
    for (const path of paths) for (let v = 0; v < path.length; v += 3) grow([path[v], path[v + 1], path[v + 2]]);
    cam.target = scale(add(lo, hi), 0.5);
    const r = Math.max(0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 0.05);
    cam.dist = (1.15 * r) / Math.sin(cam.fovy / 2);
    // Look from the "front": along the base z axis when it is horizontal (a planar robot
    // moving in the base x-y plane, gravity along -y), else from +x, -y (a 3/4 view).
    const z = [0, 0, 1], zh = sub(z, scale(up, dot(z, up)));
    const front = Math.hypot(zh[0], zh[1], zh[2]) > 0.5
      ? add(normalize(zh), scale(cross(up, normalize(zh)), -0.35)) : [1, -1.3, 0];
    const fh = sub(front, scale(up, dot(front, up)));
    cam.az = Math.atan2(dot(fh, e2), dot(fh, e1));
    cam.el = 0.35;
  }
  function eye() {
    const h = [Math.cos(cam.el) * Math.cos(cam.az), Math.cos(cam.el) * Math.sin(cam.az), Math.sin(cam.el)];
    return add(cam.target, scale(add(add(scale(e1, h[0]), scale(e2, h[1])), scale(up, h[2])), cam.dist));
  }
  function viewProj() {
    const aspect = canvas.width / Math.max(1, canvas.height);
    return mul(perspective(cam.fovy, aspect, cam.dist / 100, cam.dist * 20), lookAt(eye(), cam.target, up));
  }
  (function mouse() {
    let drag = null;
    canvas.addEventListener("contextmenu", (e) => e.preventDefault());
    canvas.addEventListener("pointerdown", function (e) {
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener("pointerup", () => { drag = null; });
    canvas.addEventListener("pointermove", function (e) {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        const z = normalize(sub(eye(), cam.target)), x = normalize(cross(up, z)), y = cross(z, x);
        const s = (2 * cam.dist * Math.tan(cam.fovy / 2)) / canvas.clientHeight;
        cam.target = add(cam.target, add(scale(x, -dx * s), scale(y, dy * s)));
      } else {
        cam.az -= dx * 0.008;
        cam.el = Math.max(-1.5, Math.min(1.5, cam.el + dy * 0.008));
      }
      draw();
    });
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      cam.dist *= Math.exp(e.deltaY * 0.001);
      draw();
    }, { passive: false });
    canvas.addEventListener("dblclick", () => { fitCamera(); draw(); });
  })();

  // -------------------------------------------------------------- drawing
  const show = { grid: true, frames: false, axes: false, coms: D.skeleton, path: true };
  let current = null; // the run sample shown (null: the static pose q0)

  function draw() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.round(canvas.clientWidth * dpr), h = Math.round(canvas.clientHeight * dpr);
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    const k = current, poses = bodyPoses(k), VP = viewProj(), E = eye();
    // Triangles.
    gl.useProgram(meshProg);
    gl.uniformMatrix4fv(U.VP, false, VP);
    gl.uniform3fv(U.eye, E);
    for (const p of parts) {
      if (p.g === "com" && !show.coms) continue;
      let c = p.c;
      // A body whose joint is past a limit (or its torque past the effort limit) turns red.
      if (k !== null && p.b >= 0 && p.g === "robot" && runFlags[k * nq + p.b]) c = [0.9, 0.1, 0.1, 1];
      gl.uniformMatrix4fv(U.M, false, mul(poseOf(poses, p.b), p.t));
      gl.uniform4fv(U.color, c);
      gl.bindVertexArray(meshes[p.mesh].vao);
      gl.drawElements(gl.TRIANGLES, meshes[p.mesh].count, gl.UNSIGNED_INT, 0);
    }
    // Lines.
    const lines = overlayLines(poses, k);
    const P = new Float32Array(lines.length * 6), C = new Float32Array(lines.length * 6);
    lines.forEach(function (l, i) {
      P.set(l[0], 6 * i); P.set(l[1], 6 * i + 3); C.set(l[2], 6 * i); C.set(l[2], 6 * i + 3);
    });
    gl.useProgram(lineProg);
    gl.uniformMatrix4fv(U.lineVP, false, VP);
    gl.bindVertexArray(lineVao);
    gl.bindBuffer(gl.ARRAY_BUFFER, lineBuf);
    gl.bufferData(gl.ARRAY_BUFFER, P, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, colBuf);
    gl.bufferData(gl.ARRAY_BUFFER, C, gl.DYNAMIC_DRAW);
    gl.drawArrays(gl.LINES, 0, 2 * lines.length);
    gl.bindVertexArray(null);
    report(poses, VP);
  }

  // The DOM report: joint values, time, and where the robot is on the screen (#probe holds
  // the projected centre of the last body's first part, in CSS pixels of the page).
  const jointItems = Array.from(document.querySelectorAll("#joints li"));
  jointItems.forEach(function (li) {
    const v = document.createElement("span");
    v.className = "value";
    li.appendChild(document.createTextNode(" "));
    li.appendChild(v);
  });
  // The probe: the last body's first part and the centroid of its vertices (mesh frame).
  const probePart = (function () {
    const robot = parts.filter((p) => p.g === "robot");
    if (!robot.length) return null;
    const last = robot.reduce((a, p) => (p.b > a.b ? p : a), robot[0]);
    const pos = meshes[last.mesh].pos;
    let c = [0, 0, 0];
    for (let v = 0; v < pos.length; v += 3) c = add(c, [pos[v], pos[v + 1], pos[v + 2]]);
    return { b: last.b, t: last.t, centre: scale(c, 3 / Math.max(3, pos.length)) };
  })();
  function report(poses, VP) {
    const k = current;
    for (let i = 0; i < nq; i++) {
      const q = k === null ? D.q0[i] : runQ[k * nq + i];
      let text = "q = " + q.toFixed(3);
      if (runTau && k !== null) text += ", τ = " + runTau[k * nq + i].toFixed(2);
      const flag = k === null ? 0 : runFlags[k * nq + i];
      if (flag & PAST_LIMIT) text += " past limit";
      if (flag & PAST_EFFORT) text += " past effort";
      jointItems[i].lastChild.textContent = text;
      jointItems[i].classList.toggle("past", flag !== 0);
    }
    document.getElementById("time").textContent = k === null ? "0" : String(+runT[k].toFixed(4));
    if (probePart) {
      const c = apply(mul(poseOf(poses, probePart.b), probePart.t), probePart.centre);
      const x = apply(VP, c), wv = VP[3] * c[0] + VP[7] * c[1] + VP[11] * c[2] + VP[15];
      const r = canvas.getBoundingClientRect();
      const probe = document.getElementById("probe");
      probe.dataset.x = (r.left + ((x[0] / wv + 1) / 2) * r.width).toFixed(1);
      probe.dataset.y = (r.top + ((1 - x[1] / wv) / 2) * r.height).toFixed(1);
    }
  }

  // Toggles.
  for (const key of Object.keys(show)) {
    const box = document.getElementById("show-" + key);
    box.checked = show[key];
    box.addEventListener("change", function () { show[key] = box.checked; draw(); });
  }
  if (D.warnings.length)
    document.getElementById("warnings").textContent = "Warnings: " + D.warnings.join(" ");

  // -------------------------------------------------------------- animation
  const player = { t: 0, playing: false, speed: 1, last: null };
  const slider = document.getElementById("slider"), playButton = document.getElementById("play");
  function sampleAt(t) { // the last sample at or before t (binary search)
    let lo = 0, hi = run.n - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (runT[mid] <= t + 1e-9) lo = mid; else hi = mid - 1; }
    return lo;
  }
  function seek(t) {
    player.t = Math.max(0, Math.min(run.duration, t));
    current = sampleAt(player.t);
    slider.value = String(Math.round((1000 * player.t) / Math.max(run.duration, 1e-12)));
    draw();
    drawPlot();
  }
  function tick(now) {
    if (!player.playing) return;
    if (player.last !== null) {
      let t = player.t + ((now - player.last) / 1000) * player.speed;
      if (t > run.duration) t = 0; // loop
      seek(t);
    }
    player.last = now;
    requestAnimationFrame(tick);
  }
  function setPlaying(on) {
    player.playing = on;
    player.last = null;
    playButton.textContent = on ? "Pause" : "Play";
    if (on) requestAnimationFrame(tick);
  }
  if (run) {
    document.getElementById("bottom").hidden = false;
    playButton.addEventListener("click", () => setPlaying(!player.playing));
    slider.addEventListener("input", () => seek((slider.value / 1000) * run.duration));
    document.getElementById("speed").addEventListener("change", (e) => { player.speed = +e.target.value; });
    document.addEventListener("keydown", function (e) {
      if (e.key === " " && e.target.tagName !== "INPUT" && e.target.tagName !== "SELECT") {
        e.preventDefault(); setPlaying(!player.playing);
      }
    });
    const list = document.getElementById("violations");
    for (const v of run.violations) {
      const div = document.createElement("div");
      div.className = "past";
      div.textContent = D.joints[v.joint] + (v.kind === "limit" ? " past its position limit" : " past its effort limit") +
        " in " + v.count + " samples from t = " + (+(v.first_time - run.t0).toFixed(4)) + " s (worst " + (+v.worst.toPrecision(4)) + ")";
      list.appendChild(div);
    }
  } else {
    document.getElementById("run-info").hidden = true;
  }

  // -------------------------------------------------------------- plot
  // Panels q, τ and energy over time; red bands where a joint is past a limit (q panel) or
  // its effort limit (τ panel); a cursor at the shown time. Click to seek.
  const plotCanvas = document.getElementById("plot");
  const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];
  let plotImage = null;
  function panels() {
    const out = [{ name: "q", series: D.joints.map((_, i) => (k) => runQ[k * nq + i]), flag: PAST_LIMIT }];
    if (runTau) out.push({ name: "τ", series: D.joints.map((_, i) => (k) => runTau[k * nq + i]), flag: PAST_EFFORT });
    if (run.energy.length) {
      const e = run.energy.map((s) => f32(s.v));
      out.push({ name: "energy", series: e.map((v) => (k) => v[k]), labels: run.energy.map((s) => s.name) });
    }
    return out;
  }
  function drawPlot() {
    if (!run) return;
    const dpr = window.devicePixelRatio || 1;
    const W = Math.round(plotCanvas.clientWidth * dpr), H = Math.round(plotCanvas.clientHeight * dpr);
    const out = plotCanvas.getContext("2d");
    if (plotCanvas.width !== W || plotCanvas.height !== H || !plotImage) {
      // The curves are drawn once into an off-screen canvas; each frame copies it and adds
      // the cursor.
      plotCanvas.width = W; plotCanvas.height = H;
      const off = document.createElement("canvas");
      off.width = W; off.height = H;
      const ctx = off.getContext("2d");
      const ps = panels(), pw = W / ps.length, L = 34 * dpr, B = 14 * dpr;
      ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
      ctx.font = 10 * dpr + "px sans-serif";
      ps.forEach(function (p, j) {
        const x0 = j * pw + L, w = pw - L - 6 * dpr, y0 = 12 * dpr, h = H - y0 - B;
        let lo = Infinity, hi = -Infinity;
        for (const s of p.series) for (let k = 0; k < run.n; k++) { lo = Math.min(lo, s(k)); hi = Math.max(hi, s(k)); }
        if (!(hi > lo)) { lo -= 1; hi += 1; }
        const X = (k) => x0 + (runT[k] / Math.max(run.duration, 1e-12)) * w;
        const Y = (v) => y0 + h - ((v - lo) / (hi - lo)) * h;
        if (p.flag) { // violation bands
          ctx.fillStyle = "rgba(220,0,0,0.15)";
          for (let k = 0; k < run.n; k++) {
            let any = false;
            for (let i = 0; i < nq; i++) if (runFlags[k * nq + i] & p.flag) any = true;
            if (any) ctx.fillRect(X(k) - dpr, y0, Math.max(2 * dpr, X(Math.min(k + 1, run.n - 1)) - X(k)), h);
          }
        }
        ctx.strokeStyle = "#999"; ctx.strokeRect(x0, y0, w, h);
        p.series.forEach(function (s, i) {
          ctx.strokeStyle = PALETTE[i % PALETTE.length]; ctx.lineWidth = dpr;
          ctx.beginPath();
          for (let k = 0; k < run.n; k++) (k ? ctx.lineTo : ctx.moveTo).call(ctx, X(k), Y(s(k)));
          ctx.stroke();
        });
        ctx.fillStyle = "#333";
        ctx.fillText(p.name + (p.labels ? " (" + p.labels.join(", ").replace(/_energy/g, "") + ")" : ""), x0 + 4 * dpr, y0 - 2 * dpr);
        ctx.fillText(+hi.toPrecision(3) + "", j * pw + 2 * dpr, y0 + 8 * dpr);
        ctx.fillText(+lo.toPrecision(3) + "", j * pw + 2 * dpr, y0 + h);
        ctx.fillText("0", x0, H - 2 * dpr);
        ctx.fillText(+run.duration.toPrecision(4) + " s", x0 + w - 40 * dpr, H - 2 * dpr);
        p.box = { x0: x0, w: w, y0: y0, h: h };
      });
      plotImage = { canvas: off, panels: ps };
    }
    out.drawImage(plotImage.canvas, 0, 0);
    out.strokeStyle = "#000"; out.lineWidth = dpr;
    for (const p of plotImage.panels) {
      const x = p.box.x0 + (player.t / Math.max(run.duration, 1e-12)) * p.box.w;
      out.beginPath(); out.moveTo(x, p.box.y0); out.lineTo(x, p.box.y0 + p.box.h); out.stroke();
    }
  }
  plotCanvas.addEventListener("click", function (e) {
    if (!run || !plotImage) return;
    const r = plotCanvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1, x = (e.clientX - r.left) * dpr;
    for (const p of plotImage.panels)
      if (x >= p.box.x0 && x <= p.box.x0 + p.box.w) seek(((x - p.box.x0) / p.box.w) * run.duration);
  });
  window.addEventListener("resize", function () { plotImage = null; draw(); drawPlot(); });

  // -------------------------------------------------------------- start
  // The URL hash chooses the start: #t=0.5 (a time of the run, paused), &play=1, &grid=0,
  // &frames=1, &axes=1, &coms=0|1, &path=0, &size=700x450 (a fixed size of the 3-D view in
  // CSS pixels, so that its picture does not depend on the window's height).
  const hash = new URLSearchParams(location.hash.replace(/^#/, ""));
  const fixed = /^(\d+)x(\d+)$/.exec(hash.get("size") || "");
  if (fixed) {
    canvas.style.width = fixed[1] + "px";
    canvas.style.height = fixed[2] + "px";
    canvas.style.minHeight = "0";
  }
  for (const key of Object.keys(show))
    if (hash.has(key)) { show[key] = hash.get(key) === "1"; document.getElementById("show-" + key).checked = show[key]; }
  fitCamera();
  if (run) {
    seek(hash.has("t") ? parseFloat(hash.get("t")) || 0 : 0);
    if (hash.get("play") === "1") setPlaying(true);
  } else {
    draw();
  }
  document.body.dataset.ready = "1";
})();
