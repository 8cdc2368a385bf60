"""Test-wide settings: Hypothesis runs derandomized in CI (reproducible, no flaky deadlines)."""
import os

import pytest

from hypothesis import HealthCheck, settings

settings.register_profile("dev", deadline=None)
settings.register_profile("ci", deadline=None, derandomize=True, print_blob=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci" if os.environ.get("CI") else "dev")


# The browser tests' shared fixtures (tests/test_browser.py, tests/test_where_used.py): one Chromium
# and one server per test module.
@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    from scripts.live_app import launch_browser

    with sync_playwright() as pw:
        b = launch_browser(pw)
        yield b
        b.close()


@pytest.fixture(scope="module")
def app_url():
    """The app as shipped (serve.py) on a free loopback port, or APP_URL: the container, the balancer."""
    if os.environ.get("APP_URL"):
        yield os.environ["APP_URL"].rstrip("/")
        return
    from scripts.live_app import running_app

    with running_app() as url:
        yield url
