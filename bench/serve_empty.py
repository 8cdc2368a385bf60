"""The benchmarks' baselines on the app's own server (serve.run: the same config, Nagle off), unwarmed.

    python bench/serve_empty.py --server.port 8502                       # one slider (lecture load)
    python bench/serve_empty.py --script empty_controls.py --server.port 8502   # number box + slider
"""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import serve  # noqa: E402

args = sys.argv[1:]
script = "empty_app.py"
if args[:1] == ["--script"]:
    script, args = args[1], args[2:]
serve.run(ROOT / "bench" / script, args)
