// The lesson's answers, companion figures and derivation in one Streamlit element (ui/page.py,
// ui/figure.together): each part drawn by its own module (text.js, figure.js) into a slot of its own,
// exactly as it would be drawn in an element of its own. Streamlit does an element's work on every run
// (a components-v2 element registers two widgets and a presenter that each later run applies), so one
// element where there were three or four is most of what a run costs beyond the new value's numbers
// (issue 28, BENCHMARKS.md section 1). A part keeps its slot across runs by its key, so a figure that
// did not change is left alone (a running animation goes on) and a cell of the answers whose value did
// not change is not touched.
"use strict";

const decoder = new TextDecoder();
// A part's module, as ui/figure.declared's stub names it (the page's URL resolving its path), so that the
// browser's one module map gives the elements that import it directly and this one the same module.
const load = (url) => import(new URL(url, location.href).href);

// The lesson's downloads and the link that reproduces the page on paper (ui/takehome.lesson_links_data),
// as ui/takehome.lesson_links draws them where a run has no answers. Set as text and attributes, never
// parsed as HTML.
function drawLinks(slot, text) {
  if (slot.dlShown === text) return;
  slot.dlShown = text;
  const d = JSON.parse(text);
  const make = (tag, attributes, ...children) => {
    const el = document.createElement(tag);
    for (const [name, value] of Object.entries(attributes)) el.setAttribute(name, value);
    el.append(...children);
    return el;
  };
  const downloads = d.downloads.map(([label, href, name]) => make("a", {href, download: name, title: d.title},
    make("span", {"aria-hidden": "true", class: "dl-download-icon"}, "↓"), label));
  const printed = make("div", {class: "dl-lesson-links"}, make("p", {class: "dl-print-only dl-print-link"},
    `${d.print_words} `, make("a", {href: d.print}, d.print)));
  slot.replaceChildren(...(downloads.length ? [make("div", {class: "dl-downloads", role: "group", "aria-label": "Downloads"}, ...downloads)] : []),
                       printed);
}

export function render({data, parentElement}) {
  const d = JSON.parse(typeof data === "string" ? data : decoder.decode(data));
  // the parts a gap apart, as Streamlit sets its elements
  Object.assign(parentElement.style, {display: "flex", flexDirection: "column", gap: "1rem"});
  // A part is never moved: a plot moved in the page measures itself while out of it and stays squashed
  // (Study to Lecture puts the figures before the answers). A new order draws every part afresh.
  const keys = d.parts.map((part) => part.key), shown = [...parentElement.children].map((el) => el.dataset.part);
  if (shown.filter((key) => keys.includes(key)).join("\n") !== keys.filter((key) => shown.includes(key)).join("\n"))
    parentElement.replaceChildren();
  for (const el of [...parentElement.children]) if (!keys.includes(el.dataset.part)) el.remove();  // (first: the rest stay put)
  const slots = new Map([...parentElement.children].map((el) => [el.dataset.part, el]));
  d.parts.forEach((part, i) => {
    const data = JSON.stringify(part.data);  // each part's module is handed its data as its own element's would be
    let slot = slots.get(part.key);
    if (!slot) {
      slot = document.createElement("div");
      slot.className = "dl-part";
      slot.dataset.part = part.key;
    }
    if (parentElement.children[i] !== slot) parentElement.insertBefore(slot, parentElement.children[i] || null);
    if (!part.module) { drawLinks(slot, data); return; }
    load(part.module).then((module) => {
      slot.querySelector(":scope > .dl-part-failed")?.remove();
      return module.render({data, parentElement: slot});
    }).catch(() => {  // said in the part's place (the page reloaded fetches it again)
      if (slot.childElementCount) return;
      const failed = document.createElement("p");
      failed.className = "dl-part-failed";
      failed.textContent = "This part of the page did not load: reload the page to see it.";
      slot.append(failed);
    });
  });
}
