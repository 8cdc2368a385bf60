// The page's typeset text (ui/results.py), a Streamlit components-v2 module in the page's own DOM,
// in two elements: the answers (the answers table, notes, the ledger across an impact, the checks)
// and the derivation (the steps, a title and a display equation each, and the worked solution's
// slips).
//
// A new value changes only the numbers. Streamlit's Markdown would parse and typeset the whole text
// again and let React patch it, which made the browser lay out and repaint all of it on every
// change (a third of a change's time: BENCHMARKS.md section 6). Here each formula is typeset once
// per distinct text (KaTeX, ui/katex: the version of Streamlit's own Markdown, whose stylesheet is
// in the page), and a cell or a step whose text did not change is not touched. Everything else is
// set as text, never parsed as HTML: only KaTeX's own output is inserted as HTML.
"use strict";

const CSS = `
.dl-text { font-family: var(--st-font, "Source Sans Pro", sans-serif); color: var(--st-text-color, inherit); }
.dl-text h3 { font-size: 1.75rem; font-weight: 600; line-height: 1.2; margin: 0; padding: 0.75rem 0 1rem 0; }
.dl-text h4 { font-size: 1.5rem; font-weight: 600; line-height: 1.2; margin: 0; padding: 0.75rem 0 1rem 0; }
.dl-text h3, .dl-text h4 { scroll-margin-top: 4rem; }  /* a link to one lands below Streamlit's header */
.dl-text h4.dl-sub { font-size: 1.25rem; padding: 0.375rem 0 1rem 0; }
/* The page's size, larger in the lecture view (Streamlit sets p, ul and ol in 1rem everywhere). */
.dl-text p, .dl-text ul, .dl-text li { font-size: 1em; }
.dl-text p { margin: 0 0 1rem 0; line-height: 1.6; }
.dl-text .dl-muted { color: var(--st-gray-text-color, inherit); }
.dl-text .dl-caption { opacity: 0.75; }
.dl-text .dl-math { margin: 0 0 1rem 0; }
/* A wide equation scrolls sideways, which clips it above and below too: its room between equations is padding,
   inside the clip, so a tall numerator (2·π·0.5000 over 1.200) is never cut off at its top. */
.dl-text .dl-math .katex-display { margin: 0; padding: 0.75em 0; overflow-x: auto; overflow-y: hidden; }
.dl-text ul { margin: 0 0 1rem 0; padding-left: 1.5rem; line-height: 1.6; }
.dl-text li { margin: 0.2em 0; }
.dl-text table { border-collapse: collapse; margin: 0 0 1rem 0; line-height: 1.6; }
.dl-text th, .dl-text td { padding: 0.375rem 0.75rem; text-align: left; vertical-align: middle;
  border: 1px solid var(--st-dataframe-border-color, rgba(49, 51, 63, 0.1)); }
.dl-text th { font-weight: 700; }
.dl-text .dl-good { color: var(--st-green-text-color, #0C5A44); }
.dl-text .dl-bad { color: var(--st-red-text-color, #9E303B); }
.dl-text .dl-changes { color: var(--st-orange-text-color, #9B4519); }
.dl-text .dl-nowrap { white-space: nowrap; }
.dl-text .dl-mark { display: inline-block; min-width: 1.1em; text-align: center; font-weight: 700; margin-right: 0.2em; }
/* The course's four steps, and the free-body diagrams drawn at the head of Step 2 (server-made SVG). */
.dl-text h4.dl-part { font-size: 1.2rem; padding: 0.5rem 0 0.6rem 0; }
.dl-text figure.dl-fbd-figure { margin: 0 0 1rem 0; display: inline-block; vertical-align: top; margin-right: 1rem;
  width: min(100%, 30rem); }
.dl-text figure.dl-fbd-figure svg { width: 100%; height: auto; display: block; border: 1px solid rgba(49, 51, 63, 0.2);
  border-radius: 0.25rem; }
.dl-text figure.dl-fbd-figure figcaption { font-size: 0.9em; opacity: 0.8; margin-top: 0.25rem; }
.dl-text .dl-sr { position: absolute; width: 1px; height: 1px; overflow: hidden; clip-path: inset(50%); white-space: nowrap; }
`;

let katexPromise = null, katexFailures = 0;
const typeset = new Map();  // (display?) + TeX -> KaTeX's HTML, kept across runs and pages

// Should KaTeX's script not load (a network that drops mid-visit), the formulas show as their TeX
// and the numbers, words and tables as usual; the next run tries to load KaTeX again and, if it
// comes, typesets everything shown (``render`` forgets what was drawn without it).
const asTeX = {renderToString: (tex) => Object.assign(document.createElement("code"), {textContent: tex}).outerHTML};

function html(katex, tex, display) {
  const key = (display ? "D" : "I") + tex;
  let out = typeset.get(key);
  if (out === undefined) {
    out = katex.renderToString(tex, {displayMode: display, throwOnError: false, output: "htmlAndMathml"});
    if (typeset.size > 4000) typeset.clear();
    if (katex !== asTeX) typeset.set(key, out);
  }
  return out;
}

const make = (tag, className, text) => {
  const el = document.createElement(tag);
  if (className) el.className = className;
  if (text !== undefined) el.textContent = text;
  return el;
};

// A heading with the id Streamlit's Markdown would give it, so a shared link (…/disk_wall#answers)
// still lands on it: the browser's own scroll to the fragment comes before this element exists.
function heading(tag, className = "") {
  const el = make(tag, className);
  el.update = (text) => put(el, text, () => {
    el.textContent = text;
    el.id = text.toLowerCase().replace(/[^\p{L}\p{N}]+/gu, "-").replace(/^-|-$/g, "");
    if (el.id && decodeURIComponent(location.hash.slice(1)) === el.id) requestAnimationFrame(() => el.scrollIntoView());
  });
  return el;
}

// A header cell that only a screen reader reads (a column whose content names itself).
const unseen = (text) => make("span", "dl-sr", text);

// An element's content, redone only when its value changed since the last run.
function put(el, value, fill) {
  const key = JSON.stringify(value);
  if (el.dlShown === key) return;
  el.dlShown = key;
  if (fill) fill(el, value); else el.textContent = value;
}

// ``parent``'s children, one per item, made by ``create`` as needed, extra ones removed.
function children(parent, count, create) {
  while (parent.children.length < count) parent.append(create());
  while (parent.children.length > count) parent.lastChild.remove();
  return [...parent.children];
}

// Text with $inline math$ typeset, as the solvers write their step titles, ledger, checks and
// notes (the symbols beside the equations typeset like them); a slip's text also has **bold** and
// *emphasis* (``marks``). Everything else is set as text.
function inline(katex, text, into, marks = false) {
  const parts = marks ? /\$([^$]+)\$|\*\*([^*]+)\*\*|\*([^*\s][^*]*)\*/g : /\$([^$]+)\$/g;
  let at = 0;
  for (const m of text.matchAll(parts)) {
    const before = text.slice(at, m.index);
    // an opening bracket stays on the line of the symbol it opens ("(mg, a force…", not "(" / "mg")
    const opener = m[1] !== undefined && /[(\[]$/.test(before) ? before.slice(-1) : "";
    into.append(before.slice(0, before.length - opener.length));
    if (m[1] !== undefined) {
      const span = make("span");
      span.innerHTML = html(katex, m[1], false);
      if (opener) {
        const kept = make("span", "dl-nowrap", opener);
        kept.append(span);
        into.append(kept);
      } else {
        into.append(span);
      }
    } else {
      into.append(make(m[2] !== undefined ? "strong" : "em", "", m[2] ?? m[3]));
    }
    at = m.index + m[0].length;
  }
  into.append(text.slice(at));
}

// A table with a header row; ``cell(td, value, column)`` fills a body cell.
function table(header, cell) {
  const el = make("table");
  const head = make("tr");
  for (const name of header) {
    const th = make("th");
    th.append(name);
    head.append(th);
  }
  el.append(make("thead"), make("tbody"));
  el.tHead.append(head);
  el.update = (rows) => {
    children(el.tBodies[0], rows.length, () => make("tr")).forEach((tr, i) => {
      children(tr, rows[i].length, () => make("td")).forEach((td, j) => put(td, rows[i][j], (c, v) => cell(c, v, j)));
    });
  };
  return el;
}

class Answers {
  constructor(root) {
    this.heading = heading("h3");
    // The symbol typeset, the quantity as text, the value in bold.
    this.table = table([unseen("symbol"), "quantity", "value"], (td, value, column) => {
      if (column === 0) td.innerHTML = html(this.katex, value, false);
      else if (column === 2) td.replaceChildren(make("strong", "", value));
      else td.textContent = value;
    });
    this.notes = make("div");
    this.ledgerHeading = heading("h4", "dl-sub");
    // What is conserved across the impact, what changes, and why.
    this.ledger = table(["quantity", "before", "after", unseen("conserved or not, and why")], (td, value, column) => {
      td.replaceChildren();
      if (column === 0) { inline(this.katex, value, td); return; }
      if (column < 3) { td.textContent = value; return; }
      const [conserved, why] = value;
      td.append(make("span", conserved ? "dl-good" : "dl-changes", conserved ? "conserved" : "changes"), ": ");
      inline(this.katex, why, td);
    });
    this.checksHeading = heading("h4", "dl-sub");
    this.checks = make("ul");
    root.append(this.heading, this.table, this.notes, this.ledgerHeading, this.ledger, this.checksHeading, this.checks);
  }

  update(katex, d) {
    this.katex = katex;  // the table's cells typeset with this run's KaTeX
    this.heading.update(d.heading);
    this.table.update(d.answers);
    children(this.notes, d.notes.length, () => make("p", "dl-muted")).forEach((p, i) => put(p, d.notes[i], (el, note) => {
      el.replaceChildren();
      inline(katex, note, el);
    }));
    this.ledgerHeading.hidden = this.ledger.hidden = !d.ledger.length;
    this.ledgerHeading.update(d.ledger_heading);
    this.ledger.update(d.ledger.map(([quantity, before, after, conserved, why]) => [quantity, before, after, [conserved, why]]));
    this.checksHeading.update(d.checks_heading);
    // Each check: agrees or differs, its name, the closed form against the second method, and why.
    children(this.checks, d.checks.length, () => make("li")).forEach((li, i) => put(li, d.checks[i], (el, [ok, name, closed, second, why]) => {
      const mark = make("span", `dl-mark ${ok ? "dl-good" : "dl-bad"}`, ok ? "✓" : "✗");
      mark.setAttribute("aria-hidden", "true");  // said in words: "agrees" to a screen reader, "differs" to all
      const title = make("strong"), reason = make("span", "dl-muted");
      inline(katex, name, title);
      inline(katex, why, reason);
      el.replaceChildren(mark, ...(ok ? [unseen("agrees: ")] : [make("strong", "dl-bad", "differs"), " "]), title,
                         `: ${closed} vs ${second}`, make("br"), reason);
    }));
  }
}

class Derivation {
  constructor(root) {
    this.heading = heading("h3");
    this.caption = make("p", "dl-caption");
    this.steps = make("div");
    this.slips = make("div");
    root.append(this.heading, this.caption, this.steps, this.slips);
  }

  update(katex, d) {
    this.heading.update(d.heading);
    put(this.caption, d.caption);
    this.caption.hidden = !d.caption;
    children(this.steps, d.steps.length, () => {
      const step = make("div");
      const p = make("p");
      p.append(make("strong"), make("span"));
      step.append(make("div", "dl-before"), p, make("div", "dl-math"));
      return step;
    });
    // Each of the course's four steps opens with its heading; Step 2 with the free-body diagrams, drawn by
    // the server from the problem's declarations (viz/diagram.py: only numbers and declared labels in them).
    const heads = new Map((d.parts || []).map(([at, title]) => [at, title]));
    // A step broken for a phone with a row set smaller comes broken for a wide column too: taken where the
    // column holds that width in KaTeX's em (the server's estimate runs up to 15 % short).
    const drawn = this.steps.querySelector(".katex-display > .katex");  // (before any: KaTeX's 1.21 em)
    const katexEm = parseFloat(getComputedStyle(drawn || this.steps).fontSize) * (drawn ? 1 : 1.21);
    const wide = this.steps.clientWidth >= d.wide_em / 0.85 * katexEm;
    const column = this.steps.clientWidth;
    [...this.steps.children].forEach((step, i) => {
      const [title, narrow, broad] = d.steps[i];
      const roomy = broad && wide && !(step.dlTooWide >= column);  // (where it overflowed, not again at this width)
      const part = heads.get(i);
      const isDiagrams = part !== undefined && /^Step 2/.test(part);
      put(step.firstChild, [part, isDiagrams ? d.diagrams : null], (before) => {
        before.replaceChildren();
        if (part === undefined) return;
        before.append(make("h4", "dl-part", part));
        if (!isDiagrams) return;
        for (const [svg, caption] of d.diagrams || []) {  // (the text alternative: the SVG's aria-label)
          const fig = make("figure", "dl-fbd-figure");
          fig.innerHTML = svg;
          // as wide as its drawing may grow (the SVG's own max-width), so two diagrams stand side by side where
          // the column holds both (the ladder's, against the wall and after leaving it), not one under the other
          const grows = fig.firstElementChild && fig.firstElementChild.style.maxWidth;
          if (grows) fig.style.maxWidth = grows;
          fig.append(make("figcaption", "", caption));
          before.append(fig);
        }
      });
      put(step.children[1], [i, title], (p) => {
        p.firstChild.textContent = `${i + 1}.`;
        p.lastChild.replaceChildren(" ");
        inline(katex, title, p.lastChild);
      });
      const draw = (tex) => put(step.lastChild, tex, (math) => { math.innerHTML = html(katex, tex, true); });
      draw(roomy ? broad : narrow);
      // Where the estimate fell short (it is measured once KaTeX's fonts are in: wider than the fallback's), the
      // phone's rows.
      const fits = () => {
        const display = step.lastChild.querySelector(".katex-display");
        if (step.lastChild.dlShown !== JSON.stringify(broad) || !display || display.scrollWidth <= display.clientWidth + 1) return;
        step.dlTooWide = this.steps.clientWidth;
        draw(narrow);
      };
      if (roomy) {
        fits();
        document.fonts.ready.then(() => requestAnimationFrame(fits));
      }
    });
    put(this.slips, [d.slips_heading, d.slips], (el) => {
      el.replaceChildren();
      if (!d.slips.length) return;
      const ul = make("ul");
      for (const note of d.slips) {
        const li = make("li");
        inline(katex, note, li, true);
        ul.append(li);
      }
      el.append(make("h4", "", d.slips_heading), ul);
    });
  }
}

const VIEWS = {answers: Answers, derivation: Derivation};
const views = new WeakMap();
const decoder = new TextDecoder();

export async function render({data, parentElement}) {
  const d = JSON.parse(typeof data === "string" ? data : decoder.decode(data));
  const liveModule = d.live ? import(new URL(d.live.module, location.href).href) : null;  // beside KaTeX's
  // KaTeX's script (UMD) sets window.katex when it runs; loaded once per page. Tried again on the next run
  // where it failed, under a URL of its own: the browser keeps a failed module's import as failed (Chromium 150).
  const katexURL = new URL(d.katex, location.href);
  if (katexFailures) katexURL.searchParams.set("retry", String(katexFailures));
  katexPromise ??= import(katexURL.href).then(() => window.katex)
    .catch(() => { katexPromise = null; katexFailures++; return asTeX; });
  const katex = await katexPromise;
  let view = views.get(parentElement);
  if (!view) {
    if (!document.getElementById("dl-text-style"))  // one stylesheet for the page
      document.head.append(Object.assign(make("style", "", CSS), {id: "dl-text-style"}));
    const root = make("div", `dl-text dl-${d.view}`);
    parentElement.replaceChildren(root);
    views.set(parentElement, view = new VIEWS[d.view](root));
  }
  view.update(katex, d);
  if (katex === asTeX)  // drawn without KaTeX: drawn again on the next run (headings keep their place)
    for (const el of parentElement.querySelectorAll(":not(h3, h4)")) delete el.dlShown;
  if (d.live || following.has(parentElement)) followLive(parentElement, d.live, liveModule);
}

// The answers follow a dragged lesson control (live.js, imported on the lesson page only), with these
// answers on the page already: the run's values, which a screen reader is told once after a release.
// Each run's view starts after the last one's (a run without it, Practice, ends it); a view that cannot
// load leaves the answers as the server drew them.
const following = new WeakMap();  // the answers' element -> the promise of live.js's end of its view
function followLive(parentElement, live, module) {
  const last = following.get(parentElement) || Promise.resolve(null);
  const next = last.then((stop) => {  // (a run's follow takes over the last view itself: it says the answer once)
    if (!live) { if (stop) stop(); return null; }
    let holder = parentElement.querySelector(":scope > .dl-live-holder");
    if (!holder) parentElement.append(holder = make("div", "dl-live-holder"));
    return module.then((m) => m.follow(live.data, holder));
  }).catch(() => null);
  following.set(parentElement, next);
}
