"""The room's answers as the projector shows them: a bar per category (right, each named slip, other;
or a regime question's choices), each round's bar beside the other's (the first vote, then the vote
after a discussion). Plain data, like every figure here: the counts come from room/store.py."""
from __future__ import annotations

import textwrap
from collections import Counter

from viz.common import COLORS, Figure

ROUND_COLORS = (COLORS["body"], COLORS["accent"], COLORS["velocity"], COLORS["force"])
LABEL_WIDTH = 26  # characters of a bar's label per line: the projector's type is large


def round_name(number: int) -> str:
    return "First vote" if number == 1 else "After discussion" if number == 2 else f"Vote {number}"


def _label(text: str, right: bool) -> str:
    return "<br>".join(textwrap.wrap(("✓ " if right else "") + text, LABEL_WIDTH)) or " "


def histogram(bars: tuple[tuple[str, str], ...], counts: dict[int, Counter], right: str | None = None) -> Figure:
    """``bars``: (category, label) in order; ``counts``: each round's answers by category (one a bar does
    not name counts as the last bar, "other"); ``right``: the right category, marked once revealed."""
    rounds = sorted(counts) or [1]
    named = {category for category, _ in bars}
    labels = [_label(label, category == right) for category, label in bars]
    data, said = [], []
    for n in rounds:
        found = Counter(counts.get(n, {}))
        stray = sum(v for k, v in found.items() if k not in named)
        values = [found.get(category, 0) + (stray if i == len(bars) - 1 else 0) for i, (category, _) in enumerate(bars)]
        data.append({"type": "bar", "orientation": "h", "y": labels, "x": values, "name": round_name(n),
                     "marker": {"color": ROUND_COLORS[(n - 1) % len(ROUND_COLORS)]},
                     "text": [str(v) for v in values], "textposition": "outside", "cliponaxis": False})
        total = sum(values)
        said.append(f"{round_name(n)}, {total} answer{'s' * (total != 1)}"
                    + "".join(f"; {label} {v}" for (_, label), v in zip(bars, values) if v))
    most = max((max(d["x"], default=0) for d in data), default=0)
    lines = sum(label.count("<br>") + 1 for label in labels)  # a projector's first screen holds it beside the code
    height = max(240, min(440, 70 + lines * 22 + 30 * len(bars) * len(rounds)))
    layout = {"height": height, "barmode": "group", "bargap": 0.25, "hovermode": False, "dragmode": False,
              "margin": {"l": 10, "r": 30, "t": 10, "b": 50},
              "legend": {"orientation": "h", "y": -0.12, "x": 0, "yanchor": "top"}, "showlegend": len(rounds) > 1,
              "xaxis": {"title": {"text": "answers"}, "rangemode": "tozero", "range": [0, max(4, most) * 1.15],
                        **({"dtick": 1} if most <= 8 else {}), "fixedrange": True},
              "yaxis": {"autorange": "reversed", "automargin": True, "fixedrange": True}}
    description = (". ".join(said) + "."
                   + (f" The right answer: {next(label for c, label in bars if c == right)}." if right in named else ""))
    return Figure("room_histogram", "", {"data": data, "layout": layout}, description, animated=False, height=height)
