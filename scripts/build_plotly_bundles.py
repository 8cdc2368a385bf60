"""Build the figure component's plotly.js from the npm package: only the trace types the figures use.

    python scripts/build_plotly_bundles.py [--out ui/plotly_bundles]

The pins are ui/plotly_bundles/build/package-lock.json (plotly.js, the version inside the pinned plotly
Python package, and esbuild); the entries are build/basic.js (scatter and bar: every 2-D figure) and
build/gl3d.js (and scatter3d, for a page with a 3-D scene), both on build/core.js (plotly.js's core with
only the layout components the figures use). npm installs the locked tree once into a
cache keyed by the lock (about 170 MB, half a minute), then esbuild bundles each entry as plotly.js's
own build does (esbuild-config.js: an IIFE defining ``Plotly``, ``global`` as ``window``, ES2016,
minified). Stylesheets are left out: plotly.js injects its own from build/plotcss.js, and the one
stylesheet an entry reaches is maplibre's, which only a map subplot asks for.
tests/server/test_figure_bundles.py reruns this and compares the output byte for byte with the files
served, so they cannot drift from the pins.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import shutil
import subprocess
import sys
from pathlib import Path

BUNDLES = Path(__file__).resolve().parent.parent / "ui" / "plotly_bundles"
PINS = BUNDLES / "build"
KINDS = {"basic": "scatter, bar", "gl3d": "scatter, bar, scatter3d"}
CACHE = Path.home() / ".cache" / "dynamics-lab" / "plotly-build"


def installed() -> Path:
    """The locked npm tree, installed once per lock (``npm ci`` checks every package's integrity)."""
    lock = (PINS / "package-lock.json").read_bytes()
    home = CACHE / hashlib.sha256(lock + (PINS / "package.json").read_bytes()).hexdigest()[:16]
    if not (home / ".installed").exists():
        shutil.rmtree(home, ignore_errors=True)
        home.mkdir(parents=True)
        for name in ("package.json", "package-lock.json"):
            shutil.copy(PINS / name, home / name)
        subprocess.run(["npm", "ci", "--ignore-scripts", "--no-audit", "--no-fund", "--loglevel=error"],
                       cwd=home, check=True)
        (home / ".installed").touch()
    return home


def plotly_version(home: Path) -> str:
    return json.loads((home / "node_modules" / "plotly.js" / "package.json").read_text())["version"]


def build(out: Path) -> list[Path]:
    home = installed()
    version = plotly_version(home)
    written = []
    for entry in PINS.glob("*.js"):
        shutil.copy(entry, home / entry.name)
    for kind, traces in KINDS.items():
        target = out / f"plotly-{kind}.min.js"
        banner = (f"/**\n* plotly.js ({kind} - minified) v{version}\n* traces: {traces}; built from the npm package"
                  f" by scripts/build_plotly_bundles.py\n* Copyright 2012-2026, Plotly, Inc.\n* All rights reserved.\n"
                  f"* Licensed under the MIT license\n*/")
        subprocess.run([str(home / "node_modules" / ".bin" / "esbuild"), f"{kind}.js", "--bundle", "--minify",
                        "--format=iife", "--global-name=Plotly", "--define:global=window", "--define:define.amd=false",
                        "--target=es2016", "--alias:regl=@plotly/regl", "--alias:stream=stream-browserify",
                        "--loader:.css=empty", "--log-level=warning",
                        f"--banner:js={banner}", f"--outfile={target.resolve()}"], cwd=home, check=True)
        written.append(target)
    return written


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=BUNDLES)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for path in build(args.out):
        print(path, path.stat().st_size, "bytes")


if __name__ == "__main__":
    sys.exit(main())
