"""Screenshots of every page in headless Chromium: light and dark theme, wide and narrow.

    python scripts/screenshots.py [--out screenshots] [--query "lecture=1"]
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from ui.catalog import PROBLEMS  # noqa: E402

SIZES = {"wide": (1400, 1000), "narrow": (800, 1000)}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", default="screenshots")
    parser.add_argument("--query", default="")
    parser.add_argument("--pages", nargs="*", default=None)
    parser.add_argument("--themes", nargs="*", default=["light"])
    parser.add_argument("--sizes", nargs="*", default=["wide"])
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
                context = browser.new_context(viewport={"width": w, "height": h}, color_scheme=theme)
                page = context.new_page()
                for path in paths:
                    page.goto(f"{url}/{path}" + (f"?{args.query}" if args.query else ""))
                    wait_until_idle(page)
                    page.wait_for_timeout(1200)
                    name = out / f"{path or 'home'}-{theme}-{size}.png"
                    # Streamlit scrolls its main block, not the document: grow the window to fit it.
                    tall = page.evaluate("document.querySelector('[data-testid=\"stMain\"]').scrollHeight")
                    page.set_viewport_size({"width": w, "height": max(h, int(tall))})
                    page.wait_for_timeout(500)
                    page.screenshot(path=str(name))
                    page.set_viewport_size({"width": w, "height": h})
                    print(name)
                context.close()
        browser.close()


if __name__ == "__main__":
    main()
