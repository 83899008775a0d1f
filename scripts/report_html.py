"""report_html: the walk report as one self-contained HTML page (scripts/analyze_bag).

The page holds its data (JSON), style and script inline: no network, no external file or font.
It draws on <canvas> elements:
  - the walk animated from the recorded TF (every link's world position, which sim_node computes
    from the joint states by forward kinematics): a front view (y-z) and a side view (x-z) stick
    figure, and a top view (x-y) with the footholds planned (outline) and executed (filled), the
    CoM path, the CoM and its instantaneous capture point x + xd / omega, omega = sqrt(g / z_com);
  - per step: verdict, certificate, check and OCP time, touchdown error;
  - one step's reachable sets (forward and backward swing sole outputs per slice, top view), with
    the swing path of the certified transition (the OCP's trajectory the swing tracked) and the
    witness junction pair drawn through them; a selector for the step;
  - the Hausdorff distance per slice of every check;
  - with two bags, both runs side by side on one time axis.
The animation writes its current frame into the DOM (#frame, data-frame) and the page title, so
a headless browser can see that it advances.
"""
import json
import math

import numpy as np

G = 9.81
MAX_FRAMES = 600          # animation frames per run (the TF rate is 100 Hz)
MAX_SET_POINTS = 80       # output samples per set and slice kept for the page
MAX_SLICES = 24           # slices per check kept for the page


def _r(x, d=4):
    x = float(x)
    return round(x, d) if math.isfinite(x) else None


def _pt(p):
    return [_r(p.x), _r(p.y), _r(p.z)]


def _sub(points, n):
    if len(points) <= n:
        return list(points)
    idx = np.linspace(0, len(points) - 1, n).astype(int)
    return [points[i] for i in idx]


def run_data(run):
    """The JSON-able content of one Run (analyze_bag.Run)."""
    frames = []
    links = []
    if run.tf_pos:
        names = sorted({f for pos in run.tf_pos for f in pos if f != "world"})
        edges = [(c, p) for c, p in sorted(run.parents.items())
                 if p != "world" and c in names and p in names]
        links = names
        index = {n: i for i, n in enumerate(names)}
        step = max(1, int(math.ceil(len(run.tf_pos) / MAX_FRAMES)))
        for k in range(0, len(run.tf_pos), step):
            pos = run.tf_pos[k]
            frames.append({"t": _r(run.tf_t[k], 3),
                           "p": [[_r(v) for v in pos[n]] if n in pos else None for n in names]})
        edge_idx = [[index[c], index[p]] for c, p in edges]
    else:
        edge_idx = []
    step = max(1, int(math.ceil(len(run.com_t) / (2 * MAX_FRAMES))))
    com = []
    for k in range(0, len(run.com_t), step):
        p, v = run.com_p[k], run.com_v[k]
        z = max(float(p[2]), 1e-3)
        omega = math.sqrt(G / z)
        com.append([_r(run.com_t[k], 3), _r(p[0]), _r(p[1]), _r(p[2]),
                    _r(p[0] + v[0] / omega), _r(p[1] + v[1] / omega)])
    steps = []
    for s in run.steps:
        steps.append({
            "index": int(s.index), "swing": s.swing_side, "touched": bool(s.touched_down),
            "fell": bool(s.fell), "plan_time": _r(s.plan_time, 3),
            "touchdown_time": _r(s.touchdown_time, 3), "planned": _pt(s.planned),
            "executed": _pt(s.executed), "tvr": _pt(s.planned_tvr),
            "clipped": bool(s.offset_clipped), "verdict": s.verdict,
            "certificate": getattr(s, "certificate", "") or "",
            "on_fail": getattr(s, "failed_check_action", "") or "",
            "check_time": _r(s.check_time, 4), "ocp_time": _r(s.ocp_time, 4),
            "ocp_status": s.ocp_status, "error": _r(s.touchdown_error, 4),
            "hausdorff": _r(s.hausdorff_distance, 6),
        })
    checks = []
    for k, r in enumerate(run.reach):
        slices = [sl for sl in r.slices if sl.forward_outputs or sl.backward_outputs
                  or sl.forward_boundary or sl.backward_boundary]
        kept = _sub(slices, MAX_SLICES)
        t0 = r.header.stamp.to_sec()
        path = run.transition_path_at(t0)
        checks.append({
            "t0": _r(t0, 3), "verdict": r.verdict, "certificate": r.certificate,
            "foothold": _pt(r.foothold), "swing_frame": r.swing_frame,
            "witness": ([_pt(r.witness_forward), _pt(r.witness_backward)]
                        if r.witness_distance >= 0 else None),
            "path": [[_r(v) for v in p] for p in path] if path else None,
            "slices": [{"t": _r(sl.time, 4),
                        "f": [_pt(p) for p in _sub(sl.forward_outputs, MAX_SET_POINTS)],
                        "b": [_pt(p) for p in _sub(sl.backward_outputs, MAX_SET_POINTS)],
                        "fb": [_pt(p) for p in sl.forward_boundary],
                        "bb": [_pt(p) for p in sl.backward_boundary]} for sl in kept],
            "hausdorff": [[_r(sl.time, 4), float("%.4g" % sl.hausdorff_distance)]
                          for sl in r.slices if 0 <= sl.hausdorff_distance < float("inf")],
        })
    start_soles = []
    if run.tf_pos:
        for f in ("l_sole", "r_sole", "left_sole_link", "right_sole_link"):
            if f in run.tf_pos[0]:
                start_soles.append([_r(v) for v in run.tf_pos[0][f]])
    return {"name": run.name, "mode": run.mode, "start_soles": start_soles, "fell": bool(run.fell),
            "end": run.fields.get("end", ""), "links": links, "edges": edge_idx,
            "frames": frames, "com": com, "steps": steps, "checks": checks,
            "summary": [[k, v] for k, v in run.summary()]}


PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>walk report</title>
<style>
body { font: 13px/1.35 sans-serif; margin: 10px; color: #222; background: #fff; }
h1 { font-size: 18px; margin: 4px 0 8px; } h2 { font-size: 15px; margin: 14px 0 6px; }
.runs { display: flex; gap: 14px; align-items: flex-start; }
.run { flex: 1 1 0; min-width: 0; border: 1px solid #ccc; padding: 6px; }
.views { display: flex; gap: 4px; flex-wrap: wrap; }
canvas { border: 1px solid #ddd; background: #fcfcfc; }
table { border-collapse: collapse; font-size: 12px; }
td, th { border: 1px solid #ccc; padding: 2px 5px; text-align: right; }
th { background: #f0f0f0; } td.l, th.l { text-align: left; }
.controls { margin: 6px 0; } .legend span { margin-right: 10px; white-space: nowrap; }
.sw { display: inline-block; width: 12px; height: 10px; vertical-align: middle; margin-right: 3px; }
.no { color: #b00; font-weight: bold; } .yes { color: #070; }
</style></head>
<body>
<h1>Walk report</h1>
<div class="controls">
<button id="play">pause</button>
<input id="slider" type="range" min="0" max="1000" value="0" style="width: 50%">
t = <span id="time">0.000</span> s, frame <span id="frame" data-frame="0">0</span>
</div>
<div class="legend">
<span><i class="sw" style="background:#1f77b4"></i>robot (left leg darker)</span>
<span><i class="sw" style="border:2px solid #2ca02c;width:9px;height:7px"></i>foothold planned</span>
<span><i class="sw" style="background:#ff7f0e"></i>foothold executed (and the start)</span>
<span><i class="sw" style="background:#9467bd"></i>CoM</span>
<span><i class="sw" style="background:#8c564b"></i>capture point</span>
<span><i class="sw" style="background:#e377c2"></i>forward set</span>
<span><i class="sw" style="background:#17becf"></i>backward set</span>
<span><i class="sw" style="background:#000"></i>certified swing path</span>
</div>
<div class="runs" id="runs"></div>
<script id="data" type="application/json">__DATA__</script>
<script>
"use strict";
const DATA = JSON.parse(document.getElementById("data").textContent);
const C = {robot: "#1f77b4", robotL: "#0d3d66", planned: "#2ca02c", executed: "#ff7f0e",
           com: "#9467bd", cp: "#8c564b", fwd: "#e377c2", bwd: "#17becf", path: "#000000",
           fall: "#d62728", grid: "#e4e4e4"};
function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const k in (attrs || {})) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  return e;
}
// A view maps two world coordinates into a canvas with equal scale.
function View(canvas, box) {
  const pad = 12, W = canvas.width, H = canvas.height;
  const sx = (W - 2 * pad) / Math.max(box[1] - box[0], 1e-6);
  const sy = (H - 2 * pad) / Math.max(box[3] - box[2], 1e-6);
  const s = Math.min(sx, sy);
  const cx = (box[0] + box[1]) / 2, cy = (box[2] + box[3]) / 2;
  return {ctx: canvas.getContext("2d"), s: s,
          X: a => W / 2 + (a - cx) * s, Y: b => H / 2 - (b - cy) * s, W: W, H: H};
}
function bounds(points, margin) {
  let b = [Infinity, -Infinity, Infinity, -Infinity];
  for (const p of points) {
    if (!p) continue;
    b = [Math.min(b[0], p[0]), Math.max(b[1], p[0]), Math.min(b[2], p[1]), Math.max(b[3], p[1])];
  }
  if (!isFinite(b[0])) b = [-1, 1, -1, 1];
  return [b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin];
}
function line(v, pts, color, width, dash) {
  const c = v.ctx; c.strokeStyle = color; c.lineWidth = width; c.setLineDash(dash || []);
  c.beginPath(); let first = true;
  for (const p of pts) {
    if (!p) { first = true; continue; }
    if (first) c.moveTo(v.X(p[0]), v.Y(p[1])); else c.lineTo(v.X(p[0]), v.Y(p[1]));
    first = false;
  }
  c.stroke(); c.setLineDash([]);
}
function dot(v, p, color, r) {
  const c = v.ctx; c.fillStyle = color; c.beginPath();
  c.arc(v.X(p[0]), v.Y(p[1]), r, 0, 2 * Math.PI); c.fill();
}
function sole(v, p, color, filled) {
  const hl = DATA.sole[0], hw = DATA.sole[1], c = v.ctx;
  const x0 = v.X(p[0] - hl), y0 = v.Y(p[1] + hw), w = 2 * hl * v.s, h = 2 * hw * v.s;
  if (filled) { c.fillStyle = color; c.fillRect(x0, y0, w, h); }
  else { c.strokeStyle = color; c.lineWidth = 2.5; c.strokeRect(x0, y0, w, h); }
}
function frameAt(run, t) {
  const f = run.frames; if (!f.length) return -1;
  let lo = 0, hi = f.length - 1;
  while (lo < hi) { const m = (lo + hi + 1) >> 1; if (f[m].t <= t) lo = m; else hi = m - 1; }
  return lo;
}
function comAt(run, t) {
  const c = run.com; if (!c.length) return null;
  let lo = 0, hi = c.length - 1;
  while (lo < hi) { const m = (lo + hi + 1) >> 1; if (c[m][0] <= t) lo = m; else hi = m - 1; }
  return c[lo];
}
const panels = [];
let tEnd = 0;
for (const run of DATA.runs) {
  if (run.frames.length) tEnd = Math.max(tEnd, run.frames[run.frames.length - 1].t);
  if (run.com.length) tEnd = Math.max(tEnd, run.com[run.com.length - 1][0]);
}
function stickView(run, canvas, ax) {
  // ax: world axes [horizontal, vertical]; the box follows the pelvis horizontally.
  return {canvas: canvas, ax: ax, run: run};
}
function drawStick(sv, fi, t) {
  const run = sv.run, canvas = sv.canvas, ax = sv.ax;
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (fi < 0) { ctx.fillText("no /tf in the bag", 20, 20); return; }
  const P = run.frames[fi].p;
  const pts = P.filter(p => p).map(p => [p[ax[0]], p[ax[1]]]);
  const b = bounds(pts, 0.15);
  const mid = (b[0] + b[1]) / 2;
  const v = View(canvas, [mid - 0.75, mid + 0.75, -0.1, Math.max(b[3], 1.3)]);
  line(v, [[mid - 2, 0], [mid + 2, 0]], "#888", 1);
  for (const [i, j] of run.edges) {
    if (!P[i] || !P[j]) continue;
    const left = run.links[i].startsWith("l") || run.links[i].indexOf("left") >= 0;
    line(v, [[P[i][ax[0]], P[i][ax[1]]], [P[j][ax[0]], P[j][ax[1]]]],
         left ? C.robotL : C.robot, 5);
  }
  const c = comAt(run, t);
  if (c) dot(v, [c[1 + ax[0]], c[1 + ax[1]]], C.com, 5);
  ctx.fillStyle = "#333"; ctx.font = "12px sans-serif";
  ctx.fillText(ax[0] === 1 ? "front view (y-z)" : "side view (x-z)", 6, 14);
}
function drawTop(tv, t) {
  const run = tv.run, canvas = tv.canvas, v = tv.view;
  v.ctx.clearRect(0, 0, canvas.width, canvas.height);
  for (const s of run.steps) {
    if (s.touched && s.touchdown_time <= t + 1e-9) sole(v, s.executed, C.executed, true);
  }
  for (const p of run.start_soles) sole(v, p, C.executed, true);  // where the feet start
  for (const s of run.steps) sole(v, s.planned, C.planned, false);
  line(v, run.com.filter(c => c[0] <= t).map(c => [c[1], c[2]]), C.com, 1.5);
  const c = comAt(run, t);
  if (c) { dot(v, [c[1], c[2]], C.com, 5); dot(v, [c[4], c[5]], C.cp, 5);
           line(v, [[c[1], c[2]], [c[4], c[5]]], C.cp, 1, [3, 3]); }
  const fi = frameAt(run, t);
  if (fi >= 0) {
    const P = run.frames[fi].p;
    for (const [i, j] of run.edges)
      if (P[i] && P[j]) line(v, [[P[i][0], P[i][1]], [P[j][0], P[j][1]]], C.robot, 2);
  }
  const fell = run.steps.find(s => s.fell);
  if (fell && c && t >= tEnd - 1e-6) { v.ctx.fillStyle = C.fall; v.ctx.font = "bold 14px sans-serif";
    v.ctx.fillText("fell", v.X(c[1]) + 8, v.Y(c[2])); }
  v.ctx.fillStyle = "#333"; v.ctx.font = "12px sans-serif";
  v.ctx.fillText("top view (x-y): footholds, CoM, capture point", 6, 14);
}
function fmt(x, d) { return (x === null || x === undefined || x < 0) ? "-" : x.toFixed(d); }
function stepTable(run) {
  const t = el("table");
  const hr = el("tr");
  for (const h of ["step", "swing", "touchdown [s]", "verdict", "certificate", "check [s]",
                   "OCP [s]", "OCP", "error [m]"]) hr.appendChild(el("th", {}, h));
  t.appendChild(hr);
  for (const s of run.steps) {
    const r = el("tr");
    const cells = [s.index + (s.fell ? " (fell)" : ""), s.swing, fmt(s.touchdown_time, 3),
                   s.verdict + (s.on_fail ? " → " + s.on_fail : ""), s.certificate || "-",
                   s.check_time > 0 ? s.check_time.toFixed(3) : "-",
                   s.ocp_time > 0 ? s.ocp_time.toFixed(3) : "-", s.ocp_status, fmt(s.error, 4)];
    cells.forEach((c, k) => r.appendChild(el("td", {class: k === 3 || k === 4 || k === 7 ? "l" : ""}, String(c))));
    if (s.fell) r.className = "no";
    t.appendChild(r);
  }
  return t;
}
function drawSets(canvas, chk) {
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  if (!chk) { ctx.fillText("no check with sets in this run", 20, 20); return; }
  const all = [];
  for (const s of chk.slices) for (const k of ["f", "b", "fb", "bb"]) for (const p of s[k]) all.push(p);
  if (chk.path) for (const p of chk.path) all.push(p);
  all.push(chk.foothold);
  const v = View(canvas, bounds(all, 0.03));
  for (const s of chk.slices) {
    for (const p of s.f) dot(v, p, C.fwd, 1.5);
    for (const p of s.b) dot(v, p, C.bwd, 1.5);
  }
  for (const s of chk.slices) {
    if (s.fb.length > 1) line(v, s.fb.concat([s.fb[0]]), C.fwd, 1);
    if (s.bb.length > 1) line(v, s.bb.concat([s.bb[0]]), C.bwd, 1);
  }
  if (chk.path) line(v, chk.path, C.path, 2.5);
  if (chk.witness) { line(v, chk.witness, C.fall, 2); dot(v, chk.witness[0], C.fall, 4); }
  const f = chk.foothold; ctx.fillStyle = "#000";
  ctx.font = "16px sans-serif"; ctx.fillText("★", v.X(f[0]) - 6, v.Y(f[1]) + 6);
  ctx.font = "12px sans-serif"; ctx.fillStyle = "#333";
  ctx.fillText("swing sole, top view: " + chk.verdict + (chk.certificate ? " (certificate: " + chk.certificate + ")" : ""), 6, 14);
  if (!chk.path) ctx.fillText("no transition trajectory recorded for this check", 6, 28);
}
function drawHausdorff(canvas, run) {
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const curves = run.checks.filter(c => c.hausdorff.length);
  if (!curves.length) { ctx.fillText("no Hausdorff distances in this run", 20, 20); return; }
  let t1 = 0, lo = Infinity, hi = -Infinity;
  for (const c of curves) for (const [t, d] of c.hausdorff) {
    t1 = Math.max(t1, t); const l = Math.log10(Math.max(d, 1e-6)); lo = Math.min(lo, l); hi = Math.max(hi, l); }
  lo = Math.floor(lo); hi = Math.ceil(hi + 1e-9); if (hi <= lo) hi = lo + 1;
  const L = 46, R = canvas.width - 8, T = 18, B = canvas.height - 24;
  ctx.strokeStyle = "#999"; ctx.strokeRect(L, T, R - L, B - T);
  ctx.fillStyle = "#333"; ctx.font = "11px sans-serif";
  for (let e = lo; e <= hi; e++) { const y = B - (e - lo) / (hi - lo) * (B - T);
    ctx.fillText("1e" + e, 4, y + 4); ctx.strokeStyle = C.grid; ctx.beginPath(); ctx.moveTo(L, y); ctx.lineTo(R, y); ctx.stroke(); }
  ctx.fillText("time from swing start [s] (0 - " + t1.toFixed(2) + ")", L + 4, canvas.height - 6);
  ctx.fillText("Hausdorff distance per slice [m], every check", L, 12);
  curves.forEach((c, k) => {
    ctx.strokeStyle = "hsl(" + (k * 47 % 360) + ",60%,45%)"; ctx.lineWidth = 1.2; ctx.beginPath();
    c.hausdorff.forEach(([t, d], i) => {
      const x = L + t / Math.max(t1, 1e-9) * (R - L);
      const y = B - (Math.log10(Math.max(d, 1e-6)) - lo) / (hi - lo) * (B - T);
      if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
    ctx.stroke(); });
}
const root = document.getElementById("runs");
for (const run of DATA.runs) {
  const div = el("div", {class: "run"});
  div.appendChild(el("h2", {}, run.name + " (" + run.mode + ")" + (run.fell ? ": fell, " + run.end : ": walked")));
  const views = el("div", {class: "views"});
  const front = el("canvas", {width: 230, height: 260, class: "front"});
  const side = el("canvas", {width: 230, height: 260, class: "side"});
  const top = el("canvas", {width: 300, height: 260, class: "top"});
  views.appendChild(front); views.appendChild(side); views.appendChild(top);
  div.appendChild(views);
  const pts = [];
  for (const s of run.steps) { pts.push([s.planned[0], s.planned[1]]); pts.push([s.executed[0], s.executed[1]]); }
  for (const c of run.com) { pts.push([c[1], c[2]]); pts.push([c[4], c[5]]); }
  const p = {run: run, front: stickView(run, front, [1, 2]), side: stickView(run, side, [0, 2]),
             top: {run: run, canvas: top, view: View(top, bounds(pts, 0.2))}};
  panels.push(p);
  div.appendChild(el("h2", {}, "Steps"));
  div.appendChild(stepTable(run));
  div.appendChild(el("h2", {}, "Reachable sets of one step"));
  const withSets = run.checks.map((c, i) => [c, i]).filter(([c]) => c.slices.length);
  const sel = el("select");
  const sets = el("canvas", {width: 420, height: 300, class: "sets"});
  if (!withSets.length) {
    div.appendChild(el("p", {}, run.checks.length ? "no check of this run kept its sets" :
                             "this run checked no step (policy without the reachability check)"));
  } else {
    withSets.forEach(([c, i]) => sel.appendChild(el("option", {value: i},
      "check " + (i + 1) + " at t = " + c.t0.toFixed(2) + " s: " + c.verdict + (c.certificate ? " (" + c.certificate + ")" : ""))));
    const firstCert = withSets.find(([c]) => c.verdict === "reachable" && c.path);
    if (firstCert) sel.value = String(firstCert[1]);
    sel.onchange = () => drawSets(sets, run.checks[+sel.value]);
    div.appendChild(sel); div.appendChild(el("br")); div.appendChild(sets);
    drawSets(sets, run.checks[+sel.value]);
  }
  if (run.checks.some(c => c.hausdorff.length)) {
    div.appendChild(el("h2", {}, "Hausdorff distance"));
    const hc = el("canvas", {width: 420, height: 200, class: "hausdorff"});
    div.appendChild(hc); drawHausdorff(hc, run);
  }
  div.appendChild(el("h2", {}, "Summary"));
  const st = el("table");
  for (const [k, v] of run.summary) { const r = el("tr"); r.appendChild(el("td", {class: "l"}, k));
    r.appendChild(el("td", {class: "l"}, v)); st.appendChild(r); }
  div.appendChild(st);
  root.appendChild(div);
}
let t = 0, playing = true, frame = 0, last = null;
const slider = document.getElementById("slider");
function render() {
  for (const p of panels) {
    const fi = frameAt(p.run, t);
    drawStick(p.front, fi, t); drawStick(p.side, fi, t); drawTop(p.top, t);
  }
  document.getElementById("time").textContent = t.toFixed(3);
  const f = document.getElementById("frame");
  f.textContent = String(frame); f.setAttribute("data-frame", String(frame));
  document.title = "walk report: frame " + frame + ", t = " + t.toFixed(3) + " s";
  slider.value = String(Math.round(1000 * t / Math.max(tEnd, 1e-9)));
}
function tick() {
  if (playing) {
    t += 0.02 * 0.5;  // half real time at 50 frames per second
    if (t > tEnd) t = 0;
    frame += 1;
    render();
  }
}
document.getElementById("play").onclick = () => {
  playing = !playing; document.getElementById("play").textContent = playing ? "pause" : "play"; };
slider.oninput = () => { t = tEnd * (+slider.value) / 1000; frame += 1; render(); };
render();
setInterval(tick, 20);
</script>
</body></html>
"""


def write_html(runs, path, sole=(0.1, 0.05)):
    """Writes the page of one or two runs to `path`; sole: the half length and half width of
    the sole rectangle drawn for a foothold [m]."""
    data = {"runs": [run_data(r) for r in runs], "sole": [float(sole[0]), float(sole[1])]}
    text = json.dumps(data, separators=(",", ":"), allow_nan=False)
    text = text.replace("</", "<\\/")  # no "</script>" inside the data
    with open(path, "w") as f:
        f.write(PAGE.replace("__DATA__", text))
    return path
