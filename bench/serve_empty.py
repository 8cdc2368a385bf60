"""The lecture-load baseline on the app's own server (serve.run: the same config, Nagle off), unwarmed.

    python bench/serve_empty.py --server.port 8502
"""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import serve  # noqa: E402

serve.run(ROOT / "bench" / "empty_app.py", sys.argv[1:])
