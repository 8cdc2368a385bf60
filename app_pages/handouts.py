"""For instructors: printable handouts for a class, and their answer keys."""
from ui.handouts import handouts_page

handouts_page()
