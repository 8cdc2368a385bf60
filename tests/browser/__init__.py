"""The tests in Debian's Chromium, through Playwright: importing any of them (or a helper of theirs, as
tests/house/test_read_only_code.py does) skips them on a workstation without Chromium and fails in CI,
where .ci/run installs it."""
import os
from pathlib import Path

import pytest

from scripts.live_app import CHROMIUM

if not Path(CHROMIUM).exists():
    if os.environ.get("CI"):
        raise RuntimeError(f"CI needs Chromium at {CHROMIUM} (.ci/run installs Debian's chromium)")
    pytest.skip(f"no Chromium at {CHROMIUM}: apt-get install chromium", allow_module_level=True)

pytest.importorskip("playwright.sync_api")
