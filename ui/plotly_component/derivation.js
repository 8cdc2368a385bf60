// The derivation (ui/results.py), a Streamlit components-v2 module in the page's own DOM: the
// heading, the steps (a title and a display equation each) and the worked solution's slips.
//
// A new value changes only the steps with the numbers. Streamlit's Markdown would parse and
// typeset the whole text again and let React patch it, which made the browser lay out and repaint
// the derivation on every change (a third of a change's time: BENCHMARKS.md section 6). Here each
// equation is typeset once per distinct text (KaTeX, ui/katex: the version of Streamlit's own
// Markdown, whose stylesheet is in the page), and a step whose text did not change is not touched.
"use strict";

const CSS = `
.dl-derivation { font-family: var(--st-font, "Source Sans Pro", sans-serif); color: var(--st-text-color, inherit); }
.dl-derivation h3 { font-size: 1.75rem; font-weight: 600; line-height: 1.2; margin: 0; padding: 0.75rem 0 1rem 0; }
.dl-derivation h4 { font-size: 1.5rem; font-weight: 600; line-height: 1.2; margin: 0; padding: 0.75rem 0 1rem 0; }
.dl-derivation p, .dl-derivation li { font-size: 1em; }  /* the page's size: larger in the lecture view */
.dl-derivation p { margin: 0 0 1rem 0; line-height: 1.6; }
.dl-derivation .dl-muted { opacity: 0.75; }
.dl-derivation .dl-math { margin: 0 0 1rem 0; }
.dl-derivation .dl-math .katex-display { margin: 0.5em 0; overflow-x: auto; overflow-y: hidden; }
.dl-derivation ul { margin: 0 0 1rem 0; padding-left: 1.5rem; line-height: 1.6; }
`;

let katexPromise = null;
const typeset = new Map();  // (display?) + TeX -> KaTeX's HTML, kept across runs and pages

function html(katex, tex, display) {
  const key = (display ? "D" : "I") + tex;
  let out = typeset.get(key);
  if (out === undefined) {
    out = katex.renderToString(tex, {displayMode: display, throwOnError: false, output: "htmlAndMathml"});
    if (typeset.size > 4000) typeset.clear();
    typeset.set(key, out);
  }
  return out;
}

// A slip's text: plain text with $inline math$, **bold** and *emphasis*, as the solvers write them.
// Built as nodes (text is never parsed as HTML); only KaTeX's own output is inserted as HTML.
function inline(katex, text, into) {
  const parts = /\$([^$]+)\$|\*\*([^*]+)\*\*|\*([^*\s][^*]*)\*/g;
  let at = 0;
  for (const m of text.matchAll(parts)) {
    into.append(text.slice(at, m.index));
    if (m[1] !== undefined) {
      const span = document.createElement("span");
      span.innerHTML = html(katex, m[1], false);
      into.append(span);
    } else {
      const mark = document.createElement(m[2] !== undefined ? "strong" : "em");
      mark.textContent = m[2] ?? m[3];
      into.append(mark);
    }
    at = m.index + m[0].length;
  }
  into.append(text.slice(at));
}

class Derivation {
  constructor(parent) {
    if (!document.getElementById("dl-derivation-style"))  // one stylesheet for the page
      document.head.append(Object.assign(document.createElement("style"), {id: "dl-derivation-style", textContent: CSS}));
    this.root = document.createElement("div");
    this.root.className = "dl-derivation";
    this.heading = document.createElement("h3");
    this.caption = document.createElement("p");
    this.caption.className = "dl-muted";
    this.steps = document.createElement("div");
    this.slips = document.createElement("div");
    this.root.append(this.heading, this.caption, this.steps, this.slips);
    parent.replaceChildren(this.root);
    this.shown = [];  // per step: [title, tex]
    this.slipsShown = null;
  }

  update(katex, d) {
    if (this.heading.textContent !== d.heading) this.heading.textContent = d.heading;
    if (this.caption.textContent !== d.caption) this.caption.textContent = d.caption;
    this.caption.hidden = !d.caption;
    d.steps.forEach(([title, tex], i) => {
      let step = this.steps.children[i];
      if (!step) {
        step = document.createElement("div");
        const p = document.createElement("p");
        p.append(document.createElement("strong"), document.createTextNode(""));
        const math = document.createElement("div");
        math.className = "dl-math";
        step.append(p, math);
        this.steps.append(step);
        this.shown[i] = [null, null];
      }
      const [oldTitle, oldTex] = this.shown[i];
      if (title !== oldTitle) {
        const p = step.firstChild;
        p.firstChild.textContent = `${i + 1}.`;
        p.lastChild.textContent = ` ${title}`;
      }
      if (tex !== oldTex) step.lastChild.innerHTML = html(katex, tex, true);
      this.shown[i] = [title, tex];
    });
    while (this.steps.children.length > d.steps.length) this.steps.lastChild.remove();
    this.shown.length = d.steps.length;
    const slips = JSON.stringify([d.slips_heading, d.slips]);
    if (slips !== this.slipsShown) {
      this.slips.replaceChildren();
      if (d.slips.length) {
        const h = document.createElement("h4");
        h.textContent = d.slips_heading;
        const ul = document.createElement("ul");
        for (const note of d.slips) {
          const li = document.createElement("li");
          inline(katex, note, li);
          ul.append(li);
        }
        this.slips.append(h, ul);
      }
      this.slipsShown = slips;
    }
  }
}

const views = new WeakMap();
const decoder = new TextDecoder();

export async function render({data, parentElement}) {
  const d = JSON.parse(typeof data === "string" ? data : decoder.decode(data));
  // KaTeX's script (UMD) sets window.katex when it runs; loaded once per page.
  katexPromise ??= import(new URL(d.katex, location.href).href).then(() => window.katex);
  const katex = await katexPromise;
  let view = views.get(parentElement);
  if (!view) views.set(parentElement, view = new Derivation(parentElement));
  view.update(katex, d);
}
