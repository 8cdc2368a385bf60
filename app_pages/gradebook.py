"""For instructors: assignments, their signed links and the gradebook."""
from ui.assignments import instructor_page

instructor_page()
