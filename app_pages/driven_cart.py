"""Cart with driven wheels."""
from ui.page import problem_page

problem_page("driven_cart")
