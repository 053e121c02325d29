#!/usr/bin/env python3
"""Exercises in the chapters: their markup, its lint, and the student edition.

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
--root says otherwise) and reports `file:line: message`, like tools/lint.py.
Hidden tests are required only where a tests/hidden/ directory exists, so the
same lint passes in a student kit, which has none.
"""
import argparse
import json
import os
import re
import sys

MARKER = re.compile(r'^(\s*)// (BEGIN|END) (SOLUTION|STUB)\s*$')
# Anything that looks like a marker but is not one exactly would reach the
# tangle and the book as a comment: `//BEGIN SOLUTION`, `// begin stub`, ...
NEAR_MARKER = re.compile(r'^\s*/[/*]\s*(BEGIN|END)\s*(SOLUTION|STUB)', re.IGNORECASE)
PLACEHOLDER = re.compile(r'^(\s*)// NOT IMPLEMENTED\s*$')
DEFINITION = re.compile(r'^<<(.+)>>=\s*$')
CHUNK_END = re.compile(r'^@(\s|$)')
# A use's name ends at the first `>>`, as notangle reads it: `<<>> <<X>>` is an
# empty use and a use of X, not one use of `>> <<X`.
USE = re.compile(r'(?<!@)<<(.*?)>>')
FENCE = re.compile(r'^(```|~~~)')
HEADER = re.compile(r'^(#{1,6})\s+(.*?)\s*$')
HEADER_ATTRIBUTES = re.compile(r'\s*\{([^{}]*)\}\s*$')
DIV_FENCE = re.compile(r'^:{3,}(.*)$')
ATTRIBUTE = re.compile(r'''\s*(?:\#(?P<id>[^\s}]+)|\.(?P<cls>[^\s}]+)|(?P<key>[\w-]+)=
                           (?:"(?P<dq>(?:[^"\\]|\\.)*)"|'(?P<sq>[^']*)'|(?P<bare>[^\s"'}]+)))''',
                       re.VERBOSE)
EXERCISE_ID = re.compile(r'^ex-(\d+)\.(\d+)$')
TEST_MACRO = re.compile(r'^\s*(TEST|TEST_F|TEST_P|TYPED_TEST|TYPED_TEST_P|EXERCISE_TEST)\s*\('
                        r'\s*(\w+)\s*,\s*(\w+)\s*\)')
EXERCISE_SUITE = re.compile(r'(?:^|/)Ex(\d+)_(\d+)_\w+$')
LOOKS_LIKE_EXERCISE_SUITE = re.compile(r'(?:^|/)Ex\d')
CHAPTER_FILE = re.compile(r'^(\d\d)-[^/]*\.md$')
MAX_CODE_COLUMNS = 80
FRAGMENT_SEPARATOR = ';'


class MarkupError(Exception):
    pass


# ---------------------------------------------------------------------------
# Regions inside one chunk (shared by the lint, the student edition and the
# noweb filter that removes the markers from the tangle)

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


# ---------------------------------------------------------------------------
# Chapters

class Section:
    def __init__(self, ident, title, number, level, path, line):
        self.id, self.title, self.number = ident, title, number
        self.level, self.path, self.line = level, path, line

    def label(self):
        if not self.number:
            return 'Section "%s"' % self.title
        return '%s %s' % ('Chapter' if self.level == 1 else 'Section', self.number)


class Chunk:
    def __init__(self, name, path, line):
        self.name, self.path, self.line = name, path, line
        self.body = []
        self.regions = []


class Exercise:
    def __init__(self, ident, path, line, chapter):
        self.id, self.path, self.line, self.chapter = ident, path, line, chapter
        self.points = None
        self.title = self.section_id = self.hint = None
        self.fragments = []
        self.section = None
        self.regions = []
        self.public_tests = []   # (suite, name, path, line)
        self.hidden_tests = []

    @property
    def number(self):
        return self.id[len('ex-'):]

    @property
    def suite_prefix(self):
        return 'Ex%s_' % self.number.replace('.', '_')

    def as_dict(self, hidden=True):
        d = {'id': self.id, 'chapter': self.chapter, 'file': self.path,
             'title': self.title, 'points': self.points,
             'section': self.section_id,
             'section_number': self.section.number if self.section else None,
             'fragments': self.fragments, 'suite_prefix': self.suite_prefix,
             'public_tests': sorted({'%s.%s' % t[:2] for t in self.public_tests})}
        if hidden:
            d['hidden_tests'] = sorted({'%s.%s' % t[:2] for t in self.hidden_tests})
        return d


class Chapter:
    def __init__(self, path, number):
        self.path, self.number = path, number
        self.lines = []
        self.chunks = []
        self.regions = []
        self.exercises = []
        self.sections = []


def chapter_number(path):
    match = CHAPTER_FILE.match(os.path.basename(path))
    return match.group(1) if match else None


def parse_attributes(text):
    """Pandoc attributes `#id .class key=value key="v w"` -> (id, classes, dict),
    or None where the text is not a pandoc attribute list."""
    ident, classes, attrs = None, [], {}
    pos = 0
    text = text.strip()
    while pos < len(text):
        match = ATTRIBUTE.match(text, pos)
        if not match or match.end() == pos:
            return None
        if match.group('id'):
            ident = match.group('id')
        elif match.group('cls'):
            classes.append(match.group('cls'))
        else:
            value = match.group('dq')
            if value is not None:
                value = re.sub(r'\\(.)', r'\1', value)
            else:
                value = match.group('sq') if match.group('sq') is not None \
                    else match.group('bare')
            attrs[match.group('key')] = value
        pos = match.end()
        while pos < len(text) and text[pos].isspace():
            pos += 1
    return ident, classes, attrs


def exercise_order(exercise):
    match = EXERCISE_ID.match(exercise.id or '')
    return (int(match.group(1)), int(match.group(2))) if match else (1 << 30, 0)


class Book:
    """The exercises of a set of chapters, with their tests; errors collected
    as `file:line: message`."""

    def __init__(self, paths, root='.', tests=True):
        self.errors = []
        self.root = root
        self.chapters = [self.parse(path) for path in paths]
        self.exercises = sorted((e for c in self.chapters for e in c.exercises),
                                key=exercise_order)
        self.check_book()
        self.public_suites = {}   # suite -> [(path, line, name)]
        self.hidden = []          # (suite, name, path, line)
        if tests:
            self.check_tests()

    def error(self, path, line, message):
        self.errors.append('%s:%d: %s' % (path, line, message))

    # -- one chapter ------------------------------------------------------------

    def parse(self, path):
        number = chapter_number(path)
        chapter = Chapter(path, number)
        try:
            with open(path, encoding='utf-8') as f:
                chapter.lines = f.read().split('\n')
        except (OSError, UnicodeDecodeError) as e:
            self.error(path, 0, 'cannot read chapter: %s' % e)
            return chapter
        if number is None:
            self.error(path, 0, 'a chapter file is named NN-slug.md; exercise ids and '
                       'test directories come from NN')
        chunk = None
        in_fence = False
        divs = []           # stack of ('exercise', Exercise) | ('hint', line) | ('div', line)
        counters = [int(number or 0), 0, 0, 0, 0, 0]
        lines = chapter.lines
        for n, text in enumerate(lines, 1):
            if chunk is not None:
                if CHUNK_END.match(text) or DEFINITION.match(text):
                    self.finish_chunk(chapter, chunk)
                    chunk = None
                    if CHUNK_END.match(text):
                        continue
                else:
                    chunk.body.append(text)
                    continue
            definition = DEFINITION.match(text)
            if definition:
                chunk = Chunk(definition.group(1), path, n)
                chunk.section = chapter.sections[-1] if chapter.sections else None
                chapter.chunks.append(chunk)
                continue
            if MARKER.match(text) or NEAR_MARKER.match(text) or PLACEHOLDER.match(text):
                self.error(path, n, 'exercise marker outside a code chunk: markers stand '
                           'between <<Name>>= and @ (a ```c++ block is not a chunk)')
            if FENCE.match(text):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            header = HEADER.match(text)
            if header:
                self.header(chapter, n, len(header.group(1)), header.group(2), counters)
                continue
            div = DIV_FENCE.match(text)
            if div:
                self.div_fence(chapter, n, div.group(1).strip().rstrip(':').strip(), divs)
        if chunk is not None:
            self.finish_chunk(chapter, chunk)
        for kind, item in divs:
            if kind == 'exercise':
                self.error(path, item.line, 'exercise div %s is never closed by :::'
                           % (item.id or ''))
        return chapter

    def header(self, chapter, n, level, text, counters):
        ident, unnumbered = None, False
        attributes = HEADER_ATTRIBUTES.search(text)
        if attributes:
            parsed = parse_attributes(attributes.group(1))
            if parsed:
                ident = parsed[0]
                unnumbered = 'unnumbered' in parsed[1] or '-' in parsed[1]
                text = text[:attributes.start()]
        title = text.strip().rstrip('#').strip()
        if level == 1:
            number = str(counters[0])
        elif unnumbered:
            number = None
        else:
            counters[level - 1] += 1
            for i in range(level, len(counters)):
                counters[i] = 0
            number = '.'.join(str(c) for c in counters[:level])
        chapter.sections.append(Section(ident, title, number, level, chapter.path, n))

    def div_fence(self, chapter, n, rest, divs):
        path = chapter.path
        if not rest:
            if not divs:
                self.error(path, n, 'closing ::: without an open div')
            else:
                divs.pop()
            return
        if rest.startswith('{') and rest.endswith('}'):
            parsed = parse_attributes(rest[1:-1])
            if parsed is None:
                self.error(path, n, 'cannot read the div\'s attributes %s' % rest)
                divs.append(('div', n))
                return
        else:
            parsed = (None, [rest.split()[0]], {})
        ident, classes, attrs = parsed
        inside = [item for kind, item in divs if kind == 'exercise']
        if 'exercise' in classes:
            if inside:
                self.error(path, n, 'an exercise div inside exercise %s' % inside[-1].id)
            divs.append(('exercise', self.exercise(chapter, n, ident, attrs)))
        elif 'hint' in classes:
            if not inside:
                self.error(path, n, 'a hint div must stand inside an exercise div')
            else:
                inside[-1].hint = inside[-1].hint or ('div', n)
            divs.append(('hint', n))
        else:
            divs.append(('div', n))

    def exercise(self, chapter, n, ident, attrs):
        path = chapter.path
        exercise = Exercise(ident, path, n, chapter.number)
        chapter.exercises.append(exercise)
        if not ident:
            self.error(path, n, 'exercise div without an id: write {.exercise #ex-%d.K '
                       '...}' % int(chapter.number or 0))
        else:
            match = EXERCISE_ID.match(ident)
            if not match:
                self.error(path, n, 'exercise id %s is not of the form ex-N.K' % ident)
            elif chapter.number and int(match.group(1)) != int(chapter.number):
                self.error(path, n, 'exercise id %s in chapter %s: the number before the '
                           'dot is the chapter\'s (ex-%d.K)'
                           % (ident, chapter.number, int(chapter.number)))
        points = attrs.get('points')
        if points is None:
            self.error(path, n, 'exercise %s has no points= attribute' % (ident or ''))
        elif not re.match(r'^[1-9]\d*$', points):
            self.error(path, n, 'exercise %s: points=%s is not a positive integer'
                       % (ident or '', points))
        else:
            exercise.points = int(points)
        exercise.title = attrs.get('title')
        if not exercise.title:
            self.error(path, n, 'exercise %s has no title="..." attribute' % (ident or ''))
        exercise.section_id = attrs.get('section')
        if not exercise.section_id:
            self.error(path, n, 'exercise %s has no section= attribute naming the book '
                       'section it practises (section=sec:...)' % (ident or ''))
        if attrs.get('hint', '').strip():
            exercise.hint = ('attribute', n)
        exercise.fragments = [f.strip() for f in
                              attrs.get('fragments', '').split(FRAGMENT_SEPARATOR)
                              if f.strip()]
        if not exercise.fragments:
            self.error(path, n, 'exercise %s has no fragments="Name; Other name" attribute '
                       'naming the fragments it stubs' % (ident or ''))
        unknown = sorted(set(attrs) - {'points', 'title', 'section', 'hint', 'fragments'})
        if unknown:
            self.error(path, n, 'exercise %s: unknown attribute(s) %s'
                       % (ident or '', ', '.join(unknown)))
        return exercise

    def finish_chunk(self, chapter, chunk):
        regions, errors = find_regions(chunk.body)
        for index, message in errors:
            self.error(chapter.path, chunk.line + 1 + index, message)
        for region in regions:
            region.path, region.chunk = chapter.path, chunk
            region.solution = [(region.line(i), chunk.body[i])
                               for i in range(region.begin + 1, region.end)]
            if region.stub_begin is not None:
                region.stub = [(region.line(i), chunk.body[i])
                               for i in range(region.stub_begin + 1, region.stub_end)]
            chunk.regions.append(region)
            chapter.regions.append(region)

    # -- across chapters ----------------------------------------------------------

    def check_book(self):
        by_id = {}
        for exercise in self.exercises:
            if not exercise.id:
                continue
            if exercise.id in by_id:
                first = by_id[exercise.id]
                self.error(exercise.path, exercise.line, 'duplicate exercise id %s (first at '
                           '%s:%d)' % (exercise.id, first.path, first.line))
            else:
                by_id[exercise.id] = exercise
        self.by_id = by_id
        sections = {}
        for order, chapter in enumerate(self.chapters):
            for section in chapter.sections:
                if section.id:
                    sections.setdefault(section.id, (order, section))
        for order, chapter in enumerate(self.chapters):
            chunk_names = {c.name for c in chapter.chunks}
            claimed = {}
            for exercise in chapter.exercises:
                if exercise.hint is None:
                    self.error(exercise.path, exercise.line, 'exercise %s has no hint: add '
                               'hint="..." or a ::: hint div inside it' % exercise.id)
                if exercise.section_id:
                    found = sections.get(exercise.section_id)
                    if not found:
                        self.error(exercise.path, exercise.line, 'exercise %s: section=%s is '
                                   'not the id of a header' % (exercise.id,
                                                               exercise.section_id))
                    elif found[0] > order:
                        self.error(exercise.path, exercise.line, 'exercise %s: section %s is '
                                   'in a later chapter (%s)' % (exercise.id,
                                   exercise.section_id, found[1].path))
                    else:
                        exercise.section = found[1]
                for name in exercise.fragments:
                    if name not in chunk_names:
                        self.error(exercise.path, exercise.line, 'exercise %s: fragment '
                                   '<<%s>> is not defined in this chapter'
                                   % (exercise.id, name))
                        continue
                    if name in claimed:
                        self.error(exercise.path, exercise.line, 'exercise %s: fragment '
                                   '<<%s>> already belongs to exercise %s; give each '
                                   'exercise\'s code a fragment of its own'
                                   % (exercise.id, name, claimed[name].id))
                        continue
                    claimed[name] = exercise
                    regions = [r for r in chapter.regions if r.chunk.name == name]
                    if not regions:
                        self.error(exercise.path, exercise.line, 'exercise %s: fragment '
                                   '<<%s>> has no // BEGIN SOLUTION ... // END SOLUTION'
                                   % (exercise.id, name))
                    for region in regions:
                        region.exercise = exercise
                        exercise.regions.append(region)
            for region in chapter.regions:
                if region.exercise is None:
                    self.error(region.path, region.line(region.begin), 'this solution in '
                               '<<%s>> belongs to no exercise: name the fragment in the '
                               'fragments= of an exercise div in this chapter'
                               % region.chunk.name)

    def test_files(self, directory):
        path = os.path.join(self.root, directory)
        if not os.path.isdir(path):
            return []
        return sorted(os.path.join(directory, name) for name in os.listdir(path)
                      if name.endswith(('.cpp', '.h', '.hpp', '.cc')))

    def scan_tests(self, directory):
        """(suite, name, path, line) for every TEST(...) in a directory's files."""
        found = []
        for path in self.test_files(directory):
            with open(os.path.join(self.root, path), encoding='utf-8',
                      errors='replace') as f:
                for n, text in enumerate(f, 1):
                    match = TEST_MACRO.match(text)
                    if match:
                        found.append((match.group(2), match.group(3), path, n,
                                      match.group(1)))
        return found

    def check_tests(self):
        hidden_required = os.path.isdir(os.path.join(self.root, 'tests', 'hidden'))
        for chapter in self.chapters:
            if chapter.number is None:
                continue
            for hidden, directory in ((False, 'tests/ch%s' % chapter.number),
                                      (True, 'tests/hidden/ch%s' % chapter.number)):
                for suite, name, path, line, macro in self.scan_tests(directory):
                    if hidden:
                        self.hidden.append((suite, name, path, line))
                    else:
                        self.public_suites.setdefault(suite, []).append((path, line, name))
                    exercise_id = self.suite_exercise(suite)
                    if exercise_id is None:
                        if LOOKS_LIKE_EXERCISE_SUITE.search(suite):
                            self.error(path, line, 'test suite %s looks like an exercise\'s '
                                       'but is not named ExN_K_Name' % suite)
                        elif hidden:
                            self.error(path, line, 'hidden test suite %s names no exercise: '
                                       'hidden tests are named ExN_K_Name' % suite)
                        continue
                    exercise = self.by_id.get(exercise_id)
                    if exercise is None:
                        self.error(path, line, 'test suite %s names exercise %s, which does '
                                   'not exist' % (suite, exercise_id))
                    elif exercise.chapter != chapter.number:
                        self.error(path, line, 'test suite %s names exercise %s of chapter '
                                   '%s; it belongs in tests/%sch%s/'
                                   % (suite, exercise_id, exercise.chapter,
                                      'hidden/' if hidden else '', exercise.chapter))
                    else:
                        if macro != 'EXERCISE_TEST':
                            self.error(path, line, 'test %s.%s of exercise %s is declared '
                                       'with %s: declare it with EXERCISE_TEST and reach the '
                                       'exercise\'s code through its exercise calls '
                                       '(tests/calls/calls.h)' % (suite, name, exercise_id,
                                                                  macro))
                        (exercise.hidden_tests if hidden else
                         exercise.public_tests).append((suite, name, path, line))
            # The grader compiles a chapter's public and hidden tests into one
            # judge (tests/calls/judge.cpp): a name may not be defined twice.
            public = {}
            for exercise in chapter.exercises:
                for suite, name, path, line in exercise.public_tests:
                    public['%s.%s' % (suite, name)] = (path, line)
                for suite, name, path, line in exercise.hidden_tests:
                    if '%s.%s' % (suite, name) in public:
                        self.error(path, line, 'hidden test %s.%s has the name of a public '
                                   'test (%s:%d): give it another'
                                   % ((suite, name) + public['%s.%s' % (suite, name)]))
            for exercise in chapter.exercises:
                if not exercise.id or not EXERCISE_ID.match(exercise.id):
                    continue
                if not exercise.public_tests:
                    self.error(exercise.path, exercise.line, 'exercise %s has no tests: add '
                               'a suite named %sName in tests/ch%s/'
                               % (exercise.id, exercise.suite_prefix, chapter.number))
                if hidden_required and not exercise.hidden_tests:
                    self.error(exercise.path, exercise.line, 'exercise %s has no hidden '
                               'tests: add a suite named %sName in tests/hidden/ch%s/'
                               % (exercise.id, exercise.suite_prefix, chapter.number))

    @staticmethod
    def suite_exercise(suite):
        match = EXERCISE_SUITE.search(suite)
        return 'ex-%d.%d' % (int(match.group(1)), int(match.group(2))) if match else None


# ---------------------------------------------------------------------------
# The student edition

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


# ---------------------------------------------------------------------------

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
