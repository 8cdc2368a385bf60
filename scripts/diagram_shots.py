"""Screenshots of each page's free-body diagrams (Step 2 of the derivation) at the three sizes, to
look at as a professor would: NAME-SIZE-fbd.png in --out.

    python scripts/diagram_shots.py [--out screenshots] [--pages disk_wall ...] [--url http://127.0.0.1:8501]
"""
from __future__ import annotations

import argparse
import contextlib
import sys
from pathlib import Path

from playwright.sync_api import sync_playwright

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from scripts.screenshots import PHONE, SIZES  # noqa: E402
from solvers.registry import PROBLEM_IDS  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", default="screenshots")
    parser.add_argument("--pages", nargs="*", default=list(PROBLEM_IDS))
    parser.add_argument("--sizes", nargs="*", default=["laptop", "projector", "phone"], choices=list(SIZES))
    parser.add_argument("--url", default="")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with (contextlib.nullcontext(args.url) if args.url else running_app()) as url, sync_playwright() as pw:
        browser = launch_browser(pw)
        for size in args.sizes:
            w, h = SIZES[size]
            context = browser.new_context(viewport={"width": w, "height": h}, **(PHONE if size.startswith("phone") else {}))
            page = context.new_page()
            for pid in args.pages:
                page.goto(f"{url}/{pid}" + ("?lecture=1" if size == "projector" else ""))
                wait_until_idle(page)
                head = page.locator("h4.dl-part", has_text="Step 2").first
                head.wait_for(timeout=30000)
                head.scroll_into_view_if_needed()
                box = head.locator("xpath=..").bounding_box()
                page.screenshot(path=str(out / f"{pid}-{size}-fbd.png"), full_page=True,
                                clip={"x": 0, "y": box["y"], "width": w, "height": min(box["height"] + 10, 1400)})
                print(out / f"{pid}-{size}-fbd.png")
            context.close()


if __name__ == "__main__":
    main()
