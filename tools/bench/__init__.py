"""The measurements the book prints (measure.py, book_numbers.py), the benchmark's
comparison of compilers and its tables, and the timing of the edit-test loop."""
