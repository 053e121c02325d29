"""The noweb side of a chapter: reading its chunks, checking its format (lint),
tangling it into C++ and the filters the tangle runs."""
