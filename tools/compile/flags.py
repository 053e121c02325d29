"""The compiler and compile flags of tools/compile/flags.mk, for Python.

    from tools.compile import flags
    flags.words('WORKER_CXXFLAGS')  -> ['-std=c++17', '-O0', ...]

The makefiles include flags.mk; the grader and compile_commands.py read it
here, without make (a grading image has none), so every compile of the book's
code takes its flags from that one file. It is read as make reads the lines
it holds (its header says which): NAME := WORDS or NAME ?= WORDS, a word
being $(NAME) of a line above; anything else refuses to be read, rather than
be read otherwise than make reads it.
"""
import functools
import os
import re

PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'flags.mk')
ASSIGNMENT = re.compile(r'^([A-Z_]+)\s*[:?]=\s*(.*)$')
REFERENCE = re.compile(r'^\$\(([A-Z_]+)\)$')


@functools.lru_cache(maxsize=None)
def definitions(path=PATH):
    """{name: [word, ...]} of every line of the file, references expanded."""
    values = {}
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith('#'):
                continue
            match = ASSIGNMENT.match(line)
            if not match or '#' in match.group(2) or line.endswith('\\'):
                raise ValueError('%s:%d: not a line flags.py reads: %s' % (path, number, line))
            words = []
            for word in match.group(2).split():
                reference = REFERENCE.match(word)
                if reference:
                    if reference.group(1) not in values:
                        raise ValueError('%s:%d: $(%s) is not defined above' % (
                            path, number, reference.group(1)))
                    words += values[reference.group(1)]
                elif '$' in word:
                    raise ValueError('%s:%d: not a word flags.py reads: %s' % (path, number, word))
                else:
                    words.append(word)
            values[match.group(1)] = words
    return values


def words(name):
    """The words of the variable `name` of flags.mk, as a list."""
    return list(definitions()[name])


def value(name):
    """The variable `name` of flags.mk, as one string."""
    return ' '.join(words(name))
