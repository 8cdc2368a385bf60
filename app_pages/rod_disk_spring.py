"""Rod and disk on a torsional spring."""
from ui.page import problem_page

problem_page("rod_disk_spring")
