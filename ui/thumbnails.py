"""The home page's pictures: each problem's viz module draws its THUMBNAIL (an SVG sketch); here it
becomes a Markdown image whose alt text is the sketch's label."""
from __future__ import annotations

import base64
import functools
import re

from solvers import registry
from viz.catalog import drawings


@functools.cache
def thumbnail_markdown(problem_id: str) -> str:
    """The picture as a Markdown image (a data URI) whose alt text is the picture's label."""
    registry.solver(problem_id)  # a KeyError that says which problems exist, for an unknown id
    svg = drawings(problem_id).thumbnail
    label = re.search(r'aria-label="([^"]*)"', svg).group(1)
    return f"![{label}](data:image/svg+xml;base64,{base64.b64encode(svg.encode()).decode()})"
