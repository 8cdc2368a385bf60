"""The lecture-load baseline: an app whose only page holds one slider."""
import streamlit as st

st.slider("x", 0.0, 1.0, 0.5, key="x")
