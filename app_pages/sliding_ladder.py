"""A ladder slides down a smooth wall onto a smooth floor."""
from ui.page import problem_page

problem_page("sliding_ladder")
