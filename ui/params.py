"""The parameter panel: one control per solver parameter, built from the solver's spec, with every
value mirrored into the URL (in the units the page shows) so that a link reproduces a state.

A value read from the URL is parsed with ``float()`` only (never evaluated), checked against the
solver's own range, and replaced by the default with a warning naming it when it is malformed or
out of range. Combinations are left to the solver, whose message the page shows.
"""
from __future__ import annotations

import difflib
import math
import re
from typing import Any

import streamlit as st

from solvers.core import Choice, Number, ParameterError
from solvers import units
from solvers.catalog import Problem
from edge.inline_scripts import SLIDER_NAMES
from ui.results import literal, plain

MAX_URL_VALUE = 32  # characters; longer values are not numbers anyone typed
# A number as a link writes it: ASCII digits, a point, an exponent; or infinity (μ = ∞ on the disk's page).
URL_NUMBER = re.compile(r"[+-]?(?:(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|inf(?:inity)?)\Z", re.IGNORECASE)


def control_key(problem: Problem, system: str, name: str) -> str:
    """The Streamlit key of a parameter's control (its element's selector: edge.streamlit_dom.keyed)."""
    return f"{problem.id}__{system}__{name}"


_GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "Delta": "Δ", "epsilon": "ε", "theta": "θ",
          "lambda": "λ", "mu": "μ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ", "psi": "ψ",
          "omega": "ω", "Omega": "Ω", "ell": "ℓ", "infty": "∞"}
_DIGIT_SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def symbol_text(latex: str) -> str:
    """A parameter's LaTeX symbol as plain text for a label a screen reader reads: Greek letters
    as themselves and a numeric subscript as subscript digits (\\theta_0 → θ₀, m_1 → m₁); a
    letter subscript keeps its underscore, as the student types it (m_s)."""
    text = re.sub(r"\\([A-Za-z]+)", lambda m: _GREEK.get(m.group(1), m.group(1)), latex)
    text = re.sub(r"[{}\s]", "", text)
    base, _, sub = text.partition("_")
    if sub.isdigit():
        return base + sub.translate(_DIGIT_SUBSCRIPTS)
    return text


def is_slider(p: Number) -> bool:
    return p.dimension == "angle" or (p.low == 0 and p.high == 1)


def display_format(p: Number) -> str:
    """How the control writes the number (printf style), which the URL copies: a slider to its
    step's decimals (a whole-degree slider shows 30, not 30.00), a box to six figures."""
    return f"%.{_slider_decimals(p)}f" if is_slider(p) else "%.6g"


def _slider_decimals(p: Number) -> int:
    """The decimals of a slider's step (at most six): what it writes."""
    step = float(p.step or 0.01)
    decimals = 0
    while decimals < 6 and abs(step * 10**decimals - round(step * 10**decimals)) > 1e-9:
        decimals += 1
    return decimals


def as_shown(p: Number, shown: float) -> float:
    """``shown`` (display units) rounded to what its control shows."""
    return shown if math.isinf(shown) else float(display_format(p) % shown)


def _parse_url_value(p: Any, raw: str, system: str) -> tuple[Any, str | None]:
    """(display value, None) if ``raw`` is acceptable for ``p``, else (None, why)."""
    if len(raw) > MAX_URL_VALUE:
        return None, "is too long"
    if isinstance(p, Choice):
        return (raw, None) if raw in p.options else (None, f"must be one of {', '.join(p.options)}")
    text = raw.strip()
    if not URL_NUMBER.match(text):  # (Python's float would take 1_0 as 10 and ٣ as 3)
        return None, "is not a number"
    typed = float(text)
    if math.isinf(typed) and p.allow_inf and typed > 0:
        return typed, None
    shown = as_shown(p, typed) if math.isfinite(typed) else typed  # the control can show no finer: keep what it shows
    try:
        p.validate(units.to_si(shown, p.dimension, system))
    except ParameterError:
        if math.isfinite(typed) and shown != typed:  # 89.9999 on a slider of tenths: 90, out of range
            return None, f"rounds to {display_format(p) % shown} on its control, which is out of range ({shown_range(p, system)})"
        return None, f"is out of range ({shown_range(p, system)})"
    return shown, None


def _precision(p: Number) -> str:
    """How finely ``p``'s control writes its number, in words."""
    if not is_slider(p):
        return "box, which writes six significant figures"
    decimals = _slider_decimals(p)
    unit = "°" if p.dimension == "angle" else ""
    return "slider, which writes " + ("whole degrees" if unit and not decimals else
                                      "whole numbers" if not decimals else f"to {10.0 ** -decimals:.{decimals}f}{unit}")


def _as_written(p: Number, shown: float, system: str) -> str:
    """``shown`` (display units) as its control writes it, with its unit."""
    return units.with_unit(display_format(p) % shown, p.dimension, system)


def shown_range(p: Number, system: str) -> str:
    """The values a parameter may take, in the unit its control shows (degrees for an angle, lb in
    US units): its physical range, narrowed to the magnitudes the model is meant for."""
    def show(v: float) -> str:
        return units.format_quantity(v, p.dimension, system)

    bounds = p.model_bounds()
    if bounds and p.low == 0 and not p.low_inclusive:  # strictly positive: a thousandth to a thousand times
        text = f"from {show(bounds[0])} to {show(bounds[1])}"
    else:
        # the model's magnitude, where it narrows the range (not for e, at most 1 already): a top for a
        # quantity that is never negative, a size for one that may be
        capped, never_negative = bounds and (p.high is None or p.high > bounds[1]), p.low is not None and p.low >= 0
        parts = []
        if p.low is not None:
            parts.append(("at least " if p.low_inclusive else "greater than ") + show(p.low))
        if capped and never_negative:
            parts.append(f"at most {show(bounds[1])}")
        elif p.high is not None:
            parts.append(("at most " if p.high_inclusive else "less than ") + show(p.high))
        text = " and ".join(parts) if parts else "any number"
        if capped and not never_negative:
            text += f", at most {show(bounds[1])} in size"
    return text + (", or inf" if p.allow_inf else "")


def check_in_range(problem: Problem, values: dict, system: str) -> None:
    """Raise ParameterError, in the units the controls show, for a value beyond its range (the
    solver's own message is in SI: "L = -0.3048 is out of range" for a box showing −1 ft)."""
    for p in problem.solver.PARAMS:
        value = values[p.name]
        if isinstance(p, Choice) or isinstance(value, str) or math.isnan(value):
            continue  # an option is checked against its list; an emptied box gets the solver's message
        try:
            p.validate(value)
        except ParameterError:
            raise ParameterError(f"{symbol_text(p.symbol)} ({p.label}) = {units.format_quantity(value, p.dimension, system)} "
                                 f"is out of range: it must be {shown_range(p, system)}.") from None


def _url_warning(p: Any, raw: str, why: str, markdown: bool = True, instead: str = "the default") -> str:
    """What the page says of a link's value it cannot take: in Markdown (the value shown as typed, never
    as a link or formatting), or plain text (the download route's refusal)."""
    shown = raw if len(raw) <= MAX_URL_VALUE else raw[:MAX_URL_VALUE] + "…"
    if not markdown:
        return f"The link's value for {p.name} ({p.label}), “{shown}”, {why}."
    return f"The link's value for **{p.name}** ({p.label}), “{literal(shown)}”, {why}; using {instead} instead."


MAX_UNKNOWN_SHOWN = 5  # names of a link's unknown keys listed in its warning


def unknown_in_link(problem: Problem, keys, flags) -> str | None:
    """What the page says of a link's keys that are neither this problem's parameters nor one of the
    page's ``flags`` (``?theta=30`` for θ₀'s ``theta0``, another problem's ``V``), or None: the address
    keeps only what the page knows, so a mistyped name would otherwise vanish without a word."""
    names = [p.name for p in problem.solver.PARAMS]
    unknown = [k for k in keys if k not in names and k not in flags]
    if not unknown:
        return None
    shown = [f"“{literal(k[:MAX_URL_VALUE])}”" for k in unknown[:MAX_UNKNOWN_SHOWN]]
    if len(unknown) > MAX_UNKNOWN_SHOWN:
        shown.append(f"{len(unknown) - MAX_UNKNOWN_SHOWN} more")
    listed = shown[0] if len(shown) == 1 else ", ".join(shown[:-1]) + " and " + shown[-1]
    near = ([n for n in names if n.lower() == unknown[0].lower()] or difflib.get_close_matches(unknown[0], names, n=1, cutoff=0.6)
            if len(unknown) == 1 else [])  # ?v=3 for V: a name that differs in case only first
    meant = f" (did you mean **{near[0]}**?)" if near else ""
    return (f"The link names {listed}{meant}, which {'is not a parameter' if len(unknown) == 1 else 'are not parameters'} "
            f"of this problem: left out. Its parameters: {', '.join(names)}.")


def _initial_values(problem: Problem, system: str, base: dict) -> list[str]:
    """Put a value in session state for every control that has none yet: the last values this
    session used (in SI, if the unit system just changed), else the URL (``read_link``), else ``base``
    (a variant's numbers) or the default."""
    remembered = st.session_state.get(f"{problem.id}__si", {})
    fresh = [p for p in problem.solver.PARAMS if control_key(problem, system, p.name) not in st.session_state]
    values, linked, warnings = ({}, {}, []) if all(p.name in remembered for p in fresh) else (
        read_link(problem, st.query_params, system, base))
    for p in fresh:
        value = remembered[p.name] if p.name in remembered else values[p.name]
        st.session_state[control_key(problem, system, p.name)] = (
            value if isinstance(p, Choice) else
            linked[p.name] if p.name not in remembered and p.name in linked else
            units.shown_value(value, p.dimension, system))
    return warnings


def read_link(problem: Problem, query, system: str, base: dict | None = None,
              markdown: bool = True) -> tuple[dict, dict, list[str]]:
    """What a page's address gives (``query``: its parameters by name, e.g. st.query_params): every
    parameter's value (SI), the link's where it takes it, else ``base``'s (a variant's) or the default;
    the values it takes as their controls show them (display units, to the control's precision); and a
    warning for each value it refuses (Markdown, or plain text). No Streamlit: the page and the download
    route read links alike."""
    base = base or {}
    values, linked, warnings = {}, {}, []
    for p in problem.solver.PARAMS:
        values[p.name] = base.get(p.name, p.default)
        raw = query.get(p.name)
        if raw is None:
            continue
        parsed, why = _parse_url_value(p, raw, system)
        if why is None:
            linked[p.name] = parsed
            values[p.name] = parsed if isinstance(p, Choice) else units.to_si(parsed, p.dimension, system)
            if markdown and isinstance(p, Number) and math.isfinite(parsed) and parsed != float(raw.strip()):
                # ?theta2=30.5 on a slider of whole degrees: taken as 30, and said (the file a download
                # route makes cites the value it used)
                warnings.append(_url_warning(p, raw, f"is finer than its {_precision(p)}", instead=_as_written(p, parsed, system)))
        else:
            warnings.append(_url_warning(p, raw, why, markdown))
    for p, top, why in past_following_tops(problem, values, set(linked), system):
        default = base.get(p.name, p.default)
        warnings.append(_url_warning(p, query[p.name], why, markdown, instead="the default" if default <= top else
                                     f"that largest value, {units.format_quantity(top, p.dimension, system)},"))
        values[p.name] = min(default, top)
        del linked[p.name]
    return values, linked, warnings


def past_following_tops(problem: Problem, values: dict, linked: set, system: str) -> list[tuple[Number, float, str]]:
    """The parameters named in ``linked`` whose value in ``values`` (SI) is past a top that follows another
    parameter's (the stick's impact point, s ≤ l/2: ``ui_high_per``), each with that top (SI) and why, in words
    (in ``system``'s units).
    A link's such value falls back to the default, at most that top, as any value out of range does: ?s=99
    refused the whole page and stretched its slider to 99."""
    past = []
    for p in problem.solver.PARAMS:
        if not (isinstance(p, Number) and p.ui_high_per and p.name in linked):
            continue
        name, share = p.ui_high_per
        top = share * values[name]
        if values[p.name] > top * (1 + 1e-12):
            past.append((p, top, f"is past its largest value for this {name} ({p.name} ≤ {share:g} {name} = "
                                 f"{units.format_quantity(top, p.dimension, system)})"))
    return past


def _label(p: Any, system: str) -> str:
    """A control's label in plain text (θ₀ — release angle above the horizontal (°)): Streamlit
    gives it to screen readers as it is, so TeX there would be read out as dollars and backslashes."""
    if isinstance(p, Choice):
        return p.label.capitalize()
    u = units.unit(p.dimension, system)
    return f"{symbol_text(p.symbol)} — {p.label}" + (f" ({u})" if u else "")


def _slider(p: Number, key: str, system: str, container, others: dict | None = None) -> float:
    current = float(st.session_state[key])
    st.session_state[key] = current
    lo, hi, step = slider_range(p, system, others)
    # ``value``: the state's own (the state wins anyway); given, Streamlit does not copy the whole
    # session state to guess the slider's kind, a good part of a run's cost (BENCHMARKS.md §1)
    return container.slider(_label(p, system), min(lo, current), max(hi, current), current, key=key,
                            step=step, format=display_format(p), help=p.help or None)


def slider_range(p: Number, system: str, params: dict | None = None) -> tuple[float, float, float]:
    """(low, high, step) of ``p``'s slider in the unit it shows: an angle's or a fraction's as its
    spec gives it, any other lesson number's by ``lesson_range`` (before a value outside it widens it)."""
    if is_slider(p):
        return (float(p.ui_low if p.ui_low is not None else p.low), float(p.ui_high if p.ui_high is not None else p.high),
                float(p.step or 0.01))
    return lesson_range(p, system, params)


def round_step(step: float) -> float:
    """The round step (1, 2, 2.5 or 5 times a power of ten) nearest ``step`` in ratio."""
    power = 10.0 ** math.floor(math.log10(step))
    return float(f"{min((m * power for m in (1, 2, 2.5, 5, 10)), key=lambda s: abs(math.log(s / step))):.12g}")


def lesson_range(p: Number, system: str, params: dict | None = None) -> tuple[float, float, float]:
    """(low, high, step) of a lesson's dimensional slider in the unit it shows: the model's usual
    values (``ui_low``–``ui_high``) on a grid of a round step (0.1 m/s; 0.25 ft/s in US units:
    ``round_step``), so a drag lands on numbers a person would type. A value off the grid (a link's,
    a unit switch's) is shown as it is, to six figures as a box shows it, and kept until moved.
    ``params`` (SI): the other parameters now, for a top that follows one of them (``ui_high_per``)."""
    factor = units.to_display(1.0, p.dimension, system)
    step = float(p.step or 0.01) if factor == 1.0 else round_step(float(p.step or 0.01) * factor)
    ui_low = p.ui_low if p.ui_low is not None else p.default / 10
    ui_high = p.ui_high if p.ui_high is not None else p.default * 10
    if p.ui_high_per and params and isinstance(params.get(p.ui_high_per[0]), (int, float)) \
            and math.isfinite(params[p.ui_high_per[0]]):
        ui_high = min(ui_high, params[p.ui_high_per[0]] * p.ui_high_per[1])
    lo = math.ceil(round(ui_low * factor / step, 9)) * step
    hi = math.floor(round(ui_high * factor / step, 9)) * step
    if p.low is not None and (lo < p.low * factor or (lo == p.low * factor and not p.low_inclusive)):
        lo += step
    hi = max(hi, lo + step)  # (a top following a very small value: one step at least)
    return float(f"{lo:.12g}"), float(f"{hi:.12g}"), step


def _control(p: Any, problem: Problem, system: str, container, lesson: dict | None = None) -> Any:
    """A parameter's control: a choice's radio, μ = ∞'s toggle, a slider for an angle or a fraction
    (to its step's decimals) and for every number of the lesson (dragged on the stage, six figures),
    else a number box (under "More parameters", for exact values). ``lesson``: the other parameters
    (SI) of a lesson's control, whose range may follow one of them."""
    key = control_key(problem, system, p.name)
    if isinstance(p, Choice):
        return container.radio(_label(p, system), p.options, key=key, format_func=p.label_of,
                               help=p.help or None)
    if p.allow_inf:
        value = st.session_state[key]
        no_slip = container.toggle(f"No slip at the contact ({symbol_text(p.symbol)} = ∞)",
                                   value=math.isinf(value), key=key + "__inf")
        if no_slip:
            return math.inf
        if math.isinf(value):
            st.session_state[key] = float(p.ui_high or 1.0) / 2
    if is_slider(p) or lesson is not None:
        return _slider(p, key, system, container, lesson)
    factor = units.to_display(1.0, p.dimension, system)
    step = float(f"{(p.step or 0.01) * factor:.1g}")
    return container.number_input(_label(p, system), key=key, step=step, format=display_format(p),
                                  help=p.help or None)


def _in_si(p: Any, shown: Any, system: str, known: Any = None) -> Any:
    """A control's value in SI. ``known``: the SI value it started from (this session's, the
    variant's or the default); while the control still shows it, it stands for that very value, so
    a unit switch changes no number the physics uses (10 lb on show is still the 4.536 kg sphere)."""
    if isinstance(p, Choice):
        return shown
    if shown is None:  # an emptied number box
        return math.nan
    if isinstance(known, (int, float)) and math.isfinite(known) and shown == units.shown_value(known, p.dimension, system):
        return known
    return units.to_si(float(shown), p.dimension, system)


def _shown(p: Number, value: float, system: str, on_control: Any = None) -> str:
    """``value`` (SI) as its control writes it (and the URL copies it): L=2.29659, 10 lb. ``on_control``: the
    value its control holds, which it is where it stands for ``value``: a typed 13.125 lb stays 13.125, where
    converting back from kilograms would give the 13.13 a unit switch shows."""
    if isinstance(on_control, (int, float)) and math.isfinite(on_control) and math.isclose(
            units.to_si(float(on_control), p.dimension, system), value, rel_tol=1e-12):
        return f"{as_shown(p, on_control):g}"
    shown = units.shown_value(value, p.dimension, system)
    return "inf" if math.isinf(shown) else f"{as_shown(p, shown):g}"


def _differs(p: Any, value: Any, base: dict, system: str, on_control: Any = None) -> bool:
    """Whether ``value`` (SI) is not the starting value (the variant's, else the default) as the
    control shows them: 10 lb is the textbook's 4.536 kg sphere, a typed 9.9999 lb is not (``_shown``)."""
    start = base.get(p.name, p.default)
    if isinstance(p, Choice) or isinstance(value, str):
        return value != start
    if math.isnan(value):
        return False
    return _shown(p, value, system, on_control) != _shown(p, start, system)


def refused_values_notice() -> None:
    """What the page says when a value the browser sent for a control was refused (edge/widget_values)."""
    st.warning("A value this browser sent for a control could not be read, so the control keeps its last "
               "value. Reloading the page sets everything right.")


def parameter_panel(problem: Problem, system: str, base: dict | None = None,
                    container=None, stage=None) -> tuple[dict, list[str]]:
    """Draw the controls; return (parameters in SI for ``solve``, warnings about the URL).

    The problem's primary parameters (the lesson's) are always shown, in ``stage`` if given (beside
    the figure), else in ``container``; the others in ``container`` behind a "More parameters"
    toggle, which starts open when one of them is not at its starting value (a link that changes
    a mass shows it). A hidden parameter keeps its value. The lesson page draws the two parts in
    two runs of their own (``more_parameters`` in the page's, ``lesson_parameters`` in the stage's
    fragment), which is the same."""
    container = container or st.sidebar
    stage = stage or container.container()  # the lesson's first, above "More parameters"
    warnings = more_parameters(problem, system, base, container)
    return lesson_parameters(problem, system, base, stage), warnings


def _split(problem: Problem) -> tuple[list, list]:
    """(the lesson's parameters, the others), in the solver's order."""
    params = problem.solver.PARAMS
    first = [p for p in params if p.name in problem.primary] or list(params)
    return first, [p for p in params if p not in first]


def _known(problem: Problem, base: dict) -> dict:
    remembered = st.session_state.get(f"{problem.id}__si", {})
    return {p.name: remembered.get(p.name, base.get(p.name, p.default)) for p in problem.solver.PARAMS}


def more_parameters(problem: Problem, system: str, base: dict | None, container) -> list[str]:
    """Give every control its starting value, and draw the parameters other than the lesson's in
    ``container`` behind the "More parameters" toggle; return warnings about the URL."""
    base = base or {}
    warnings = _initial_values(problem, system, base)
    _, rest = _split(problem)
    known = _known(problem, base)
    if rest:
        more_key = f"{problem.id}__more"
        if more_key not in st.session_state:
            st.session_state[more_key] = any(_differs(p, _stored(problem, p, system, known), base, system) for p in rest)
        more = container.toggle("More parameters", key=more_key,
                                help=", ".join(p.label for p in rest).capitalize() + ".")
        for p in rest:
            if more:
                _control(p, problem, system, container)
            else:
                # Re-set it as a plain value: Streamlit drops the state of a widget not drawn in a run.
                key = control_key(problem, system, p.name)
                st.session_state[key] = st.session_state[key]
    container.html(SLIDER_NAMES, unsafe_allow_javascript=True)
    return warnings


def _stored(problem: Problem, p: Any, system: str, known: dict) -> Any:
    return _in_si(p, st.session_state[control_key(problem, system, p.name)], system, known[p.name])


def lesson_parameters(problem: Problem, system: str, base: dict | None, stage) -> dict:
    """Draw the lesson's controls in ``stage``; return every parameter in SI for ``solve`` (the
    others as ``more_parameters`` left them)."""
    first, rest = _split(problem)
    known = _known(problem, base or {})
    others = {p.name: _stored(problem, p, system, known) for p in rest}
    values = {p.name: _in_si(p, _control(p, problem, system, stage, lesson=others), system, known[p.name])
              for p in first}
    values.update(others)
    values = {p.name: values[p.name] for p in problem.solver.PARAMS}  # the solver's order
    st.session_state[f"{problem.id}__si"] = dict(values)
    return values


def parameters_of_link(problem: Problem, query, system: str, base: dict | None = None,
                       markdown: bool = True) -> tuple[dict, list[str]]:
    """The parameters (SI) a page's address gives, and a warning for each value it refuses (``read_link``)."""
    values, _, warnings = read_link(problem, query, system, base, markdown)
    return values, warnings


def fixed_parameters(problem: Problem, system: str, base: dict, seed: int,
                     container=None) -> tuple[dict, list[str]]:
    """A variant link's givens (SI), which nothing on the page can change: the variant's, or a
    value the link sets itself; listed where the controls would be, as fixed. Return (parameters,
    warnings about the URL)."""
    container = container or st.sidebar
    values, warnings = parameters_of_link(problem, st.query_params, system, base)
    lines = []
    for p in problem.solver.PARAMS:
        value = values[p.name]
        own = p.name in st.query_params and _differs(p, value, base, system)
        shown = (f"{p.label.capitalize()}: {p.label_of(value)}" if isinstance(p, Choice) else
                 f"{symbol_text(p.symbol)} = {units.format_quantity(value, p.dimension, system)}")
        lines.append(f"- {plain(shown)}" + (" *(from the link)*" if own else ""))
    container.markdown(f"### Parameters · variant {seed}\n**Fixed by the variant link**: the numbers of your "
                       "problem. For other numbers, open the problem from the navigation.\n\n" + "\n".join(lines))
    return values, warnings


def mirror_to_url(problem: Problem, values: dict, system: str, flags: dict[str, str],
                  base: dict | None = None) -> None:
    """Write the parameters that differ from ``base`` or the defaults (display units) and the page
    flags into the URL."""
    wanted = {}
    base = base or {}
    for p in problem.solver.PARAMS:
        v = values[p.name]
        on_control = st.session_state.get(control_key(problem, system, p.name))
        if _differs(p, v, base, system, on_control):  # what the control shows, no more: L=2.29659, not 2.296587927
            wanted[p.name] = v if isinstance(p, Choice) else _shown(p, v, system, on_control)
    wanted.update({k: v for k, v in flags.items() if v})
    current = {k: st.query_params.get(k) for k in st.query_params.keys()}
    # (a name given twice, ?V=2&V=3: the page took the last, and the address keeps only it)
    if current != wanted or any(len(st.query_params.get_all(k)) > 1 for k in current):
        st.query_params.from_dict(wanted)
