"""Exercise regions inside one chunk: `// BEGIN SOLUTION` ... `// END SOLUTION`,
and the optional `// BEGIN STUB` ... `// END STUB` after it (docs/exercises.md).

Shared by the lint and the student edition (tools/exercises/), the noweb
filter that removes the markers from the tangle (tools/noweb/markup_filter.py)
and the grader's compile wall.
"""
import re

from tools.noweb.chunks import USE

MARKER = re.compile(r'^(\s*)// (BEGIN|END) (SOLUTION|STUB)\s*$')
# Anything that looks like a marker but is not one exactly would reach the
# tangle and the book as a comment: `//BEGIN SOLUTION`, `// begin stub`, ...
NEAR_MARKER = re.compile(r'^\s*/[/*]\s*(BEGIN|END)\s*(SOLUTION|STUB)', re.IGNORECASE)
PLACEHOLDER = re.compile(r'^(\s*)// NOT IMPLEMENTED\s*$')


class MarkupError(Exception):
    pass



class Region:
    """One `// BEGIN SOLUTION` ... `// END SOLUTION` in a chunk, and its stub.

    begin, end: indexes of the two markers in the chunk's body;
    stub_begin, stub_end: indexes of `// BEGIN STUB` and `// END STUB`, or None.
    """
    def __init__(self, begin, indent):
        self.begin, self.indent = begin, indent
        self.end = self.stub_begin = self.stub_end = None
        # Filled in by the chapter parser:
        self.path = self.chunk = self.exercise = None
        self.solution = []   # (line number, text)
        self.stub = None     # (line number, text) list, or None for a generated stub

    def line(self, index):
        return self.chunk.line + 1 + index


def find_regions(body):
    """Returns (regions, errors) for a chunk's body lines; an error is
    (index, message). A region must close in the chunk that opens it."""
    regions, errors = [], []
    state, region = 'code', None   # code | solution | after | stub
    for i, text in enumerate(body):
        marker = MARKER.match(text)
        if state == 'after':
            state = 'code'
            if marker and marker.group(2, 3) == ('BEGIN', 'STUB'):
                region.stub_begin = i
                state = 'stub'
                continue
        if not marker:
            if NEAR_MARKER.match(text):
                errors.append((i, 'malformed exercise marker: write exactly '
                               '"// BEGIN SOLUTION", "// END SOLUTION", '
                               '"// BEGIN STUB" or "// END STUB" on a line of its own'))
            elif state in ('solution', 'stub') and USE.search(text):
                errors.append((i, 'fragment use <<%s>> inside a %s block: the other '
                               'edition would leave that fragment unused; put the '
                               'markers inside <<%s>> instead'
                               % (USE.search(text).group(1), state, USE.search(text).group(1))))
            elif PLACEHOLDER.match(text) and state != 'stub':
                errors.append((i, '"// NOT IMPLEMENTED" stands for the stub\'s throw and '
                               'belongs inside a BEGIN STUB ... END STUB block'))
            continue
        edge, kind = marker.group(2, 3)
        if state == 'code' and (edge, kind) == ('BEGIN', 'SOLUTION'):
            region = Region(i, marker.group(1))
            regions.append(region)
            state = 'solution'
        elif state == 'solution' and (edge, kind) == ('END', 'SOLUTION'):
            region.end = i
            if i == region.begin + 1 or all(not t.strip() for t in body[region.begin + 1:i]):
                errors.append((region.begin, 'empty solution: there is nothing '
                               'between BEGIN SOLUTION and END SOLUTION'))
            state = 'after'
        elif state == 'stub' and (edge, kind) == ('END', 'STUB'):
            region.stub_end = i
            state = 'code'
        elif (edge, kind) == ('BEGIN', 'STUB'):
            errors.append((i, 'BEGIN STUB must follow END SOLUTION on the next line'
                           if state == 'code' else 'BEGIN STUB inside an open %s block'
                           % state))
        elif edge == 'BEGIN':
            errors.append((i, 'BEGIN SOLUTION inside an open %s block (markers do not '
                           'nest)' % state))
        else:
            errors.append((i, '%s %s without a matching BEGIN %s' % (edge, kind, kind)))
    if state == 'solution':
        errors.append((region.begin, 'BEGIN SOLUTION is never closed by END SOLUTION in '
                       'this chunk'))
    elif state == 'stub':
        errors.append((region.stub_begin, 'BEGIN STUB is never closed by END STUB in '
                       'this chunk'))
    return [r for r in regions if r.end is not None], errors


def solution_lines_to_keep(body):
    """The solution edition of a chunk: markers and stub blocks dropped.
    Returns one boolean per body line."""
    regions, errors = find_regions(body)
    if errors:
        raise MarkupError(errors[0][1])
    keep = [True] * len(body)
    for region in regions:
        keep[region.begin] = keep[region.end] = False
        if region.stub_begin is not None:
            for i in range(region.stub_begin, region.stub_end + 1):
                keep[i] = False
    return keep
