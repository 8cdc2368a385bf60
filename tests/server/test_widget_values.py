"""The widget-value check (edge/widget_values.py) against Streamlit's own state: a value of the
widget's kind passes (a number box's int_value as its double_value), one of another kind, one the
deserializer refuses and a number that is not finite are treated as not sent, said once."""
from __future__ import annotations

import pytest
from streamlit.proto.WidgetStates_pb2 import WidgetState
from streamlit.runtime.state import session_state
from streamlit.runtime.state.common import WidgetMetadata

from edge import widget_values


@pytest.fixture(autouse=True)
def installed():
    widget_values.install()
    widget_values._refused.clear()
    widget_values._logged.clear()


def number_box(state: WidgetState, value_type="double_value"):
    def deserialize(v):
        if v is None:
            return None
        if not isinstance(v, (int, float)):
            raise TypeError("must be real number")
        return float(v)
    states = session_state.WStates()
    states.set_widget_metadata(WidgetMetadata(id=state.id, deserializer=deserialize, serializer=lambda v: v,
                                              value_type=value_type))
    states.set_widget_from_proto(state)
    return states


def state(**field) -> WidgetState:
    s = WidgetState(id="box")
    for name, value in field.items():
        if name == "int_array_value":
            s.int_array_value.data.extend(value)
        else:
            setattr(s, name, value)
    return s


@pytest.mark.parametrize("field, value", [("double_value", 2.5), ("int_value", 3)])
def test_a_value_of_the_widgets_kind_passes(field, value):
    assert number_box(state(**{field: value}))["box"] == value
    assert widget_values.take_refusals() == set()


@pytest.mark.parametrize("field, value", [("string_value", "hello"), ("bool_value", True),
                                          ("int_array_value", [1, 2, 3]), ("double_value", float("nan")),
                                          ("double_value", float("inf"))])
def test_a_value_that_cannot_be_read_is_not_sent_and_said_once(field, value):
    states = number_box(state(**{field: value}))
    for _ in range(3):  # read again and again, as a rerun does
        with pytest.raises(KeyError):
            states["box"]
        assert states.get("box") is None
    assert len(widget_values.take_refusals()) == 1
    assert widget_values.take_refusals() == set()  # said once, then forgotten
    assert len(widget_values._logged) == 1


def test_a_cleared_value_passes_as_streamlit_reads_it():
    """A WidgetState with no field set is a widget cleared (value=None): not refused."""
    assert number_box(WidgetState(id="box"))["box"] is None
    assert widget_values.take_refusals() == set()
