"""The code is read-only (issue 52): the server writes nothing into its own directory. Its served files
keyed by their content (the components' modules, the plotly bundles, KaTeX, and the poses generated while
a page runs) go to an asset directory (``ui.figure.assets``: ``DL_ASSET_DIR``, else the system's temporary
directory), so a container can run with a read-only root file system, as the Kubernetes Deployment does."""
from __future__ import annotations

import re
import shutil
import stat
import subprocess
from pathlib import Path

from scripts.live_app import ROOT, running_server
from tests.browser.test_browser import open_page


def shipped_copy(into: Path) -> Path:
    """The repository's tracked files (what the image copies), in ``into``, every file and directory
    made read-only."""
    tracked = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    for name in filter(None, tracked.decode().split("\0")):
        source = ROOT / name
        if source.is_file():
            (into / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, into / name)
    for path in sorted(into.rglob("*"), key=lambda p: len(p.parts), reverse=True):
        path.chmod(stat.S_IRUSR | stat.S_IRGRP | stat.S_IROTH | (stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH if path.is_dir() else 0))
    into.chmod(0o555)
    return into


def every_file(root: Path) -> dict[str, tuple[int, int]]:
    """Each file and directory under ``root``: its size and modification time (what any write changes;
    root, as in CI, writes through read-only permissions, so the copy's are not the check)."""
    return {str(p.relative_to(root)): (p.stat().st_size, p.stat().st_mtime_ns) for p in root.rglob("*")}


def test_the_server_runs_a_page_from_a_read_only_copy_of_the_code(browser, tmp_path):
    code = shipped_copy(tmp_path / "code")
    before = every_file(code)
    assets = tmp_path / "assets"
    env = {"DL_ASSET_DIR": str(assets), "DL_DATA_DIR": str(tmp_path / "data"), "DL_DATABASE_URL": "",
           "PYTHONDONTWRITEBYTECODE": "1"}
    try:
        with running_server(env=env, root=code) as server:
            context, page, errors = open_page(browser, f"{server.url}/pendulum_rebound")
            page.locator(".dl-figure .dl-graph .main-svg").first.wait_for(timeout=60_000)
            page.locator(".dl-answers table").first.wait_for(timeout=60_000)
            assert not errors, errors
            context.close()
            said = server.log.read_text(errors="replace")
    finally:
        for path in [code, *code.rglob("*")]:  # writable again, for tmp_path's clean-up
            if path.is_dir():
                path.chmod(0o755)
    assert every_file(code) == before  # nothing written into the code
    served = {p.name for p in assets.iterdir()}
    assert any(re.fullmatch(r"figure\.[0-9a-f]{16}\.js", n) for n in served), served
    assert any(re.fullmatch(r"pose\.[0-9a-f]{16}\.js", n) for n in served), served  # generated as the page ran
    assert "Traceback" not in said and "PermissionError" not in said, said[-2000:]


def test_the_deployment_runs_with_a_read_only_root_file_system():
    """The Kubernetes Deployment: the root file system read-only, /tmp (where the asset directory
    defaults to) a scratch volume of the pod's own."""
    deployment = (ROOT / "deploy" / "k8s" / "dynamics-lab.yaml").read_text()
    assert "readOnlyRootFilesystem: true" in deployment and "readOnlyRootFilesystem: false" not in deployment
    assert re.search(r"volumeMounts: \[\{name: scratch, mountPath: /tmp\}\]", deployment)
    assert re.search(r"- name: scratch\n\s+emptyDir:", deployment)
