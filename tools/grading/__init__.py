"""Grading a student's chapters behind a wall: reading the submission,
checking it against the book, building and running it in a sandbox, judging,
reporting (results.json, JUnit, CSV), batches and the Gradescope autograder."""
