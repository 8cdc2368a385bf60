"""Each problem's drawings (``viz/<pid>.py``) as one record: the one place the app finds a problem's viz
module by its id and reads what the module may declare (the protocol: docs/adding-a-problem.md, checked by
tests/physics/test_protocol.py)."""
from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache


@dataclass(frozen=True)
class OnRequest:
    """A costly extra figure behind a switch, drawn only when asked for (in a worker process: viz/on_request.py)."""
    label: str  # the switch's words ("Letting it run down")
    flag: str  # the link's flag that keeps it open (?rundown=1)
    draw: Callable  # solution -> Figure


@dataclass(frozen=True)
class Drawings:
    figures: Callable  # (solution, system="si") -> the page's figures, the motion first
    thumbnail: str  # the home page's sketch (viz.common.thumbnail)
    at_limit: Callable | None  # (params, system) -> the figures that show why a physical limit stops the model
    key_pose: Callable | None  # the stage figure's bodies at its key instant, for the browser's live pose
    pose_at: Callable | None  # (params, answers, t, system, xp) -> its bodies at any time: the browser draws the frames
    on_request: OnRequest | None
    sketch: Callable  # params -> the problem's sketch (viz/sketch.py): its bodies at the start, the givens marked


@cache
def drawings(pid: str) -> Drawings:
    """The drawings of the registered problem ``pid``."""
    module = importlib.import_module(f"viz.{pid}")
    return Drawings(module.figures, module.THUMBNAIL, getattr(module, "at_limit", None),
                    getattr(module, "key_pose", None), getattr(module, "pose_at", None), getattr(module, "ON_REQUEST", None),
                    module.sketch)
