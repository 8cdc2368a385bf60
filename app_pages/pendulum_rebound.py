"""Rod-and-sphere pendulum bounces off a floor or a wall."""
from ui.page import problem_page

problem_page("pendulum_rebound")
