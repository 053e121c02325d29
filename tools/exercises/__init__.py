"""Exercises: the markup of a solution and its stub in a chapter, the student
and solution kits made from it, their validation, and course plans."""
