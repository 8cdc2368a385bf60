"""Dynamics Lab: the entry point. A home page and one page per problem, grouped by method."""
import streamlit as st

from edge import widget_values
from edge.streamlit_dom import css
from solvers.catalog import GROUPS, PROBLEMS
from ui.home import home
from ui.params import refused_values_notice
from ui.session import take_instructor_link

# An emoji icon is drawn in the browser (an SVG data URL); a Material icon here would be fetched from
# fonts.gstatic.com, which a lecture-hall network or a course site's policy may not reach.
st.set_page_config(page_title="Dynamics Lab", page_icon="🔄", layout="wide")

# A problem's title wraps instead of ending in "…" (Streamlit cuts page links and the navigation's
# entries to one line: "Rod-and-sphere pendulum bounces off the floo…"). A link reached by the keyboard
# is outlined in its own text's colour (Streamlit tints it a faint grey, the same as the current page's:
# on that one, focus could not be seen), dark on the light theme, light on the dark.
st.html(css("""<style>
  $sidebarNavLink span[label], $sidebarNavLink span[label] *,
  $pageLink > span:last-child, $pageLink > span:last-child * {
    white-space: normal; overflow: visible; text-overflow: clip; height: auto;
  }
  $sidebarNavLink:focus-visible, $pageLink:focus-visible {
    outline: 2px solid currentColor; outline-offset: -2px;
  }
  /* A table cell is 400 px at most: a student's link (one long word) was cut mid-signature. */
  $table td a, $table td code { overflow-wrap: anywhere; }
  /* A choice longer than its box (an answer's label on a phone) ends in "…", not cut mid-word with no sign. */
  $selectbox input { text-overflow: ellipsis; }
</style>"""))

widget_values.install()  # (serve.py installs it before the first session; this covers `streamlit run`)
take_instructor_link()  # ?instructor=KEY leaves the address bar on every page, the home page too
if widget_values.take_refusals():
    refused_values_notice()

# /room: a question put to the lecture hall, answered on phones (ui/room.py); reached by its code's link, not listed
pages = {"": [st.Page(home, title="Home", icon=":material/home:", default=True),
              st.Page("app_pages/lecture_question.py", title="Your lecture's question", icon=":material/how_to_vote:",
                      url_path="room", visibility="hidden")]}
for group in GROUPS:
    pages[group] = [st.Page(p.page_path, title=p.title, icon=p.icon, url_path=p.id)
                    for p in PROBLEMS if p.group == group]
# The Assignments page is at /assignments, the address its title names; /gradebook, where it was first,
# opens it too (links already given out, bookmarks), without a second entry in the navigation.
pages["For instructors"] = [st.Page("app_pages/gradebook.py", title="Assignments", icon=":material/assignment:",
                                   url_path="assignments"),
                            st.Page("app_pages/gradebook.py", title="Assignments", icon=":material/assignment:",
                                    url_path="gradebook", visibility="hidden"),
                            st.Page("app_pages/handouts.py", title="Handouts", icon=":material/print:", url_path="handouts")]
st.navigation(pages).run()
