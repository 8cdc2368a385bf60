// Live values while a lesson control is dragged (ui/live.py), imported by the answers' element (text.js)
// on the lesson page only (Study and Lecture: never in Practice, a variant or an assignment, where it
// would give the answers away).
//
// Streamlit reruns the page when a slider is released; while it is dragged (mouse or touch) its thumb's
// value changes in the page alone, and here a key held on it (or pressed again and again) does the same
// until the key is up (see "a held key" below). This module watches the stage's controls
// (the slider's range input, a number box's typing), and on the next animation frame (one per frame,
// however many events came) evaluates the problem's generated function (solvers/live.py: generated
// from the solver's sympy chain, never typed here) with the value shown, converted to SI, and writes
// the answers' values as the page formats them (``plainNumber``: solvers/formatting.plain_number's
// rules). What it cannot compute (an integral, a refused value, past a physical limit) is marked
// "updating…", never left stale: the figure, its caption (but its headline, see liveCaption), the notes, the checks and the derivation
// are dimmed and say so until the server's run replaces them. A regime the drag enters is said in
// words above the answers. Once the run after the release is done, everything is the server's
// again, and the main answer is said once to a screen reader (a polite live region).
"use strict";

const STYLE = `
.dl-live-stale { opacity: 0.35 !important; transition: none; }  /* over the caption's own .75 */
.dl-figure { position: relative; }
/* one line over the figure's title, clear of Play below it (a long note is cut short: …) */
.dl-live-badge { position: absolute; top: 0; left: 0; right: 0; z-index: 5; font-size: 1rem; line-height: 1.35; padding: 0.05em 0.6em; margin: 0 0 0.3rem 0; border-radius: 0.4em;
  white-space: nowrap; overflow: hidden; text-overflow: ellipsis;
  background: var(--st-orange-background-color, #FFF3E0); color: var(--st-orange-text-color, #9B4519); }
.dl-live-badge .dl-live-note { font-size: 0.8rem; margin-left: 0.6em; opacity: 0.9; }
.dl-live-badge.dl-live-note-only { white-space: normal; }  /* over Play too: the figure is dimmed, nothing to play */
.dl-live-badge.dl-live-note-only .dl-live-note { display: none; }
.dl-figure.dl-lecture .dl-live-badge { font-size: 1.3rem; }  /* read from the back of the room, as the title it covers */
/* a phone: the headline and its unit whole (the figure is dimmed), over two lines where the answer's words
   are long ("angular speed when the top leaves the wall: …"), never cut */
@media (max-width: 640px) { .dl-live-badge .dl-live-note { display: none; } .dl-live-badge { white-space: normal; } }
.dl-live-status { font-size: 0.95rem; margin: 0 0 0.5rem 0; color: var(--st-orange-text-color, #9B4519); font-weight: 600; }
.dl-live-status:empty { display: none; }
.dl-live-value { font-variant-numeric: tabular-nums; }
.dl-live-waiting { font-weight: 400; font-style: italic; color: var(--st-orange-text-color, #9B4519); }
/* a stage slider's −/+ (one step each) on a narrow screen, under the ends of its track, thumb-sized: the
   track keeps the column's whole width (between them it had a third of it, too short to drag to a value) */
.dl-step { display: none; }
@media (max-width: 640px) {
  ${DOM.stageControls} .dl-stepped { position: relative; padding-bottom: 32px; }
  ${DOM.stageControls} .dl-stepped ${DOM.sliderThumbValue} { z-index: 1; }
  /* 44 px wide, 32 tall: wholly below the track's 40 px of touch, so a finger a little low on the thumb
     still drags it (44 tall, they reached 12 px into it and took the drag) */
  ${DOM.stageControls} .dl-step { display: block; position: absolute; bottom: 0; width: 44px; height: 32px; padding: 0;
    font-size: 1.4rem; line-height: 1; border-radius: 0.5rem; cursor: pointer; touch-action: manipulation;
    border: 1px solid rgba(128, 128, 128, 0.6); background: rgba(128, 128, 128, 0.12); color: inherit; }  /* the theme's text, light or dark */
  /* the track's end values (shown while it is touched) under its ends, the −/+ just inside them (between the
     −/+ they stood bunched mid-track, "0 100" in 64 px of a 172 px track) */
  ${DOM.stageControls} .dl-stepped ${DOM.sliderTickBar} { margin-left: var(--dl-ends-margin, 48px);
    margin-right: var(--dl-ends-margin, 48px); }
  ${DOM.stageControls} .dl-stepped ${DOM.sliderTickBar} p { font-size: 0.75rem; }
  /* shown at rest too (Streamlit shows them only while the track is touched): a finger sees the range before
     it moves, and the −/+ stand inside values that are there, not inside a gap */
  ${DOM.stageControls} .dl-stepped ${DOM.sliderTickBar} { opacity: 1 !important; }
  ${DOM.stageControls} .dl-step[data-steps='-1'] { left: var(--dl-low-end, 0px); }
  ${DOM.stageControls} .dl-step[data-steps='1'] { right: var(--dl-high-end, 0px); }
}
/* a short phone (360×740): at the track's ends, so that the figure, Play and the controls still share the first
   screen (under the track they would push the second row of controls below it) */
@media (max-width: 640px) and (max-height: 800px) {
  ${DOM.stageControls} .dl-stepped { padding-bottom: 0; }
  ${DOM.stageControls} .dl-stepped > [role='group'] { padding-left: 56px; padding-right: 56px; }
  ${DOM.stageControls} .dl-step { bottom: 4px; }  /* level with the thumb */
  ${DOM.stageControls} .dl-step[data-steps='-1'] { left: 0; }
  ${DOM.stageControls} .dl-step[data-steps='1'] { right: 0; }
  ${DOM.stageControls} .dl-stepped ${DOM.sliderTickBar} { margin-left: -6px; margin-right: -6px; }
}
@media print { .dl-step { display: none !important; } }
.dl-live-sr { position: absolute; width: 1px; height: 1px; overflow: hidden; clip-path: inset(50%); white-space: nowrap; }
`;
const UPDATING = "updating…";

// ------------------------------------------------------------------ numbers as the page writes them
const SUPERSCRIPT = {"0": "⁰", "1": "¹", "2": "²", "3": "³", "4": "⁴", "5": "⁵", "6": "⁶", "7": "⁷", "8": "⁸", "9": "⁹", "-": "⁻"};

// Python's float(f"{x:.{sig}g}"): the exact binary value rounded to ``sig`` figures, a tie to even
// (JavaScript's toPrecision breaks a tie away from zero).
export function roundSig(x, sig) {
  const away = Number(x.toPrecision(sig));
  const [mantissa, exponent] = x.toExponential(Math.min(100, sig + 24)).split("e");
  const digits = mantissa.replace("-", "").replace(".", "");
  if (!/^50*$/.test(digits.slice(sig)) || Number(digits[sig - 1]) % 2 === 1) return away;
  return Number(`${x < 0 ? "-" : ""}${digits[0]}.${digits.slice(1, sig)}e${exponent}`);
}

// solvers/formatting.plain_number: ``sig`` figures and a true minus; digits grouped by narrow no-break
// spaces from ten thousand, a typeset power of ten from ``groupedBelow`` and below 10⁻⁴, never −0.
export function plainNumber(x, sig = 4, groupedBelow = 1e6) {
  if (x === Infinity) return "∞";
  if (x === -Infinity) return "−∞";
  const rounded = roundSig(x, sig);
  if (rounded === 0) return "0";
  const size = Math.abs(rounded);
  let text;
  if (size >= groupedBelow || size < 1e-4) {
    let [mantissa, exponent] = rounded.toExponential(sig - 1).split("e");
    if (mantissa.includes(".")) mantissa = mantissa.replace(/0+$/, "").replace(/\.$/, "");
    text = `${mantissa}\u202f×\u202f10${String(Number(exponent)).replace(/./g, (c) => SUPERSCRIPT[c])}`;
  } else if (size >= 1e4) {
    const decimals = Math.max(0, sig - String(Math.trunc(size)).length);
    let [whole, fraction] = rounded.toFixed(decimals).split(".");
    whole = whole.replace(/\B(?=(\d{3})+(?!\d))/g, "\u202f");
    if (fraction !== undefined) fraction = fraction.replace(/0+$/, "");
    text = fraction ? `${whole}.${fraction}` : whole;
  } else {
    text = String(rounded);
  }
  return text.replace(/-/g, "−");
}

// ui/results.answer_rows: the value in the unit shown (degrees glued), an angle in radians too.
export function quantity(x, [, unit, factor, angle], groupedBelow) {
  const shown = plainNumber(x * factor, 4, groupedBelow);
  const value = !unit ? shown : unit === "°" ? shown + unit : `${shown} ${unit}`;
  return angle ? `${value} (${plainNumber(x, 4, groupedBelow)} rad)` : value;
}

// solvers/formatting.plain_fixed: ``decimals`` decimals, a tie to even (Python's format; JavaScript's
// toFixed breaks a tie away from zero), a true minus, never −0.
export function plainFixed(x, decimals = 1) {
  let text = x.toFixed(decimals);
  const exact = Math.abs(x).toFixed(Math.min(100, decimals + 30)), point = exact.indexOf(".");
  const kept = exact.slice(0, point + 1 + decimals).replace(/\.$/, "");
  if (/^50*$/.test(exact.slice(point + 1 + decimals)) && Number(kept.slice(-1)) % 2 === 0) text = (x < 0 ? "-" : "") + kept;
  return Number(text) === 0 ? text.replace("-", "") : text.replace("-", "−");
}

// viz.common.headline_text: a caption's headline with these values (SI), or null if one is missing.
export function headlineText(parts, values, groupedBelow) {
  let text = "";
  for (const part of parts) {
    if (typeof part === "string") { text += part; continue; }
    const [name, kind, digits] = part, x = values[name];
    if (!Number.isFinite(x)) return null;
    const degrees = x * (180 / Math.PI);  // Python's math.degrees
    text += kind === "n" ? plainNumber(x, digits, groupedBelow)
      : kind === "deg" ? plainFixed(degrees, digits) + "°" : plainNumber(degrees, digits, groupedBelow) + "°";
  }
  return text;
}

// numpy's round(x, digits), as viz.common.r rounds every coordinate a figure draws: x·10^digits to the
// nearest integer, a tie to even (Math.round breaks a tie upward), then divided back.
export function roundedLike(x, digits) {
  if (x === null || !Number.isFinite(x)) return null;  // a gap (NaN) in a polyline
  const scale = 10 ** digits, y = x * scale, floor = Math.floor(y), rest = y - floor;
  const whole = rest > 0.5 || (rest === 0.5 && floor % 2 !== 0) ? floor + 1 : floor;
  return whole / scale;
}

// A generated pose (solvers/live.pose_source: trace -> [xs, ys]) for parameters ``p`` and the live
// values, rounded as the figure's own coordinates are; null where an input is missing.
export function poseOf(fn, p, values, digits) {
  const drawn = fn(p, values, (x) => roundedLike(x, digits));
  if (!drawn) return null;
  const out = {};
  for (const [name, rows] of Object.entries(drawn)) out[name] = rows.map((row) => row.map((x) => roundedLike(x, digits)));
  return out;
}

// A motion whose frames the browser computes (viz/common.py: animated_in_browser), from the module
// generated for it (ui/live.py: motion_source: the live values, the frames' times and the bodies'
// pose at a time): the times (to the microsecond, as the server writes them) and each moving trace's
// rows, one per frame, rounded as the server rounds its own; a trail as the path so far of its point.
// ``ranges``: the axes widened where the frames reach past them (viz/common.py: holding, to ``hold``
// of the larger span). Null where the generated code has no value for these parameters.
// A motion integrated here (``gen.integrated``: solvers/live.py's Integrated) has no closed form for its
// times: they are ``frames`` instants evenly over it and each framed leg's end, and the state at each
// is among the values the pose reads, by the state's names. ``anim.traced``: static traces drawn from
// such a motion, [trace, pose name], at its ``curve`` instants (a plot against time: one point of the pose per instant).
// ``anim.posed``: [name, trail, keep, axes] (a trail keeps its last ``keep`` points, if given; ``axes``, what the
// pose's rows are: "xyz", or "y" for bars' heights).
export function motionOf(gen, anim, layout, digits) {
  const p = fromJSON(anim.params), live = gen.values(p);
  if (!live || !live.values) return null;
  const v = Object.assign({}, live.values), round = (x) => roundedLike(x, digits);
  for (const e of gen.events || []) v[e.name] = e.applies ? firstCrossing(e, p, v, round) : Infinity;
  const run = gen.integrated ? integrated(gen.integrated, p, v, round) : null;
  if (gen.integrated && !run) return null;
  const drawn = run ? {t: [run.instants(run.frames)]} : gen.times(p, v, round);
  if (!drawn) return null;
  const at = (t) => gen.pose(p, run ? Object.assign({}, v, run.stateAt(t)) : v, round, t);
  // (each trace's rows by axis: x and y, and z in a 3-D scene; a trail is in the plane)
  const times = drawn.t[0], coords = anim.posed.map(() => ({})), paths = anim.posed.map(() => ({x: [], y: []}));
  for (const [i, t] of times.entries()) {
    const pose = at(t);
    if (!pose) return null;
    anim.posed.forEach(([name, trail, keep, axes = "xyz"], n) => {
      const rows = pose[name].map((row) => row.map(round));
      if (trail) {
        paths[n].x.push(rows[0][0]);
        paths[n].y.push(rows[1][0]);
      }
      const from = keep == null ? 0 : Math.max(0, i - keep);
      rows.forEach((row, k) => {
        const axis = axes[k];
        (coords[n][axis] ||= []).push(trail ? paths[n][axis].slice(from) : row);
      });
    });
  }
  const traced = [];
  for (const [trace, name] of (run && anim.traced) || []) {
    const line = {trace, x: [], y: []};
    for (const t of run.instants(gen.integrated.curve)) {
      const pose = at(t);
      if (!pose) return null;
      line.x.push(round(pose[name][0][0]));
      line.y.push(round(pose[name][1][0]));
    }
    traced.push(line);
  }
  return {times: times.map((t) => roundedLike(t, 6)), coords, traced,
          ranges: anim.hold == null ? null : holding(coords, layout, anim.hold, digits)};
}

// ------------------------------------------------------------------ a motion integrated in the browser
// (issue 51: solvers/live.py's Integrated, generated by ui/live.py as ``integrated``): each leg from the
// last one's end (after its ``then``, an impact), by an adaptive Dormand–Prince 5(4) step (the tableau,
// error estimate, step control and first step of scipy's RK45) to the declared rtol and atol, until its
// ``ends`` falls through zero; a leg that does not end within ``horizon`` ends the motion there. The
// state between two steps is one step of the method from the earlier (to the step's own accuracy: a
// cubic through the two would be off by 1e-7 rad on a step of 0.1 s), and a leg's end is found on it
// by the Illinois method (regula falsi, the stale end's value halved), to 1e-15 of the time or g = 0. Null where a generated function has no value (an input not finite).
const DP_A = [[], [1 / 5], [3 / 40, 9 / 40], [44 / 45, -56 / 15, 32 / 9],
  [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729], [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]];
const DP_B = [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84];
const DP_E = [-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40];

export function integrated(spec, p, v, round) {
  const names = spec.state, [rtol, atol] = spec.tolerances;
  const named = (y) => Object.fromEntries(names.map((n, i) => [n, y[i]]));
  const scope = Object.assign({}, v);  // the values and the state, set in place before each call
  const call = (fn, y) => {
    if (y) for (let i = 0; i < names.length; i++) scope[names[i]] = y[i];
    const out = fn(p, scope, round);
    return out ? out.y[0] : null;
  };
  const f = (y) => call(spec.rates, y), horizon = call(spec.horizon)?.[0];
  let y = call(spec.start);
  if (!y || !Number.isFinite(horizon)) return null;
  const legs = [], framed = [];
  let t = 0, begin = 0;  // (the frames start at the end of a leg that ``opens`` them, else at 0)
  for (const leg of spec.legs) {
    const ends = (z) => call(leg.ends, z)?.[0];
    const run = integrateLeg(f, ends, t, y, t + horizon, rtol, atol);
    if (!run) return null;
    legs.push(run);
    t = run.t[run.t.length - 1];
    y = run.y[run.y.length - 1];
    if (!run.ended) break;
    if (leg.opens) begin = t;
    if (leg.framed) framed.push(t);
    if (call(leg.last, y)?.[0]) break;
    if (leg.then) {
      y = call(leg.then, y);
      if (!y) return null;
    }
  }
  const end = t, fastest = spec.fastest ? call(spec.fastest)?.[0] : null;
  if (spec.fastest && !Number.isFinite(fastest)) return null;
  return {
    // how many even instants the frames take (solvers/live.py: Integrated.frame_count)
    frames: fastest == null ? spec.frames : Math.max(spec.frames, Math.min(spec.most, Math.ceil((end - begin) * fastest / spec.turn) + 1)),
    // ``count`` instants evenly from the beginning to the end (numpy.linspace's) and each framed end, in order;
    // an even instant within 1e-6 of the span of a framed end is that end (solvers/live.py's frame_instants)
    instants(count) {
      const span = end - begin, near = 1e-6 * span;
      const times = Array.from({length: count}, (_, i) => (i === count - 1 ? end : begin + (i * span) / (count - 1)));
      for (const f of framed) {
        let i = 0;
        for (let j = 1; j < count; j++) if (Math.abs(times[j] - f) < Math.abs(times[i] - f)) i = j;
        if (Math.abs(times[i] - f) <= near) times[i] = f; else times.push(f);
      }
      return [...new Set(times)].sort((a, b) => a - b);
    },
    // the state at ``t``: from the leg it falls in (a leg's end: the leg that ends there, before its ``then``)
    stateAt(time) {
      const leg = legs.find((l) => time <= l.t[l.t.length - 1]) || legs[legs.length - 1];
      const ts = leg.t;
      if (time >= ts[ts.length - 1]) return named(leg.y[ts.length - 1]);
      if (time <= ts[0]) return named(leg.y[0]);
      let lo = 0, hi = ts.length - 1;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (ts[mid] <= time) lo = mid; else hi = mid;
      }
      const at = dpStep(f, leg.y[lo], leg.dy[lo], time - ts[lo]);
      return at ? named(at.y) : named(leg.y[lo]);
    },
  };
}

// One Dormand–Prince step of ``h`` from ``y`` (its rates ``k0``): the new state and the seven stages'
// rates (the last, the new state's); null where a rate has no value.
function dpStep(f, y, k0, h) {
  const K = [k0];
  for (let s = 1; s < 6; s++) {
    const k = f(y.map((yi, i) => yi + h * DP_A[s].reduce((acc, a, j) => acc + a * K[j][i], 0)));
    if (!k) return null;
    K.push(k);
  }
  const yNew = y.map((yi, i) => yi + h * DP_B.reduce((acc, b, j) => acc + b * K[j][i], 0));
  const kNew = f(yNew);
  if (!kNew) return null;
  K.push(kNew);
  return {y: yNew, K};
}

// One leg: the steps' times, states and rates, ``ended`` where ``ends`` fell through zero before ``until``.
function integrateLeg(f, ends, t0, y0, until, rtol, atol) {
  const n = y0.length, norm = (x) => Math.sqrt(x.reduce((s, xi) => s + xi * xi, 0) / n);
  const ts = [t0], ys = [y0], dys = [];
  let k0 = f(y0);
  const g0 = ends(y0);
  if (!k0 || !Number.isFinite(g0)) return null;
  dys.push(k0);
  if (g0 <= 0) return {t: ts, y: ys, dy: dys, ended: true};
  // the first step (scipy's select_initial_step)
  const scale0 = y0.map((yi) => atol + Math.abs(yi) * rtol);
  const d0 = norm(y0.map((yi, i) => yi / scale0[i])), d1 = norm(k0.map((ki, i) => ki / scale0[i]));
  const h0 = d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1;
  const k1 = f(y0.map((yi, i) => yi + h0 * k0[i]));
  if (!k1) return null;
  const d2 = norm(k1.map((ki, i) => (ki - k0[i]) / scale0[i])) / h0;
  let h = Math.min(100 * h0, d1 <= 1e-15 && d2 <= 1e-15 ? Math.max(1e-6, h0 * 1e-3) : (0.01 / Math.max(d1, d2)) ** (1 / 5));
  let t = t0, y = y0;
  for (let steps = 0; steps < 100000 && t < until; steps++) {
    h = Math.min(h, until - t);
    const step = dpStep(f, y, k0, h);
    if (!step) return null;
    const {y: yNew, K} = step, kNew = K[6];
    const error = norm(y.map((yi, i) => h * DP_E.reduce((acc, e, j) => acc + e * K[j][i], 0)
                                 / (atol + Math.max(Math.abs(yi), Math.abs(yNew[i])) * rtol)));
    if (!Number.isFinite(error)) return null;
    if (error > 1) {  // rejected: a smaller step
      h *= Math.max(0.2, 0.9 * error ** -0.2);
      continue;
    }
    const tNew = t + h, gNew = ends(yNew);
    if (!Number.isFinite(gNew)) return null;
    if (gNew <= 0) {  // the leg ends in this step: where, by the Illinois method on the step from t
      let lo = t, hi = tNew, gLo = ends(y), gHi = gNew, yEnd = yNew, kEnd = kNew, side = 0;
      for (let i = 0; i < 200 && hi - lo > 1e-15 * Math.max(1, Math.abs(hi)); i++) {
        let mid = (lo * gHi - hi * gLo) / (gHi - gLo);  // where the chord crosses zero
        if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;  // no double between them
        const at = dpStep(f, y, k0, mid - t);
        if (!at) return null;
        const g = ends(at.y);
        if (!Number.isFinite(g)) return null;
        if (g > 0) {
          [lo, gLo] = [mid, g];
          if (side === 1) gHi /= 2;  // the same end twice: halve the other's weight
          side = 1;
        } else {
          [hi, gHi, yEnd, kEnd] = [mid, g, at.y, at.K[6]];
          if (side === -1) gLo /= 2;
          side = -1;
        }
        if (g === 0) break;
      }
      ts.push(hi); ys.push(yEnd); dys.push(kEnd);
      return {t: ts, y: ys, dy: dys, ended: true};
    }
    ts.push(tNew); ys.push(yNew); dys.push(kNew);
    t = tNew; y = yNew; k0 = kNew;
    h *= error === 0 ? 10 : Math.min(10, 0.9 * error ** -0.2);
  }
  return {t: ts, y: ys, dy: dys, ended: false};
}

// An event's time (solvers/live.py: Event, first_crossing): the first point of the grid of ``points`` steps
// over (0, until] where the crossing is below 0, then halved between it and the point before to 1e-13 of
// it (the server's brentq: to 1e-12 s); Infinity where it never is.
function firstCrossing(e, p, v, round) {
  const value = (t) => e.crossing(p, v, round, t).f[0][0], until = e.until(p, v, round).t[0][0];
  let before = 0;
  for (let i = 1; i <= e.points; i++) {
    const t = i === e.points ? until : i * (until / e.points);  // numpy.linspace's points
    if (value(t) < 0) {
      if (i === 1) return t;
      let lo = before, hi = t;
      while (hi - lo > 1e-13 * hi) {
        const mid = 0.5 * (lo + hi);
        if (value(mid) < 0) hi = mid; else lo = mid;
      }
      return hi;
    }
    before = t;
  }
  return Infinity;
}

function holding(coords, layout, pad, digits) {
  const reach = (key) => {
    const all = coords.flatMap((c) => c[key].flat()).filter((x) => x !== null && Number.isFinite(x));
    return [Math.min(...all), Math.max(...all)];
  };
  const [x, y] = [reach("x"), reach("y")];
  const margin = pad * Math.max(x[1] - x[0], y[1] - y[0], 1e-9);
  const held = (range, [lo, hi]) => [roundedLike(Math.min(range[0], lo - margin), digits), roundedLike(Math.max(range[1], hi + margin), digits)];
  return {x: held(layout.xaxis.range, x), y: held(layout.yaxis.range, y)};
}

// A generated function from its source (solvers/live.py), loaded as a module from a data: URL: how
// node evaluates the generated code against the server's numbers (tests/pages/test_live.py). The page
// imports the same code as the modules ui/live.py serves (loadModule).
const loadedFunctions = new Map();
export function load(source) {
  let fn = loadedFunctions.get(source);
  if (!fn) {
    const url = "data:text/javascript," + encodeURIComponent(`export default ${source};`);
    loadedFunctions.set(source, fn = import(url).then((m) => m.default));
  }
  return fn;
}

// A generated module served by the app (ui/live.py: the live values' function, a figure's pose), by its path.
const loadedModules = new Map();
function loadModule(path) {
  let fn = loadedModules.get(path);
  if (!fn) loadedModules.set(path, fn = import(new URL(path, location.href).href).then((m) => m.default));
  return fn;
}

// The parameters as JSON carries them: an infinite one (μ = ∞) as the word "inf" (ui/live.py).
export const fromJSON = (params) => Object.fromEntries(Object.entries(params).map(([k, v]) => [k, v === "inf" ? Infinity : v]));

// ------------------------------------------------------------------ the page while a control moves
let state = null;   // this page's data (the last run's), and the drag under way
let frame = 0;      // the animation frame requested, if any
let resting = 0;    // the timer that ends a live view whose controls are back at the run's values
const RESTING_MS = 300;

const $$ = (selector) => [...document.querySelectorAll(selector)];
const stage = () => document.querySelector(DOM.stage);
const answersTable = () => document.querySelector(".dl-text.dl-answers table");

// What the server drew that a live value cannot redraw: dimmed, with a word, until the run replaces it.
function staleParts() {
  const answers = document.querySelector(".dl-text.dl-answers");
  const own = answers ? [answers.querySelector("h3"), answersTable(), answers.querySelector(".dl-live-status")] : [];
  const caption = state.caption && state.caption.el, posed = state.pose && state.pose.fig.graph;
  return [...$$(".dl-figure > :not(.dl-live-badge)").filter((el) => el !== caption && el !== posed), ...(answers ? [...answers.children].filter((el) => !own.includes(el)) : []),
          ...$$(".dl-text.dl-derivation")];
}

function controlValue(name) {
  const [, key, factor] = state.data.follows.find(([n]) => n === name);
  const box = document.querySelector(`.${DOM.keyPrefix}${CSS.escape(key)} input`);
  if (!box) return null;
  if (dragged && dragged.input === box && dragged.value !== null && box.value === dragged.seen) return dragged.value;
  if (box.type === "range") return restingValue(box, state.params[name] * factor);
  return box.value === "" ? NaN : Number(box.value);
}

// A slider's value: the run's (``run``, as shown) while the slider shows it (its text, react-aria's
// state, to the figures it is written with) and its range input holds what the browser made of it; a
// value off the slider's steps (a link's 0.53 on a slider of 0.05 steps, a unit switch's 13.1234 ft) is
// shown as it is, but the input keeps it rounded to a step, as HTML sanitises a range's value.
export function restingValue(input, run) {
  const {min, max, step} = rangeOf(input), value = Number(input.value), text = Number(input.getAttribute("aria-valuetext"));
  const near = (a, b, tolerance) => Math.abs(a - b) <= tolerance * Math.max(1, Math.abs(b));
  return near(sanitised(run, min, max, step), value, 1e-9) && near(text, run, 1e-5) ? run : value;
}

// HTML's value sanitisation of a range input: the nearest step from its minimum (a tie: the greater),
// within its bounds.
export function sanitised(value, min, max, step) {
  const top = min + Math.floor((max - min) / step + 1e-9) * step;
  return clamp(min + Math.floor((value - min) / step + 0.5) * step, min, top);
}

// ------------------------------------------------------------------ a drag, in the frame it moves in
// The pointer's move comes with a frame (Chromium hands continuous input to the page just before its
// animation frame), but react-aria moves the thumb in a React render after that frame: read from the
// input, the answers would follow one frame behind. So a drag's value is worked out here from the
// pointer, as react-aria's slider works it out (useSlider's move: the thumb's place when the move
// starts plus the pointer's travel, over the track's width; useSliderState: to whole steps within the
// range), and used until React has drawn a value of its own. The pointer is captured by the track for
// the drag, as a touch is: the page is not hit-tested on every move, nor its hover styles redrawn.
//
// And the moves are kept from react-aria: its render of Streamlit's slider for each one took 6–8 ms
// after the move's frame (the slider's styled components insert a CSS rule for each new value, and
// the whole page is restyled), so a move now and then missed its frame. live.js draws what that
// render would, on each frame: the thumb at the value, its value as the thumb writes it (to the
// decimals it shows), the track's filled part (its gradient's stops) and the value's place at the
// ends of the track (as Streamlit's own layout effect places it). On release, one move to where the
// pointer is tells react-aria the value, and its release commits it as after any drag (a cancelled
// drag puts the thumb back). Where the slider is not drawn as expected, react-aria keeps the moves.
let dragged = null;  // {input, track, pageX, start, seen, value, drawn, last}: the stage slider being dragged

const clamp = (x, min, max) => Math.min(Math.max(x, min), max);
// A range input's bounds and step as numbers (a step of "any" or none: one).
const rangeOf = (input) => ({min: Number(input.min), max: Number(input.max), step: Number(input.step) || 1});

// @react-stately/utils' roundToStepPrecision and snapValueToStep
function roundToStep(value, step) {
  const text = String(step), e = text.toLowerCase().indexOf("e-"), point = text.indexOf(".");
  const precision = e > 0 ? Math.abs(Math.floor(Math.log10(Math.abs(step)))) + e : point >= 0 ? text.length - point : 0;
  if (precision <= 0) return value;
  const scale = 10 ** precision;
  return Math.round(value * scale) / scale;
}
export function snapToStep(value, min, max, step) {
  const remainder = (value - min) % step;
  let snapped = roundToStep(Math.abs(remainder) * 2 >= step ? value + Math.sign(remainder) * (step - Math.abs(remainder)) : value - remainder, step);
  if (snapped < min) snapped = min;
  else if (snapped > max) snapped = min + Math.floor(roundToStep((max - min) / step, step)) * step;
  return roundToStep(snapped, step);
}

// The value react-aria gives a thumb dragged ``travel`` px over a track ``size`` px wide from ``start`` (0–1).
export function draggedValue(start, travel, size, min, max, step) {
  const percent = clamp((start * size + travel) / size, 0, 1), atPercent = percent * (max - min) + min;
  return snapToStep(clamp(Math.round((atPercent - min) / step) * step + min, min, max), min, max, step);
}

function onDragStart(event) {
  const slider = event.target.closest && event.target.closest(`${DOM.stageControls} ${DOM.slider}`);
  // (none on a page without the live view: a run the solver refused has no answers to follow, and
  // react-aria draws the drag back to a value it takes)
  if (!slider || !state || !event.isPrimary || event.button !== 0 || event.target.closest(".dl-step")) return;
  const input = slider.querySelector("input[type='range']"), track = input && input.closest("[role='group'] > [data-orientation]");
  if (!track || !track.contains(event.target)) return;  // (a press on the label starts no drag)
  dragged = {input, track, pageX: event.pageX, start: null, seen: null, value: null, drawn: drawnParts(slider, track, input), last: null};
  try { track.setPointerCapture(event.pointerId); } catch (e) { /* a pointer already gone */ }
  window.addEventListener("pointermove", onDragMove, true);
  for (const type of ["pointerup", "pointercancel"]) window.addEventListener(type, onDragEnd, true);
}

function onDragMove(event) {
  if (!dragged || !event.isPrimary) return;
  const {input, track} = dragged, {min, max, step} = rangeOf(input);
  if (!(max > min)) return;
  if (dragged.start === null) dragged.start = (startValue(input) - min) / (max - min);  // after the press's render
  dragged.value = draggedValue(dragged.start, event.pageX - dragged.pageX, track.getBoundingClientRect().width, min, max, step);
  dragged.seen = input.value;  // what React shows until it draws this move (never, when drawn here)
  if (dragged.drawn) {
    event.stopImmediatePropagation();  // react-aria's own listener is the window's too, after this one
    dragged.last = event;
  }
  schedule();
}

// The control just released stays where it was on the screen, whatever the run puts above it (a
// refusal past a limit pushed a phone's slider below the screen): for a few seconds after the release,
// a move of its top is scrolled back, until the person scrolls or touches the page themselves.
const KEPT_MS = 4000;
let keeping = null;
function keepInPlace(element) {
  const key = [...element.classList].find((c) => c.startsWith(DOM.keyPrefix));
  if (!key) return;
  if (keeping) keeping.stop();
  const top = element.getBoundingClientRect().top, until = performance.now() + KEPT_MS;
  const stop = () => { keeping = null; for (const type of ["wheel", "touchstart", "keydown"]) window.removeEventListener(type, stop, true); };
  for (const type of ["wheel", "touchstart", "keydown"]) window.addEventListener(type, stop, true);
  const mine = keeping = {stop};
  const step = () => {
    if (keeping !== mine) return;
    if (performance.now() > until) { stop(); return; }
    const now = document.querySelector(`.${CSS.escape(key)}`);
    const moved = now ? now.getBoundingClientRect().top - top : 0;
    if (Math.abs(moved) > 1) (scrollerOf(now) || window).scrollBy(0, moved);
    requestAnimationFrame(step);
  };
  requestAnimationFrame(step);
}

function scrollerOf(element) {
  for (let el = element.parentElement; el; el = el.parentElement) {
    const overflow = getComputedStyle(el).overflowY;
    if ((overflow === "auto" || overflow === "scroll") && el.scrollHeight > el.clientHeight) return el;
  }
  return null;
}

function onDragEnd(event) {
  const ended = dragged;
  dragged = null;
  window.removeEventListener("pointermove", onDragMove, true);
  for (const type of ["pointerup", "pointercancel"]) window.removeEventListener(type, onDragEnd, true);
  if (ended && ended.drawn && ended.last) {
    say(ended.input, ended.drawn.said, ended.drawn.valueBefore);  // the slider's own again (a release's render gives its new value)
    if (event.type === "pointerup") {
      const control = ended.track.closest(`[class*='${DOM.keyPrefix}']`);
      if (control) keepInPlace(control);
      // react-aria has seen none of the moves: one before its release, to the middle of the step the thumb
      // shows, so that its arithmetic lands there too (at the release's own point, half a step could round
      // the other way: θ₀ showed 28° and became 29°)
      const {pointerId, pointerType, isPrimary} = ended.last, {clientY, screenY} = event;
      const shift = ended.value === null ? 0 : travelTo(ended) - (event.pageX - ended.pageX);
      const clientX = event.clientX + shift, screenX = event.screenX + shift;
      ended.track.dispatchEvent(new PointerEvent("pointermove", {bubbles: true, cancelable: true, composed: true,
        pointerId, pointerType, isPrimary, clientX, clientY, screenX, screenY, buttons: 1}));
    } else {
      Object.assign(ended.drawn.thumb.style, {left: ended.drawn.left});
      setThumbText(ended.drawn, ended.drawn.text);
    }
    setTimeout(() => { ended.drawn.fill.style.backgroundImage = ""; }, 0);  // the slider's own again, from React's render
  }
  schedule();
}

// The pointer's travel from where the drag started that puts the thumb on the value shown, in the middle of its step.
function travelTo({input, track, start, value}) {
  const {min, max} = rangeOf(input);
  return ((value - min) / (max - min) - start) * track.getBoundingClientRect().width;
}

// Where a drag starts: the value the slider shows (off its steps too, as react-aria's state has it).
function startValue(input) {
  const follow = state && state.data.follows.find(([, key]) => input.closest(`.${DOM.keyPrefix}${CSS.escape(key)}`));
  return follow ? restingValue(input, state.params[follow[0]] * follow[2]) : Number(input.value);
}

// The parts of a stage slider that a drag moves, as Streamlit 1.67 draws them, or null.
function drawnParts(slider, track, input) {
  const thumb = [...track.children].find((child) => child.contains(input) && child.style.left);
  const label = thumb && thumb.querySelector(DOM.sliderThumbValue);
  const text = label && label.querySelector("p"), shown = text && /^-?\d+(?:\.(\d+))?$/.exec(text.textContent);
  const fill = track.firstElementChild, gradient = fill ? getComputedStyle(fill).backgroundImage : "";
  if (!shown || !(text.firstChild instanceof Text) || (gradient.match(/-?[\d.]+%/g) || []).length !== 4) return null;
  const follow = state && state.data.follows.find(([, key]) => slider.closest(`.${DOM.keyPrefix}${CSS.escape(key)}`));
  const general = follow && /^%\.(\d+)g$/.exec(follow[3] || "");  // "%.6g": six figures, no trailing zeros
  return {root: slider, thumb, label, fill, gradient, decimals: (shown[1] || "").length, figures: general ? Number(general[1]) : 0,
          left: thumb.style.left, text: text.textContent, said: input.getAttribute("aria-valuetext"), valueBefore: input.value};
}

// The thumb, its value and the filled track at ``value``, as the slider's own render would draw them.
function drawThumb(drag) {
  const {input, drawn, value} = drag;
  const {min, max} = rangeOf(input), percent = ((value - min) / (max - min)) * 100;
  drawn.thumb.style.left = `${percent}%`;
  setThumbText(drawn, thumbText(value, drawn));
  say(input, thumbText(value, drawn), value);  // what a screen reader gets, as a render of the slider would give it
  let stop = 0;  // [fill start, fill start, fill end, fill end]: the end moves
  drawn.fill.style.backgroundImage = drawn.gradient.replace(/-?[\d.]+%/g, (at) => (stop++ >= 2 ? `${percent}%` : at));
  // Streamlit's layout effect: the value kept within the slider at either end of the track
  const box = drawn.root.getBoundingClientRect(), thumb = drawn.thumb.getBoundingClientRect(), label = drawn.label.getBoundingClientRect();
  const half = thumb.width / 2, centre = thumb.left + half;
  if (Math.round(centre - label.width / 2) < Math.round(box.left)) Object.assign(drawn.label.style, {left: `${box.left - centre + half}px`, right: ""});
  else if (Math.round(centre + label.width / 2) > Math.round(box.right)) Object.assign(drawn.label.style, {left: "", right: `${centre + half - box.right}px`});
  else Object.assign(drawn.label.style, {left: "", right: ""});
  drag.seen = input.value;  // (the value just given it: React has drawn no other)
}

// A value as the slider's format writes it (sprintf-js, which Streamlit uses): "%.6g" or "%.2f".
export const thumbText = (value, {decimals, figures}) => (figures ? String(Number(value.toPrecision(figures))) : value.toFixed(decimals));

// The value a range input gives a screen reader: its text (Streamlit writes it after each render of the
// slider) and its value, which Chromium's accessibility tree reads for a range input (not the text).
function say(input, text, value) {
  if (text === null) input.removeAttribute("aria-valuetext");
  else if (input.getAttribute("aria-valuetext") !== text) input.setAttribute("aria-valuetext", text);
  if (String(input.value) !== String(value)) input.value = value;
}

// React's own text node (a node put in its place would be left standing when React writes the next value).
function setThumbText(drawn, text) {
  const node = drawn.label.querySelector("p")?.firstChild;
  if (node instanceof Text && node.data !== text) node.data = text;
}

function shownParams() {
  const params = {...state.params};
  for (const [name, , factor] of state.data.follows) {
    const shown = controlValue(name);
    if (shown !== null) params[name] = shown / factor;  // shown = SI × factor (solvers/units.py)
  }
  return params;
}

// A control showing another value than the run's (a box emptied to type in shows none yet).
function changed(params) {
  return state.data.follows.some(([name]) => differs(params[name], state.params[name]));
}

function differs(shown, ran) {
  return !Number.isNaN(shown) && !Object.is(shown, ran) && !(Math.abs(shown - ran) <= 1e-12 * Math.abs(ran));
}

function begin() {
  if (state.live) return;
  state.live = true;
  document.body.classList.add("dl-live-dragging");
  liveCaption();
  holdPose();
  for (const el of staleParts()) el.classList.add("dl-live-stale");
  const fig = document.querySelector(`${DOM.stage} .dl-figure`);
  // Over the figure's title, not dimmed with it, and taking no room: nothing under the finger moves.
  if (fig && !document.querySelector(".dl-live-badge")) {
    const badge = Object.assign(document.createElement("p"), {className: "dl-live-badge"});
    badge.append(Object.assign(document.createElement("strong"), {className: "dl-live-headline"}),
                 Object.assign(document.createElement("span"), {className: "dl-live-said"}),
                 Object.assign(document.createElement("span"), {className: "dl-live-note", textContent: MOTION_UPDATING}));
    fig.prepend(badge);
    // all of the title covered (the projector's is taller than a line); where the title is not shown (the
    // projector's stage), the controls' row in its place (their edges showed under a line of headline)
    const title = fig.querySelector(".dl-title"), controls = fig.querySelector(".dl-controls");
    const over = title && title.offsetHeight <= 1 && controls && !controls.hidden ? controls : title;
    if (over) badge.style.minHeight = `${over.offsetTop + over.offsetHeight}px`;
  }
}

// The stage figure's caption: its headline (viz.common.headline: the run's words, numbers in slots)
// apart from the rest, which is dimmed; its own announcements off while it changes on every frame.
function liveCaption() {
  const el = document.querySelector(`${DOM.stage} .dl-figure .dl-description`), head = state.data.headline;
  if (!el || !head || !el.textContent.startsWith(head.text)) return;
  state.caption = {el, text: el.textContent, said: el.getAttribute("aria-live")};
  el.setAttribute("aria-live", "off");
  el.replaceChildren(Object.assign(document.createElement("span"), {className: "dl-live-caption", textContent: head.text}),
                     Object.assign(document.createElement("span"), {className: "dl-live-stale", textContent: state.caption.text.slice(head.text.length)}));
}

// The headline for these values while the regime is the run's (its words are that regime's), else dimmed.
function drawCaption(params, result) {
  const head = state.caption && state.caption.el.querySelector(".dl-live-caption");
  if (!head) return;
  const text = result.regime === state.regime && result.values
    ? headlineText(state.data.headline.parts, {...params, ...result.values}, state.data.grouped_below) : null;
  head.classList.toggle("dl-live-stale", text === null);
  const shown = text === null ? state.data.headline.text : text;
  if (head.textContent !== shown) head.textContent = shown;
}

// ------------------------------------------------------------------ the figure's pose at its key instant
// The stage figure's moving bodies at its key instant (the impact, θ₂…) follow the drag: the viz
// module's own key_pose, generated for the browser (solvers/live.pose_source: never typed here),
// evaluated with the live values and rounded as the figure's coordinates are. While a drag lasts the
// figure is paused at its key frame (Play waits), those traces are moved there (figure.js: pose, the
// path Play takes), every other trace (a trail, the plots against time, the surfaces) is dimmed, and
// a 2-D pose past the axes widens them (figure.js: widen). Outside the run's regime, or before the
// generated code is here, the whole graph is dimmed as "updating…", never shown as if it were live.
const MOTION_UPDATING = "the motion is updating…";
const POSE_LIVE = "key instant live · the motion is updating…";
const DIMMED = 0.3;

function stageFigure() {
  const el = document.querySelector(`${DOM.stage} .dl-figure`);
  return el && el.dlFigure && el.dlFigure.Plotly && el.dlFigure.frames.length ? el.dlFigure : null;
}

function holdPose() {
  const fig = state.data.pose && stageFigure();
  if (!fig) return;
  fig.hold();  // paused (Play waits); its key frame is shown with the first live pose
  const names = fig.graph.data.map((t) => t.name);
  state.pose = {fig, drawn: fig.current, names, live: null, traces: null};
}

function drawPose(params, result) {
  const pose = state.pose;
  if (!pose || pose.fig.current !== pose.drawn) return;
  let drawn = state.poseFn && result.regime === state.regime && result.values
    ? poseOf(state.poseFn, params, result.values, state.data.pose.digits) : null;
  // a body the server's figure does not have (a spring where the run had none): not drawn, unless it shows
  if (drawn) for (const [name, rows] of Object.entries(drawn)) if (!pose.names.includes(name)) {
    if (rows.some((row) => row.some((v) => v !== null))) { drawn = null; break; }
    delete drawn[name];
  }
  const live = drawn !== null;
  if (live !== pose.live) {
    pose.live = live;
    pose.fig.graph.classList.toggle("dl-live-stale", !live);
    setText(".dl-live-note", live ? POSE_LIVE : MOTION_UPDATING);
  }
  if (!live) return;
  if (!pose.traces) {  // the posed traces, and the others dimmed
    pose.traces = Object.keys(drawn).map((name) => pose.names.indexOf(name));
    const others = pose.names.map((_, i) => i).filter((i) => !pose.traces.includes(i));
    // the key frame with the others dimmed, in one redraw, before any pose is drawn (plotly's animate while
    // a restyle redraws loses the other subplot's traces)
    pose.ready = pose.fig.showHeld(others, DIMMED, pose.traces);
  }
  // Only a changed pose is drawn, and none while a key burst is committed (its step back and forth):
  // plotly's animate then would delay the page's rendering of the run that follows.
  const key = JSON.stringify(drawn);
  if (key === pose.key || performance.now() - committing < 200) return;
  pose.key = key;
  pose.next = Object.values(drawn).map(([x, y, z]) => (z ? {x, y, z} : {x, y}));
  if (pose.waiting) return;  // one pose drawn at a time, the newest
  pose.waiting = true;
  // after this frame is painted: the answers first, the figure (plotly's redraw) just after
  pose.ready.then(() => setTimeout(() => {
    pose.waiting = false;
    if (state.pose !== pose || pose.fig.current !== pose.drawn) return;
    quiet(pose.fig.pose(pose.traces, pose.next));
  }, 0), () => { pose.waiting = false; });
}

// The server's figure again: its frame and trace opacities back (unless the run drew a new figure).
function releasePose() {
  const pose = state.pose;
  if (!pose) return;
  state.pose = null;
  pose.fig.graph.classList.remove("dl-live-stale");
  // After this task: a run's new figure (drawn in its place, nothing to restore) may come with this render.
  setTimeout(() => {
    if (pose.fig.current === pose.drawn) pose.fig.release(); else pose.fig.held = null;
  }, 0);
}

function quiet(promise) { if (promise && promise.catch) promise.catch(() => {}); }

// Back to the server's drawing: every live value and mark gone.
function end() {
  if (!state || !state.live) return;
  state.live = false;
  releasePose();
  if (state.caption) {  // (unless the run has written the figure's new caption already)
    const {el, text, said} = state.caption;
    if (el.querySelector(".dl-live-caption")) el.textContent = text;
    if (said === null) el.removeAttribute("aria-live"); else el.setAttribute("aria-live", said);
    state.caption = null;
  }
  document.body.classList.remove("dl-live-dragging");
  for (const el of $$(".dl-live-stale")) el.classList.remove("dl-live-stale");
  for (const el of $$(".dl-live-badge, .dl-live-value")) el.remove();
  for (const el of $$("[data-dl-live-hidden]")) { el.hidden = false; el.removeAttribute("data-dl-live-hidden"); }
  const status = document.querySelector(".dl-live-status");
  if (status) status.textContent = "";
}

// One frame: the values for what the controls show now.
function draw() {
  frame = 0;
  if (dragged && dragged.drawn && dragged.value !== null) drawThumb(dragged);
  if (!state) return;
  const started = performance.now();
  const params = shownParams(), moved = changed(params);
  if (!moved && !state.live) return;
  // Back at the run's values (a key burst or a drag ending where it began, nothing to run): the live
  // view ends once the controls rest there (not at once: typing or dragging through them would flicker).
  clearTimeout(resting);
  if (!moved) resting = setTimeout(settle, RESTING_MS);
  begin();
  let result = {regime: "loading", values: null};  // the function not here yet: every value waits
  if (state.fn) try { result = state.fn(params); } catch (e) { result = {regime: "refused", values: null}; }
  const table = answersTable();
  if (table) {
    [...table.tBodies[0].rows].forEach((tr, i) => {
      const row = state.data.answers[i], cell = tr.cells[2];
      if (!row || !cell) return;
      const x = result.values ? result.values[row[0]] : undefined;
      const text = Number.isFinite(x) ? quantity(x, row, state.data.grouped_below) : UPDATING;
      let live = cell.querySelector(".dl-live-value");
      if (!live) {
        for (const child of cell.children) { child.hidden = true; child.setAttribute("data-dl-live-hidden", ""); }
        cell.append(live = Object.assign(document.createElement("strong"), {className: "dl-live-value"}));
      }
      live.classList.toggle("dl-live-waiting", text === UPDATING);
      if (live.textContent !== text) live.textContent = text;
    });
  }
  const said = state.data.said[result.regime];
  const regimeText = result.regime === "refused" ? "This value is outside what the model allows: the page will say why on release."
    : result.regime !== state.regime && said ? `Now: ${said}.` : "";
  const status = statusLine();
  if (status && status.textContent !== regimeText) status.textContent = regimeText;
  // The headline on the stage, where the eye is while dragging: the main answer, and a regime entered.
  // Past a limit (no values, the figure dimmed) the note alone, on as many lines as it takes: "ω₂: updating…"
  // says nothing, and cut to one line on a phone the note said nothing either ("Now: the spri…").
  // (the answer the dragged control changes: solvers/live.leads; the first answer before any has moved)
  const control = state.data.follows.find(([name]) => differs(params[name], state.params[name]));
  const main = state.data.answers[(control && (state.data.leads || {})[control[0]]) || 0];
  const x = result.values && main ? result.values[main[0]] : undefined;
  const noteOnly = !result.values && !!regimeText;
  // (a phone: an angle in degrees alone, its radians cut the line: "… 35.26° (0.…")
  const shownAs = main && NARROW.matches ? [...main.slice(0, 3), false, ...main.slice(4)] : main;
  setText(".dl-live-headline", main && !noteOnly ? `${main[4]}: ${Number.isFinite(x) ? quantity(x, shownAs, state.data.grouped_below) : UPDATING}` : "");
  setText(".dl-live-said", noteOnly ? regimeText : regimeText ? ` · ${regimeText}` : "");
  const badge = document.querySelector(".dl-live-badge");
  if (badge) badge.classList.toggle("dl-live-note-only", noteOnly);
  drawCaption(params, result);
  drawPose(params, result);
  performance.measure("dl-live-draw", {start: started});  // its own cost, for bench/live_drag.py
}

// as the badge's own style's phone (none under node, where the tests run this module)
const NARROW = typeof matchMedia === "function" ? matchMedia("(max-width: 640px)") : {matches: false};

function setText(selector, text) {
  const el = document.querySelector(selector);
  if (el && el.textContent !== text) el.textContent = text;
}

function statusLine() {
  const table = answersTable();
  if (!table) return null;
  let status = table.parentElement.querySelector(".dl-live-status");
  if (!status) table.before(status = Object.assign(document.createElement("p"), {className: "dl-live-status"}));
  return status;
}

function schedule() { if ((state || (dragged && dragged.drawn)) && !frame) frame = requestAnimationFrame(draw); }

// The stage's controls: a slider's value (react-aria sets its range input while it is dragged), a
// number box's typing, a held key (below).
function watch() {
  const controls = document.querySelector(DOM.stageControls) || document.body;
  if (controls.dlLiveWatched) return;
  controls.dlLiveWatched = true;
  new MutationObserver(() => { addSteppers(); schedule(); }).observe(controls, {subtree: true, attributes: true,
    characterData: true, childList: true, attributeFilter: ["aria-valuetext", "value"]});
  addSteppers();
  controls.addEventListener("click", onStep);
  for (const type of ["input", "pointermove", "keydown", "keyup", "pointerup"]) controls.addEventListener(type, schedule, true);
  controls.addEventListener("keydown", onKeyDown, true);  // before react-aria's (React listens at its root)
  controls.addEventListener("keyup", onKeyUp, true);
  controls.addEventListener("focusout", onFocusOut, true);
  controls.addEventListener("pointerdown", onPointerDown, true);
  controls.addEventListener("pointerdown", onDragStart, true);
}

// The run after a release: when the app is idle again, the server's drawing stands.
let watchingRuns = false;
function watchRuns() {
  if (watchingRuns) return;
  const app = document.querySelector(DOM.app);
  if (!app) return;
  watchingRuns = true;
  new MutationObserver(() => {
    if (app.getAttribute(DOM.attributes.scriptState) === DOM.scriptIdle) requestAnimationFrame(() => settle());
  }).observe(app, {attributes: true, attributeFilter: [DOM.attributes.scriptState]});
}

// A run that drew no live view (a refused value: no answers, no figure) takes its element away without
// a call to the cleanup render returned: the server's page stands, nothing live on it, and nothing
// follows a control until a run draws the view again. Watched on the page itself (when the run's state
// attribute changes is no sure moment: the element may go after it).
let dropped = false;  // (the run that draws the view again says its main answer, as after any release)
function gone() {
  if (!state || state.parent.isConnected) return false;
  dropped = dropped || state.live;
  end();
  state = null;
  return true;
}
let watchingPage = false;
function watchPage() {
  if (watchingPage) return;
  watchingPage = true;
  new MutationObserver(() => { if (state && state.live) gone(); }).observe(document.body, {childList: true, subtree: true});
}

function settle() {
  if (!state) return;
  if (gone()) return;
  const params = shownParams();
  if (state.live && !changed(params)) end();
}

// The main answer, said once after a run that a stage control started (not on every frame).
function announce() {
  let region = document.getElementById("dl-live-announce");
  if (!region) {
    region = Object.assign(document.createElement("div"), {id: "dl-live-announce", className: "dl-live-sr"});
    region.setAttribute("aria-live", "polite");
    document.body.append(region);
  }
  const table = answersTable();
  const row = table && table.tBodies[0].rows[0];
  const text = row ? `${row.cells[1].textContent}: ${row.cells[2].textContent}` : "";
  if (region.textContent !== text) region.textContent = text;
}

// ------------------------------------------------------------------ a held key, a burst of presses
// Streamlit's slider (react-aria) commits every key press, and each commit is a run of the page. On
// the stage a key moves a slider as a drag does: the thumb, its shown value and the live answers
// follow each press (a held key's repeats too), and the value is committed once, when no key has
// been down for COMMIT_AFTER ms (or the slider loses focus). The slider's own keyboard contract is
// kept: an arrow moves one step (with Shift, a page), Page Up/Down a page (a tenth of the range, in
// whole steps, as react-aria's pageSize), Home/End the ends. The moves go through the range input's
// own value and "input" event (the path react-aria's slider takes for assistive technology), which
// changes the thumb without a commit; the commit is the slider's own keyboard path: one step back,
// and the same key once more, which react-aria ends with its onChangeEnd, as for any key press.
const COMMIT_AFTER = 250;
const MOVES = {ArrowRight: 1, ArrowUp: 1, ArrowLeft: -1, ArrowDown: -1, PageUp: "page", PageDown: "-page", Home: "min", End: "max"};
const REPLAYED = Symbol("dl-replayed");
let held = null;  // {input, timer}: the slider moved by keys (or taps) and not yet committed
let committing = -Infinity;  // when the last burst was committed

// The value's own setter (React watches the element's), as a person's input would set it.
const setValue = (input, value) => Object.getOwnPropertyDescriptor(HTMLInputElement.prototype, "value").set.call(input, value);

export function pageSize(min, max, step) {  // react-aria's: a tenth of the range in whole steps, one step at least
  return Math.max(step, Math.round((max - min) / 10 / step) * step);
}

function stageSlider(el) {
  return el instanceof HTMLInputElement && el.type === "range" && el.closest(`${DOM.stageControls} ${DOM.slider}`) ? el : null;
}

// The value the slider takes (the input sanitises it to its range and steps) and tells React of it.
function moveTo(input, how) {
  const {min, max, step} = rangeOf(input);
  if (how === "min" || how === "max") setValue(input, String(how === "min" ? min : max));
  else {
    const steps = typeof how === "number" ? how : (how[0] === "-" ? -1 : 1) * Math.round(pageSize(min, max, step) / step);
    if (steps > 0) input.stepUp(steps); else input.stepDown(-steps);
  }
  input.dispatchEvent(new Event("input", {bubbles: true}));
}

function onKeyDown(event) {
  const input = stageSlider(event.target), how = MOVES[event.key];
  if (!input || event[REPLAYED] || how === undefined || event.altKey || event.ctrlKey || event.metaKey) return;
  event.preventDefault();
  event.stopPropagation();  // react-aria would commit it (and the page run)
  if (held && held.input !== input) commit();
  if (!held) held = {input, timer: 0};
  clearTimeout(held.timer);
  moveTo(input, typeof how === "number" && event.shiftKey ? (how > 0 ? "page" : "-page") : how);
  schedule();
}

function onKeyUp(event) {
  if (!held || MOVES[event.key] === undefined) return;
  clearTimeout(held.timer);
  held.timer = setTimeout(commit, COMMIT_AFTER);
}

// The slider's own commit of the value it shows: one step back through the input, then the key that
// steps forward again, handled by react-aria (after React has drawn the step back).
function commit() {
  if (!held) return;
  const {input} = held;
  clearTimeout(held.timer);
  held = null;
  committing = performance.now();  // its step back and forth: the pose stays as drawn
  if (!input.isConnected) return;
  const value = Number(input.value), {min, max} = rangeOf(input);
  if (!(max > min)) return;
  const key = value > min ? "ArrowRight" : "ArrowLeft";
  moveTo(input, value > min ? -1 : 1);
  setTimeout(() => {
    const replay = new KeyboardEvent("keydown", {key, code: key, bubbles: true, cancelable: true});
    replay[REPLAYED] = true;
    input.dispatchEvent(replay);
  }, 0);
}

function onFocusOut(event) {
  if (held && event.target === held.input) commit();
}

// A pointer on the slider being held by keys: react-aria's drag commits on its release.
function onPointerDown(event) {
  if (held && !event.target.closest(".dl-step") && held.input.closest(DOM.slider).contains(event.target)) {
    clearTimeout(held.timer);
    held = null;
  }
}

// ------------------------------------------------------------------ one step by thumb (a phone)
// A finger on a half-width slider cannot hit one step (1° of θ₂ on some 80 px): on a narrow screen each
// stage slider has a − and a + button (44 × 32 px, over WCAG's 24 px) at the ends of its track, named for
// screen readers ("θ₂ one step lower"). A tap moves one step as a key press does (above): live, and a
// burst of taps is one run, COMMIT_AFTER ms after the last. Hidden on a wide screen and on paper.
function addSteppers() {
  for (const slider of document.querySelectorAll(`${DOM.stageControls} ${DOM.slider}`)) {
    placeSteppers(slider);
    if (slider.querySelector(":scope > .dl-step")) continue;
    const input = slider.querySelector("input[type='range']");
    if (!input) continue;
    const symbol = (input.getAttribute("aria-label") || "").split(" — ")[0];
    slider.classList.add("dl-stepped");
    for (const [steps, sign, words] of [[-1, "−", "one step lower"], [1, "+", "one step higher"]]) {
      const button = Object.assign(document.createElement("button"), {type: "button", className: "dl-step", textContent: sign});
      button.dataset.steps = String(steps);
      button.setAttribute("aria-label", `${symbol} ${words}`.trim());
      slider.append(button);
    }
  }
}

// The −/+ just inside the track's end values under its ends (their text's width, in the values' own font,
// and a gap); where the two would then be closer than STEPPERS_APART, at the slider's ends with the values
// between them, as before. Measured again when the values' text changes (the units) or the slider's size
// does (a phone turned), not on each of a drag's values (the observer above calls this on every one).
const STEPPERS_APART = 12;
let ink = null;  // a canvas's 2-D context, made on first use (none under node, where the tests load this module)
function placeSteppers(slider, resized = false) {
  const ends = slider.querySelectorAll(`${DOM.sliderTickBar} p`);
  const track = slider.querySelector("[role='group'] > [data-orientation]");
  if (ends.length !== 2 || !track) return;
  const said = `${ends[0].textContent} ${ends[1].textContent}`;
  if (!resized && slider.dataset.dlEnds === said) return;
  slider.dataset.dlEnds = said;
  if (!slider.dlResized) (slider.dlResized = new ResizeObserver(() => placeSteppers(slider, true))).observe(slider);
  ink = ink || document.createElement("canvas").getContext("2d");
  const width = (p) => { ink.font = getComputedStyle(p).font; return ink.measureText(p.textContent).width; };
  const own = slider.getBoundingClientRect(), along = track.getBoundingClientRect();
  const low = Math.ceil(along.left - own.left + width(ends[0])) + 6, high = Math.ceil(own.right - along.right + width(ends[1])) + 6;
  const inside = own.width - low - high - 2 * 44 >= STEPPERS_APART;
  for (const [name, value] of [["--dl-low-end", inside ? low : 0], ["--dl-high-end", inside ? high : 0],
                               ["--dl-ends-margin", inside ? 0 : 48]])
    if (slider.style.getPropertyValue(name) !== `${value}px`) slider.style.setProperty(name, `${value}px`);  // (observed: no loop)
}

function onStep(event) {
  const button = event.target.closest && event.target.closest(".dl-step");
  const input = button && stageSlider(button.parentElement.querySelector("input[type='range']"));
  if (!input) return;
  event.preventDefault();
  if (held && held.input !== input) commit();
  if (!held) held = {input, timer: 0};
  clearTimeout(held.timer);
  moveTo(input, Number(button.dataset.steps));
  held.timer = setTimeout(commit, COMMIT_AFTER);
  schedule();
}

// The answers' element (text.js) hands over what the run sent (ui/live.py) and an element of its own;
// the function returned ends the live view when the answers come without it.
export function follow(d, parentElement) {
  if (!document.getElementById("dl-live-style"))
    document.head.append(Object.assign(document.createElement("style"), {id: "dl-live-style", textContent: STYLE}));
  parentElement.replaceChildren();
  const params = fromJSON(d.params);
  const wasLive = (state && state.live) || dropped;
  dropped = false;
  if (state) end();
  performance.clearMeasures("dl-live-draw");  // one drag's worth kept, not a session's
  state = {data: d, parent: parentElement, params, regime: d.regime, live: false, fn: null, caption: null, pose: null, poseFn: null};
  const mine = state;
  loadModule(d.values).then((fn) => { mine.fn = fn; });
  if (d.pose) loadModule(d.pose.url).then((fn) => { mine.poseFn = fn; }, () => {});  // (none: the figure stays dimmed)
  if (wasLive) requestAnimationFrame(announce);
  watch();
  watchRuns();
  watchPage();
  return () => { if (state && state.data === d) { end(); state = null; } };
}
