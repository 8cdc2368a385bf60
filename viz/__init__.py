"""Plotly figure builders: pure functions from a Solution (and its solver's motion) to figure data."""
