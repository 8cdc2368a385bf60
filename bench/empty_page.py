"""The baseline for the benchmarks: an empty Streamlit page with one slider."""
import streamlit as st

st.slider("x", 0.0, 1.0, 0.5, key="x")
