#!/usr/bin/env python3
"""noweb filter: the tangle of the solution edition, without exercise markup.

notangle runs this between noweb's markup and its tangler (notangle -filter,
as tools/noweb/tangle.py does). In every code chunk it drops the marker lines
`// BEGIN SOLUTION`, `// END SOLUTION` and each `// BEGIN STUB` ... `// END STUB`
block, so that the code compiled and the readable tangle in tangled/ hold the
reference code and nothing else (docs/exercises.md). The student edition needs
no filter of its own: its chapters already hold the stubs (tools/exercises/student.py).

After dropped lines it tells the tangler where the next line came from
(`@line`), so that `#line` directives keep pointing at the chapter's lines.
Malformed markup stops the tangle with file:line (make lint says more).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from tools.exercises.regions import MarkupError, solution_lines_to_keep  # noqa: E402


def chunk_lines(records):
    """Splits a code chunk's records into lines: (records, text) per line."""
    lines, current = [], []
    for record in records:
        current.append(record)
        if record == '@nl':
            lines.append(current)
            current = []
    if current:
        lines.append(current)
    return [(line, ''.join(r[len('@text '):] if r.startswith('@text ') else
                           '<<%s>>' % r[len('@use '):] if r.startswith('@use ') else ''
                           for r in line)) for line in lines]


def main():
    records = sys.stdin.read().split('\n')
    out = []
    path, line_number = '?', 0   # lines of the current file read so far
    i = 0
    while i < len(records):
        record = records[i]
        if record.startswith('@file '):
            path, line_number = record[len('@file '):], 0
        if not record.startswith('@begin code'):
            out.append(record)
            if record in ('@nl', '@index nl'):
                line_number += 1
            i += 1
            continue
        end = i + 1
        while end < len(records) and not records[end].startswith('@end code'):
            end += 1
        # The first line of a chunk is its header (<<Name>>=).
        lines = chunk_lines(records[i + 1:end])
        header, body = lines[:1], lines[1:]
        try:
            keep = solution_lines_to_keep([text for _, text in body])
        except MarkupError as e:
            sys.exit('markup_filter: %s:%d: %s (run make lint)' % (path, line_number + 1, e))
        out.append(record)
        for line, _ in header:
            out.extend(line)
        line_number += 1
        dropped = False
        for (line, _), kept in zip(body, keep):
            if kept:
                if dropped:
                    # noweb's tangler numbers from the line after the one given.
                    out.append('@line %d' % (line_number + 2))
                    dropped = False
                out.extend(line)
            line_number += sum(1 for r in line if r in ('@nl', '@index nl'))
            dropped = dropped or not kept
        if dropped:
            out.append('@line %d' % (line_number + 2))
        i = end
    sys.stdout.write('\n'.join(out))


if __name__ == '__main__':
    main()
