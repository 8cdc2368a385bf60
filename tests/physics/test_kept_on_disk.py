"""What the sympy work gives, kept on disk between processes (solvers/kept.py): the generated JavaScript and
the derivations. What a later process reads is what making it gives, under a key of the code and the
arguments; no cache where none is wanted or writable."""
from __future__ import annotations

import importlib
import os
import pickle

import pytest

from solvers import kept, live, registry
from ui import live as ui_live

GENERATORS = [(live.function_source, ("disk_wall", ())),
              (ui_live.pose_source, ("rod_disk_spring", (("disk", "welded"),), "si")),
              (ui_live.motion_source, ("pendulum_rebound", (("sphere", "solid"), ("surface", "floor")), "us"))]


def files(where) -> list:
    return sorted(p for p in where.rglob("*.js"))


@pytest.mark.parametrize("generator, args", GENERATORS, ids=lambda g: getattr(g, "__name__", ""))
def test_what_is_read_back_is_what_generation_gives(generator, args, tmp_path, monkeypatch):
    on_disk = generator.__wrapped__  # under the process's lru_cache
    generated = on_disk.__wrapped__(*args)  # (what it calls, generated once in this process: kept in memory)
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))
    assert on_disk(*args) == generated and len(files(tmp_path)) == 1  # written
    (only,) = files(tmp_path)
    only.write_text("// marked")
    assert on_disk(*args) == "// marked"  # read back, not generated again
    monkeypatch.setattr(kept, "code_key", lambda: "other code")
    assert on_disk(*args) == generated and len(files(tmp_path)) == 2  # changed code: a key of its own


def test_the_code_key_follows_every_file_that_shapes_the_text(tmp_path, monkeypatch):
    """A copy of the code with one viz module changed by a byte has another key."""
    import shutil

    for folder in ("solvers", "viz"):
        shutil.copytree(kept.CODE / folder, tmp_path / folder)
    (tmp_path / "ui").mkdir()
    for name in ("live.py", "figure.py"):
        shutil.copy(kept.CODE / "ui" / name, tmp_path / "ui" / name)
    monkeypatch.setattr(kept, "CODE", tmp_path)
    keys = []
    for change in (None, "viz/sliding_ladder.py", "ui/figure.py", "solvers/units.py"):
        if change:
            with open(tmp_path / change, "a") as f:
                f.write("\n")
        kept.code_key.cache_clear()
        keys.append(kept.code_key())
    kept.code_key.cache_clear()
    assert len(set(keys)) == len(keys), keys


def test_off_or_unwritable_generates_as_before(tmp_path, monkeypatch):
    on_disk = live.function_source.__wrapped__
    generated = on_disk.__wrapped__("stick_ball", (("mode", "stick"),))
    monkeypatch.setenv("DL_GENERATED_CACHE", "off")
    assert on_disk("stick_ball", (("mode", "stick"),)) == generated
    blocked = tmp_path / "a file, not a directory"
    blocked.write_text("")
    monkeypatch.setenv("DL_GENERATED_CACHE", str(blocked))
    assert on_disk("stick_ball", (("mode", "stick"),)) == generated
    assert os.path.isfile(blocked)
    # no home to be found (a container's uid without an account, HOME unset): no cache, no failure
    monkeypatch.delenv("DL_GENERATED_CACHE")
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)

    def nowhere():
        raise RuntimeError("Could not determine home directory.")
    monkeypatch.setattr(kept.Path, "home", staticmethod(nowhere))
    assert kept.cache_dir() is None
    assert on_disk("stick_ball", (("mode", "stick"),)) == generated


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_a_derivation_read_back_is_the_derivation(pid, tmp_path, monkeypatch):
    """A derivation pickled by one process and loaded by the next (``kept_pickled``): the same steps, the same
    chain, and the same numbers and numeric steps from its code compiled again, for the textbook's values."""
    module = importlib.import_module(f"solvers.{pid}")
    made = module._derived if pid == "sliding_ladder" else module.derivation.__wrapped__  # (kept, under functools.cache)
    solution = module.solve()
    asked = []  # the arguments the solution's derivation is made with (its derivation_of), as it asks
    monkeypatch.setattr(module, "derivation", lambda *args: asked.append(args) or made.__wrapped__(*args))
    module.derivation_of(solution)
    monkeypatch.undo()
    args = () if pid == "sliding_ladder" else asked[0]
    fresh = made.__wrapped__(*args)
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))
    assert made(*args) is not None and len(list(tmp_path.rglob("*.pickle"))) == 1
    loaded = made(*args)  # from the disk
    derivation, loaded_derivation = (fresh[0], loaded[0]) if pid == "sliding_ladder" else (fresh, loaded)
    assert loaded_derivation is not derivation
    assert loaded_derivation.steps == derivation.steps and loaded_derivation.chain == derivation.chain
    # the textbook's values (and 0.7 for an input the solver works out first: the ladder's time integrals)
    values = {name: solution.params.get(name, 0.7) for name in derivation._made_of[0]}
    values = {name: value for name, value in values.items() if not isinstance(value, str)}
    numbers = derivation.evaluate(values)
    assert loaded_derivation.evaluate(values) == numbers
    assert loaded_derivation.numeric_steps(values | numbers) == derivation.numeric_steps(values | numbers)
    assert pickle.loads(pickle.dumps(derivation)).steps == derivation.steps
