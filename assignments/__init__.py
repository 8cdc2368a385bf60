"""Assignments: signed per-student links, every attempt recorded in a database, the gradebook.

No Streamlit here (the page is ``ui/assignments.py``): ``signing`` signs and checks links with the
course secret, ``identity`` turns a link (or, later, an LTI launch) into a student identity,
``db`` holds the schema and the one engine per process, ``records`` every read and write."""
