// The figure component (ui/figure.py), a Streamlit components-v2 module: no iframe, the figure
// lives in the page. plotly.js is loaded once per page load (a partial bundle, ui/plotly_bundles)
// and compiled once; a rerun with a new figure updates the graph in place with Plotly.react, and a
// rerun with the same figure leaves it alone (a running animation goes on).
//
// ui/figure.py registers a two-line module that imports this file (served under a name keyed by
// its content, cached a year) and calls render() with Streamlit's arguments on every run.
"use strict";

const CSS = `
.dl-figure { font-family: var(--st-font, "Source Sans Pro", sans-serif); line-height: 1.4; color: var(--st-text-color, #31333F); outline: none; }
.dl-figure .dl-controls { display: flex; flex-wrap: wrap; gap: 8px; align-items: center; margin: 2px 0 4px 2px; }
.dl-figure .dl-controls[hidden] { display: none; }
.dl-figure .dl-controls button { white-space: nowrap; font: inherit; font-size: 14px; padding: 3px 12px; margin: 0;
  border-radius: 6px; cursor: pointer; border: 1px solid rgba(128,128,128,.6); background: transparent; color: inherit; }
.dl-figure .dl-controls button:focus-visible { outline: 3px solid #E69F00; outline-offset: 1px; }
.dl-figure .dl-controls button.dl-forces[aria-pressed="true"] { background: #b3261e; border-color: #b3261e; color: #fff; }
.dl-figure .dl-controls button.dl-forces[aria-busy="true"] { opacity: .6; cursor: progress; }
.dl-figure .dl-controls button[hidden] { display: none; }
.dl-figure .dl-hint { font-size: 12px; opacity: .7; }
.dl-figure .dl-time { display: flex; align-items: center; gap: 8px; flex: 1 1 220px; min-width: 180px; }
.dl-figure .dl-time input { flex: 1 1 auto; min-width: 120px; margin: 0; accent-color: #0072B2; }
.dl-figure .dl-time input:focus-visible { outline: 3px solid #E69F00; outline-offset: 2px; }
.dl-figure .dl-readout { font-size: 14px; font-variant-numeric: tabular-nums; white-space: nowrap; min-width: 6.5em; }
.dl-figure h4.dl-title { font-family: inherit; font-size: 1.25rem; font-weight: 600; line-height: 1.3;
  margin: 0.2rem 0 0.4rem 0; padding: 0; color: inherit; }
.dl-figure .dl-description { font-size: 14px; opacity: .75; margin: 0.2rem 0 0.6rem 0; line-height: 1.5; }
.dl-figure.dl-lecture .dl-controls button { font-size: 20px; padding: 6px 18px; }
.dl-figure.dl-lecture .dl-hint, .dl-figure.dl-lecture .dl-description, .dl-figure.dl-lecture .dl-readout { font-size: 18px; }
.dl-figure.dl-lecture h4.dl-title { font-size: 1.6rem; }
/* The projector's stage: the motion under the page's title as tall as the screen lets it (the rod and disk was
   drawn 292 px tall at 1280×720). The figure's own heading is read to a screen reader, not shown (a drag's live
   headline stands there, over the controls), and the keys are in the buttons' titles, not a line of their own. */
.dl-figure.dl-lecture.dl-staged h4.dl-title { position: absolute; width: 1px; height: 1px; margin: 0; overflow: hidden;
  clip-path: inset(50%); white-space: nowrap; }
.dl-figure.dl-lecture.dl-staged .dl-hint { display: none; }
/* the traces drawn over a held 3-D scene: hidden in WebGL, not in its legend */
.dl-figure .dl-scene-held .legend .traces { opacity: 1 !important; }
.dl-figure .dl-key { display: none; font-size: 14px; font-style: italic; margin: 0.2rem 0; }
@media (hover: none) { .dl-figure .dl-hint { display: none; } }
/* A phone's stage: the caption's first two lines under the motion, the whole of it on a tap (the graph's
   name carries all of it for a screen reader), so the lesson's controls below stay in the first screen. */
@media (max-width: 640px) {
  .dl-figure.dl-staged .dl-description:not(.dl-open) { display: -webkit-box; -webkit-line-clamp: 2;
    -webkit-box-orient: vertical; overflow: hidden; cursor: pointer; }
  .dl-figure.dl-staged .dl-description { margin-bottom: 0; }
}
@media (max-width: 640px) and (max-height: 760px) {  /* a short phone (360×740): its first line */
  .dl-figure.dl-staged .dl-description:not(.dl-open) { -webkit-line-clamp: 1; }
}
@media print {
  .dl-figure { break-inside: avoid; }
  .dl-figure .dl-controls, .dl-figure .dl-hint { display: none !important; }
  .dl-figure .dl-key:not(:empty) { display: block; }
}
`;

const HTML = `
<h4 class="dl-title"></h4>
<div class="dl-controls" hidden>
  <button class="dl-play" type="button" aria-label="Play the animation" aria-keyshortcuts="Space" title="Space: play/pause">▶ Play</button>
  <button class="dl-pause" type="button" aria-label="Pause the animation" aria-keyshortcuts="Space" title="Space: play/pause">❚❚ Pause</button>
  <button class="dl-back" type="button" aria-label="Step back one frame" aria-keyshortcuts="ArrowLeft" title="←: step back">◀</button>
  <button class="dl-forward" type="button" aria-label="Step forward one frame" aria-keyshortcuts="ArrowRight" title="→: step forward">▶</button>
  <button class="dl-forces" type="button" aria-pressed="false" hidden
    title="Lay the free-body diagram's forces on the motion, each arrow at its point, drawn to its size in that frame">Forces</button>
  <label class="dl-time"><span class="dl-readout"></span><input class="dl-scrub" type="range" min="0" max="0" step="1" value="0"></label>
  <span class="dl-hint">Space: play/pause · ← →: step</span>
</div>
<div class="dl-graph" role="img"></div>
<p class="dl-key"></p>
<p class="dl-description" aria-live="polite"></p>`;

// ------------------------------------------------------------------ plotly.js, once per page load
// A page with a 3-D scene loads the gl3d bundle, which draws everything basic draws: once it is
// here, every figure uses it (one plotly.js compiled per page load, even across page switches).
const loaded = {};   // bundle URL -> Promise of its Plotly
function plotlyFor(url) {
  const superset = Object.keys(loaded).find(u => u.includes("plotly-gl3d."));
  if (superset && !url.includes("plotly-gl3d.")) return loaded[superset];
  if (!loaded[url]) loaded[url] = new Promise((resolve, reject) => {
    const script = document.createElement("script");
    script.src = url;
    script.onload = () => resolve(window.Plotly);
    script.onerror = () => { delete loaded[url]; reject(new Error("could not load " + url)); };
    document.head.appendChild(script);
  });
  return loaded[url];
}

function quiet(promise) { if (promise && promise.catch) promise.catch(() => {}); }  // an interrupted animation rejects

// ------------------------------------------------------------------ a 3-D scene's render loop, parked
// plotly's 3-D scene (gl-plot3d) asks for every animation frame, to see whether its camera or data
// changed: a page holding one never idles, so Chromium starts its frames on a fixed 60 Hz clock and a
// pointer move waits up to a frame for the next one, where a page at rest starts one for it at once
// (a 2-D page given the same endless loop waited as long: BENCHMARKS.md, live dragging). While a
// control is dragged the scene is held and drawn over (sceneOverlay), so its loop is parked: its next
// request for a frame is kept, not made, and made again on release (the scene then draws what
// changed). The loop is known by its own source (it stops on the scene's ``_stopped`` or a lost
// context), as the pinned plotly bundle writes it; any other callback is passed on untouched.
let parking = null;  // the held figure whose scene's loop is parked
const parked = new Set();
const isSceneLoop = (() => {
  const seen = new WeakMap();
  return (cb) => {
    if (typeof cb !== "function") return false;
    if (!seen.has(cb)) { const text = Function.prototype.toString.call(cb); seen.set(cb, text.length < 200 && text.includes("._stopped") && text.includes(".contextLost")); }
    return seen.get(cb);
  };
})();
function parkSceneLoops(figure) {
  if (!window.dlNativeFrame) {
    const native = window.dlNativeFrame = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (cb) => {
      if (parking && !parking.root.isConnected) resumeSceneLoops();  // (its page left while held)
      if (parking && isSceneLoop(cb)) { parked.add(cb); return 0; }
      return native(cb);
    };
  }
  parking = figure;
}
function resumeSceneLoops() {
  parking = null;
  for (const cb of parked) window.dlNativeFrame(cb);
  parked.clear();
}
export const parkedSceneLoops = () => parked.size;  // (for the tests)

// ------------------------------------------------------------------ one figure on the page
// The least of the first screen a fit_screen figure is fitted to (px): with less left below its top
// it is drawn at its own height (Figure.screenHeight).
const MIN_FITTED = 200;

class Figure {
  constructor(parent) {
    if (!document.getElementById("dl-figure-style")) {
      const style = document.createElement("style");
      style.id = "dl-figure-style";
      style.textContent = CSS;
      document.head.appendChild(style);
    }
    this.root = document.createElement("div");
    this.root.className = "dl-figure";
    this.root.tabIndex = -1;  // a click on the figure gives it the keys; no extra tab stop
    this.root.innerHTML = HTML;
    this.root.dlFigure = this;  // for ui/plotly_component/live.js: the pose at the key instant while a control is dragged
    this.held = null;  // (the frame shown before, while held at the key instant)
    parent.appendChild(this.root);
    const $ = (c) => this.root.querySelector(c);
    this.title = $(".dl-title");
    this.controls = $(".dl-controls");
    this.graph = $(".dl-graph");
    this.description = $(".dl-description");
    this.description.addEventListener("click", () => this.description.classList.toggle("dl-open"));
    this.keyCaption = $(".dl-key");
    this.keyFrame = 0;
    this.frames = [];
    this.printing = false;
    onPaper.add(this);
    // The time slider is an HTML range input, not plotly's slider: plotly draws a slider's every
    // step as SVG on each redraw (about half of a redraw's time for 100 frames), and a range input
    // scrubs by mouse, touch and keyboard (← →, Home, End, Page Up/Down) by itself.
    this.scrub = $(".dl-scrub");
    this.readout = $(".dl-readout");
    this.times = [];
    this.timeLabel = ["t = ", " s"];
    this.current = null;   // what is drawn now: the same text is not drawn again
    this.seq = 0;
    this.frames = [];
    this.frameNames = [];
    this.frameIndex = 0;
    this.playing = false;
    this.playSeq = 0;      // a Play loop stops when this moves on (Pause, a step, a new figure)
    this.Plotly = null;
    // The graph follows its room: plotly.js listens to the window only, and the sidebar collapsing
    // widens the main column without resizing the window.
    this.width = 0;
    new ResizeObserver(() => {
      const width = this.root.clientWidth;
      if (width === this.width || !this.Plotly || !this.graph.layout) return;
      this.width = width;
      quiet(this.Plotly.Plots.resize(this.graph).then(() => this.fitDrawn()));
    }).observe(this.root);
    // The stage's Forces switch (ui/figure.show's ``forces``): the server draws the overlay (a rerun), and
    // the run's figure says whether it is on; until then the button says it is on its way.
    this.forces = $(".dl-forces");
    this.trigger = null;  // Streamlit's setTriggerValue, from the latest render
    this.forces.addEventListener("click", () => {
      if (!this.trigger || this.forces.getAttribute("aria-busy") === "true") return;
      this.forces.setAttribute("aria-busy", "true");
      this.trigger("forces", this.forces.getAttribute("aria-pressed") !== "true");
    });
    $(".dl-play").addEventListener("click", () => this.play());
    $(".dl-pause").addEventListener("click", () => this.pause());
    $(".dl-back").addEventListener("click", () => { this.pause(); this.goTo(this.frameIndex - 1); });
    $(".dl-forward").addEventListener("click", () => { this.pause(); this.goTo(this.frameIndex + 1); });
    this.scrub.addEventListener("input", () => { this.pause(); this.goTo(Number(this.scrub.value)); });
    this.root.addEventListener("keydown", (e) => {
      if (!this.frameNames.length || e.target === this.scrub && e.key !== " ") return;  // the range input steps itself
      if (e.key === " " && e.target === this.forces) return;  // the Forces button's own press (Space plays elsewhere)
      if (e.key === " ") { e.preventDefault(); this.playing ? this.pause() : this.play(); }
      else if (e.key === "ArrowRight") { e.preventDefault(); this.pause(); this.goTo(this.frameIndex + 1); }
      else if (e.key === "ArrowLeft") { e.preventDefault(); this.pause(); this.goTo(this.frameIndex - 1); }
    });
  }

  needsRedraw() { return !!(this.graph.layout && this.graph.layout.scene); }
  goTo(index) {
    if (!this.frameNames.length) return;
    quiet(this.show((index + this.frameNames.length) % this.frameNames.length));
  }
  // One frame drawn, and its time shown. A 3-D scene's moving traces are updated in the scene in
  // place (sceneFrame); anything else through plotly's animate, which for a 3-D scene would replot
  // the whole scene (about 150 ms a frame in software rendering).
  show(index) {
    this.frameIndex = index;
    this.showTime(index);
    if (this.sceneFrame(index)) return Promise.resolve();
    return this.Plotly.animate(this.graph, [this.frameNames[index]], {mode: "immediate",
      frame: {duration: 0, redraw: this.needsRedraw()}, transition: {duration: 0}});
  }
  // A frame of a 3-D scene set on its traces' WebGL objects, which redraw on the scene's next
  // animation frame; the graph's data follow, so a later redraw (a resize) shows the same frame.
  // False where plotly.js's scene is not as expected: then plotly's own animate draws it.
  sceneFrame(index) {
    const frame = this.frames[index];
    return !!frame && this.sceneUpdate(frame.traces, frame.data);
  }
  sceneUpdate(traces, data) {
    const scene = this.scene;
    if (!scene || !scene.glplot || !scene.traces) return false;
    const targets = traces.map((t) => {
      const full = (this.graph._fullData || [])[t];
      const object = full && scene.traces[full.uid];
      return object && typeof object.update === "function" ? [t, full, object] : null;
    });
    if (targets.some((target) => !target)) return false;
    targets.forEach(([t, full, object], n) => {
      for (const k of ["x", "y", "z"]) if (data[n][k]) full[k] = this.graph.data[t][k] = data[n][k];
      object.update(full);
    });
    scene.glplot.redraw();
    return true;
  }
  // plotly's 3-D scene of this figure (its camera, data scale and gl-plot3d), or undefined.
  get scene() {
    const layout = this.graph._fullLayout;
    return layout && layout.scene && layout.scene._scene;
  }
  // A held 3-D scene's posed traces (lines, markers) drawn in an SVG laid over the scene, each point
  // projected as plotly.js projects a 3-D annotation (the scene's camera, model and data scale, onto
  // its domain): WebGL hides them for the hold (showHeld) and is not redrawn while the control moves.
  // Each redraw of the scene in software WebGL took 7–9 ms a pose, and the next move waited for it.
  sceneOverlay(traces, data) {
    const held = this.held, layout = this.graph._fullLayout, scene = this.scene;
    if (!held || !held.overlay || traces.some((t) => !held.overlay.includes(t))) return false;
    if (!scene || !scene.glplot || !scene.glplot.cameraParams || !scene.dataScale) return false;
    const project = sceneProjection(scene.glplot.cameraParams, scene.dataScale, layout._size, layout.scene.domain);
    if (!held.svg) {
      const gl = this.graph.querySelector(".gl-container");
      if (!gl) return false;
      const svg = held.svg = document.createElementNS(SVG, "svg");
      svg.setAttribute("class", "dl-scene-pose");
      svg.setAttribute("aria-hidden", "true");
      Object.assign(svg.style, {position: "absolute", left: "0", top: "0", pointerEvents: "none", overflow: "hidden",
                                width: layout.width + "px", height: layout.height + "px"});
      // Clipped to the plot area clear of the legend (WebGL clips to the scene's box, which a bigger
      // tilt than the run's outgrows: the overlay shows it whole, off the legend's rows above or column beside).
      let {l, t, w, h} = layout._size;
      const legend = this.graph.querySelector(".legend"), here = this.graph.getBoundingClientRect();
      const key = legend && legend.getBoundingClientRect();
      if (key && key.width && key.left - here.left >= l + w / 2) w = Math.min(w, key.left - here.left - 2 - l);  // a column beside
      else if (key && key.height && key.bottom - here.top <= t + h / 2) {  // rows above
        const below = Math.max(t, key.bottom - here.top + 2);
        [t, h] = [below, t + h - below];
      }
      const clip = `dl-scene-clip-${++overlays}`;
      svg.innerHTML = `<clipPath id="${clip}"><rect x="${l}" y="${t}" width="${Math.max(0, w)}" height="${Math.max(0, h)}"/></clipPath>` +
        `<g clip-path="url(#${clip})"><g></g><g></g></g>`;
      gl.after(svg);  // above the scene, below the legend and annotations
      held.layers = [...svg.lastChild.children];  // the markers over every line, as WebGL's depth shows them here
      held.marks = new Map();
    }
    const [lines, markers] = held.layers;
    traces.forEach((t, n) => {
      const full = this.graph._fullData[t], {x, y, z} = data[n];
      if (!held.marks.has(t)) held.marks.set(t, [lines, markers].map((layer) => layer.appendChild(document.createElementNS(SVG, "g"))));
      const [line, mark] = held.marks.get(t);
      const points = x.map((_, i) => (x[i] === null || y[i] === null || z[i] === null ? null : project(x[i], y[i], z[i])));
      // WebGL's widths: a scatter3d line is drawn half its width in pixels, a marker about 1.4 its size across
      line.innerHTML = full.mode.includes("lines")
        ? `<path d="${points.map((p, i) => (p ? (i && points[i - 1] ? "L" : "M") + p.join(",") : "")).join("")}" fill="none" ` +
          `stroke="${full.line.color}" stroke-width="${full.line.width / 2}" stroke-linejoin="round" stroke-linecap="round"/>` : "";
      mark.innerHTML = full.mode.includes("markers")
        ? points.filter((p) => p).map((p) => `<circle cx="${p[0]}" cy="${p[1]}" r="${0.7 * full.marker.size}" fill="${full.marker.color}"/>`).join("") : "";
      Object.assign(this.graph.data[t], {x, y, z});  // so the frame held and released is the one drawn
    });
    return true;
  }
  // 2-D traces (lines, 'toself' fills, markers) drawn at these coordinates by setting their SVG as
  // plotly.js draws it (each run of points between gaps a path, on the axes as they stand), in a
  // fraction of a millisecond: plotly's animate redraws every moving trace of the figure, 6–16 ms a
  // pose here, longer than a frame leaves. A run fewer than drawn (an arrow gone at a zero force)
  // leaves its path empty; false where a trace's drawing is of another kind, has fewer paths than it
  // needs (an arrow that was not drawn) or other markers: then plotly's animate draws it, and the next
  // pose is written here again. Plotly's next redraw (the frame held, or the
  // run's new figure) draws these traces afresh.
  svgUpdate(traces, data) {
    const layout = this.graph._fullLayout, groups = new Map();
    if (!layout) return false;
    for (const g of this.graph.querySelectorAll(".scatterlayer .trace")) {
      const trace = g.__data__ && g.__data__[0] && g.__data__[0].trace;
      if (trace) groups.set(trace.index, [g, trace]);
    }
    const writes = [];  // [element, attribute, value], written once every trace is known to be drawable
    for (const [n, t] of traces.entries()) {
      const [g, trace] = groups.get(t) || [];
      const xa = trace && layout[trace.xaxis.replace("x", "xaxis")], ya = trace && layout[trace.yaxis.replace("y", "yaxis")];
      const {x, y} = data[n];
      if (!g || !xa || !ya || !x || !y || x.length !== y.length || !["lines", "markers"].includes(trace.mode)) return false;
      const at = (i) => `${Math.round(xa.c2p(x[i]) * 100) / 100},${Math.round(ya.c2p(y[i]) * 100) / 100}`;
      const runs = [];
      let run = [];
      for (let i = 0; i <= x.length; i++) {
        if (i < x.length && x[i] !== null && y[i] !== null) run.push(at(i));
        else if (run.length) { runs.push(run); run = []; }
      }
      if (trace.mode === "markers") {
        const marks = g.querySelectorAll(".points .point"), shown = runs.flat();
        if (marks.length !== shown.length) return false;
        marks.forEach((mark, i) => writes.push([mark, "transform", `translate(${shown[i]})`]));
        continue;
      }
      const lines = g.querySelectorAll(".js-line"), fill = g.querySelector(".js-fill");
      if (lines.length < runs.length || !["none", "toself"].includes(trace.fill) || (trace.fill === "toself" && !fill && runs.length)) return false;
      const paths = runs.map((points) => "M" + points.join("L"));
      lines.forEach((line, i) => writes.push([line, "d", paths[i] || ""]));
      if (fill) writes.push([fill, "d", paths.map((path) => path + "Z").join("")]);
    }
    for (const [el, name, value] of writes) el.setAttribute(name, value);
    traces.forEach((t, n) => Object.assign(this.graph.data[t], {x: data[n].x, y: data[n].y}));  // so a redraw (a resize) keeps the pose
    return true;
  }
  // Traces drawn at these coordinates at once (live.js: the bodies at the key instant while a lesson
  // control is dragged): a held 3-D scene's over it (sceneOverlay), another 3-D scene's in place, 2-D
  // ones in their SVG, anything else through plotly's animate, given every moving trace (it redraws
  // only the subplots of the traces it gets, and empties the others).
  pose(traces, data) {
    const widened = this.widen(traces, data);
    if (widened) return widened;
    if (this.sceneOverlay(traces, data) || this.sceneUpdate(traces, data) || this.svgUpdate(traces, data)) return Promise.resolve();
    const others = (this.frames[0] ? this.frames[0].traces : []).filter((t) => !traces.includes(t));
    return this.Plotly.animate(this.graph, {data: [...data, ...others.map((t) => ({x: this.graph.data[t].x, y: this.graph.data[t].y}))],
                                            traces: [...traces, ...others]},
                               {mode: "immediate", frame: {duration: 0, redraw: false}, transition: {duration: 0}});
  }
  // A held pose past a 2-D plot's axes (a longer ladder, a larger cart dragged) widens them to hold it,
  // by a fifth of their span more than it needs, so that a drag onward redraws seldom; never narrower
  // during the drag, and put back on release (a run's new figure comes with its own). A 3-D scene's box
  // (Euler's disk dragged larger) grows as a whole (widenScene). Returns plotly's redraw, or null where
  // the pose fits.
  widen(traces, data) {
    const layout = this.graph._fullLayout;
    if (!this.held || !layout) return null;
    if (this.scene) return this.widenScene(traces, data);
    const reach = {};  // axis name -> [lowest, highest] of the pose on it
    traces.forEach((t, n) => {
      const trace = this.graph._fullData[t];
      if (!trace || !trace.xaxis || !trace.yaxis) return;
      for (const [axis, values] of [[trace.xaxis.replace("x", "xaxis"), data[n].x], [trace.yaxis.replace("y", "yaxis"), data[n].y]])
        for (const v of values || []) if (v !== null && Number.isFinite(v)) {
          const r = (reach[axis] ??= [v, v]);
          r[0] = Math.min(r[0], v); r[1] = Math.max(r[1], v);
        }
    });
    const update = {};
    for (const [axis, [lo, hi]] of Object.entries(reach)) {
      const shown = layout[axis] && layout[axis].range, given = this.graph.layout[axis];
      if (!shown || !given || !Array.isArray(given.range) || layout[axis].type !== "linear") continue;
      const [a, b] = [Math.min(...shown), Math.max(...shown)];
      if (lo >= a && hi <= b) continue;
      const margin = 0.2 * (b - a);
      update[`${axis}.range`] = [Math.min(a, lo - margin), Math.max(b, hi + margin)];
      (this.held.ranges ??= {})[`${axis}.range`] ??= [...given.range];
    }
    if (!Object.keys(update).length) return null;
    traces.forEach((t, n) => Object.assign(this.graph.data[t], {x: data[n].x, y: data[n].y}));  // drawn by the relayout
    return this.Plotly.relayout(this.graph, update);
  }
  // A 3-D scene's box grown about the origin by one factor on every axis (one scale on all three kept; the
  // axis titles, anchored at its edges, moved with them), enough to hold the pose and a fifth more; its one
  // redraw in WebGL, then the pose over it. Null where the pose fits, or an axis's range leaves out 0.
  widenScene(traces, data) {
    const given = this.graph.layout.scene, full = this.graph._fullLayout.scene;
    const axes = ["xaxis", "yaxis", "zaxis"];
    if (!given || !full || axes.some((a) => !given[a] || !Array.isArray(given[a].range))) return null;
    let need = 1;
    traces.forEach((_, n) => ["x", "y", "z"].forEach((c, k) => {
      const [lo, hi] = full[axes[k]].range;
      for (const v of data[n][c] || []) if (v !== null && Number.isFinite(v)) {
        if (v > hi) need = hi > 0 ? Math.max(need, v / hi) : Infinity;
        if (v < lo) need = lo < 0 ? Math.max(need, v / lo) : Infinity;
      }
    }));
    if (need <= 1 || !Number.isFinite(need)) return null;
    const grow = 1.2 * need, update = {};
    const ranges = (this.held.ranges ??= {});  // what release puts back
    for (const a of axes) {
      update[`scene.${a}.range`] = full[a].range.map((v) => v * grow);
      ranges[`scene.${a}.range`] ??= [...given[a].range];
      if (Array.isArray(given[a].tickvals)) {  // the figure's few ticks would crowd its old box: plotly's own, as few
        Object.assign(update, {[`scene.${a}.tickvals`]: null, [`scene.${a}.nticks`]: 4});
        ranges[`scene.${a}.tickvals`] ??= [...given[a].tickvals];
        ranges[`scene.${a}.nticks`] ??= given[a].nticks ?? null;
      }
    }
    if (given.annotations) {
      update["scene.annotations"] = full.annotations.map(
        (n, i) => Object.assign({}, given.annotations[i], {x: n.x * grow, y: n.y * grow, z: n.z * grow}));
      ranges["scene.annotations"] ??= given.annotations.map((n) => Object.assign({}, n));
    }
    const held = this.held;
    return this.Plotly.relayout(this.graph, update).then(() => {
      if (this.held !== held || !this.scene || !this.scene.glplot) return;
      this.scene.glplot.redraw();  // (its loop parked while held: this one frame, at the new scale)
      this.sceneOverlay(traces, data);
    });
  }
  // Play keeps the animation's stated time (frames × frame time): each animation frame of the
  // browser draws the frame due at that moment, and a frame whose time has passed while the last
  // one was drawn is skipped. A slow machine drops frames, not time.
  play() {
    if (!this.frameNames.length || this.held) return;  // held at its key instant while a control is dragged
    const last = this.frameNames.length - 1, frameMs = Number(this.graph.dataset.frameMs || 60);
    const from = this.frameIndex >= last ? 0 : this.frameIndex;
    const start = performance.now() - from * frameMs, seq = ++this.playSeq;
    this.playing = true;
    const tick = async () => {
      if (seq !== this.playSeq) return;
      const due = Math.min(last, Math.floor((performance.now() - start) / frameMs));
      if (due !== this.frameIndex) {
        try { await this.show(due); } catch (e) { /* a frame interrupted by a newer one */ }
      }
      if (seq !== this.playSeq) return;
      if (due >= last) { this.playing = false; return; }
      requestAnimationFrame(tick);
    };
    if (from !== this.frameIndex) quiet(this.show(from));
    requestAnimationFrame(tick);
  }
  showTime(index) {
    this.scrub.value = String(index);
    const t = this.times[index];
    this.readout.textContent = t === undefined ? "" : this.timeLabel[0] + t.toFixed(this.timeDigits || 2) + this.timeLabel[1];
    this.scrub.setAttribute("aria-valuetext", this.readout.textContent);
  }
  pause() {
    this.playing = false;
    this.playSeq++;
  }
  // Held while a lesson control is dragged: paused (Play waits). live.js then shows the key frame with
  // the traces ``dimmed`` (one redraw) and moves its bodies there; on release the frame shown before and
  // every trace's own opacity come back, again in one redraw (none if the key frame was never shown).
  hold() {
    if (this.held) return;
    this.pause();
    this.held = {frame: this.frameIndex, shown: false};
  }
  // A 3-D scene's ``posed`` traces are hidden there (drawn over it by sceneOverlay while held).
  showHeld(dimmed, opacity, posed = []) {
    if (!this.held || this.held.shown) return Promise.resolve();
    this.held.shown = true;
    const overlay = this.scene ? posed : [];
    this.held.overlay = overlay.length ? overlay : null;
    this.graph.classList.toggle("dl-scene-held", !!this.held.overlay);
    const held = this.held;
    return this.restyleFrame(this.keyFrame, dimmed.map(() => opacity), dimmed, overlay, "legendonly").then(() => {
      const scene = this.scene;
      if (this.held !== held || !held.overlay || !scene || !scene.glplot) return;
      scene.glplot.redraw();  // the posed traces hidden in WebGL now, then no frame until release
      parkSceneLoops(this);
    });
  }
  release() {
    const held = this.held;
    this.held = null;
    this.dropOverlay(held);
    if (held && held.shown) quiet(this.restyleFrame(held.frame, this.graph.data.map(() => null), this.graph.data.map((_, i) => i),
                                                    held.overlay || [], true)
      .then(() => held.ranges && this.Plotly.relayout(this.graph, held.ranges)));
  }
  dropOverlay(held) {
    if (held && held.svg) held.svg.remove();
    if (held && held.overlay) resumeSceneLoops();
    this.graph.classList.remove("dl-scene-held");
  }
  // Frame ``index``'s moving traces, these traces' opacities, and the ``shown`` traces' visibility, in
  // one restyle.
  restyleFrame(index, opacities, traces, shown = [], visible = true) {
    const frame = this.frames[index];
    if (!frame) return Promise.resolve();
    const all = [...new Set([...frame.traces, ...traces, ...shown])], update = {opacity: all.map((t) => {
      const n = traces.indexOf(t);
      return n < 0 ? undefined : opacities[n];
    })};
    if (shown.length) update.visible = all.map((t) => (shown.includes(t) ? visible : undefined));
    for (const [n, d] of frame.data.entries())
      for (const k of Object.keys(d)) if (k !== "type") (update[k] ??= all.map(() => undefined))[all.indexOf(frame.traces[n])] = d[k];
    this.frameIndex = index;
    this.showTime(index);
    return this.Plotly.restyle(this.graph, update, all);
  }


  // The motion on the stage (ui/page.py) fills what is left of the first screen below its top, so
  // the whole figure and its Play button show without scrolling (the page's scroll offset is added
  // back); where the lesson's controls stand below it (a phone stacks the stage's columns), the room
  // from the graph's foot to theirs is kept too (its caption, the controls). Capped at the figure's own
  // height; and that height, as any figure's further down, where less than MIN_FITTED of the first
  // screen is left below its top (it starts at the screen's foot or past it: nothing to fit to).
  screenHeight(height) {
    const main = this.root.closest(DOM.main);
    const graph = this.graph.getBoundingClientRect();
    const top = graph.top + (main ? main.scrollTop : 0);
    const stage = this.root.closest(DOM.stage);
    const controls = stage && stage.querySelector(DOM.stageControls);
    const box = controls && controls.getBoundingClientRect();
    const below = box && box.height && box.top > graph.top ? box.bottom - graph.bottom : 0;  // caption, controls
    const room = Math.floor(window.innerHeight - top - (below || this.captionLine()) - 12);
    return room < MIN_FITTED ? height : Math.min(height, room);
  }

  // The caption's first line, kept on the first screen under the motion where nothing else is counted
  // below it (a projector cut that line in half at the screen's foot); 0 without a caption.
  captionLine() {
    if (!this.description.textContent) return 0;
    const style = getComputedStyle(this.description);
    return Math.ceil(parseFloat(style.lineHeight) || 1.5 * parseFloat(style.fontSize)) + 4;
  }

  async draw(args, theme, seq) {
    this.title.textContent = args.title || "";
    this.forces.hidden = typeof args.forces !== "boolean";
    this.forces.setAttribute("aria-pressed", String(args.forces === true));
    this.forces.removeAttribute("aria-busy");
    // The text a screen reader gets, at once: it does not wait for plotly.js.
    this.graph.setAttribute("aria-label", (args.title ? args.title + ". " : "") + (args.description || ""));
    this.description.textContent = args.description || "";
    const spec = args.spec, style = args.style;
    // (a motion the browser computes: its modules fetched beside plotly.js, not after it)
    const motion = spec.animation && spec.animation.posed ? this.computeMotion(spec, args.motion) : null;
    const Plotly = await plotlyFor(args.bundle);
    if (seq !== this.seq) return;  // a newer run came while plotly.js loaded
    if (motion && !(await motion)) return;
    if (seq !== this.seq) return;  // a newer run came while the motion's modules loaded
    if (this.Plotly && this.Plotly !== Plotly) Plotly.purge(this.graph);  // drawn by the other bundle
    this.Plotly = Plotly;
    const layout = themeLayout(spec.layout || {}, theme);
    const slider = (layout.sliders || [])[0];
    if (slider) {  // drawn as the range input above the graph; its room below the axes is not needed
      delete layout.sliders;
      layout.margin = Object.assign({}, layout.margin, {b: layout.scene ? 10 : Math.min((layout.margin || {}).b || 60, 60)});
      const current = slider.currentvalue || {};
      this.timeLabel = [current.prefix || "t = ", current.suffix || ""];
    }
    this.root.classList.toggle("dl-lecture", !!style);
    this.root.classList.toggle("dl-staged", !!args.fit_screen);
    // A phone's stage has no room for a motion's legend of many rows: its caption says what each body is.
    // A plot on the stage (beside a refusal: the cart's ẍ–μ curves) keeps its legend: nothing else names its lines.
    if (args.fit_screen && spec.animation && this.root.clientWidth < 500) layout.showlegend = false;
    if (style) spec.data = emphasised(spec.data, layout, style);
    const thin = args.fit_screen && !style ? outlineScale(this.root.clientWidth) : 1;  // a projector keeps them thick
    if (thin < 1) spec.data = scaled(spec.data, thin, Math.max(thin, 0.75));
    const frames = unfold(spec.animation, spec.data);
    // Outlines as the last drawing's axes would draw them (fitDrawn corrects them after, if far off).
    const outlineWidths = spec.data.map(t => t.fill === "toself" && t.line ? t.line.width : null);
    const before = this.graph._fullLayout;
    if (before && before.xaxis && !layout.scene)
      for (const [t, width] of outlines(before.xaxis, before.yaxis, spec.data, frames, outlineWidths))
        spec.data[t] = Object.assign({}, spec.data[t], {line: Object.assign({}, spec.data[t].line, {width: width})});
    this.controls.hidden = !spec.animation;  // before measuring: the controls sit above the graph
    this.fitHeight = args.fit_screen ? args.height : 0;
    layout.height = this.fitHeight ? this.screenHeight(this.fitHeight) : args.height;
    layout.autosize = true;
    // A 3-D scene is drawn as large as the graph's height allows: on a wide graph its legend stands in a
    // column at the right, not in rows above it.
    if (layout.scene && layout.showlegend !== false && this.root.clientWidth > SCENE_GROWTH * layout.height)
      layout.legend = Object.assign({}, layout.legend, LEGEND_BESIDE);
    // A motion drawn to scale beside a legend in a column (the lecture's) that takes the width its scale
    // needs (the stick on a 1024 px projector: 190 px of plot beside 330 px of names) has it in rows above.
    if (style && squeezedBeside(spec.data, layout, this.root.clientWidth))
      layout.legend = Object.assign({}, layout.legend, LEGEND_ABOVE);
    // A motion with a second plot (the pendulum's θ(t), the rod's energy bars) on the projector's stage:
    // where its legend in a column would draw the bodies a tenth smaller than none (the sphere was 35 px
    // across, the rod's disk 30), the caption below names them instead, as on a phone's stage. (Rows above
    // draw them no larger than none: they take the height a tall motion needs.)
    if (style && args.fit_screen && layout.yaxis2 && layout.showlegend !== false && (layout.legend || {}).orientation === "v") {
      const room = legendWidth(spec.data, layout), width = this.root.clientWidth;
      if (pairScale(layout, width, 0) > 1.1 * pairScale(layout, width, room)) layout.showlegend = false;
    }
    const legendBeside = layout.showlegend !== false && (layout.legend || {}).orientation === "v";
    const legendRoom = legendWidth(spec.data, layout);
    layout.height = sceneHeight(layout, layout.height, this.root.clientWidth);
    // WebGL sizes the scene's box to the graph's height: where the graph is wider than tall (beside its
    // legend), the box is drawn up to SCENE_GROWTH times larger, to fill the width too.
    if (layout.scene && layout.scene.aspectratio) {
      const wide = (this.root.clientWidth - (legendBeside ? legendRoom : 0)) / Math.max(1, plotHeight(layout));
      const grow = Math.min(SCENE_GROWTH, Math.max(1, wide)), ratio = layout.scene.aspectratio;
      layout.scene = Object.assign({}, layout.scene, {aspectratio: {x: ratio.x * grow, y: ratio.y * grow, z: ratio.z * grow}});
    }
    const lowest = axisRoom(layout, (layout.yaxis2 ? layout.xaxis2 : layout.xaxis) || {});
    if (slider && !layout.scene)  // the lowest plot's x tick labels and title, no more
      layout.margin.b = Math.min(layout.margin.b, Math.ceil(lowest));
    const side = beside(layout, this.root.clientWidth - (layout.margin.l ?? 80) - (layout.margin.r ?? 80)
                                - (legendBeside ? legendRoom : 0), plotHeight(layout));
    if (side) {  // both plots' x axes now at the foot
      applied(layout, side);
      layout.margin.b = Math.max(layout.margin.b, Math.ceil(Math.max(lowest, axisRoom(layout, layout.xaxis || {}))));
    }
    applied(layout, stacked(layout, plotHeight(layout)));
    this.pause();
    this.dropOverlay(this.held);
    this.held = null;
    this.printing = false;
    // One update in place: data, layout and the frames replaced together (no new plot).
    await Plotly.react(this.graph, {data: spec.data, layout: layout, frames: frames,
                                    config: {displayModeBar: false, responsive: true,
                                            plotGlPixelRatio: glPixelRatio()}});
    if (seq !== this.seq) return;
    this.frames = frames;
    this.frameNames = frames.map(f => f.name);
    this.times = spec.animation ? spec.animation.times : [];
    this.timeDigits = timeDigits(this.times);
    this.keyFrame = Math.min(args.key_frame || 0, Math.max(0, frames.length - 1));
    const t = this.times[this.keyFrame];
    this.keyCaption.textContent = frames.length && args.key_caption
      ? `Printed at t = ${t.toFixed(this.timeDigits)} s: ${args.key_caption}.` : "";
    this.scrub.max = String(Math.max(0, this.times.length - 1));
    this.scrub.setAttribute("aria-label", (args.title ? args.title + ": " : "") + "time");
    this.showTime(0);
    this.graph.dataset.frameMs = (spec.animation && spec.animation.frame_ms) || 60;
    this.controls.hidden = !this.frameNames.length;
    this.frameIndex = 0;
    this.width = this.root.clientWidth;
    this.outlineWidths = outlineWidths;
    await this.fitDrawn();
    if (this.fitHeight) this.watchStage();
  }

  // An animation whose frames the browser computes (viz/common.py: animated_in_browser, issue 51): its
  // times, rows and held axes from the generated motion (live.js: motionOf), put where the server's
  // would be. False (nothing drawn) where the motion has no value for these parameters.
  async computeMotion(spec, motion) {
    const [live, gen] = await Promise.all([import(new URL(motion.live, location.href).href),
                                           import(new URL(motion.module, location.href).href)]);
    const m = live.motionOf(gen, spec.animation, spec.layout, motion.digits);
    if (!m) return false;
    spec.animation.times = m.times;
    spec.animation.coords = m.coords;
    spec.animation.traces.forEach((j, n) => {  // the first frame's (x, y, and z in a 3-D scene)
      for (const [axis, rows] of Object.entries(m.coords[n])) spec.data[j][axis] = rows[0];
    });
    for (const line of m.traced) Object.assign(spec.data[line.trace], {x: line.x, y: line.y});  // a plot against time
    if (m.ranges) {
      spec.layout.xaxis = Object.assign({}, spec.layout.xaxis, {range: m.ranges.x});
      spec.layout.yaxis = Object.assign({}, spec.layout.yaxis, {range: m.ranges.y});
    }
    return true;
  }

  // What follows the size the graph is drawn at, after every change of it (a new figure, the screen
  // refitted, the sidebar opened or closed): room between stacked plots for the upper one's tick
  // labels and axis title, few enough ticks on a short axis that they never touch, and each filled
  // body's outline at most a fraction of its drawn size, so a small sphere stays a sphere, not a ring.
  fitDrawn() {
    const full = this.graph._fullLayout;
    if (!full || !full._size || !this.Plotly) return Promise.resolve();
    const relayout = stacked(this.graph.layout, full._size.h), traces = [], widths = [];
    // (a change of a quarter or more: a new figure starts from the last one's estimate, drawn in the same update)
    for (const [t, width] of outlines(full.xaxis, full.yaxis, this.graph._fullData, this.frames, this.outlineWidths)) {
      const now = this.graph._fullData[t].line.width;
      if (Math.abs(width - now) > Math.max(0.15, 0.25 * width)) { traces.push(t); widths.push(width); }
    }
    if (!relayout && !traces.length) return Promise.resolve();
    return this.Plotly.update(this.graph, traces.length ? {"line.width": widths} : {}, relayout || {},
                              traces.length ? traces : undefined).catch(() => {});
  }

  // A figure fitted to the first screen fits again when what shares the screen with it changes: the
  // lesson's controls drawn (or redrawn taller) after it, what is above it grown, the window turned or resized.
  watchStage() {
    const stage = this.root.closest(DOM.stage);
    if (!this.refitting) {
      this.refitting = () => {
        if (!this.fitHeight || !this.Plotly || !this.graph.layout || this.printing) return;
        const height = sceneHeight(this.graph.layout, this.screenHeight(this.fitHeight), this.root.clientWidth);
        // autosize kept: a height relayout alone turns it off, and the width would no longer follow the sidebar
        if (Math.abs(height - this.graph.layout.height) > 2)
          quiet(this.Plotly.relayout(this.graph, {height: height, autosize: true}).then(() => this.fitDrawn()));
      };
      this.stageWatch = new ResizeObserver(() => this.refitting());
      window.addEventListener("resize", () => this.refitting());
    }
    // The stage grows when the controls are drawn or change; the page's column grows too when what is
    // above the stage does (the title set in its web font, a notice), which moves the stage down unresized.
    const column = this.root.closest(DOM.mainBlock);
    for (const [watched, element] of [["watched", stage], ["watchedColumn", column]]) {
      if (!element || element === this[watched]) continue;
      if (this[watched]) this.stageWatch.unobserve(this[watched]);
      this.stageWatch.observe(element);
      this[watched] = element;
    }
    this.refitting();
  }

  // On paper (the browser's Print, or print media): the animation's key instant, drawn at the
  // paper's width, its caption beneath; the screen's frame and width come back after.
  print(on) {
    if (!this.Plotly || !this.graph.layout || on === this.printing) return;
    this.printing = on;
    if (on) {
      if (this.playing) this.pause();
      this.shownFrame = this.frameIndex;
      this.showFrame(this.keyFrame);
      this.Plotly.relayout(this.graph, {width: PAPER_WIDTH});
    } else {
      this.Plotly.relayout(this.graph, {width: null, autosize: true});
      this.showFrame(this.shownFrame || 0);
    }
  }
  // A frame drawn at once (restyle, not animate: a print is laid out right after the event).
  showFrame(index) {
    const frame = this.frames[index];
    if (!frame) return;
    const update = {};
    for (const [n, d] of frame.data.entries())
      for (const k of Object.keys(d)) if (k !== "type") (update[k] ??= frame.data.map(() => undefined))[n] = d[k];
    this.Plotly.restyle(this.graph, update, frame.traces);
    this.frameIndex = index;
    this.showTime(index);
  }

  update(text, theme) {
    const key = text + "|" + theme.text + "|" + theme.dark;
    this.forces.removeAttribute("aria-busy");  // (the run answered the Forces switch, changed or not)
    if (key === this.current) return;  // the same figure: leave it (and its animation) alone
    this.current = key;
    const seq = ++this.seq;
    quiet(this.draw(JSON.parse(text), theme, seq).catch((e) => {
      if (this.current === key) this.current = null;  // try again on the next run
      throw e;
    }));
  }
}

// ------------------------------------------------------------------ the figure's data, for plotly
function themeOf(element) {
  const css = getComputedStyle(element);
  const text = css.getPropertyValue("--st-text-color").trim() || "#31333F";
  const bg = css.getPropertyValue("--st-background-color").trim();
  const rgb = (bg.match(/^#([0-9a-f]{6})$/i) || [])[1];
  const dark = !!rgb && [0, 2, 4].reduce((s, i) => s + parseInt(rgb.slice(i, i + 2), 16), 0) < 3 * 128;
  return {text: text, dark: dark};
}

function themeLayout(layout, theme) {
  const grid = theme.dark ? "rgba(250,250,250,0.12)" : "rgba(49,51,63,0.12)";
  const out = Object.assign({}, layout, {paper_bgcolor: "rgba(0,0,0,0)", plot_bgcolor: "rgba(0,0,0,0)",
                                         font: Object.assign({color: theme.text, family: "Source Sans Pro, sans-serif"}, layout.font || {})});
  for (const key of Object.keys(out)) {
    // ticklabeloverflow "allow": plotly would otherwise measure every tick label in the page after
    // each redraw, to hide one past the graph's edge (5 ms a change in a page this size).
    if (/^[xy]axis\d*$/.test(key)) out[key] = Object.assign({gridcolor: grid, zerolinecolor: grid, linecolor: grid,
                                                              ticklabeloverflow: "allow"}, out[key]);
  }
  if (out.scene) {
    out.scene = Object.assign({}, out.scene);
    for (const a of ["xaxis", "yaxis", "zaxis"]) out.scene[a] = Object.assign({gridcolor: grid, color: theme.text}, out.scene[a]);
  }
  return out;
}

// A compact animation (viz/common.py: animated) unfolded into plotly frames, one per time, each
// carrying only the moving traces' coordinates (as viz.common.expanded).
function unfold(anim, data) {
  if (!anim) return [];
  const names = anim.times.map((_, i) => String(i));
  const kinds = anim.traces.map(j => data[j].type || "scatter");
  const coords = anim.coords.map(c => unpack(c, names.length));
  return names.map((name, i) => ({name: name, traces: anim.traces, data: coords.map((c, n) => {
    const update = {type: kinds[n]};
    for (const k of Object.keys(c)) update[k] = c[k][i];
    return update;
  })}));
}

// A moving trace's rows (key -> one row per frame) from what the server sent (viz/common.py:
// compacted, and unpacked, which this mirrors): the rows themselves; a trail's path and where each
// frame's slice starts; a spiral spring's turns and start; or a template and one affine map per frame.
function unpack(c, frames) {
  if (c.slices) {
    const s = c.slices, out = {};
    s.keys.forEach((k, n) => { out[k] = s.starts.map((a, i) => s.paths[n].slice(a, i + 1)); });
    return out;
  }
  if (c.spirals) {
    const s = c.spirals, x = [], y = [];
    for (let i = 0; i < frames; i++) {
      const xr = new Array(s.n), yr = new Array(s.n);
      for (let p = 0; p < s.n; p++) {
        const f = s.n > 1 ? p / (s.n - 1) : 0;
        const phase = s.start[i] + 2 * Math.PI * s.turns[i] * f, rad = s.inner + (s.outer - s.inner) * f;
        xr[p] = rad * Math.cos(phase); yr[p] = rad * Math.sin(phase);
      }
      x.push(xr); y.push(yr);
    }
    return {x: x, y: y};
  }
  if (c.affine) {
    const a = c.affine, d = a.keys.length, points = a.template[0].length, out = {};
    a.keys.forEach(k => { out[k] = []; });
    for (let i = 0; i < frames; i++) {
      const m = a.maps[i];  // (d + 1) rows of d: the linear part, then the offset
      const rows = a.keys.map(() => new Array(points));
      for (let p = 0; p < points; p++) {
        const gap = a.template[0][p] === null;
        for (let e = 0; e < d; e++) {
          let v = m[d * d + e];
          for (let j = 0; j < d; j++) v += a.template[j][p] * m[j * d + e];
          rows[e][p] = gap ? null : v;
        }
      }
      a.keys.forEach((k, e) => out[k].push(rows[e]));
    }
    return out;
  }
  return c;
}

// Lecture sizing (issue 14), applied on top of the figure's own layout and styles: every text at
// least style.min_font px, lines and markers thicker, for the back row of a lecture hall. The
// numbers live in ui/figure.py (LECTURE); the figures themselves are not changed.
function emphasised(data, layout, style) {
  const min = style.min_font;
  const at = (font) => Object.assign({}, font || {}, {size: Math.max((font && font.size) || 0, min)});
  layout.font = at(layout.font);
  layout.legend = Object.assign({}, layout.legend, {font: at((layout.legend || {}).font)},
    // (not beside a 3-D scene, which is as wide as it is deep and needs the width)
    style.legend_right && !layout.scene ? LEGEND_BESIDE : {});
  if (layout.title) layout.title = Object.assign({}, layout.title, {font: at(Object.assign({size: style.title_font}, (layout.title || {}).font))});
  const axis = (a) => Object.assign({}, a, {tickfont: at((a || {}).tickfont), automargin: true,
    title: Object.assign({}, (a || {}).title, {font: at(((a || {}).title || {}).font)})});
  for (const key of Object.keys(layout)) if (/^[xy]axis\d*$/.test(key)) layout[key] = axis(layout[key]);
  if (layout.scene) for (const a of ["xaxis", "yaxis", "zaxis"]) layout.scene[a] = axis(layout.scene[a]);
  if (layout.annotations) layout.annotations = layout.annotations.map(n => Object.assign({}, n, {font: at(n.font)}));
  if (layout.sliders) layout.sliders = layout.sliders.map(sl => Object.assign({}, sl, {font: at(sl.font),
    currentvalue: Object.assign({}, sl.currentvalue, {font: at((sl.currentvalue || {}).font)})}));
  return scaled(data, style.line_scale, style.marker_scale);
}

// Lines and markers drawn ``line`` and ``marker`` times as thick.
function scaled(data, line, marker) {
  return data.map(t => {
    const out = Object.assign({}, t);
    if (t.line && t.line.width) out.line = Object.assign({}, t.line, {width: t.line.width * line});
    if (t.marker && t.marker.size) out.marker = Object.assign({}, t.marker, {size: t.marker.size * marker});
    return out;
  });
}

// Stacked plots (a second y axis whose domain ends below the first's): the gap between them holds the
// upper plot's x tick labels and title at their font size, and the lower plot's short y axis gets few
// enough ticks that their labels never touch, for a plot area ``height`` px tall. The update for
// Plotly.relayout, or null.
function stacked(layout, height) {
  const upper = layout.yaxis || {}, lower = layout.yaxis2 || {}, xa = layout.xaxis || {};
  if (!upper.domain || !lower.domain || lower.domain[1] > upper.domain[0] || !(height > 0)) return null;
  const size = (font) => (font && font.size) || (layout.font || {}).size || 12;
  const need = Math.min(0.45, axisRoom(layout, xa) / height), gap = upper.domain[0] - lower.domain[1];
  const out = {};
  let bottom = lower.domain[1];
  if (gap < need - 0.02) {  // both plots give room in proportion to their heights
    const top = 1 - upper.domain[0], low = lower.domain[1] - lower.domain[0];
    const scale = (1 - need - lower.domain[0]) / (top + low);
    bottom = lower.domain[0] + low * scale;
    out["yaxis.domain"] = [bottom + need, upper.domain[1]];
    out["yaxis2.domain"] = [lower.domain[0], bottom];
  }
  const room = (bottom - lower.domain[0]) * height / size(lower.tickfont);  // in lines of tick labels
  const ticks = room < 4 ? 2 : Math.max(3, Math.min(6, Math.floor(room / 1.8)));  // (plotly draws at most this many)
  if (!(lower.nticks <= ticks)) out["yaxis2.nticks"] = ticks;
  return Object.keys(out).length ? out : null;
}

// A motion above a second plot (energy bars, θ(t)) on a wide, short graph (a projector's stage, a laptop's):
// where the motion is taller than wide (a swinging rod), drawn beside the second plot, at the graph's
// whole height, its bodies come out larger than above it (at a little over half the height): the
// arrangement that draws the motion at the larger scale (by a quarter at least), the second plot keeping
// MIN_BESIDE px (its tick labels side by side, not slanted over each other). Null where stacking is as
// good (a wide motion, a phone) or the layout has no such pair.
const MIN_BESIDE = 210;  // (three bars' names in lecture type)
// A legend in a column at the plot's right, or in rows above it (as viz.common.base_layout puts it).
const LEGEND_BESIDE = {orientation: "v", x: 1.02, xanchor: "left", y: 1, yanchor: "top"};
const LEGEND_ABOVE = {orientation: "h", x: 0, xanchor: "left", y: 1.02, yanchor: "bottom"};
// The width a legend in a column beside a plot or a 3-D scene takes, before plotly draws it: its longest
// name at 0.42 em a character (plotly's sans-serif, measured: "centre of mass G (at rest)" 240 px at 18 px),
// and its symbol and padding.
function legendWidth(data, layout) {
  return 40 + 0.42 * legendSize(layout) * Math.max(0, ...legendNames(data).map((name) => name.length));
}
const legendSize = (layout) => ((layout.legend || {}).font || {}).size || (layout.font || {}).size || 12;
const legendNames = (data) => data.filter((t) => t.showlegend !== false && t.name).map((t) => String(t.name));

// The height (px) a legend of ``names`` entries takes in rows above a plot ``plotWidth`` px wide: as many rows
// as plotly's equal columns of the widest name (``column`` px) need.
function legendRows(layout, names, plotWidth, column) {
  return Math.ceil(names / Math.max(1, Math.floor(plotWidth / column))) * 1.45 * legendSize(layout);
}

// Whether a single motion drawn to scale beside a legend in a column would be drawn larger (by more than a
// tenth) with the legend in rows above it: the rows (as many as plotly's equal columns of the widest name
// need) take height, the column takes width.
function squeezedBeside(data, layout, width) {
  const xa = layout.xaxis || {}, ya = layout.yaxis || {};
  if (layout.showlegend === false || (layout.legend || {}).orientation !== "v" || layout.scene || layout.yaxis2
      || !ya.scaleanchor || !Array.isArray(xa.range) || !Array.isArray(ya.range)) return false;
  const spanX = Math.abs(xa.range[1] - xa.range[0]), spanY = Math.abs(ya.range[1] - ya.range[0]);
  const plotWidth = width - ((layout.margin || {}).l ?? 80) - ((layout.margin || {}).r ?? 80), height = plotHeight(layout);
  const column = legendWidth(data, layout), names = legendNames(data).length;
  const rows = legendRows(layout, names, plotWidth, column);
  const beside = Math.min((plotWidth - column) / spanX, height / spanY);
  const above = Math.min(plotWidth / spanX, (height - rows) / spanY);
  return spanX > 0 && spanY > 0 && above > 1.1 * beside;
}
// The scale (px a unit) a motion above its second plot, or beside it where that is larger (``beside``), is
// drawn at in a graph ``width`` px wide beside a legend in a column ``room`` px wide (0: no legend).
function pairScale(layout, width, room) {
  const xa = layout.xaxis || {}, up = layout.yaxis || {};
  if (!Array.isArray(xa.range) || !Array.isArray(up.range) || !up.domain) return 0;
  const margin = layout.margin || {};
  const plotWidth = width - (margin.l ?? 80) - (margin.r ?? 80) - room;
  const height = layout.height - (margin.t ?? 80) - (margin.b ?? 80);
  const spanX = Math.abs(xa.range[1] - xa.range[0]), spanY = Math.abs(up.range[1] - up.range[0]);
  if (!(spanX > 0 && spanY > 0 && plotWidth > 0 && height > 0)) return 0;
  const stackedScale = Math.min(plotWidth / spanX, height * (up.domain[1] - up.domain[0]) / spanY);
  const side = beside(layout, plotWidth, height);
  return side ? Math.max(stackedScale, Math.min(side["xaxis.domain"][1] * plotWidth / spanX, height / spanY)) : stackedScale;
}

function beside(layout, width, height) {
  const up = layout.yaxis || {}, low = layout.yaxis2 || {}, xa = layout.xaxis || {};
  if (!up.domain || !low.domain || low.domain[1] > up.domain[0] || !layout.xaxis2 || !up.scaleanchor
      || !xa.range || !up.range || !(width > 0 && height > 0)) return null;
  const spanX = Math.abs(xa.range[1] - xa.range[0]), spanY = Math.abs(up.range[1] - up.range[0]);
  const stackedScale = Math.min(width / spanX, height * (up.domain[1] - up.domain[0]) / spanY);
  const gap = (3.2 * ((layout.font || {}).size || 12) + 16) / width;  // the second plot's y tick labels and title
  // the motion's width at the whole height, short of what the second plot keeps
  const share = Math.min(0.72, height * spanX / spanY / width, 1 - gap - MIN_BESIDE / width);
  const besideScale = Math.min(share * width / spanX, height / spanY);
  if (!(besideScale > 1.1 * stackedScale)) return null;
  return {"xaxis.domain": [0, share], "yaxis.domain": [0, 1], "xaxis2.domain": [share + gap, 1], "yaxis2.domain": [0, 1]};
}

// The room an x axis needs below its plot for its tick labels and title, in px.
function axisRoom(layout, xa) {
  const base = (layout.font || {}).size || 12, size = (font) => (font && font.size) || base;
  return (xa.showticklabels === false ? 0 : size(xa.tickfont) * 1.35 + 8)
         + (xa.title && xa.title.text ? size(xa.title.font) * 1.35 + 10 : 0) + 8;
}

// A 3-D scene's graph no taller than its box needs: on a graph narrower than tall (a phone's), WebGL draws
// the box to the width and leaves bands above and below a flat box (Euler's disk: a hundred px each). The
// plot is made as short as the box drawn to the width needs (BOX_SHARE of the width across, as tall as the
// camera's elevation shows it), and no shorter than SCENE_GROWTH times less than the width, so that the
// box's growth below draws it at the same size. ``height`` as it would be otherwise; a scene beside its
// legend is wide already.
const SCENE_GROWTH = 1.5, BOX_SHARE = 0.8;
function sceneHeight(layout, height, width) {
  const scene = layout.scene || {}, box = scene.aspectratio, eye = (scene.camera || {}).eye;
  if (!box || !eye || (layout.legend || {}).orientation === "v") return height;
  const elevation = Math.atan2(eye.z, Math.hypot(eye.x, eye.y)), across = (box.x + box.y) / Math.SQRT2;
  const tall = (box.z * Math.cos(elevation) + across * Math.sin(elevation)) / across;  // on screen, per width
  const spare = plotHeight(Object.assign({}, layout, {height})) - width * Math.max(1 / SCENE_GROWTH, BOX_SHARE * tall);
  return spare > 0 ? height - Math.floor(spare) : height;
}

// The plot area's height a layout gets (its margins and a legend row above taken off), before plotly draws it.
function plotHeight(layout) {
  const margin = layout.margin || {}, legend = layout.showlegend !== false && (layout.legend || {}).orientation === "h";
  return layout.height - (margin.t ?? 80) - (margin.b ?? 80) - (legend ? 2 * ((layout.font || {}).size || 12) * 1.4 : 0);
}

function applied(layout, update) {  // a relayout's "a.b" keys set on a plain layout
  for (const [key, value] of Object.entries(update || {})) {
    const [axis, field] = key.split(".");
    layout[axis] = Object.assign({}, layout[axis], {[field]: value});
  }
  return layout;
}

// Each filled body's outline (a sphere, a disk, the cart's body) at most 1/14 of its drawn size (its
// first frame's smaller extent in pixels on the axes ``xa``, ``ya`` as drawn), at least 1.5 px, at most
// its styled width (``widths``: null for a trace that is not a filled body). trace -> its outline's width.
function outlines(xa, ya, data, frames, widths) {
  const out = new Map();
  if (!xa || !ya || !xa.l2p || !widths || !widths.some(w => w)) return out;
  const first = new Map((frames[0] ? frames[0].traces : []).map((t, n) => [t, frames[0].data[n]]));
  const span = (values, axis) => {
    const v = Array.from(values).filter(u => u !== null && isFinite(u));
    return v.length ? Math.abs(axis.l2p(Math.max(...v)) - axis.l2p(Math.min(...v))) : 0;
  };
  widths.forEach((width, t) => {
    const trace = data[t], d = first.get(t) || trace;
    if (!width || !trace || (trace.xaxis || "x") !== "x" || (trace.yaxis || "y") !== "y" || !d || !d.x || !d.y) return;
    const size = Math.min(span(d.x, xa), span(d.y, ya));
    out.set(t, Math.round(10 * Math.min(width, Math.max(1.5, size / 14))) / 10);
  });
  return out;
}

// The motion's outlines follow the stage's width: drawn for about 700 px, down to half as thick on a
// phone, so a small sphere stays a sphere, not a ring.
// WebGL draws a 3-D scene at plotly's plotGlPixelRatio, 2 by default: on a screen of one device pixel
// a CSS pixel that is four pixels drawn for each shown, which a machine without a GPU rasterises on
// every pose of a drag. The screen's own ratio (1 to 3, as plotly allows) draws what is shown.
function glPixelRatio() { return Math.min(3, Math.max(1, Math.round(window.devicePixelRatio || 1))); }

// Decimals of the time readout: two, or as many as tell most of the frames apart (stick and ball's
// second impact 1.3 ms after the first: 36 frames all read "t = 0.00 s"), at most five.
function timeDigits(times) {
  const steps = times.slice(1).map((t, i) => Math.abs(t - times[i])).filter((dt) => dt > 0).sort((a, b) => a - b);
  const typical = steps.length ? steps[Math.floor(steps.length / 2)] : 1;
  return Math.min(5, Math.max(2, Math.ceil(-Math.log10(typical))));
}

const SVG = "http://www.w3.org/2000/svg";
let overlays = 0;  // a page's 3-D overlays so far (each one's clip path its own id)

// A 3-D point (data units) to the graph's pixels, as plotly.js places a 3-D annotation: projection ×
// view × model (column-major, WebGL's) of the point times the scene's data scale, then the clip
// coordinates onto the scene's domain of the plot area.
function sceneProjection(camera, dataScale, size, domain) {
  const times = (m, v) => [0, 1, 2, 3].map((row) => m[row] * v[0] + m[4 + row] * v[1] + m[8 + row] * v[2] + m[12 + row] * v[3]);
  const left = size.l + domain.x[0] * size.w, width = size.w * (domain.x[1] - domain.x[0]);
  const top = size.t + (1 - domain.y[1]) * size.h, height = size.h * (domain.y[1] - domain.y[0]);
  return (x, y, z) => {
    const p = times(camera.projection, times(camera.view, times(camera.model, [x * dataScale[0], y * dataScale[1], z * dataScale[2], 1])));
    return [Math.round((left + 0.5 * (1 + p[0] / p[3]) * width) * 100) / 100,
            Math.round((top + 0.5 * (1 - p[1] / p[3]) * height) * 100) / 100];
  };
}

function outlineScale(width) { return Math.max(0.5, Math.min(1, width / 700)); }

// ------------------------------------------------------------------ on paper
// The width a figure is drawn at for print: an A4 or Letter page's text block (ui/page.py PRINT_CSS
// sets 12 mm side margins) holds about 700 CSS px.
const PAPER_WIDTH = 680;
const onPaper = new Set();  // every Figure made on this page
function printing(on) {
  for (const figure of onPaper) {
    if (figure.root.isConnected) figure.print(on); else onPaper.delete(figure);
  }
  document.documentElement.dataset.dlPrinting = on ? "1" : "";
}
window.addEventListener("beforeprint", () => printing(true));
window.addEventListener("afterprint", () => printing(false));
matchMedia("print").addEventListener("change", (e) => printing(e.matches));

// ------------------------------------------------------------------ Streamlit's entry, every run
const figures = new WeakMap();   // Streamlit's element for a mounted figure -> its Figure
const decoder = new TextDecoder();

export function render({data, parentElement, setTriggerValue}) {
  let figure = figures.get(parentElement);
  if (!figure) figures.set(parentElement, figure = new Figure(parentElement));
  figure.trigger = setTriggerValue || null;
  figure.update(typeof data === "string" ? data : decoder.decode(data), themeOf(parentElement));
}
