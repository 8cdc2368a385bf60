"""LTI 1.3 (1EdTech LTI Advantage): the app as a tool inside Canvas, Moodle, Blackboard or D2L."""
