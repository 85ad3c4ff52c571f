// pocketeer's preview page: the drawing, the pockets and a program drawn on a canvas, with a
// legend, a scale bar, the origin, a play slider and the report. Everything it shows comes
// from the JSON in #data (written by pocketeer's export::preview); it asks the network for
// nothing. Address fragments: #play=F opens the slider at the fraction F of the program,
// #mark=N zoomed on mark N (both may be given: #play=0.5&mark=2);
// #selftest moves the slider to the end and writes what it found into #selftest (the browser
// test reads it).
"use strict";
const problems = [];
window.addEventListener("error", (e) => problems.push("error: " + e.message));
window.addEventListener("unhandledrejection", (e) => problems.push("rejection: " + e.reason));
document.addEventListener("securitypolicyviolation", (e) => problems.push("blocked request: " + e.blockedURI));
for (const level of ["error", "warn"]) {
  const original = console[level].bind(console);
  console[level] = (...args) => { problems.push(level + ": " + args.join(" ")); original(...args); };
}

const D = JSON.parse(document.getElementById("data").textContent);
const KIND_NAMES = D.kinds; // cut, link, entry, rapid, retract
const K_CUT = KIND_NAMES.indexOf("cut"), K_LINK = KIND_NAMES.indexOf("link"),
  K_ENTRY = KIND_NAMES.indexOf("entry"), K_RAPID = KIND_NAMES.indexOf("rapid"),
  K_RETRACT = KIND_NAMES.indexOf("retract");
const STYLE = {
  cut: { color: "#1f5fbf", width: 1.3, label: "cut (arrows: direction)" },
  link: { color: "#12a3a3", width: 1.3, label: "link at depth, through cut stock" },
  entry: { color: "#1a9a2a", width: 2.4, label: "entry: plunge, ramp or helix (numbered in order)" },
  rapid: { color: "#d03030", width: 1, dash: [6, 4], label: "rapid at the safe height" },
  retract: { color: "#8a2be2", width: 1.5, label: "retract straight up" },
};
const MARK_COLOR = { repair: "#d0008a", "not-cut": "#e07000", gouge: "#c00000", leftover: "#a000c0", warning: "#b08000" };

// ---- reading the packed data -------------------------------------------------------------
function Reader(b64) {
  const s = atob(b64);
  this.b = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) this.b[i] = s.charCodeAt(i);
  this.i = 0;
}
Reader.prototype.uint = function () {
  let v = 0, mul = 1, b;
  do { b = this.b[this.i++]; v += (b & 127) * mul; mul *= 128; } while (b >= 128);
  return v;
};
Reader.prototype.int = function () {
  const u = this.uint();
  return u % 2 === 0 ? u / 2 : -(u + 1) / 2;
};
function readRings(packed) {
  const r = new Reader(packed.data), out = [];
  for (let k = 0; k < packed.count; k++) {
    const tag = r.uint(), n = r.uint(), pts = new Float64Array(2 * n);
    let x = 0, y = 0;
    for (let j = 0; j < n; j++) { x += r.int(); y += r.int(); pts[2 * j] = x * D.quantum; pts[2 * j + 1] = y * D.quantum; }
    out.push({ tag, pts });
  }
  return out;
}
function readMoves(packed) {
  const n = packed.count, q = D.quantum, r = new Reader(packed.data);
  const M = {
    n, X: new Float64Array(n + 1), Y: new Float64Array(n + 1), Z: new Float64Array(n + 1),
    K: new Uint8Array(n), ARC: new Uint8Array(n), CX: new Float32Array(n), CY: new Float32Array(n),
    SW: new Float32Array(n), L: new Uint32Array(n), F: new Float32Array(n), T: new Float32Array(n),
  };
  let x = Math.round(packed.start[0] / q), y = Math.round(packed.start[1] / q), z = Math.round(packed.start[2] / q);
  let line = 0, feed = 0, ms = 0;
  M.X[0] = x * q; M.Y[0] = y * q; M.Z[0] = z * q;
  for (let i = 0; i < n; i++) {
    const head = r.uint();
    M.K[i] = head & 7;
    line += r.int(); M.L[i] = line;
    const x0 = x, y0 = y;
    x += r.int(); y += r.int(); z += r.int();
    M.X[i + 1] = x * q; M.Y[i + 1] = y * q; M.Z[i + 1] = z * q;
    if (head & 8) { M.ARC[i] = 1; M.CX[i] = (x0 + r.int()) * q; M.CY[i] = (y0 + r.int()) * q; M.SW[i] = r.int() * 1e-6; }
    if (head & 16) feed = r.uint() / 1000;
    M.F[i] = M.K[i] === K_RAPID || M.K[i] === K_RETRACT ? 0 : feed;
    ms += r.int(); M.T[i] = ms / 1000;
  }
  return M;
}

const pocketRings = readRings(D.pockets), openPaths = readRings(D.open), leftoverRings = readRings(D.leftovers);
const M = readMoves(D.moves);
const notCut = new Set(D.not_cut);

// Depth levels: the heights the program cuts at, deepest last.
const levels = [];
{
  const seen = new Set();
  for (let i = 0; i < M.n; i++) {
    if (M.K[i] !== K_CUT) continue;
    const z = Math.round(M.Z[i + 1] * 1e4) / 1e4;
    if (!seen.has(z)) { seen.add(z); levels.push(z); }
  }
  levels.sort((a, b) => b - a);
}
const deepest = levels.length ? levels[levels.length - 1] : null;

// Entries in order: where each run of entry moves begins.
const entries = [];
for (let i = 0; i < M.n; i++) if (M.K[i] === K_ENTRY && (i === 0 || M.K[i - 1] !== K_ENTRY)) entries.push(i);

// ---- the page -----------------------------------------------------------------------------
function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") e.className = v; else if (k === "style") e.style.cssText = v; else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}
const view = el("div", { id: "view" });
const canvas = el("canvas", { id: "canvas" });
const scale = el("div", { id: "scale" }, el("div", { id: "scalebar" }), el("span", { id: "scalelabel" }));
view.append(canvas, scale, el("div", { id: "hint" }, "wheel: zoom · drag: pan"));
const side = el("div", { id: "side" });
document.body.append(view, side);

side.append(el("h1", {}, D.title));
const summary = el("table", { id: "summary" });
for (const [k, v] of D.summary) summary.append(el("tr", {}, el("td", {}, k), el("td", {}, v)));
side.append(el("h2", {}, "Summary"), summary);

// Legend: every layer with its look, and a box to show or hide it.
const visible = { drawing: true, "not-cut": true, open: true, marks: true, leftovers: true, swept: false, cut: true, link: true, entry: true, rapid: true, retract: true };
const legend = el("div", { id: "legend" });
function legendRow(key, swatch, label) {
  const box = el("input", { type: "checkbox", "data-layer": key });
  box.checked = visible[key];
  box.addEventListener("change", () => { visible[key] = box.checked; redraw(); });
  legend.append(el("label", {}, box, swatch, label));
}
legendRow("drawing", el("span", { class: "swatch fill", style: "background:#dde6f0" }), "pocket (walls black, islands white)");
legendRow("not-cut", el("span", { class: "swatch fill", style: "background:repeating-linear-gradient(45deg,#e07000 0 2px,#fff 2px 5px)" }), "pocket not cut");
legendRow("open", el("span", { class: "swatch dash", style: "border-color:#e07000" }), "open chain, ignored");
for (const k of KIND_NAMES) {
  const s = STYLE[k];
  legendRow(k, el("span", { class: "swatch" + (s.dash ? " dash" : ""), style: "border-color:" + s.color }), s.label);
}
legendRow("swept", el("span", { class: "swatch fill", style: "background:rgba(40,160,80,.35)" }), "area swept at the final depth");
legendRow("leftovers", el("span", { class: "swatch fill", style: "background:rgba(160,0,192,.5)" }), "material left (from the check)");
legendRow("marks", el("span", { class: "swatch dot", style: "border-color:#d0008a" }), "numbered marks (list below)");
side.append(el("h2", {}, "Legend"), legend);

// Controls: fit, depth pass.
const controls = el("div", { id: "controls" });
const fitButton = el("button", { id: "fit", type: "button" }, "Fit");
fitButton.addEventListener("click", () => { fit(); redraw(); });
const depth = el("select", { id: "depth" }, el("option", { value: "all" }, "all depth passes"));
for (const z of levels) depth.append(el("option", { value: String(z) }, "pass at Z " + fmtLen(z)));
depth.addEventListener("change", redraw);
controls.append(fitButton, depth);
side.append(el("h2", {}, "View"), controls);

// Play: the program up to move N, the tool at its end.
const slider = el("input", { id: "slider", type: "range", min: "0", max: String(M.n), step: "1", value: String(M.n) });
const playButton = el("button", { id: "playbutton", type: "button" }, "▶ play");
const back = el("button", { type: "button", title: "one move back" }, "◀");
const fwd = el("button", { type: "button", title: "one move on" }, "▶");
const readout = el("div", { id: "readout" });
side.append(el("h2", {}, "Program"), el("div", { id: "play" }, playButton, " ", back, fwd), slider, readout);
slider.addEventListener("input", () => { stopPlay(); redraw(); });
back.addEventListener("click", () => { slider.value = String(Math.max(0, +slider.value - 1)); redraw(); });
fwd.addEventListener("click", () => { slider.value = String(Math.min(M.n, +slider.value + 1)); redraw(); });
let playing = null;
function stopPlay() { if (playing !== null) { cancelAnimationFrame(playing); playing = null; playButton.textContent = "▶ play"; } }
playButton.addEventListener("click", () => {
  if (playing !== null) { stopPlay(); return; }
  if (+slider.value >= M.n) slider.value = "0";
  playButton.textContent = "❚❚ pause";
  const step = Math.max(1, Math.ceil(M.n / 900));
  const tick = () => {
    slider.value = String(Math.min(M.n, +slider.value + step));
    redraw();
    if (+slider.value < M.n) playing = requestAnimationFrame(tick); else stopPlay();
  };
  playing = requestAnimationFrame(tick);
});

// Marks: numbered, click to look.
if (D.marks.length) {
  const list = el("ol", { id: "marks" });
  D.marks.forEach((m, k) => {
    const li = el("li", { "data-kind": m.kind }, el("span", { class: "n", style: "background:" + MARK_COLOR[m.kind] }, String(k + 1)), m.text);
    li.addEventListener("click", () => { zoomTo(m.x, m.y); redraw(); });
    list.append(li);
  });
  side.append(el("h2", {}, "Marks"), list);
}
if (D.report) side.append(el("h2", {}, "Report"), el("pre", { id: "report" }, D.report));

// ---- numbers ------------------------------------------------------------------------------
function fmtLen(mm) { return D.inches ? (mm / 25.4).toFixed(4) + " in" : mm.toFixed(3) + " mm"; }
function fmtNum(mm) { return D.inches ? (mm / 25.4).toFixed(4) : mm.toFixed(3); }
function fmtTime(s) {
  s = Math.round(s);
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  return h ? `${h}h${String(m).padStart(2, "0")}m${String(r).padStart(2, "0")}s` : m ? `${m}m${String(r).padStart(2, "0")}s` : `${r}s`;
}

// ---- view transform -----------------------------------------------------------------------
let cx = 0, cy = 0, s = 1; // world centre on screen, pixels per mm
let W = 0, H = 0, dpr = 1;
function fit() {
  const [x0, y0, x1, y1] = D.extent;
  cx = (x0 + x1) / 2; cy = (y0 + y1) / 2;
  s = Math.min(W / Math.max(x1 - x0, 1e-6), H / Math.max(y1 - y0, 1e-6)) * 0.92;
}
function zoomTo(x, y) {
  cx = x; cy = y;
  s = Math.max(s, (Math.min(W, H) / Math.max(8 * D.tool, 1e-3)));
}
const sx = (x) => (x - cx) * s + W / 2;
const sy = (y) => H / 2 - (y - cy) * s;
function resize() {
  dpr = window.devicePixelRatio || 1;
  const r = view.getBoundingClientRect();
  const first = W === 0;
  W = Math.max(1, r.width); H = Math.max(1, r.height);
  canvas.width = Math.round(W * dpr); canvas.height = Math.round(H * dpr);
  if (first) fit();
}
let drag = null;
canvas.addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); canvas.classList.add("dragging"); });
canvas.addEventListener("pointermove", (e) => {
  if (!drag) return;
  cx -= (e.clientX - drag.x) / s; cy += (e.clientY - drag.y) / s;
  drag = { x: e.clientX, y: e.clientY };
  redraw();
});
canvas.addEventListener("pointerup", () => { drag = null; canvas.classList.remove("dragging"); });
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  const r = canvas.getBoundingClientRect();
  const px = e.clientX - r.left, py = e.clientY - r.top;
  const wx = (px - W / 2) / s + cx, wy = cy - (py - H / 2) / s;
  s *= Math.exp(-e.deltaY * 0.0015);
  cx = wx - (px - W / 2) / s; cy = wy + (py - H / 2) / s;
  redraw();
}, { passive: false });
// Drawn at once: setting the canvas size clears it.
new ResizeObserver(() => { resize(); draw(); }).observe(view);

// ---- drawing ------------------------------------------------------------------------------
let hatch = null;
function hatchPattern(ctx) {
  if (hatch) return hatch;
  const c = document.createElement("canvas");
  c.width = c.height = 8;
  const g = c.getContext("2d");
  g.fillStyle = "#fff"; g.fillRect(0, 0, 8, 8);
  g.strokeStyle = "#e07000"; g.lineWidth = 2;
  g.beginPath(); g.moveTo(0, 8); g.lineTo(8, 0); g.stroke();
  hatch = ctx.createPattern(c, "repeat");
  return hatch;
}
function ringPath(path, pts, close) {
  for (let j = 0; j < pts.length; j += 2) {
    const x = sx(pts[j]), y = sy(pts[j + 1]);
    if (j === 0) path.moveTo(x, y); else path.lineTo(x, y);
  }
  if (close) path.closePath();
}
function drawDrawing(ctx) {
  const byPocket = new Map();
  for (const r of pocketRings) {
    const p = r.tag >> 1;
    if (!byPocket.has(p)) byPocket.set(p, new Path2D());
    ringPath(byPocket.get(p), r.pts, true);
  }
  for (const [p, path] of byPocket) {
    if (notCut.has(p)) { if (!visible["not-cut"]) continue; ctx.fillStyle = hatchPattern(ctx); }
    else { if (!visible.drawing) continue; ctx.fillStyle = "#dde6f0"; }
    ctx.fill(path, "evenodd");
    ctx.strokeStyle = "#111"; ctx.lineWidth = 1.2; ctx.stroke(path);
  }
  if (visible.open && openPaths.length) {
    const path = new Path2D();
    for (const r of openPaths) ringPath(path, r.pts, false);
    ctx.setLineDash([5, 4]); ctx.strokeStyle = "#e07000"; ctx.lineWidth = 1.5; ctx.stroke(path); ctx.setLineDash([]);
  }
}
function onLevel(i, level) {
  return level === null || Math.abs(M.Z[i + 1] - level) < 5e-5;
}
// Adds move i to `path` in screen coordinates; returns its end point.
function addMove(path, i, penAt) {
  const x0 = sx(M.X[i]), y0 = sy(M.Y[i]), x1 = sx(M.X[i + 1]), y1 = sy(M.Y[i + 1]);
  if (penAt !== i) path.moveTo(x0, y0);
  if (M.ARC[i]) {
    const ccx = M.CX[i], ccy = M.CY[i];
    const rad = Math.hypot(M.X[i] - ccx, M.Y[i] - ccy) * s;
    if (rad * Math.abs(M.SW[i]) > 2) {
      const a0 = Math.atan2(M.Y[i] - ccy, M.X[i] - ccx);
      path.arc(sx(ccx), sy(ccy), rad, -a0, -(a0 + M.SW[i]), M.SW[i] > 0);
      return;
    }
  }
  path.lineTo(x1, y1);
}
let lastDrawn = 0, sweptMoves = 0;
function drawProgram(ctx, upTo) {
  const level = depth.value === "all" ? null : +depth.value;
  const paths = KIND_NAMES.map(() => new Path2D());
  const pen = new Int32Array(KIND_NAMES.length).fill(-1);
  const lastX = new Float64Array(KIND_NAMES.length), lastY = new Float64Array(KIND_NAMES.length);
  const arrows = [];
  let run = 0, ax = 0, ay = 0;
  let drawn = 0;
  // The swept area: one path per tool, stroked at its diameter.
  const swept = visible.swept && deepest !== null ? D.tools.map(() => new Path2D()) : null;
  sweptMoves = 0;
  let sweptPen = -1, toolIndex = 0;
  const margin = 20;
  for (let i = 0; i < upTo; i++) {
    const k = M.K[i];
    while (toolIndex + 1 < D.tools.length && D.tools[toolIndex + 1][0] <= i) { toolIndex++; sweptPen = -1; }
    if (swept && k !== K_RAPID && k !== K_RETRACT && Math.abs(M.Z[i + 1] - deepest) < 5e-5 && Math.abs(M.Z[i] - deepest) < 5e-5) {
      addMove(swept[toolIndex], i, sweptPen);
      sweptPen = i + 1;
      sweptMoves++;
    }
    if (!visible[KIND_NAMES[k]]) continue;
    if ((k === K_CUT || k === K_LINK || k === K_ENTRY) && !onLevel(i, level)) continue;
    drawn++;
    const x1 = sx(M.X[i + 1]), y1 = sy(M.Y[i + 1]);
    // Off the screen: lift the pen.
    const x0 = sx(M.X[i]), y0 = sy(M.Y[i]);
    if (!M.ARC[i] && ((x0 < -margin && x1 < -margin) || (x0 > W + margin && x1 > W + margin) || (y0 < -margin && y1 < -margin) || (y0 > H + margin && y1 > H + margin))) {
      pen[k] = -1;
      continue;
    }
    // Shorter than a pixel and followed by more of the same: merged into the next point.
    const last = i + 1 === upTo || M.K[i + 1] !== k;
    if (pen[k] === i && !M.ARC[i] && !last && Math.abs(x1 - lastX[k]) < 0.8 && Math.abs(y1 - lastY[k]) < 0.8) {
      pen[k] = i + 1;
      continue;
    }
    if (pen[k] !== i) { lastX[k] = x0; lastY[k] = y0; }
    addMove(paths[k], i, pen[k]);
    if (k === K_CUT || k === K_RAPID) {
      run += Math.hypot(x1 - lastX[k], y1 - lastY[k]);
      if (run > (k === K_RAPID ? 160 : 90) && Math.hypot(x1 - ax, y1 - ay) > 40) {
        arrows.push([x1, y1, Math.atan2(y1 - lastY[k], x1 - lastX[k]), k]);
        run = 0; ax = x1; ay = y1;
      }
    }
    lastX[k] = x1; lastY[k] = y1;
    pen[k] = i + 1;
  }
  lastDrawn = drawn;
  if (swept) {
    ctx.save();
    ctx.strokeStyle = "rgba(40,160,80,0.35)"; ctx.lineCap = "round"; ctx.lineJoin = "round";
    swept.forEach((path, t) => { ctx.lineWidth = D.tools[t][1] * s; ctx.stroke(path); });
    ctx.restore();
  }
  for (const k of [K_LINK, K_CUT, K_RAPID, K_ENTRY]) {
    const st = STYLE[KIND_NAMES[k]];
    ctx.strokeStyle = st.color; ctx.lineWidth = st.width; ctx.setLineDash(st.dash || []);
    ctx.stroke(paths[k]);
  }
  ctx.setLineDash([]);
  for (const [x, y, a, k] of arrows) {
    ctx.save(); ctx.translate(x, y); ctx.rotate(a);
    ctx.fillStyle = STYLE[KIND_NAMES[k]].color;
    ctx.beginPath(); ctx.moveTo(5, 0); ctx.lineTo(-4, -4); ctx.lineTo(-4, 4); ctx.closePath(); ctx.fill();
    ctx.restore();
  }
  // Retracts: a ring with an upward tick where the tool leaves the stock.
  if (visible.retract) {
    ctx.strokeStyle = STYLE.retract.color; ctx.lineWidth = 1.5;
    for (let i = 0; i < upTo; i++) {
      if (M.K[i] !== K_RETRACT || M.Z[i] >= 0) continue;
      const x = sx(M.X[i]), y = sy(M.Y[i]);
      if (x < -10 || x > W + 10 || y < -10 || y > H + 10) continue;
      ctx.beginPath(); ctx.arc(x, y, 4, 0, 2 * Math.PI); ctx.moveTo(x, y - 4); ctx.lineTo(x, y - 10); ctx.stroke();
    }
  }
  // Entries in order: numbered discs where each begins.
  if (visible.entry) {
    ctx.font = "bold 11px system-ui, sans-serif"; ctx.textAlign = "center"; ctx.textBaseline = "middle";
    entries.forEach((i, n) => {
      if (i >= upTo || !onLevel(lastOfRun(i), level)) return;
      const x = sx(M.X[i]), y = sy(M.Y[i]);
      if (x < -10 || x > W + 10 || y < -10 || y > H + 10) return;
      ctx.fillStyle = STYLE.entry.color; ctx.beginPath(); ctx.arc(x, y, 8, 0, 2 * Math.PI); ctx.fill();
      ctx.fillStyle = "#fff"; ctx.fillText(String(n + 1), x, y + 0.5);
    });
  }
}
function lastOfRun(i) { while (i + 1 < M.n && M.K[i + 1] === K_ENTRY) i++; return i; }
function drawLeftoversAndMarks(ctx) {
  if (visible.leftovers && leftoverRings.length) {
    const path = new Path2D();
    for (const r of leftoverRings) ringPath(path, r.pts, true);
    ctx.fillStyle = "rgba(160,0,192,0.5)"; ctx.fill(path, "evenodd");
  }
  if (!visible.marks) return;
  ctx.font = "bold 11px system-ui, sans-serif"; ctx.textAlign = "center"; ctx.textBaseline = "middle";
  D.marks.forEach((m, k) => {
    const x = sx(m.x), y = sy(m.y);
    ctx.strokeStyle = MARK_COLOR[m.kind]; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(x, y, 11, 0, 2 * Math.PI); ctx.stroke();
    ctx.fillStyle = MARK_COLOR[m.kind]; ctx.beginPath(); ctx.arc(x + 12, y - 12, 8, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = "#fff"; ctx.fillText(String(k + 1), x + 12, y - 11.5);
    if (m.kind === "not-cut") {
      // Why, on the drawing itself: the part of the text after "not cut: ".
      const why = "not cut: " + m.text.split("not cut: ").pop();
      ctx.save();
      ctx.textAlign = "left"; ctx.font = "12px system-ui, sans-serif";
      ctx.lineWidth = 3; ctx.strokeStyle = "rgba(255,255,255,0.9)"; ctx.strokeText(why, x + 24, y - 11.5);
      ctx.fillStyle = MARK_COLOR[m.kind]; ctx.fillText(why, x + 24, y - 11.5);
      ctx.restore();
    }
  });
}
function drawOrigin(ctx) {
  const x = sx(0), y = sy(0);
  if (x < -50 || x > W + 50 || y < -50 || y > H + 50) return;
  ctx.lineWidth = 2;
  const axis = (dx, dy, color, label) => {
    ctx.strokeStyle = ctx.fillStyle = color;
    ctx.beginPath(); ctx.moveTo(x, y); ctx.lineTo(x + dx, y + dy); ctx.stroke();
    ctx.fillText(label, x + dx * 1.25, y + dy * 1.25);
  };
  ctx.font = "bold 11px system-ui, sans-serif"; ctx.textAlign = "center"; ctx.textBaseline = "middle";
  axis(36, 0, "#c02020", "X");
  axis(0, -36, "#208020", "Y");
  ctx.fillStyle = "#222"; ctx.beginPath(); ctx.arc(x, y, 3, 0, 2 * Math.PI); ctx.fill();
  ctx.textAlign = "left"; ctx.fillText("X0 Y0", x + 5, y + 10);
}
// The diameter of the tool cutting move i (the last tool loaded at or before it).
function toolAt(i) {
  let d = D.tool;
  for (const [k, dia] of D.tools) if (k <= i) d = dia;
  return d;
}
function drawTool(ctx, upTo) {
  if (M.n === 0) return;
  const x = sx(M.X[upTo]), y = sy(M.Y[upTo]);
  const tool = toolAt(Math.max(0, upTo - 1));
  ctx.fillStyle = "rgba(255,140,0,0.35)"; ctx.strokeStyle = "#c06000"; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.arc(x, y, Math.max(2, tool / 2 * s), 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
  ctx.beginPath(); ctx.moveTo(x - 4, y); ctx.lineTo(x + 4, y); ctx.moveTo(x, y - 4); ctx.lineTo(x, y + 4); ctx.stroke();
}
function drawScale() {
  const target = 110 / s; // mm under about 110 px
  const unit = D.inches ? 25.4 : 1;
  const v = target / unit, p = Math.pow(10, Math.floor(Math.log10(v)));
  const nice = [1, 2, 5, 10].map((m) => m * p).filter((m) => m <= v).pop() || p;
  document.getElementById("scalebar").style.width = (nice * unit * s).toFixed(1) + "px";
  document.getElementById("scalelabel").textContent = +nice.toPrecision(3) + (D.inches ? " in" : " mm");
}
function moveText(i) {
  const k = M.K[i];
  const word = k === K_RAPID || k === K_RETRACT ? "G0" : M.ARC[i] ? (M.SW[i] > 0 ? "G3" : "G2") : "G1";
  let t = `${word} X${fmtNum(M.X[i + 1])} Y${fmtNum(M.Y[i + 1])} Z${fmtNum(M.Z[i + 1])}`;
  if (M.ARC[i]) t += ` I${fmtNum(M.CX[i] - M.X[i])} J${fmtNum(M.CY[i] - M.Y[i])}`;
  if (M.F[i]) t += ` F${+(D.inches ? M.F[i] / 25.4 : M.F[i]).toFixed(3)}`;
  return t;
}
function updateReadout(upTo) {
  const total = M.n ? M.T[M.n - 1] : 0;
  if (upTo === 0) {
    readout.textContent = `move 0 of ${M.n}: before the first move\nX ${fmtNum(M.X[0])}  Y ${fmtNum(M.Y[0])}  Z ${fmtNum(M.Z[0])}\nelapsed 0s of ${fmtTime(total)}`;
    return;
  }
  const i = upTo - 1;
  const feed = M.F[i] ? (D.inches ? (M.F[i] / 25.4).toFixed(2) + " in/min" : M.F[i].toFixed(0) + " mm/min") : "rapid";
  readout.textContent =
    `move ${upTo} of ${M.n} (${KIND_NAMES[M.K[i]]}), line ${M.L[i]}:\n${moveText(i)}\n` +
    `X ${fmtNum(M.X[upTo])}  Y ${fmtNum(M.Y[upTo])}  Z ${fmtNum(M.Z[upTo])} ${D.inches ? "in" : "mm"}\n` +
    `feed ${feed}, tool ${fmtLen(toolAt(i))} across\nelapsed ${fmtTime(M.T[i])} of ${fmtTime(total)}`;
  readout.dataset.line = String(M.L[i]);
}
let pending = false;
function redraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}
function draw() {
  const ctx = canvas.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, W, H);
  ctx.lineJoin = "round";
  const upTo = +slider.value;
  drawDrawing(ctx);
  drawProgram(ctx, upTo);
  drawLeftoversAndMarks(ctx);
  drawOrigin(ctx);
  drawTool(ctx, upTo);
  drawScale();
  updateReadout(upTo);
  canvas.dataset.movesDrawn = String(lastDrawn);
  canvas.dataset.moves = String(M.n);
}

// The share of the canvas's pixels that differ from its background (for the self-test: a
// blank canvas is a failure).
function inkedShare() {
  const ctx = canvas.getContext("2d");
  const img = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  let n = 0;
  for (let i = 3; i < img.length; i += 16) if (img[i] > 0) n++;
  return n / (img.length / 16);
}

resize();
const hash = location.hash;
let readyMs = 0;
const play = /play=([0-9.]+)/.exec(hash);
if (play) slider.value = String(Math.round(Math.min(1, +play[1]) * M.n));
// #mark=N opens the page zoomed on mark N (as clicking it in the list does).
const markAt = /mark=([0-9]+)/.exec(hash);
if (markAt && D.marks[+markAt[1] - 1]) zoomTo(D.marks[+markAt[1] - 1].x, D.marks[+markAt[1] - 1].y);
draw();
readyMs = performance.now();
canvas.dataset.readyMs = readyMs.toFixed(0);
if (hash === "#selftest") {
  slider.value = "0";
  slider.dispatchEvent(new Event("input"));
  draw();
  slider.value = slider.max;
  slider.dispatchEvent(new Event("input"));
  const t0 = performance.now();
  draw();
  const drawMs = performance.now() - t0;
  // Zoom in with the wheel, drag, fit again; the swept area; one depth pass.
  const scaleAt = () => document.getElementById("scalelabel").textContent;
  const fitted = scaleAt();
  const r = canvas.getBoundingClientRect();
  canvas.dispatchEvent(new WheelEvent("wheel", { deltaY: -800, clientX: r.left + r.width / 2, clientY: r.top + r.height / 2, cancelable: true }));
  draw();
  const zoomed = scaleAt();
  const before = [cx, cy];
  canvas.dispatchEvent(new PointerEvent("pointerdown", { clientX: 100, clientY: 100, pointerId: 1 }));
  canvas.dispatchEvent(new PointerEvent("pointermove", { clientX: 160, clientY: 130, pointerId: 1 }));
  canvas.dispatchEvent(new PointerEvent("pointerup", { clientX: 160, clientY: 130, pointerId: 1 }));
  const panned = Math.hypot(cx - before[0], cy - before[1]) * s;
  fitButton.click();
  draw();
  const refitted = scaleAt();
  const sweptBox = document.querySelector('input[data-layer="swept"]');
  sweptBox.click();
  draw();
  const swept = sweptMoves;
  sweptBox.click();
  let passDrawn = null;
  if (levels.length > 1) {
    depth.value = String(levels[levels.length - 1]);
    depth.dispatchEvent(new Event("change"));
    draw();
    passDrawn = lastDrawn;
    depth.value = "all";
    depth.dispatchEvent(new Event("change"));
  }
  draw();
  const out = {
    problems,
    moves: M.n,
    drawn: +canvas.dataset.movesDrawn,
    slider: +slider.value,
    max: +slider.max,
    legend: document.querySelectorAll("#legend label").length,
    scale: document.getElementById("scalelabel").textContent,
    summary: Array.from(document.querySelectorAll("#summary tr")).map((r) => r.textContent),
    readout: readout.textContent,
    line: +(readout.dataset.line || 0),
    resources: performance.getEntriesByType("resource").length,
    readyMs,
    drawMs,
    fitted, zoomed, refitted, panned, swept, passDrawn, levels,
    marks: D.marks.map((m) => m.kind),
    notCut: D.not_cut,
    inked: inkedShare(),
  };
  document.body.append(el("pre", { id: "selftest" }, JSON.stringify(out)));
}
