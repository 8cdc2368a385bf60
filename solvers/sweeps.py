"""Curves of a problem's answers against one parameter on a grid (the cart's ẍ against μ, Euler's disk's
rates against the tilt), kept across sessions by what they depend on: every other parameter and the grid.
Moving the swept parameter, a lesson's control, then moves only the problem's own point on them (issue 28)."""
from __future__ import annotations

import functools
from typing import Callable

import numpy as np

Curves = dict[str, np.ndarray]


def swept(over: str, symbols) -> Callable[[Callable[[dict, np.ndarray], Curves]], Callable[[dict, np.ndarray], Curves]]:
    """Decorates ``curves(base, grid)`` (``base``: the parameters named in ``symbols`` but ``over``) into
    ``sweep(params, grid)``, whose curves are cached and read-only (shared by every later figure)."""
    def decorate(curves: Callable[[dict, np.ndarray], Curves]) -> Callable[[dict, np.ndarray], Curves]:
        @functools.lru_cache(maxsize=256)
        def kept(base: tuple, grid: bytes) -> Curves:
            computed = curves(dict(base), np.frombuffer(grid))
            for values in computed.values():
                values.flags.writeable = False
            return computed

        @functools.wraps(curves)
        def sweep(params: dict, grid) -> Curves:
            base = tuple(sorted((k, v) for k, v in params.items() if k in symbols and k != over))
            return dict(kept(base, np.asarray(grid, dtype=float).tobytes()))
        return sweep
    return decorate
