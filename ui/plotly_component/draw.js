// "Draw the free-body diagram" (ui/diagram_exercise.py), a Streamlit components-v2 module: the bodies
// isolated (the server's SVG: outlines, named points, basis; no load), on which the student adds
// forces, impulses and couples, places each at a named point and sets its direction, then presses
// Check. The drawing stays in the browser until Check sends it (one trigger, one run): the server
// judges it (practice/diagram_judge.py) and says what is wrong.
//
// Three ways to draw, one state: a pointer (tap a load to select it, drag its round handle to turn
// it, tap a point to move the selected load there), the keyboard on the drawing (← → move between
// points, ↑ ↓ turn by 15°, Delete removes, N selects the next load), and the list under it, where
// each load is a row of native controls (its point, turn buttons, remove) a screen reader reads and
// edits. Every change is announced. The student's names are text (textContent), never markup.
"use strict";

const CSS = `
.dl-draw { font-family: var(--st-font, "Source Sans Pro", sans-serif); color: var(--st-text-color, #31333F); line-height: 1.4; }
.dl-draw .dl-draw-bar { display: flex; flex-wrap: wrap; gap: 8px 12px; align-items: end; margin: 0 0 6px 0; }
.dl-draw label { display: flex; flex-direction: column; font-size: 14px; gap: 2px; }
.dl-draw select, .dl-draw input, .dl-draw button { font: inherit; font-size: 15px; min-height: 40px; border-radius: 6px;
  border: 1px solid rgba(128,128,128,.7); background: var(--st-background-color, #fff); color: inherit; padding: 4px 10px; }
.dl-draw input { width: 9em; }
.dl-draw button { cursor: pointer; }
.dl-draw button.dl-draw-primary { background: #005A8C; border-color: #005A8C;
  color: #fff; font-weight: 600; }  /* the app's primary (light theme's), as the answers' Check: red is the loads' colour */
.dl-draw :focus-visible { outline: 3px solid #E69F00; outline-offset: 2px; }
.dl-draw .dl-draw-canvas { position: relative; width: 100%; }
.dl-draw .dl-draw-canvas > svg { display: block; width: 100%; height: auto; max-height: 62vh; touch-action: pan-y; }
.dl-draw .dl-draw-canvas > svg:focus-visible { outline: 3px solid #E69F00; outline-offset: 2px; }
.dl-draw .dl-draw-help { font-size: 14px; margin: 4px 0; }
.dl-draw ol { margin: 4px 0 8px 0; padding-left: 1.6em; }
.dl-draw li { margin: 4px 0; }
.dl-draw li .dl-draw-row { display: flex; flex-wrap: wrap; gap: 6px; align-items: center; }
.dl-draw li[aria-current="true"] { background: rgba(230,159,0,.14); border-radius: 6px; }
.dl-draw li button, .dl-draw li select { min-height: 36px; font-size: 14px; padding: 2px 8px; }
.dl-draw .dl-draw-empty { font-size: 14px; margin: 4px 0; }
.dl-draw .dl-sr { position: absolute; width: 1px; height: 1px; overflow: hidden; clip: rect(0 0 0 0); white-space: nowrap; }
.dl-draw .dl-draw-handle { cursor: grab; touch-action: none; }
.dl-draw .dl-draw-spot { cursor: pointer; }
/* on paper: the bodies and the basis to draw on by hand, none of the controls */
@media print {
  .dl-draw .dl-draw-bar, .dl-draw .dl-draw-help, .dl-draw .dl-draw-empty, .dl-draw ol, .dl-draw button,
  .dl-draw .dl-draw-handle { display: none !important; }
  .dl-draw .dl-draw-canvas > svg { max-height: 7cm; }
}
`;
const SVG = "http://www.w3.org/2000/svg";
const COLOR = "#b3261e", PICKED = "#E69F00";
const ARROW = 62, HANDLE = 27, STEP = 15;
const DRAWN_NAME = 10;  // characters of a load's name written beside its arrow
const WORDS = {force: "Force", impulse: "Impulse", couple: "Couple"};
const drawings = new WeakMap();

function el(tag, attrs = {}, text = "") {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text) node.textContent = text;
  return node;
}

function svgEl(tag, attrs = {}) {
  const node = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}

const norm = (a) => ((Math.round(a) % 360) + 360) % 360;

function way(angle, kind, basis) {
  if (kind === "couple") return angle === 270 ? "clockwise" : "counter-clockwise";
  const named = {0: `along +${basis[0]}`, 90: `along +${basis[1]}`, 180: `along −${basis[0]}`, 270: `along −${basis[1]}`};
  return named[angle] || `${angle}° from +${basis[0]}`;
}

class Drawing {
  constructor(root) {
    this.root = root;
    this.loads = [];
    this.picked = -1;
    this.version = null;
    this.trigger = null;
    root.replaceChildren();
    const style = el("style");
    style.textContent = CSS;
    this.box = el("div", {class: "dl-draw"});
    root.append(style, this.box);
  }

  setup(data) {
    this.data = data;
    this.kinds = data.law === "impulse" ? ["impulse", "force", "couple"] : ["force", "impulse", "couple"];
    this.box.replaceChildren();
    const bar = el("div", {class: "dl-draw-bar"});
    const kindLabel = el("label", {}, "Kind");
    this.kind = el("select", {"data-dl": "kind"});
    for (const k of this.kinds) this.kind.append(el("option", {value: k}, WORDS[k]));
    kindLabel.append(this.kind);
    const nameLabel = el("label", {}, "Name");
    this.name = el("input", {type: "text", maxlength: "40", autocomplete: "off", spellcheck: "false",
                             placeholder: "e.g. W", "data-dl": "name"});
    nameLabel.append(this.name);
    this.pointLabel = el("label", {}, "At");
    this.point = el("select", {"data-dl": "point"});
    data.points.forEach((p, i) => this.point.append(el("option", {value: String(i)}, this.spotName(p))));
    this.pointLabel.append(this.point);
    const add = el("button", {type: "button", "data-dl": "add"}, "Add");
    add.addEventListener("click", () => this.add());
    this.name.addEventListener("keydown", (e) => { if (e.key === "Enter") { e.preventDefault(); this.add(); } });
    bar.append(kindLabel, nameLabel, this.pointLabel, add);

    const canvas = el("div", {class: "dl-draw-canvas"});
    canvas.innerHTML = data.svg;  // the server's own SVG (viz.diagram.blank): no student text in it
    this.svg = canvas.querySelector("svg");
    this.svg.removeAttribute("width");
    this.svg.removeAttribute("height");
    this.svg.style.maxWidth = `${Math.round(data.size[0] * 1.3)}px`;
    this.svg.setAttribute("tabindex", "0");
    this.svg.setAttribute("role", "application");
    this.svg.setAttribute("aria-roledescription", "drawing");
    this.svg.setAttribute("aria-label", `${this.svg.getAttribute("aria-label")} Arrow keys move and turn the selected load; `
      + "Delete removes it; N selects the next.");
    this.spots = svgEl("g");
    this.layer = svgEl("g");
    this.svg.append(this.spots, this.layer);
    for (const [i, p] of data.points.entries()) {
      const spot = svgEl("circle", {cx: p.x, cy: p.y, r: 14, fill: "transparent", class: "dl-draw-spot",
                                    "data-point": i});
      spot.addEventListener("click", (e) => { e.stopPropagation(); this.moveTo(i); });
      this.spots.append(spot);
    }
    this.svg.addEventListener("keydown", (e) => this.key(e));

    const help = el("p", {class: "dl-draw-help"},
      "Add each load at its point. Tap a load to select it, drag its round handle to turn it, tap a point to move it "
      + "there; or use the list below, or the arrow keys on the drawing. Give a reaction whose direction you do not "
      + "know as one load or as its two components.");
    this.list = el("ol", {"aria-label": "The loads drawn"});
    this.empty = el("p", {class: "dl-draw-empty"}, "No load drawn yet.");
    this.live = el("div", {class: "dl-sr", "aria-live": "polite", role: "status"});
    this.check = el("button", {type: "button", class: "dl-draw-primary", "data-dl": "check"}, "Check the diagram");
    this.check.addEventListener("click", () => this.send());
    this.box.append(bar, canvas, help, this.empty, this.list, this.check, this.live);
  }

  spotName(p) {
    return this.data.bodies.length > 1 ? `${p.name} on ${p.body}` : p.name;
  }

  pointOf(load) {
    return this.data.points.findIndex((p) => p.body === load.body && p.name === load.at);
  }

  say(text) {
    this.live.textContent = "";
    requestAnimationFrame(() => { this.live.textContent = text; });
  }

  describe(load) {
    const name = load.name ? `“${load.name}”` : "unnamed";
    return `${WORDS[load.kind]} ${name} at ${this.spotName(this.data.points[this.pointOf(load)])}, ${way(load.angle, load.kind, this.data.basis)}`;
  }

  add() {
    const p = this.data.points[Number(this.point.value) || 0];
    const kind = this.kind.value;
    const load = {kind, body: p.body, at: p.name, angle: kind === "couple" ? 90 : 270, name: this.name.value.trim().slice(0, 40)};
    this.loads.push(load);
    this.picked = this.loads.length - 1;
    this.name.value = "";
    this.draw();
    this.say(`Added: ${this.describe(load)}. Load ${this.picked + 1} of ${this.loads.length}.`);
  }

  remove(i) {
    const [gone] = this.loads.splice(i, 1);
    this.picked = Math.min(this.picked, this.loads.length - 1);
    this.draw();
    this.say(`Removed: ${this.describe(gone)}. ${this.loads.length} drawn.`);
    if (!this.loads.length) this.name.focus();
  }

  turn(i, by) {
    const load = this.loads[i];
    load.angle = load.kind === "couple" ? (load.angle === 90 ? 270 : 90) : norm(load.angle + by);
    this.draw();
    this.say(this.describe(load));
  }

  moveTo(point, i = this.picked) {
    if (i < 0 || !this.loads[i]) return;
    const p = this.data.points[point];
    Object.assign(this.loads[i], {body: p.body, at: p.name});
    this.draw();
    this.say(`Moved: ${this.describe(this.loads[i])}`);
  }

  pick(i) {
    this.picked = i;
    this.draw();
    if (this.loads[i]) this.say(`Selected: ${this.describe(this.loads[i])}`);
  }

  key(e) {
    const i = this.picked, load = this.loads[i];
    if (e.key === "n" || e.key === "N") {
      if (this.loads.length) this.pick((i + 1) % this.loads.length);
    } else if (!load) {
      return;
    } else if (e.key === "ArrowLeft" || e.key === "ArrowRight") {
      const same = this.data.points.map((p, n) => n).filter((n) => this.data.points[n].body === load.body || this.data.bodies.length > 1);
      const at = same.indexOf(this.pointOf(load));
      this.moveTo(same[(at + (e.key === "ArrowRight" ? 1 : -1) + same.length) % same.length]);
    } else if (e.key === "ArrowUp" || e.key === "ArrowDown") {
      this.turn(i, e.key === "ArrowUp" ? STEP : -STEP);
    } else if (e.key === "Delete" || e.key === "Backspace") {
      this.remove(i);
    } else {
      return;
    }
    e.preventDefault();
  }

  // the pointer turns the selected load: the angle from its point to the pointer, in the basis (y up)
  drag(e, i) {
    e.preventDefault();
    e.stopPropagation();
    this.pick(i);
    const target = this.svg;  // (the handle is redrawn while it moves: the drawing holds the pointer)
    target.setPointerCapture(e.pointerId);
    const move = (ev) => {
      const m = this.svg.getScreenCTM();
      if (!m) return;
      const q = new DOMPoint(ev.clientX, ev.clientY).matrixTransform(m.inverse());
      const p = this.data.points[this.pointOf(this.loads[i])];
      const angle = norm(Math.atan2(p.y - q.y, q.x - p.x) * 180 / Math.PI);
      if (this.loads[i].kind === "couple") this.loads[i].angle = q.x >= p.x ? 90 : 270;
      else this.loads[i].angle = angle;
      this.drawArrows();
      this.readout(i);
    };
    const up = () => {
      target.removeEventListener("pointermove", move);
      target.removeEventListener("pointerup", up);
      target.removeEventListener("pointercancel", up);
      this.draw();
      this.say(this.describe(this.loads[i]));
    };
    target.addEventListener("pointermove", move);
    target.addEventListener("pointerup", up);
    target.addEventListener("pointercancel", up);
  }

  draw() {
    this.drawArrows();
    this.drawList();
  }

  drawArrows() {
    this.layer.replaceChildren();
    this.loads.forEach((load, i) => {
      const p = this.data.points[this.pointOf(load)];
      const picked = i === this.picked;
      const color = picked ? PICKED : COLOR;
      const g = svgEl("g", {"data-load": i});
      const rad = load.angle * Math.PI / 180;
      let hx, hy;
      if (load.kind === "couple") {
        const r = 26, ccw = load.angle !== 270;
        const a0 = -0.6 * Math.PI, a1 = 0.9 * Math.PI;
        const pts = [];
        for (let k = 0; k <= 20; k++) {
          const a = a0 + (a1 - a0) * k / 20;
          pts.push([p.x + r * Math.cos(a), p.y - r * Math.sin(a)]);
        }
        if (!ccw) pts.reverse();
        g.append(svgEl("polyline", {points: pts.slice(0, -1).map((q) => q.join(",")).join(" "), fill: "none",
                                    stroke: color, "stroke-width": picked ? 4 : 3}));
        g.append(this.head(pts[pts.length - 4], pts[pts.length - 1], color, false));
        [hx, hy] = pts[Math.floor(pts.length / 2)];
      } else {
        hx = p.x + ARROW * Math.cos(rad);
        hy = p.y - ARROW * Math.sin(rad);
        const sx = p.x + (ARROW - 10) * Math.cos(rad), sy = p.y - (ARROW - 10) * Math.sin(rad);
        g.append(svgEl("line", {x1: p.x, y1: p.y, x2: sx, y2: sy, stroke: color, "stroke-width": picked ? 4 : 3}));
        g.append(this.head([p.x, p.y], [hx, hy], color, load.kind === "impulse"));
      }
      // the handle beyond the head, so a finger on it leaves the arrow in sight; the name beside the head
      const ux = load.kind === "couple" ? 1 : Math.cos(rad), uy = load.kind === "couple" ? 0 : -Math.sin(rad);
      const cx = hx + (HANDLE + 4) * ux, cy = hy + (HANDLE + 4) * uy;
      if (load.name) {
        const t = svgEl("text", {x: hx - 16 * uy, y: hy + 16 * ux + 5, "font-size": 16, fill: color,
                                 "text-anchor": "middle", "font-style": "italic"});
        // (the drawing holds a symbol's length: a longer name is cut there, written in full in the list below)
        t.textContent = load.name.length > DRAWN_NAME ? load.name.slice(0, DRAWN_NAME - 1) + "…" : load.name;
        g.append(t);
      }
      const handle = svgEl("circle", {cx, cy, r: HANDLE, fill: picked ? "rgba(230,159,0,.18)" : "transparent",
                                      stroke: picked ? PICKED : "none", "stroke-dasharray": "3 3",
                                      class: "dl-draw-handle"});
      handle.addEventListener("pointerdown", (e) => this.drag(e, i));
      g.addEventListener("click", (e) => { e.stopPropagation(); this.pick(i); });
      g.append(handle);
      this.layer.append(g);
    });
  }

  head(from, to, color, open) {
    const dx = to[0] - from[0], dy = to[1] - from[1], n = Math.hypot(dx, dy) || 1;
    const ux = dx / n, uy = dy / n, size = 12, w = 0.42;
    const bx = to[0] - ux * size, by = to[1] - uy * size;
    const pts = [to, [bx - uy * size * w, by + ux * size * w], [bx + uy * size * w, by - ux * size * w]];
    return svgEl("polygon", {points: pts.map((q) => q.map((v) => v.toFixed(1)).join(",")).join(" "),
                             fill: open ? "#ffffff" : color, stroke: color, "stroke-width": 2});
  }

  readout(i) {
    const row = this.list.children[i];
    const out = row && row.querySelector("output");
    if (out) out.textContent = way(this.loads[i].angle, this.loads[i].kind, this.data.basis);
  }

  drawList() {
    this.list.replaceChildren();
    this.empty.hidden = this.loads.length > 0;
    this.loads.forEach((load, i) => {
      const li = el("li", {"aria-current": String(i === this.picked)});
      const row = el("div", {class: "dl-draw-row"});
      const title = el("span", {}, `${WORDS[load.kind]} ${load.name ? `“${load.name}”` : "(unnamed)"} at`);
      const at = el("select", {"aria-label": `Point of load ${i + 1}`});
      this.data.points.forEach((p, n) => at.append(el("option", {value: String(n)}, this.spotName(p))));
      at.value = String(this.pointOf(load));
      at.addEventListener("change", () => { this.picked = i; this.moveTo(Number(at.value), i); });
      const dir = el("output", {"aria-label": `Direction of load ${i + 1}`}, way(load.angle, load.kind, this.data.basis));
      const ccw = el("button", {type: "button", "aria-label": load.kind === "couple" ? `Reverse load ${i + 1}` :
                                `Turn load ${i + 1} ${STEP}° counter-clockwise`}, load.kind === "couple" ? "⇄" : `↺ ${STEP}°`);
      ccw.addEventListener("click", () => { this.picked = i; this.turn(i, STEP); });
      row.append(title, at, dir, ccw);
      if (load.kind !== "couple") {
        const cw = el("button", {type: "button", "aria-label": `Turn load ${i + 1} ${STEP}° clockwise`}, `↻ ${STEP}°`);
        cw.addEventListener("click", () => { this.picked = i; this.turn(i, -STEP); });
        row.append(cw);
      }
      const del = el("button", {type: "button", "aria-label": `Remove load ${i + 1}`}, "Remove");
      del.addEventListener("click", () => this.remove(i));
      row.append(del);
      li.append(row);
      this.list.append(li);
    });
  }

  send() {
    if (!this.trigger) return;
    this.check.setAttribute("aria-busy", "true");
    this.trigger("check", JSON.stringify(this.loads));
  }

  update(data, trigger) {
    this.trigger = trigger;
    if (this.version !== data.canvas_key) {
      this.version = data.canvas_key;
      this.setup(data);
      this.loads = Array.isArray(data.drawn) ? data.drawn.map((l) => ({...l, angle: norm(Number(l.angle) || 0),
                                                                       name: String(l.name || "").slice(0, 40)}))
        .filter((l) => this.pointOf(l) >= 0) : [];
      this.picked = this.loads.length - 1;
      this.draw();
    }
    this.check.removeAttribute("aria-busy");
  }
}

const decoder = new TextDecoder();

export function render({data, parentElement, setTriggerValue}) {
  let drawing = drawings.get(parentElement);
  if (!drawing) drawings.set(parentElement, drawing = new Drawing(parentElement));
  drawing.update(JSON.parse(typeof data === "string" ? data : decoder.decode(data)), setTriggerValue || null);
}
