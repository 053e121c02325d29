#!/usr/bin/env python3
"""Exercises in the chapters: the lint of their markup, their list, the student edition.

    tools/exercises/markup.py lint CHAPTER.md...       check exercise markup and tests
    tools/exercises/markup.py list CHAPTER.md...       the exercises, with their points
    tools/exercises/markup.py student CHAPTER.md...    print the student edition of a
                                                chapter (stubs for solutions)

The conventions are in docs/exercises.md. In short: inside a chunk,

    // BEGIN SOLUTION
    ...reference code...
    // END SOLUTION
    // BEGIN STUB          (optional; without it the stub is a throw)
    ...stub code, where a line `// NOT IMPLEMENTED` becomes that throw...
    // END STUB

and, beside the exercise's prose, a pandoc div

    ::: {.exercise #ex-5.1 points=4 title="The slab test"
         section=sec:slab-test fragments="Slab test for one axis"}

(on one line) with a hint (a `hint="..."` attribute or a `::: hint` div
inside). Tests of exercise ex-5.1 are the suites named Ex5_1_*, public in
tests/ch05/, hidden in tests/hidden/ch05/.

The lint runs from the repository root (test directories are found from there;
--root says otherwise) and reports `file:line: message`, like tools/noweb/lint.py.
Hidden tests are required only where a tests/hidden/ directory exists, so the
same lint passes in a student kit, which has none.

The work is done in files of one job each, whose names other tools import
from here (tools.exercises.markup) as before:

    regions.py      the SOLUTION and STUB markers inside one chunk
    attributes.py   headers, divs and their attributes, as pandoc reads them
    book.py         the exercises of a set of chapters (Book), and their lint
    suites.py       the exercises' tests and the lint of their names
    student.py      the student edition (stubs for solutions)

The chunks themselves are read by tools/noweb/chunks.py.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
# The names that the kits, the course plans, the grader and the tests use.
from tools.exercises.attributes import chapter_number, parse_attributes  # noqa: E402,F401
from tools.exercises.book import Book  # noqa: E402
from tools.exercises.regions import (MARKER, PLACEHOLDER, MarkupError,  # noqa: E402,F401
                                     find_regions, solution_lines_to_keep)
from tools.exercises.student import (LATER_STUB, stub_code, stub_message,  # noqa: E402,F401
                                     student_edition, throw_lines)
from tools.exercises.suites import TEST_MACRO  # noqa: E402,F401
from tools.noweb.chunks import USE  # noqa: E402,F401


def load(paths, root='.', tests=True):
    book = Book(paths, root=root, tests=tests)
    return book


def report_errors(book, what='exercises'):
    for message in book.errors:
        print(message, file=sys.stderr)
    if book.errors:
        print('%s: %d error(s)' % (what, len(book.errors)), file=sys.stderr)
    return not book.errors


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('command', choices=['lint', 'list', 'student'])
    parser.add_argument('--root', default='.', help='where tests/ is (default: .)')
    parser.add_argument('--json', action='store_true', help='list: as JSON')
    parser.add_argument('chapters', nargs='+')
    args = parser.parse_args(argv)
    book = load(args.chapters, root=args.root, tests=args.command != 'student')
    if not report_errors(book, 'lint-exercises' if args.command == 'lint' else 'exercises'):
        sys.exit(1)
    if args.command == 'list':
        if args.json:
            print(json.dumps([e.as_dict() for e in book.exercises], indent=2))
        for e in ([] if args.json else book.exercises):
            print('%-8s %2d points  %-40s %s' % (e.id, e.points, e.title, e.path))
        if not args.json:
            print('%d exercises, %d points' % (len(book.exercises),
                                              sum(e.points for e in book.exercises)))
    elif args.command == 'student':
        for chapter in book.chapters:
            sys.stdout.write('\n'.join(student_edition(chapter)))


if __name__ == '__main__':
    main()
