"""Euler's disk."""
from ui.page import problem_page

problem_page("eulers_disk")
