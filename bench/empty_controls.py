"""The browser benchmark's baseline: an empty Streamlit page with one number box and one slider."""
import streamlit as st

st.number_input("a", value=1.0, key="a", format="%.6g")
st.slider("x", 0.0, 1.0, 0.5, key="x")
