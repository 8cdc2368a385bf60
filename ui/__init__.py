"""The Streamlit pieces every page shares: catalogue, units, parameter panel, results, page."""
