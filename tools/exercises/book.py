"""The exercises of a set of chapters (class Book): their divs, their regions
in the chunks, the sections they practise and, unless told not to, their
tests; every mistake reported as `file:line: message`.

The chunks are read as noweb reads them (tools/noweb/chunks.py), so that a
region is where the tangle and the grader will find it.
"""
import re

from tools.exercises import suites
from tools.exercises.attributes import (DIV_FENCE, EXERCISE_ID, HEADER, HEADER_ATTRIBUTES,
                                        chapter_number, parse_attributes)
from tools.exercises.regions import MARKER, NEAR_MARKER, PLACEHOLDER, find_regions
from tools.noweb import chunks
from tools.noweb.chunks import FENCE

FRAGMENT_SEPARATOR = ';'
# An ungraded exercise: [Title.]{.problem #ex:name} (docs/exercises.md).
PROBLEM = re.compile(r'\]\{[^}]*\.problem\b')


class Section:
    def __init__(self, ident, title, number, level, path, line):
        self.id, self.title, self.number = ident, title, number
        self.level, self.path, self.line = level, path, line

    def label(self):
        if not self.number:
            return 'Section "%s"' % self.title
        return '%s %s' % ('Chapter' if self.level == 1 else 'Section', self.number)



class Exercise:
    def __init__(self, ident, path, line, chapter):
        self.id, self.path, self.line, self.chapter = ident, path, line, chapter
        self.position = None   # its number in its chapter, ungraded exercises counted
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
        self.count = 0         # the exercises so far, graded or not (tools/book/exercises.lua)
        self.sections = []


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
            suites.check_tests(self)

    def error(self, path, line, message):
        self.errors.append('%s:%d: %s' % (path, line, message))

    # -- one chapter ------------------------------------------------------------

    def parse(self, path):
        number = chapter_number(path)
        chapter = Chapter(path, number)
        try:
            chapter.lines = chunks.read_lines(path)
        except (OSError, UnicodeDecodeError) as e:
            self.error(path, 0, 'cannot read chapter: %s' % e)
            return chapter
        if number is None:
            self.error(path, 0, 'a chapter file is named NN-slug.md; exercise ids and '
                       'test directories come from NN')
        in_fence = False
        divs = []           # stack of ('exercise', Exercise) | ('hint', line) | ('div', line)
        counters = [int(number or 0), 0, 0, 0, 0, 0]
        for item in chunks.parse(chapter.lines, path):
            if isinstance(item, chunks.Chunk):
                # A chunk as noweb reads it, given what the exercises need:
                # the section it stands in and its regions.
                item.section = chapter.sections[-1] if chapter.sections else None
                chapter.chunks.append(item)
                self.read_regions(chapter, item)
                continue
            n, text = item
            if MARKER.match(text) or NEAR_MARKER.match(text) or PLACEHOLDER.match(text):
                self.error(path, n, 'exercise marker outside a code chunk: markers stand '
                           'between <<Name>>= and @ (a ```c++ block is not a chunk)')
            if FENCE.match(text):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            chapter.count += len(PROBLEM.findall(text))
            header = HEADER.match(text)
            if header:
                self.header(chapter, n, len(header.group(1)), header.group(2), counters)
                continue
            div = DIV_FENCE.match(text)
            if div:
                self.div_fence(chapter, n, div.group(1).strip().rstrip(':').strip(), divs)
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
        chapter.count += 1
        exercise.position = chapter.count
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

    def read_regions(self, chapter, chunk):
        """The exercise regions of one chunk, in chunk.regions and chapter.regions."""
        chunk.regions = []
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

    # The kits ask the Book which exercise a suite name gives.
    suite_exercise = staticmethod(suites.suite_exercise)

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
        # The weave numbers a chapter's exercises, graded or not, in order; the
        # grader and the tests know a graded one by its id, which must agree.
        for exercise in self.exercises:
            match = EXERCISE_ID.match(exercise.id or '')
            if match and exercise.chapter and int(match.group(1)) == int(exercise.chapter) \
                    and int(match.group(2)) != exercise.position:
                number = '%d.%d' % (int(exercise.chapter), exercise.position)
                self.error(exercise.path, exercise.line, 'the exercise %s is exercise %s of '
                           'its chapter (the ungraded exercises before it count too): its id '
                           'must be ex-%s' % (exercise.id, number, number))
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
