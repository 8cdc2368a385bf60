"""Live values while dragging (solvers/live.py, ui/plotly_component/live.js) against the server.

For every page, hypothesis draws valid parameters (the problem's own ``VALID``), with the followed
controls anywhere on their range (so that drags cross regimes and limits), and node evaluates the
generated JavaScript on the whole batch at once: each value must be ``solve``'s to 1e-9 relative, the
regime ``Solution.regime``, a physical limit or a refusal no values at all; the formatting the live
view writes must be ``ui/results.answer_rows``'s, character for character."""
from __future__ import annotations

import importlib
import json
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, example, given, settings
from hypothesis import strategies as st

from solvers import live, registry, units
from solvers.core import Number, PhysicalLimitError
from solvers.formatting import plain_number
from solvers.catalog import BY_ID
from ui import figure as component

ROOT = Path(__file__).resolve().parents[2]
NODE = shutil.which("node")
# Skipped on a workstation without node; in CI (.ci/run installs Debian's nodejs) a missing node fails.
pytestmark = pytest.mark.skipif(NODE is None and not os.environ.get("CI"), reason="needs node (apt-get install nodejs)")

# Answers the browser cannot compute (integrals by quadrature): typed here from PROBLEMS.md, not read
# from the generator. Every other answer of every page must be live.
NOT_LIVE = {"sliding_ladder": {"t_leave", "t_floor"}}
BATCH = 40


def node(tmp_path: Path, program: str, payload) -> list:
    """Run ``program`` (an ES module importing live.js as ``./live.mjs``) with ``payload`` on stdin."""
    (tmp_path / "live.mjs").write_bytes(component.module("live.js")[1])  # as served: the seam's DOM first
    (tmp_path / "main.mjs").write_text('import fs from "node:fs";\nimport * as live from "./live.mjs";\n'
                                       "const input = JSON.parse(fs.readFileSync(0, 'utf8'));\n" + program)
    out = subprocess.run([NODE, str(tmp_path / "main.mjs")], input=json.dumps(payload), capture_output=True,
                         text=True, timeout=60, check=True)
    return json.loads(out.stdout)


EVALUATE = ("const fns = await Promise.all(input.map(([source]) => live.load(source)));\n"
            "console.log(JSON.stringify(input.map(([, params], i) => fns[i](live.fromJSON(params)))));")


def as_json(params: dict) -> dict:
    return {k: ("inf" if isinstance(v, float) and math.isinf(v) else v) for k, v in params.items()}


def dragged(pid: str):
    """The problem's VALID parameters with each followed control anywhere on its control's range."""
    solver = registry.solver(pid)
    valid = importlib.import_module(f"tests.physics.test_{pid}").VALID
    numbers = {p.name: p for p in solver.PARAMS if isinstance(p, Number)}
    ranges = {}
    for name in solver.LIVE.follows:
        p = numbers[name]
        low = p.ui_low if p.ui_low is not None else p.low
        ranges[name] = st.floats(float(low), float(p.ui_high), allow_nan=False).map(
            lambda shown, d=p.dimension: units.to_si(shown, d))
    return st.tuples(valid, st.fixed_dictionaries({}, optional=ranges)).map(lambda pair: pair[0] | pair[1])


def outcome(pid: str, params: dict):
    """("values", solution) | ("limit", the error) | ("refused", None)"""
    try:
        return "values", registry.solver(pid).solve(**params)
    except PhysicalLimitError as error:
        return "limit", error
    except ValueError:
        return "refused", None


def solved(pid: str, samples):
    """The solutions of those ``samples`` the solver answers (limits and refusals left out)."""
    for params in samples:
        kind, solution = outcome(pid, params)
        if kind == "values":
            yield solution


def close(a: float, b: float, scale: float) -> bool:
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12 * scale)


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_every_problem_opts_in(pid):
    assert live.declared(pid) is not None, f"{pid}: no LIVE"
    solver = registry.solver(pid)
    numbers = {p.name for p in solver.PARAMS if isinstance(p, Number)}
    assert set(solver.LIVE.follows) <= numbers & set(solver.ABOUT.primary)


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_live_values_are_the_solvers(pid, tmp_path_factory):
    # no shrinking: a failure names its parameters in the message, and shrinking a batch takes minutes
    @settings(max_examples=3, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.lists(dragged(pid), min_size=BATCH, max_size=BATCH))
    def check(samples):
        sources = [live.function_source(pid, live.options_of(pid, {**_defaults(pid), **p})) for p in samples]
        results = node(tmp_path_factory.mktemp("node"), EVALUATE,
                       [[src, as_json({**_defaults(pid), **p})] for src, p in zip(sources, samples)])
        counts = {}
        for params, got in zip(samples, results):
            kind, solution = outcome(pid, params)
            counts[kind] = counts.get(kind, 0) + 1
            if kind != "values":
                assert got["values"] is None, (params, got)
                if kind == "limit":  # the same regime, said in the same words as the release's refusal
                    assert got["regime"] != live.REFUSED, params
                    said = {c.regime: c.said for c in live.cases(pid, live.options_of(pid, {**_defaults(pid), **params}))}
                    assert said[got["regime"]].casefold() in str(solution).casefold(), (params, got["regime"], str(solution))
                continue
            assert got["regime"] == solution.regime, (params, got["regime"], solution.regime)
            shown = BY_ID[pid].answers_of(solution)
            missing = {a.name for a in shown if a.name not in got["values"]}
            assert missing == NOT_LIVE.get(pid, set()) & {a.name for a in shown}, (params, missing)
            for a in shown:
                if a.name in missing:
                    continue
                # the size of what it is computed from: an energy lost is a difference of the energies
                # before and after (the ledger's), each exact only to its own last digits
                same = [abs(solution.answers[b.name]) for b in shown if b.dimension == a.dimension] + [
                    abs(x) for row in solution.ledger if row.dimension == a.dimension for x in (row.before, row.after)]
                assert close(got["values"][a.name], solution.answers[a.name], max(same)), (
                    a.name, params, got["values"][a.name], solution.answers[a.name])
        assert counts.get("values", 0) > 0
    check()


def _defaults(pid: str) -> dict:
    return {p.name: p.default for p in registry.solver(pid).PARAMS}


def test_regimes_are_crossed():
    """The draws reach the regimes a drag can cross: the disk's stick and slip, the pendulum's release
    below the impact, the spring stopping the rod, the cart's lift-off (else the test above proves
    little about them)."""
    cases = {
        "disk_wall": [({"mu": 0.05, "omega": 40.0}, "slip"), ({"mu": 5.0}, "stick")],
        "pendulum_rebound": [({"theta0": math.radians(-60)}, "below_impact")],
        "rod_disk_spring": [({"k": 50.0}, "stops"), ({"k": 300.0}, "upright"), ({"k": 0.0}, "welded"),
                            ({"k": 300.0, "theta1": 0.5}, "spring_wins")],
        "driven_cart": [({"drive": "rear", "mu": 3.0}, "lift_off")],
        "stick_ball": [({"s": 0.9}, "off_stick")],
    }
    for pid, pairs in cases.items():
        for params, regime in pairs:
            full = {**_defaults(pid), **params}
            source = live.function_source(pid, live.options_of(pid, full))
            got = node(Path(__import__("tempfile").mkdtemp()), EVALUATE, [[source, as_json(full)]])[0]
            assert got["regime"] == regime, (pid, params, got)
            kind, solution = outcome(pid, full)
            assert (kind == "values") == (got["values"] is not None), (pid, params, kind)


# Answers are below 1e300 (``within_model_range``); plain_number itself overflows rounding 1.7975e308.
NUMBERS = st.one_of(st.floats(-1e300, 1e300), st.sampled_from([math.inf, -math.inf, 0.0, -0.0]),
                    st.floats(-1e7, 1e7), st.floats(-1, 1),
                    st.integers(-10**7, 10**7).map(lambda n: n / 8))  # n/8: exact ties at the fourth figure


@settings(max_examples=5, deadline=None, suppress_health_check=list(HealthCheck),
          phases=(Phase.explicit, Phase.reuse, Phase.generate))
@given(st.lists(NUMBERS, min_size=300, max_size=300))
def test_numbers_are_written_as_the_page_writes_them(tmp_path_factory, xs):
    got = node(tmp_path_factory.mktemp("fmt"), "console.log(JSON.stringify(input.map((x) => live.plainNumber(x === 'inf' ? "
               "Infinity : x === '-inf' ? -Infinity : x))));", [("inf" if x == math.inf else "-inf" if x == -math.inf else x)
                                                                for x in xs])
    assert got == [plain_number(x) for x in xs]


def test_quantities_are_written_as_the_answers_table_writes_them(tmp_path):
    """Units (solvers/units.py, sent as data) and an angle's radians, as ui/results.answer_rows."""
    from ui.results import answer_rows

    rows, payloads = [], []
    for pid, system in (("pendulum_rebound", "us"), ("pendulum_rebound", "si"), ("driven_cart", "si"),
                        ("sliding_ladder", "si")):
        solution = registry.solver(pid).solve()
        answers = BY_ID[pid].answers_of(solution)
        data = live.payload(pid, solution.params, answers, system, {})
        rows += [row[2] for row in answer_rows(solution, answers, system)]
        payloads += [[solution.answers[a.name], row] for a, row in zip(answers, data["answers"])]
    got = node(tmp_path, "console.log(JSON.stringify(input.map(([x, row]) => live.quantity(x, row, 1e6))));", payloads)
    assert got == rows


CAPTION = ("const fns = await Promise.all(input.map(([source]) => live.load(source)));\n"
           "console.log(JSON.stringify(input.map(([, params, parts, grouped], i) => { const p = live.fromJSON(params);"
           " const r = fns[i](p); return r.values ? live.headlineText(parts, {...p, ...r.values}, grouped) : null; })));")


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_the_caption_s_headline_follows_as_the_server_writes_it(pid, tmp_path_factory):
    """The stage figure's caption starts with its headline (viz.common.headline), and the browser's
    headline for dragged values (the generated function's values, written by live.js) is the server's
    caption for those values, character for character, wherever the regime is the server's."""
    from solvers.formatting import GROUPED_BELOW
    from viz.common import headline_text

    viz = importlib.import_module(f"viz.{pid}")
    if not viz.figures(registry.solver(pid).solve(), "si")[0].headline:
        assert pid == "eulers_disk", pid  # its caption opens with the slow-motion factor and the period in ms: not live
        return

    @settings(max_examples=2, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.lists(dragged(pid), min_size=8, max_size=8))
    def check(samples):
        cases = []
        for solution in solved(pid, samples):
            stage = viz.figures(solution, "si")[0]
            if not stage.headline:
                continue
            text = headline_text(stage.headline, {**solution.params, **solution.answers})
            assert stage.description.startswith(text) and any(not isinstance(part, str) for part in stage.headline)
            source = live.function_source(pid, live.options_of(pid, solution.params))
            cases.append(([source, as_json(solution.params), stage.headline, GROUPED_BELOW], text))
        if cases:
            assert node(tmp_path_factory.mktemp("caption"), CAPTION, [c for c, _ in cases]) == [t for _, t in cases]
    check()


FIXED = st.tuples(st.one_of(st.floats(-1e6, 1e6), st.integers(-10**6, 10**6).map(lambda n: n / 8),
                            st.sampled_from([0.0, -0.0, -0.04, 0.05, -0.05, 2.5, -2.5, 0.25])), st.integers(0, 3))


@settings(max_examples=3, deadline=None, suppress_health_check=list(HealthCheck),
          phases=(Phase.explicit, Phase.reuse, Phase.generate))
@given(st.lists(FIXED, min_size=300, max_size=300))
def test_fixed_decimals_are_written_as_the_captions_write_them(tmp_path_factory, pairs):
    """live.plainFixed against solvers.formatting.plain_fixed: exact ties (n/8) to even, no −0."""
    from solvers.formatting import plain_fixed

    got = node(tmp_path_factory.mktemp("fixed"), "console.log(JSON.stringify(input.map(([x, d]) => live.plainFixed(x, d))));",
               pairs)
    assert got == [plain_fixed(x, d) for x, d in pairs]


POSE = ("const fns = await Promise.all(input.map(([source]) => live.load(source)));\n"
        "const poses = await Promise.all(input.map(([, pose]) => live.load(pose)));\n"
        "console.log(JSON.stringify(input.map(([, , params], i) => { const p = live.fromJSON(params);"
        " const r = fns[i](p); return r.values ? live.poseOf(poses[i], p, r.values, input[i][3]) : null; })));")
# Stage figures whose key pose is not live (dimmed while dragging), and why.
NOT_POSED: dict[str, str] = {}


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_the_key_pose_follows_as_the_figure_draws_it(pid, tmp_path_factory):
    """The stage figure's key instant while a control is dragged: the browser's pose (generated from
    the viz module's own ``key_pose`` on symbols, evaluated by node with the live function's values)
    is ``key_pose`` with numpy for the dragged values to 1e-9 relative, and the figure the server
    draws for those values shows that pose at its key frame (to the figure's rounding)."""
    from ui.live import pose_source
    from viz.common import DIGITS, unpacked

    viz = importlib.import_module(f"viz.{pid}")
    if not hasattr(viz, "key_pose"):
        assert pid in NOT_POSED, f"{pid}: no key_pose (or say why in NOT_POSED)"
        return

    @settings(max_examples=2, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.lists(dragged(pid), min_size=6, max_size=6), st.sampled_from(["si", "us"]))
    def check(samples, system):
        cases = []
        for solution in solved(pid, samples):
            options = live.options_of(pid, solution.params)
            cases.append((solution, [live.function_source(pid, options), pose_source(pid, options, system),
                                     as_json(solution.params), DIGITS]))
        if not cases:
            return
        got = node(tmp_path_factory.mktemp("pose"), POSE, [c for _, c in cases])
        for (solution, _), pose in zip(cases, got):
            expected = viz.key_pose(solution.params, solution.answers, system)
            assert pose is not None, solution.params
            hidden = {name for name, rows in pose.items() if all(v is None for row in rows for v in row)}
            assert set(expected) <= set(pose) and set(pose) - set(expected) <= hidden, (solution.params, set(pose))
            scale = max(abs(v) for xy in expected.values() for row in xy for v in row if not math.isnan(v))
            for name, rows in expected.items():
                assert len(rows) == len(pose[name]), name
                for axis, want, have in zip("xyz", rows, pose[name]):
                    assert len(want) == len(have), (name, axis)
                    for w, h in zip(want, have):
                        assert (h is None) == math.isnan(w) and (h is None or close(h, w, scale)), (
                            solution.params, name, axis, h, w)
            # the figure as sent (its rows compacted, rebuilt as the browser does) draws that pose at its key frame
            stage = viz.figures(solution, system)[0]
            spec = json.loads(stage.json())
            anim = spec["animation"]
            rows_of = {spec["data"][j]["name"]: unpacked(c, len(anim["times"])) for j, c in zip(anim["traces"], anim["coords"])}
            static = {t["name"]: {k: [t[k]] * len(anim["times"]) for k in "xyz" if k in t} for t in spec["data"]
                      if t.get("x") is not None}
            for name, rows in expected.items():
                for axis, want in zip("xyz", rows):
                    have = np.array((rows_of.get(name) or static[name])[axis][stage.key_frame], dtype=float)
                    assert np.allclose(have, want, rtol=0, atol=2e-4 * max(1.0, scale), equal_nan=True), (
                        solution.params, name, axis, have, want)
    check()


@settings(max_examples=5, deadline=None, suppress_health_check=list(HealthCheck),
          phases=(Phase.explicit, Phase.reuse, Phase.generate))
@given(st.lists(st.tuples(st.sampled_from([0.0025, 0.01, 0.05, 0.1, 0.25, 0.5, 1.0, 50.0]), st.integers(-4000, 4000),
                          st.sampled_from([0.005, 0.1, 0.0, -50.0, 3.14159])), min_size=100, max_size=100))
def test_a_dragged_thumb_writes_its_value_as_the_slider_s_format(tmp_path_factory, grid):
    """live.js's thumbText, which writes a dragged stage slider's value as Streamlit would: a lesson's
    number to six figures (``%.6g``: 3.1, not 3.10000; 0.0375), an angle or a fraction to its step's
    decimals (``%.2f`` for 0.05: ui.params.display_format), here against Python's printf."""
    from solvers.core import Number
    from ui.params import display_format

    values = [round(low + k * step, 10) for step, k, low in grid]
    formats = [display_format(Number("x", 0.5, "x", "dimensionless", "x", low=0, high=1, step=step)) for step, _, _ in grid]
    on_grid = [round(k * step, 6) for step, k, _ in grid]  # (a fixed format's slider moves on its own decimals)
    got = node(tmp_path_factory.mktemp("thumb"), "console.log(JSON.stringify(input.map(([v, w, d]) => [live.thumbText(v, {figures: 6}),"
               " live.thumbText(w, {decimals: d, figures: 0})])));",
               [[v, w, int(f[2:-1])] for v, w, f in zip(values, on_grid, formats)])
    assert got == [["%.6g" % v, f % w] for v, w, f in zip(values, on_grid, formats)]


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_the_forces_overlay_follows_a_drag_as_the_figure_draws_it(pid, tmp_path_factory):
    """The stage's Forces overlay while a control is dragged: the browser's pose of its arrows and labels
    (viz.diagram.overlay_pose on symbols: each diagram's ``key`` from the live values, at the run's
    scales) evaluated by node, against the overlay the server draws for those values at the figure's
    key frame (from ``Diagram.frames`` on the solver's motion: another path to the same numbers)."""
    from ui.live import pose_source
    from ui.page import _computed
    from viz import diagram
    from viz.common import DIGITS, unpacked

    if not hasattr(importlib.import_module(f"viz.{pid}"), "key_pose"):
        return
    solver = registry.solver(pid)
    if not any(d.frames is not None for d in solver.free_body_diagrams(solver.solve().params)):
        return  # (a 3-D stage: no overlay)

    @settings(max_examples=2, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.lists(dragged(pid), min_size=4, max_size=4), st.sampled_from(["si", "us"]))
    def check(samples, system):
        cases = []
        for solution in solved(pid, samples):
            _, figures = _computed(pid, tuple(sorted(solution.params.items())), system, True)
            stage = figures[0]
            scales = stage.extra["overlay_scales"]
            params = {**solution.params, **{diagram.SCALE_NAMES[k]: v for k, v in scales.items()}}
            options = live.options_of(pid, solution.params)
            cases.append((stage, [live.function_source(pid, options), pose_source(pid, options, system, True),
                                  as_json(params), DIGITS]))
        if not cases:
            return
        got = node(tmp_path_factory.mktemp("forces"), POSE, [c for _, c in cases])
        for (stage, _), pose in zip(cases, got):
            assert pose is not None
            spec = json.loads(stage.json())
            anim = spec["animation"]
            rows_of = {spec["data"][j]["name"]: unpacked(c, len(anim["times"])) for j, c in zip(anim["traces"], anim["coords"])}
            overlaid = [t["name"] for t in spec["data"] if t.get("legendgroup") == "forces"]
            assert overlaid and len(set(overlaid)) == len(overlaid), overlaid  # (a pose finds a trace by its name)
            posed = [name for name in overlaid if name in pose]
            assert posed, (pid, overlaid, set(pose))
            width = float(np.ptp(spec["layout"]["xaxis"]["range"]))
            for name in overlaid:
                for axis in "xy":
                    want = np.array(rows_of[name][axis][stage.key_frame], dtype=float)
                    if name not in pose:  # an arrow no phase draws at the key frame
                        assert not np.isfinite(want).any(), (name, want)
                        continue
                    have = np.array([np.nan if v is None else v for v in pose[name]["xy".index(axis)]], dtype=float)
                    assert np.allclose(have, want, rtol=0, atol=1e-3 * width, equal_nan=True), (name, axis, have, want)
    check()


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_the_stage_s_headline_shows_an_answer_the_dragged_control_changes(pid):
    """While a lesson control is dragged the stage's headline shows ``solvers.live.leads``' answer for it:
    moved a little on its range (the same regime), the solver's own value of that answer changes; where
    the dependency finds none (the first answer), no answer changes."""
    from solvers.catalog import BY_ID

    problem = BY_ID[pid]
    solver = problem.solver
    numbers = {p.name: p for p in solver.PARAMS if isinstance(p, Number)}

    defaults = {p.name: p.default for p in solver.PARAMS}

    @settings(max_examples=8, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.data())
    def check(data):  # the page's defaults, a followed control anywhere on its range (a student's drag)
        name = data.draw(st.sampled_from(solver.LIVE.follows))
        p = numbers[name]
        at = data.draw(st.floats(float(p.ui_low if p.ui_low is not None else p.low), float(p.ui_high)))
        kind, solution = outcome(pid, {**defaults, name: units.to_si(at, p.dimension)})
        if kind != "values":
            return
        names = tuple(a.name for a in problem.answers_of(solution))
        lead = live.leads(pid, live.options_of(pid, solution.params), solution.regime, names)
        low = units.to_si(float(p.ui_low if p.ui_low is not None else p.low), p.dimension)
        high = units.to_si(float(p.ui_high), p.dimension)
        value = solution.params[name]
        if not math.isfinite(value):
            return
        nudge = (high - low) * data.draw(st.sampled_from([0.02, -0.02, 0.05, -0.05]))
        if not low <= value + nudge <= high:
            nudge = -nudge
        kind, moved = outcome(pid, {**solution.params, name: value + nudge})
        if kind != "values" or moved.regime != solution.regime:
            return
        shown = names[lead[name]]
        changes = {n: not close(moved.answers[n], solution.answers[n], abs(solution.answers[n]) + 1) for n in names
                   if math.isfinite(solution.answers[n]) and math.isfinite(moved.answers[n])}
        if changes.get(shown):
            return
        assert lead[name] == 0 and not any(changes.values()), (name, shown, changes, solution.params)
    check()


# ------------------------------------------------------------------ the motion the browser computes (issue 51)
MOTION = ("const gens = await Promise.all(input.map(([file]) => import('./' + file)));\n"
          "console.log(JSON.stringify(input.map(([, anim, layout, digits], i) => live.motionOf(gens[i], anim, layout, digits))));")
# States each motion computed in the browser is tried at besides the drawn ones: where an event ends it
# (the stick swinging round into the bounced ball, 1.41 s after the impact), where an integration runs long.
MOTION_EXAMPLES = {"stick_ball": [{"mode": "bounce", "s": 0.25}, {"mode": "bounce", "s": 0.1, "e": 1.0}],
                   # a long swing from near upright (300 frames), a wall at the bottom, no rebound
                   "pendulum_rebound": [{"theta0": math.radians(89), "e": 1.0, "surface": "wall"},
                                        {"surface": "wall", "e": 0.3}, {"e": 0.0},
                                        # e = SEEN: the first rebound is the slowest drawn (solvers.pendulum_rebound.stays)
                                        {"e": 0.001, "theta0": 0.17763884442409192, "L": 2.1365633284384926}],
                   # released near upright (a slow start: the longest motion; an address may ask for 1e-5 rad from it) and near flat
                   "sliding_ladder": [{"theta0": math.radians(89)}, {"theta0": math.radians(5)}, {"theta0": math.pi / 2 - 1e-5}],
                   # the control's ends: nearly flat (the fastest precession, the spin all but none) and nearly upright
                   "eulers_disk": [{"theta": math.radians(0.5)}, {"theta": math.radians(89.5), "r": 0.5}],
                   # nudged at upright (it creeps for seconds), no spring: over the top (nudged upright, and 3e-4 rad
                   # from it), no spring from 30° (at rest at 330°), θ₂ half a degree past θ₁, the disk pinned
                   "rod_disk_spring": [{"theta1": 0.0}, {"k": 0.0, "theta1": 0.0}, {"k": 0.0, "theta1": 3e-4},
                                       {"k": 0.0, "theta1": math.radians(30), "theta2": math.radians(300)},
                                       {"theta1": math.radians(30), "theta2": math.radians(30.5)}, {"disk": "pinned", "k": 45.0},
                                       # θ₂ passed 0.13° before the spring stops it (tests/physics/test_rod_disk_spring.py)
                                       {"m1": 2.874951628287427, "m2": 10.16703829397586, "L": 1.699504256378757, "R": 0.4356766195602051,
                                        "g": 18.99104393376579, "disk": "pinned", "k": 279.60003565268397, "theta1": 0.10062537109580985,
                                        "theta2": 2.3712327735774354}]}
# Stage motions the server still draws frame by frame, and why (each a step of issue 51 to come): none now.
SERVER_DRAWN: dict[str, str] = {}


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_the_browser_s_motion_is_the_server_s(pid, tmp_path_factory, monkeypatch):
    """The lesson page's motion computed in the browser (ui/live.py: motion_source; live.js: motionOf,
    in node) against the figure the server draws from the solver's own motion, which stays the
    reference: for hypothesis-drawn parameters on every page, the same frames at the same times (to
    1e-6 s), every point of every body in every frame and the axes that hold them to 1e-6 of the
    motion's size. Both sides round to 12 decimals here, not the figure's 4, so that a coordinate near a
    rounding boundary cannot differ by a unit of the rounding."""
    from ui import live as ui_live
    from viz import common

    if not ui_live.in_browser(pid):
        assert pid in SERVER_DRAWN, f"{pid}: its motion is not computed in the browser (or say why in SERVER_DRAWN)"
        return
    assert pid not in SERVER_DRAWN, f"{pid}: computed in the browser now: take it out of SERVER_DRAWN"
    monkeypatch.setattr(common, "DIGITS", 12)
    viz = importlib.import_module(f"viz.{pid}")

    @settings(max_examples=3, deadline=None, suppress_health_check=list(HealthCheck),
              phases=(Phase.explicit, Phase.reuse, Phase.generate))
    @given(st.lists(dragged(pid), min_size=12, max_size=12), st.sampled_from(["si", "us"]))
    @example([{**_defaults(pid), **state} for state in MOTION_EXAMPLES.get(pid, ())] or [_defaults(pid)], "si")
    def check(samples, system):
        cases, served = [], tmp_path_factory.mktemp("motion")
        (served / "package.json").write_text('{"type": "module"}')  # the generated files as the page imports them
        for solution in solved(pid, samples):
            spec = json.loads(viz.figures(solution, system, in_browser=True)[0].json())  # as sent
            options = live.options_of(pid, solution.params)
            name = ui_live._motion_file(pid, options, system)
            for file in (name, ui_live._values_file(pid, options)):  # (the motion imports the values beside it)
                shutil.copy(component.assets() / file, served / file)
            cases.append((solution, spec["layout"], [name, spec["animation"], spec["layout"], 12]))
        if not cases:
            return
        got = node(served, MOTION, [c for _, _, c in cases])
        for (solution, sent, (_, sent_animation, _, _)), motion in zip(cases, got):
            assert motion is not None, solution.params
            reference = viz.figures(solution, system)[0].spec  # frame by frame on the server, as the figure always was
            anim = reference["animation"]
            assert len(motion["times"]) == len(anim["times"]), solution.params
            if pid == "stick_ball" and solution.params["mode"] == "bounce" and solution.params["s"] == 0.25:
                assert 1.35 < motion["times"][-1] < 1.45  # ended by the second contact (tests/physics/test_stick_ball.py)
            # (both written to the microsecond: equal, or a unit apart where the two sit either side of a rounding boundary)
            assert np.allclose(motion["times"], anim["times"], rtol=0, atol=1.001e-6), solution.params
            rows = [{k: [np.asarray(row, dtype=float) for row in c[k]] for k in ("x", "y", "z") if k in c} for c in anim["coords"]]
            # every frame's every point of the traces on the same axes (the stage's metres, not θ(t)'s degrees)
            axes = [(reference["data"][j].get("xaxis", "x"), reference["data"][j].get("yaxis", "y")) for j in anim["traces"]]
            sizes = {a: np.nanmax(np.abs(np.concatenate([r for c, b in zip(rows, axes) if b == a for k in c for r in c[k]])))
                     for a in set(axes)}
            size = sizes[("x", "y")]  # the stage's
            for j, want, have, on in zip(anim["traces"], rows, motion["coords"], axes):
                name = reference["data"][j]["name"]
                assert set(have) == set(want), name  # (z too in a 3-D scene)
                for axis in want:
                    assert len(have[axis]) == len(want[axis]), (name, axis)
                    for frame, (w, h) in enumerate(zip(want[axis], have[axis])):
                        h = np.array([np.nan if v is None else v for v in h], dtype=float)
                        assert w.shape == h.shape and np.allclose(h, w, rtol=0, atol=1e-6 * sizes[on], equal_nan=True), (
                            solution.params, name, axis, frame)
            # a plot against time drawn from an integrated motion (θ(t) below the pendulum): every point
            assert [line["trace"] for line in motion["traced"]] == [t for t, _ in sent_animation.get("traced", [])]
            for line in motion["traced"]:
                want = reference["data"][line["trace"]]
                for axis in ("x", "y"):
                    w = np.asarray(want[axis], dtype=float)
                    h = np.array([np.nan if v is None else v for v in line[axis]], dtype=float)
                    assert w.shape == h.shape and np.allclose(h, w, rtol=0, atol=1e-6 * max(np.nanmax(np.abs(w)), 1.0)), (
                        solution.params, reference["data"][line["trace"]]["name"], axis)
            # the axes as sent, where the browser has none to widen (a 3-D scene's box: the disk's own)
            if "scene" in reference["layout"]:
                assert motion["ranges"] is None
                for key in ("xaxis", "yaxis", "zaxis"):
                    assert np.allclose(sent["scene"][key]["range"], reference["layout"]["scene"][key]["range"],
                                       rtol=0, atol=1e-6 * size), (solution.params, key)
                continue
            ranges = motion["ranges"] or {"x": sent["xaxis"]["range"], "y": sent["yaxis"]["range"]}
            for axis, key in (("x", "xaxis"), ("y", "yaxis")):
                assert np.allclose(ranges[axis], reference["layout"][key]["range"], rtol=0, atol=1e-6 * size), (
                    solution.params, axis)
    check()
