"""Spinning disk hits a rough wall."""
from ui.page import problem_page

problem_page("disk_wall")
