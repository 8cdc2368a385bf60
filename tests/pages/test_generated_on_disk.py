"""The generated JavaScript kept on disk (solvers.live.kept_on_disk): what a later process reads is what
generating gives, under a key of the code and the arguments; no cache where none is wanted or writable."""
from __future__ import annotations

import os

import pytest

from solvers import live
from ui import live as ui_live

GENERATORS = [(live.function_source, ("disk_wall", ())),
              (ui_live.pose_source, ("rod_disk_spring", (("disk", "welded"),), "si")),
              (ui_live.motion_source, ("pendulum_rebound", (("sphere", "solid"), ("surface", "floor")), "us"))]


def files(where) -> list:
    return sorted(p for p in where.rglob("*.js"))


@pytest.mark.parametrize("generator, args", GENERATORS, ids=lambda g: getattr(g, "__name__", ""))
def test_what_is_read_back_is_what_generation_gives(generator, args, tmp_path, monkeypatch):
    kept = generator.__wrapped__  # under the process's lru_cache
    generated = kept.__wrapped__(*args)  # (what it calls, generated once in this process: kept in memory)
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))
    assert kept(*args) == generated and len(files(tmp_path)) == 1  # written
    (only,) = files(tmp_path)
    only.write_text("// marked")
    assert kept(*args) == "// marked"  # read back, not generated again
    monkeypatch.setattr(live, "_code_key", lambda: "other code")
    assert kept(*args) == generated and len(files(tmp_path)) == 2  # changed code: a key of its own


def test_the_code_key_follows_every_file_that_shapes_the_text(tmp_path, monkeypatch):
    """A copy of the code with one viz module changed by a byte has another key."""
    import shutil

    for folder in ("solvers", "viz"):
        shutil.copytree(live._CODE / folder, tmp_path / folder)
    (tmp_path / "ui").mkdir()
    for name in ("live.py", "figure.py"):
        shutil.copy(live._CODE / "ui" / name, tmp_path / "ui" / name)
    monkeypatch.setattr(live, "_CODE", tmp_path)
    keys = []
    for change in (None, "viz/sliding_ladder.py", "ui/figure.py", "solvers/units.py"):
        if change:
            with open(tmp_path / change, "a") as f:
                f.write("\n")
        live._code_key.cache_clear()
        keys.append(live._code_key())
    live._code_key.cache_clear()
    assert len(set(keys)) == len(keys), keys


def test_off_or_unwritable_generates_as_before(tmp_path, monkeypatch):
    kept = live.function_source.__wrapped__
    generated = kept.__wrapped__("stick_ball", (("mode", "stick"),))
    monkeypatch.setenv("DL_GENERATED_CACHE", "off")
    assert kept("stick_ball", (("mode", "stick"),)) == generated
    blocked = tmp_path / "a file, not a directory"
    blocked.write_text("")
    monkeypatch.setenv("DL_GENERATED_CACHE", str(blocked))
    assert kept("stick_ball", (("mode", "stick"),)) == generated
    assert os.path.isfile(blocked)
