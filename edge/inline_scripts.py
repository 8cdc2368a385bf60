"""The app's own inline scripts, each put in a page by ``st.html(..., unsafe_allow_javascript=True)``.

The Content-Security-Policy (edge/headers.py) allows an inline script only by the hash of its exact text,
so each is a fixed text: what varies goes in the HTML beside it, never into the script. Streamlit's
selectors are the seam's (``$name``: edge/streamlit_dom.py), put in once, when this module is imported.
"""
from edge.streamlit_dom import css

# Streamlit names a slider's thumb twice: its aria-label, and an aria-labelledby that lists the thumb
# and its group, which carries the same aria-label ("θ₀ — release angle … θ₀ — release angle …").
# Without the aria-labelledby a screen reader reads the label once. Installed once per page load; it
# follows every slider Streamlit draws later.
SLIDER_NAMES = css("""<script>
(() => {
  if (window.dlSliderNames) return;
  window.dlSliderNames = true;
  const once = () => document.querySelectorAll("$slider input[type='range'][aria-labelledby]")
    .forEach((thumb) => thumb.removeAttribute("aria-labelledby"));
  new MutationObserver(once).observe(document.body, {childList: true, subtree: true, attributes: true,
                                                     attributeFilter: ["aria-labelledby"]});
  once();
})();
</script>""")


# The press that asks before opening the solution (or keeps it hidden) reruns the page without the button
# pressed, which left the keyboard's focus on the page's body (Tab started again from the top): the button
# that follows takes it. Drawn beside a ``data-dl-focus`` naming that button's key (ui.practice._take_focus),
# on the one run after the press; Streamlit runs it each time it draws it.
TAKE_FOCUS = css("""<script>
(() => {
  const marker = document.currentScript && document.currentScript.parentNode.querySelector("[data-dl-focus]");
  const key = marker ? marker.dataset.dlFocus : "";
  let tries = 0;
  const take = () => {
    const button = key && document.querySelector(".$keyPrefix" + CSS.escape(key) + " button");
    if (button) button.focus(); else if (key && ++tries < 60) requestAnimationFrame(take);
  };
  take();
})();
</script>""")


# A table wider than its column scrolls sideways in Streamlit's box, which a keyboard cannot reach (axe-core:
# scrollable-region-focusable; the gradebook with several problems on a projector): such a box is made a
# focusable, named region (Tab to it, then the arrow keys scroll), as Streamlit does for a table it sizes in
# pixels. Installed once per page load; it follows every table drawn or resized later.
SCROLLABLE_TABLES = css("""<script>
(() => {
  if (window.dlScrollableTables) return;
  window.dlScrollableTables = true;
  const mark = () => document.querySelectorAll("$table > div:not([tabindex])").forEach((box) => {
    if (box.scrollWidth <= box.clientWidth + 1) return;
    const table = box.querySelector("table");
    box.setAttribute("tabindex", "0");
    box.setAttribute("role", "region");
    box.setAttribute("aria-label", ((table && table.getAttribute("aria-label")) || "Table") + ", scrolls sideways");
  });
  // (an expander opened shows a table that was not laid out before: "open" and aria-expanded change)
  new MutationObserver(mark).observe(document.body, {childList: true, subtree: true, attributes: true,
                                                     attributeFilter: ["open", "aria-expanded"]});
  window.addEventListener("resize", mark);
  mark();
})();
</script>""")

# A student's link is copied whole by its Copy button (a partial selection made a link that was refused as
# changed). The button says "Copied" for a moment and a status line beside the list says it too (read out by a
# screen reader); where the page may not write the clipboard (plain http), the link is selected and the line
# says to press Ctrl+C. Beside each list of links (ui.assignments.link_list); one listener per page load.
COPY_LINKS = css("""<script>
(() => {
  if (window.dlCopyLinks) return;
  window.dlCopyLinks = true;
  document.addEventListener("click", async (event) => {
    const button = event.target.closest("button[data-dl-copy]");
    if (!button) return;
    const link = button.closest("li").querySelector("code");
    const status = button.closest(".dl-links").querySelector("[role='status']");
    const who = button.dataset.dlCopy;
    let copied = false;
    try {
      await navigator.clipboard.writeText(link.textContent);
      copied = true;
    } catch (refused) {
      const range = document.createRange();
      range.selectNodeContents(link);
      getSelection().removeAllRanges();
      getSelection().addRange(range);
      try { copied = document.execCommand("copy"); } catch (old) { copied = false; }
    }
    if (!copied) {
      status.textContent = who + "'s link is selected: press Ctrl+C (\u2318C on a Mac) to copy it.";
      return;
    }
    const word = button.querySelector(".dl-copy-word");
    word.textContent = "Copied";
    button.classList.add("dl-copied");
    status.textContent = "Copied " + who + "'s link.";
    clearTimeout(button.dlCopyTimer);
    button.dlCopyTimer = setTimeout(() => { word.textContent = "Copy"; button.classList.remove("dl-copied"); }, 3000);
  });
})();
</script>""")

ALL = (SLIDER_NAMES, TAKE_FOCUS, SCROLLABLE_TABLES, COPY_LINKS)
