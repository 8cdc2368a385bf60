"""Small static pictures for the home page's gallery: one SVG sketch per problem (no physics)."""
from __future__ import annotations

import base64
import functools
import re

from viz.common import COLORS, thumbnail as _svg

BLUE, ORANGE, GREEN, RED, PINK, GREY = (COLORS[k] for k in ("body", "accent", "velocity", "impulse", "force", "ink"))


THUMBNAILS = {
    "disk_wall": _svg(
        f'<line x1="10" y1="14" x2="190" y2="14" stroke="{GREY}" stroke-width="5"/>'
        f'<circle cx="80" cy="68" r="26" fill="{BLUE}33" stroke="{BLUE}" stroke-width="3"/>'
        f'<line x1="80" y1="68" x2="100" y2="84" stroke="{ORANGE}" stroke-width="3"/>'
        f'<line x1="80" y1="68" x2="110" y2="34" stroke="{GREEN}" stroke-width="3" marker-end="url(#g)"/>'
        f'<path d="M120,96 a36,36 0 0 0 14,-30" fill="none" stroke="{ORANGE}" stroke-width="2" stroke-dasharray="4 3"/>',
        "A spinning disk moving toward a wall"),
    "stick_ball": _svg(
        f'<line x1="120" y1="10" x2="120" y2="100" stroke="{BLUE}" stroke-width="7"/>'
        f'<circle cx="50" cy="22" r="8" fill="{RED}55" stroke="{RED}" stroke-width="2"/>'
        f'<line x1="62" y1="22" x2="100" y2="22" stroke="{GREEN}" stroke-width="3" marker-end="url(#g)"/>'
        f'<line x1="120" y1="78" x2="190" y2="78" stroke="{GREEN}" stroke-width="2" stroke-dasharray="6 4"/>',
        "A ball sliding toward the end of a stick"),
    "pendulum_rebound": _svg(
        f'<line x1="10" y1="100" x2="190" y2="100" stroke="{GREY}" stroke-width="5"/>'
        f'<line x1="60" y1="18" x2="120" y2="72" stroke="#555" stroke-width="4"/>'
        f'<circle cx="132" cy="82" r="15" fill="{BLUE}33" stroke="{BLUE}" stroke-width="3"/>'
        f'<path d="M170,20 a90,90 0 0 1 -20,46" fill="none" stroke="{ORANGE}" stroke-width="2" stroke-dasharray="4 3"/>'
        f'<text x="58" y="14" font-size="12" fill="{GREY}">O</text>',
        "A pendulum with a sphere about to strike the floor"),
    "rod_disk_spring": _svg(
        f'<path d="M70,60 m-10,0 a10,10 0 1 0 20,0 a14,14 0 1 0 -28,0 a18,18 0 1 0 36,0" fill="none" stroke="{PINK}" stroke-width="2"/>'
        f'<line x1="70" y1="60" x2="140" y2="30" stroke="#555" stroke-width="4"/>'
        f'<circle cx="154" cy="24" r="15" fill="{BLUE}33" stroke="{BLUE}" stroke-width="3"/>'
        f'<line x1="70" y1="60" x2="70" y2="6" stroke="{GREY}" stroke-width="1" stroke-dasharray="4 3"/>',
        "A rod and disk on a torsional spring"),
    "driven_cart": _svg(
        f'<line x1="5" y1="96" x2="195" y2="96" stroke="{GREY}" stroke-width="4"/>'
        f'<rect x="35" y="44" width="130" height="34" rx="4" fill="{BLUE}33" stroke="{BLUE}" stroke-width="3"/>'
        f'<circle cx="60" cy="82" r="13" fill="white" stroke="#555" stroke-width="3"/>'
        f'<circle cx="140" cy="82" r="13" fill="white" stroke="#555" stroke-width="3"/>'
        f'<line x1="150" y1="60" x2="190" y2="60" stroke="{RED}" stroke-width="3" marker-end="url(#r)"/>',
        "A four-wheeled cart accelerating"),
    "eulers_disk": _svg(
        f'<ellipse cx="100" cy="88" rx="70" ry="14" fill="none" stroke="{GREEN}" stroke-width="2" stroke-dasharray="5 4"/>'
        f'<ellipse cx="100" cy="70" rx="62" ry="22" fill="{BLUE}33" stroke="{BLUE}" stroke-width="3" transform="rotate(-12 100 70)"/>'
        f'<line x1="100" y1="70" x2="150" y2="64" stroke="{ORANGE}" stroke-width="3"/>'
        f'<circle cx="42" cy="86" r="4" fill="{RED}"/>',
        "Euler's disk spinning on a table"),
}


@functools.cache
def thumbnail_markdown(problem_id: str) -> str:
    """The picture as a Markdown image (a data URI) whose alt text is the picture's label."""
    svg = THUMBNAILS[problem_id]
    label = re.search(r'aria-label="([^"]*)"', svg).group(1)
    return f"![{label}](data:image/svg+xml;base64,{base64.b64encode(svg.encode()).decode()})"
