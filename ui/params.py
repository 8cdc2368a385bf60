"""The parameter panel: one control per solver parameter, built from the solver's spec, with every
value mirrored into the URL (in the units the page shows) so that a link reproduces a state.

A value read from the URL is parsed with ``float()`` only (never evaluated), checked against the
solver's own range, and replaced by the default with a warning naming it when it is malformed or
out of range. Combinations are left to the solver, whose message the page shows.
"""
from __future__ import annotations

import math
from typing import Any

import streamlit as st

from solvers.core import Choice, Number, ParameterError
from solvers import units
from ui.catalog import Problem

MAX_URL_VALUE = 32  # characters; longer values are not numbers anyone typed


def _key(problem: Problem, system: str, name: str) -> str:
    return f"{problem.id}__{system}__{name}"


def is_slider(p: Number) -> bool:
    return p.dimension == "angle" or (p.low == 0 and p.high == 1)


def display_format(p: Number) -> str:
    """How the control writes the number (printf style), which the URL copies: a slider to its
    step's decimals (a whole-degree slider shows 30, not 30.00), a box to six figures."""
    if not is_slider(p):
        return "%.6g"
    step = float(p.step or 0.01)
    decimals = 0
    while decimals < 6 and abs(step * 10**decimals - round(step * 10**decimals)) > 1e-9:
        decimals += 1
    return f"%.{decimals}f"


def as_shown(p: Number, shown: float) -> float:
    """``shown`` (display units) rounded to what its control shows."""
    return shown if math.isinf(shown) else float(display_format(p) % shown)


def _parse_url_value(p: Any, raw: str, system: str) -> tuple[Any, str | None]:
    """(display value, None) if ``raw`` is acceptable for ``p``, else (None, why)."""
    if len(raw) > MAX_URL_VALUE:
        return None, "is too long"
    if isinstance(p, Choice):
        return (raw, None) if raw in p.options else (None, f"must be one of {', '.join(p.options)}")
    try:
        shown = float(raw.strip())
    except ValueError:
        return None, "is not a number"
    if math.isinf(shown) and p.allow_inf and shown > 0:
        return shown, None
    if math.isfinite(shown):
        shown = as_shown(p, shown)  # the control can show no finer: keep what it shows
    try:
        p.validate(units.to_si(shown, p.dimension, system))
    except ParameterError:
        return None, f"is out of range ({p.range_text()})"
    return shown, None


def _initial_values(problem: Problem, system: str, base: dict) -> list[str]:
    """Put a value in session state for every control that has none yet: the last values this
    session used (in SI, if the unit system just changed), else the URL, else ``base`` (a
    variant's numbers) or the default."""
    warnings = []
    remembered = st.session_state.get(f"{problem.id}__si", {})
    for p in problem.solver.PARAMS:
        key = _key(problem, system, p.name)
        if key in st.session_state:
            continue
        if p.name in remembered:
            value = remembered[p.name]
            st.session_state[key] = value if isinstance(p, Choice) else (
                units.to_display(value, p.dimension, system))
            continue
        start = base.get(p.name, p.default)
        default = start if isinstance(p, Choice) else units.to_display(start, p.dimension, system)
        raw = st.query_params.get(p.name)
        value = default
        if raw is not None:
            parsed, why = _parse_url_value(p, raw, system)
            if why is None:
                value = parsed
            else:
                shown = raw if len(raw) <= MAX_URL_VALUE else raw[:MAX_URL_VALUE] + "…"
                warnings.append(f"The link's value for **{p.name}** ({p.label}), “{shown}”, {why}; "
                                f"using the default instead.")
        st.session_state[key] = value
    return warnings


def _label(p: Any, system: str) -> str:
    if isinstance(p, Choice):
        return p.label.capitalize()
    u = units.unit(p.dimension, system)
    return f"${p.symbol}$ — {p.label}" + (f" ({u})" if u else "")


def _control(p: Any, problem: Problem, system: str, container) -> Any:
    key = _key(problem, system, p.name)
    if isinstance(p, Choice):
        return container.radio(_label(p, system), p.options, key=key, format_func=p.label_of,
                               help=p.help or None)
    if p.allow_inf:
        value = st.session_state[key]
        no_slip = container.toggle(f"No slip at the contact (${p.symbol} = \\infty$)",
                                   value=math.isinf(value), key=key + "__inf")
        if no_slip:
            return math.inf
        if math.isinf(value):
            st.session_state[key] = float(p.ui_high or 1.0) / 2
        return container.number_input(_label(p, system), key=key, step=p.step, format=display_format(p),
                                      help=p.help or None)
    if is_slider(p):
        lo = float(p.ui_low if p.ui_low is not None else p.low)
        hi = float(p.ui_high if p.ui_high is not None else p.high)
        current = float(st.session_state[key])
        st.session_state[key] = current
        return container.slider(_label(p, system), min(lo, current), max(hi, current), key=key,
                                step=float(p.step or 0.01), format=display_format(p), help=p.help or None)
    factor = units.to_display(1.0, p.dimension, system)
    step = float(f"{(p.step or 0.01) * factor:.1g}")
    return container.number_input(_label(p, system), key=key, step=step, format=display_format(p),
                                  help=p.help or None)


def _in_si(p: Any, shown: Any, system: str) -> Any:
    if isinstance(p, Choice):
        return shown
    if shown is None:  # an emptied number box
        return math.nan
    return units.to_si(float(shown), p.dimension, system)


def _differs(p: Any, value: Any, base: dict) -> bool:
    """Whether ``value`` (SI) is not the starting value (the variant's, else the default)."""
    start = base.get(p.name, p.default)
    if isinstance(p, Choice) or isinstance(value, str):
        return value != start
    if math.isnan(value):
        return False
    return not math.isclose(value, start, rel_tol=1e-12, abs_tol=1e-12)


def parameter_panel(problem: Problem, system: str, base: dict | None = None,
                    container=None) -> tuple[dict, list[str]]:
    """Draw the controls; return (parameters in SI for ``solve``, warnings about the URL).

    The problem's primary parameters are always shown; the others behind a "More parameters"
    toggle, which starts open when one of them is not at its starting value (a link that changes
    a mass shows it). A hidden parameter keeps its value."""
    container = container or st.sidebar
    base = base or {}
    warnings = _initial_values(problem, system, base)
    params = problem.solver.PARAMS
    first = [p for p in params if p.name in problem.primary] or list(params)
    rest = [p for p in params if p not in first]
    values = {p.name: _in_si(p, _control(p, problem, system, container), system) for p in first}
    if rest:
        more_key = f"{problem.id}__more"
        stored = {p.name: _in_si(p, st.session_state[_key(problem, system, p.name)], system) for p in rest}
        if more_key not in st.session_state:
            st.session_state[more_key] = any(_differs(p, stored[p.name], base) for p in rest)
        more = container.toggle("More parameters", key=more_key,
                                help=", ".join(p.label for p in rest).capitalize() + ".")
        for p in rest:
            if more:
                values[p.name] = _in_si(p, _control(p, problem, system, container), system)
            else:
                # Re-set it as a plain value: Streamlit drops the state of a widget not drawn in a run.
                key = _key(problem, system, p.name)
                st.session_state[key] = st.session_state[key]
                values[p.name] = stored[p.name]
    values = {p.name: values[p.name] for p in params}  # the solver's order
    st.session_state[f"{problem.id}__si"] = dict(values)
    return values, warnings


def mirror_to_url(problem: Problem, values: dict, system: str, flags: dict[str, str],
                  base: dict | None = None) -> None:
    """Write the parameters that differ from ``base`` or the defaults (display units) and the page
    flags into the URL."""
    wanted = {}
    base = base or {}
    for p in problem.solver.PARAMS:
        v = values[p.name]
        if not _differs(p, v, base):
            continue
        if isinstance(p, Choice):
            wanted[p.name] = v
        else:
            shown = units.to_display(v, p.dimension, system)
            # What the control shows, no more: a link says L=2.29659, not L=2.296587927.
            wanted[p.name] = "inf" if math.isinf(shown) else f"{as_shown(p, shown):g}"
    wanted.update({k: v for k, v in flags.items() if v})
    current = {k: st.query_params.get(k) for k in st.query_params.keys()}
    if current != wanted:
        st.query_params.from_dict(wanted)
