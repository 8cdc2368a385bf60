"""Screenshots of every page in headless Chromium, light and dark theme, at the three sizes the app
is used at: a laptop (1400x1000), a projector (1280x720, the lecture view) and a phone (390x844,
touch, 2x pixels; a small one, 360x740, on request). Each page is shot whole (the window grown to the page's height) into
NAME-THEME-SIZE.png, and its first screen, what a person sees before scrolling, into
NAME-THEME-SIZE-first.png.

    python scripts/screenshots.py [--out screenshots] [--query "seed=3"] [--sizes laptop phone]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from edge.streamlit_dom import SELECTORS  # noqa: E402
from solvers.catalog import PROBLEMS  # noqa: E402

SIZES = {"laptop": (1400, 1000), "projector": (1280, 720), "phone": (390, 844), "phone-small": (360, 740)}
VIEW = {"projector": "lecture=1"}  # the projector shows the lecture view
PHONE = {"is_mobile": True, "has_touch": True, "device_scale_factor": 2}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", default="screenshots")
    parser.add_argument("--query", default="")
    parser.add_argument("--pages", nargs="*", default=None)
    parser.add_argument("--themes", nargs="*", default=["light"])
    parser.add_argument("--sizes", nargs="*", default=["laptop"], choices=list(SIZES))
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    paths = [""] + [p.id for p in PROBLEMS]
    if args.pages is not None:
        paths = args.pages
    with running_app() as url, sync_playwright() as pw:
        browser = launch_browser(pw)
        for theme in args.themes:
            for size in args.sizes:
                w, h = SIZES[size]
                context = browser.new_context(viewport={"width": w, "height": h}, color_scheme=theme,
                                              **(PHONE if size.startswith("phone") else {}))
                page = context.new_page()
                for path in paths:
                    query = "&".join(q for q in (VIEW.get(size, "") if path else "", args.query) if q)
                    page.goto(f"{url}/{path}" + (f"?{query}" if query else ""))
                    wait_until_idle(page)
                    page.wait_for_timeout(1200)
                    name = out / f"{path or 'home'}-{theme}-{size}.png"
                    page.screenshot(path=str(name.with_name(name.stem + "-first.png")))
                    # Streamlit scrolls its main block, not the document: grow the window to fit it.
                    tall = page.evaluate("(main) => document.querySelector(main).scrollHeight", SELECTORS["main"])
                    page.set_viewport_size({"width": w, "height": max(h, int(tall))})
                    page.wait_for_timeout(500)
                    page.screenshot(path=str(name))
                    page.set_viewport_size({"width": w, "height": h})
                    print(name)
                context.close()
        browser.close()


if __name__ == "__main__":
    main()
