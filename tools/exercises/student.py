"""The student edition of a chapter: each exercise's solution replaced by its
stub, a throw that names the exercise and the section to read
(`tools/exercises/markup.py student`, the kits and the grader use it).
"""
import re

from tools.exercises.regions import PLACEHOLDER

# The book's code column (tools/noweb/lint.py checks it): a stub fits it too.
MAX_CODE_COLUMNS = 80


def c_string(text):
    return text.replace('\\', '\\\\').replace('"', '\\"').replace('<<', '< <')


# How the stub of an exercise that a later assignment of a course plan sets
# (docs/course.md) begins its message after the exercise's id. In `make test`,
# a test that reaches such a stub is skipped, not failed: tests/calls/rpc.h
# looks for these words.
LATER_STUB = 'comes with a later assignment'


def stub_message(exercise, fragment, later=False):
    section = exercise.section
    if section is None:
        where = exercise.section_id or 'see the book'
    elif section.number:
        where = '%s, %s' % (section.label(), section.title)
    else:
        where = section.label()
    if later:
        return 'Exercise %s %s: leave <%s> (%s) as it is for now' % (
            exercise.id, LATER_STUB, fragment, where)
    return 'Exercise %s is not done yet: write <%s> (%s)' % (exercise.id, fragment, where)


def throw_lines(indent, message):
    """`throw std::logic_error("...")`, the message split over string literals
    so that no line is wider than the book's code column."""
    width = MAX_CODE_COLUMNS - len(indent) - 4 - 2 - 2
    pieces, current = [], ''
    for word in re.split(r'(?<= )', message):
        while len(c_string(word)) > width:    # a word wider than a line
            cut = width
            while len(c_string(word[:cut])) > width:
                cut -= 1
            if current:
                pieces.append(current)
                current = ''
            pieces.append(word[:cut])
            word = word[cut:]
        if current and len(c_string(current + word)) > width:
            pieces.append(current)
            current = ''
        current += word
    if current:
        pieces.append(current)
    lines = [indent + 'throw std::logic_error(']
    for i, piece in enumerate(pieces):
        end = ');' if i == len(pieces) - 1 else ''
        lines.append('%s    "%s"%s' % (indent, c_string(piece), end))
    return lines


def stub_code(region, later=False):
    message = stub_message(region.exercise, region.chunk.name, later)
    if region.stub is None:
        return throw_lines(region.indent, message)
    out = []
    for _, text in region.stub:
        placeholder = PLACEHOLDER.match(text)
        out.extend(throw_lines(placeholder.group(1), message) if placeholder else [text])
    return out


def student_edition(chapter, only=None, later=()):
    """The chapter's lines with every solution (or, with `only`, those of one
    exercise, or of a set of exercises) replaced by its stub. The markers
    stay, so the student sees where to write; stub blocks go. The stubs of the
    exercises in `later` (ids: a course's later assignments set them) say so
    in their message."""
    out = list(chapter.lines)
    if only is not None and not isinstance(only, (set, frozenset, list, tuple)):
        only = [only]
    regions = [r for r in chapter.regions if only is None or r.exercise in only]
    for region in sorted(regions, key=lambda r: r.begin + r.chunk.line, reverse=True):
        if region.stub_begin is not None:
            del out[region.line(region.stub_begin) - 1:region.line(region.stub_end)]
        out[region.line(region.begin):region.line(region.end) - 1] = \
            stub_code(region, region.exercise.id in later)
    return out
