"""The tools that make the book, the library, the exercise kits and the grades
from the chapters; docs/architecture.md maps them."""
