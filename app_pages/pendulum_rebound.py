"""Rod-and-sphere pendulum bounces off the floor."""
from ui.page import problem_page

problem_page("pendulum_rebound")
