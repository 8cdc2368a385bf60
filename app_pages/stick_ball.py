"""Ball slides into a free stick."""
from ui.page import problem_page

problem_page("stick_ball")
