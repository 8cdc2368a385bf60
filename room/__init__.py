"""Questions put to a lecture hall: what may be asked of a problem and what an answer counts as
(questions.py), and their records (store.py). No Streamlit; the pages are ui/room.py."""
