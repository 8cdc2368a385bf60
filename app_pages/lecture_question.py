"""For students in a lecture: the question the instructor put to the room, answered with the code on the screen."""
from ui.room import student_page

student_page()
