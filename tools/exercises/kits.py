#!/usr/bin/env python3
"""Student and solution kits of the exercises, their leak check and validation.

    tools/exercises/kits.py build --out DIR [--src DIR] [--no-book] [NN ...]
    tools/exercises/kits.py leaks --out DIR [--src DIR]
    tools/exercises/kits.py validate --out DIR [--edition student|solution]
    tools/exercises/kits.py try --out DIR [--src DIR] [MAKE_ARG ...]

build: DIR/student/ and DIR/solution/ (and DIR/lrt-student.tar.gz,
DIR/lrt-solution.tar.gz) for the exercises of chapters NN (all chapters when
none is given). A kit holds chapters 1 to the last chosen one: the chosen
chapters with stubs in place of solutions (student kit), the other chapters
as they are; the public tests of those chapters; the Makefile, tools/ and
tests/tools/ of this repository; book.md, figures/, data/; a README; the book
as book.pdf and as web pages in html/ (open html/index.html), and the readable
tangle in tangled/ (all built in the kit); exercises.json. The solution kit adds tests/hidden/. The student kit must pass
the leak check, which `build` runs last.

leaks: searches the student kit (every file, the text of the PDF and of the
web pages, the tarball) for
any line of a chosen exercise's solution that appears nowhere else in the
source, any two consecutive lines of a solution, and the name of any hidden
test.

validate: the solution kit, built as of every chapter with that chapter's public
and hidden tests and as of the last chapter with all of them, must pass every
test. Graded by tools/grading/grade.py in the solution kit, each chosen chapter must
score every point, and lose exactly one exercise's points with that exercise
alone stubbed. The student kit must compile as of every chapter; and for each
chosen chapter N, the code as of N built as grading builds it (the student's
chapter N, the reference text of the chapters before it) must fail every test
of chapter N's exercises, with at least one failure naming the exercise (as
the stubs do), and pass chapter N's other tests.

try: the kits as their readers use them. The student kit's own `make test`
(with MAKE_ARGs, e.g. UPTO=last) may fail a test only because of the chosen
exercises' stubs (their tests, or a later chapter's test whose failure names
one), and skip a test only at the stub of a later assignment's exercise; each
chosen exercise fails some test. The solution kit's chapters and tests must
be the source's, which the source's own `make test` runs.

--src is where chapters/, tests/, book.md, figures/ and data/ come from (the
repository by default); the Makefile, tools/ and tests/tools/ always come from
the repository that holds this script.
"""
import argparse
import glob
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(os.path.dirname(HERE)))  # the repository: import tools.*
from tools.exercises import course  # noqa: E402
from tools.exercises import markup  # noqa: E402

EDITIONS = ('solution', 'student')
# What `validate` checks: each edition's tests, then grading in the solution kit.
VALIDATIONS = EDITIONS + ('grading',)
# The toolchain's own tests go into every kit (the kit's `make test` runs
# them) except the exercise machinery's, whose fixtures hold solutions, and
# the grader's and the autograder's, which grade the repository's own
# solutions with its hidden tests: in a student kit, whose chapters hold
# stubs, they could only fail. The web edition's are left out too: they open
# pages of chapter 5, which a kit of the first chapters lacks, and a
# student's machine may have no browser.
TOOL_TESTS_LEFT_OUT = ('exercises', 'test_exercises.py', 'test_grade.py', 'attacks.py',
                       'test_grade_batch.py', 'test_grade_crash.py', 'test_grade_limits.py',
                       'test_compile_wall.py', 'test_grade_hidden.py', 'test_grade_wall.py',
                       'test_gradescope.py', 'test_html.py', '__pycache__')
# Make variables of the calling make that must not leak into a kit's make.
MAKE_ENV_DROP = ('CHAPTERS', 'BUILD', 'MAKEFLAGS', 'MFLAGS', 'MAKELEVEL', 'MAKEOVERRIDES',
                 'CH', 'UPTO', 'ONLY', 'ASOF', 'HIDDEN', 'GTEST_FILTER')
TIME_LIMIT = 600        # seconds for one test binary
TEST_TIME_LIMIT = 120   # seconds for one test, when a binary must be run test by test
MIN_SOLUTION_CHARS = 12  # shorter solution lines (without spaces) are too common to search


def shown(path):
    """A path as relative to the current directory, if it is below it."""
    rel = os.path.relpath(path)
    return path if rel.startswith('..') else rel


def fail(message):
    sys.exit('exercises: ' + message)


def stop_on(problems, message):
    """Prints the problems, if any, and fails with message (which takes
    their count, %d)."""
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        fail(message % len(problems))


def clean_env():
    env = {k: v for k, v in os.environ.items() if k not in MAKE_ENV_DROP}
    env['LC_ALL'] = 'C'
    return env


def make(kit, args, capture=True):
    cmd = ['make', '--no-print-directory', '-C', kit] + args
    proc = subprocess.run(cmd, env=clean_env(), capture_output=capture, text=True)
    return proc


def source_book(src):
    paths = sorted(glob.glob(os.path.join(src, 'chapters', '[0-9][0-9]-*.md')))
    if not paths:
        fail('no chapters in %s/chapters' % src)
    rel = [os.path.relpath(p, src) for p in paths]
    cwd = os.getcwd()
    os.chdir(src)    # the book's messages name chapters as the lint does
    try:
        book = markup.Book(rel, root='.')
    finally:
        os.chdir(cwd)
    if not markup.report_errors(book):
        fail('fix the errors above first (make lint)')
    return book


def selection(book, wanted):
    numbers = [c.number for c in book.chapters]
    if not wanted:
        return numbers
    chosen = []
    for word in wanted:
        match = re.match(r'^(?:.*/)?(\d{1,2})(?:-.*\.md)?$', word)
        if not match:
            fail('CHAPTERS names chapters by number ("03 05"), not %r' % word)
        number = '%02d' % int(match.group(1))
        if number not in numbers:
            fail('there is no chapter %s (chapters: %s)' % (number, ' '.join(numbers)))
        chosen.append(number)
    return sorted(set(chosen))


# ---------------------------------------------------------------------------
# Building the kits

def copy_tree(source, target, leave_out=('__pycache__',)):
    if os.path.isdir(source):
        shutil.copytree(source, target, ignore=shutil.ignore_patterns(*leave_out))


def copy_file(source, target):
    if os.path.isfile(source):
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(source, target)


class Choice:
    """What a pair of kits is for: the chapters given by number (every
    exercise of them), or one assignment of a course plan (docs/course.md).

    numbers: the chapters whose exercises are chosen (the kit holds chapters
    1 to the last of them); chosen: those exercises (Exercise objects);
    points: {id: points}, the plan's where it says; stubbed: the exercises
    that are stubs in the student kit: the chosen ones, and with a plan also
    those of the assignments released later (earlier chapters' included), so
    that no solution is handed out before its assignment."""

    def __init__(self, book, chapters=None, plan=None, assignment=None):
        self.plan, self.assignment = plan, None
        if plan is None:
            if assignment:
                fail('ASSIGNMENT needs PLAN (a course plan, docs/course.md)')
            self.numbers = selection(book, chapters)
            self.chosen = [e for e in book.exercises if e.chapter in self.numbers]
            self.points = {e.id: e.points for e in self.chosen}
            self.stubbed = {e.id for e in self.chosen}
            self.later = set()
            return
        if chapters:
            fail('give CHAPTERS or PLAN, not both')
        if not assignment:
            fail('PLAN needs ASSIGNMENT: the kits are those of one assignment')
        try:
            loaded = course.load(plan, {e.id: e.points for e in book.exercises})
            self.assignment = loaded.assignment(assignment)
        except course.PlanError as e:
            fail(str(e))
        ids = self.assignment.exercises
        self.chosen = [e for e in book.exercises if e.id in ids]
        self.numbers = sorted({e.chapter for e in self.chosen})
        self.points = dict(self.assignment.points)
        self.later = set(loaded.unreleased(assignment)) - set(ids)
        self.stubbed = set(ids) | self.later

    def manifest(self):
        if self.assignment is None:
            return {}
        a = self.assignment.as_dict()
        a['plan'] = os.path.basename(self.plan)
        return {'assignment': a, 'unreleased': sorted(self.later)}


def exercise_table(chosen, points):
    if not chosen:
        return 'This set has no exercises.'
    rows = ['| exercise | points | title | chapter file | section | tests |',
            '|---|---|---|---|---|---|']
    for e in chosen:
        section = e.section.label() if e.section.number else e.section.title
        rows.append('| %s | %g | %s | `%s` | %s | `%s*` |' % (
            e.number, points[e.id], e.title, e.path, section, e.suite_prefix))
    rows.append('')
    rows.append('%d exercises, %g points in all.' % (len(chosen),
                                                     sum(points[e.id] for e in chosen)))
    return '\n'.join(rows)


def later_note(book, choice):
    """For the kit of an assignment of a plan: the stubs of exercises that
    later assignments set, which are not this one's to write."""
    last = max(choice.numbers)
    later = [e for e in book.exercises if e.id in choice.later and e.chapter <= last]
    if not later:
        return ''
    return ('\n\nThe exercises %s are stubs too: a later assignment sets them, and '
            'their stubs say so. `make test` skips every test that reaches one of '
            'them, naming the exercise, instead of failing it; leave them for now.'
            % ', '.join(e.id for e in later))


def readme(edition, book, kit_chapters, choice):
    chosen_numbers, chosen = choice.numbers, choice.chosen
    with open(os.path.join(HERE, 'kit', 'README.%s.md' % edition), encoding='utf-8') as f:
        text = f.read()
    example = chosen[0] if chosen else None
    first, last = int(kit_chapters[0].number), int(kit_chapters[-1].number)
    values = {
        'CHAPTER_RANGE': '%d to %d' % (first, last) if first != last else str(first),
        'SELECTED': ', '.join(str(int(n)) for n in chosen_numbers
                              if not chosen or any(e.chapter == n for e in chosen)),
        'SELECTED_FILES': ', '.join('`%s`' % c.path for c in kit_chapters
                                    if c.number in chosen_numbers),
        'EXERCISES': exercise_table(chosen, choice.points),
        'LATER': later_note(book, choice),
        'EXAMPLE_ID': example.id if example else 'ex-N.K',
        'EXAMPLE_CH': example.chapter if example else 'NN',
        'EXAMPLE_N': str(int(example.chapter)) if example else 'N',
        'EXAMPLE_NUMBER': example.number if example else 'N.K',
        'EXAMPLE_FILTER': (example.suite_prefix + '*') if example else 'ExN_K_*',
        'EXAMPLE_FILE': os.path.basename(example.path) if example else 'NN-slug.md',
    }
    for key, value in values.items():
        text = text.replace('{{%s}}' % key, value)
    return text


def write_kit(edition, src, out, book, choice, build_book):
    kit = os.path.join(out, edition)
    if os.path.exists(kit):
        shutil.rmtree(kit)
    os.makedirs(kit)
    chosen_numbers, chosen = choice.numbers, choice.chosen
    last = max(chosen_numbers)
    kit_chapters = [c for c in book.chapters if c.number <= last]

    copy_file(os.path.join(ROOT, 'Makefile'), os.path.join(kit, 'Makefile'))
    copy_tree(os.path.join(ROOT, 'tools'), os.path.join(kit, 'tools'))
    copy_tree(os.path.join(ROOT, 'tests', 'tools'), os.path.join(kit, 'tests', 'tools'),
              TOOL_TESTS_LEFT_OUT)
    for name in ('book.md', 'references.bib', 'LICENSE', '.gitignore'):
        copy_file(os.path.join(src, name), os.path.join(kit, name))
    for name in ('figures', 'data'):
        copy_tree(os.path.join(src, name), os.path.join(kit, name))
    # The exercise calls' framework is tooling, like tools/.
    copy_tree(os.path.join(ROOT, 'tests', 'calls'), os.path.join(kit, 'tests', 'calls'))
    for chapter in kit_chapters:
        target = os.path.join(kit, chapter.path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        stubbed = [e for e in chapter.exercises if e.id in choice.stubbed]
        if edition == 'student' and stubbed:
            lines = markup.student_edition(chapter, only=stubbed, later=choice.later)
        else:
            lines = chapter.lines
        with open(target, 'w', encoding='utf-8') as f:
            f.write('\n'.join(lines))
        copy_tree(os.path.join(src, 'tests', 'ch' + chapter.number),
                  os.path.join(kit, 'tests', 'ch' + chapter.number))
        if edition == 'solution':
            copy_tree(os.path.join(src, 'tests', 'hidden', 'ch' + chapter.number),
                      os.path.join(kit, 'tests', 'hidden', 'ch' + chapter.number))
    with open(os.path.join(kit, 'README.md'), 'w', encoding='utf-8') as f:
        f.write(readme(edition, book, kit_chapters, choice))
    listed = [e.as_dict(hidden=edition == 'solution') for e in chosen]
    for e in listed:
        e['points'] = choice.points[e['id']]
    manifest = {
        'edition': edition,
        'chapters': [c.path for c in kit_chapters],
        'chosen_chapters': chosen_numbers,
        'exercises': listed,
        'points': sum(choice.points.values()),
    }
    manifest.update(choice.manifest())
    with open(os.path.join(kit, 'exercises.json'), 'w', encoding='utf-8') as f:
        json.dump(manifest, f, indent=2)
        f.write('\n')

    # The kit is built with its own Makefile, as its README tells the reader
    # to (`make`: the tangle, the library, the book; and the web edition), so
    # a kit whose `make` fails is never handed out. The two kits share the
    # web edition's compiled drawings.
    proc = make(kit, ['all', 'html', 'HTML_CACHE=' + os.path.join(out, 'html-cache')]
                if build_book else ['tangle'])
    if proc.returncode != 0:
        fail('%s kit: make failed in %s:\n%s%s' % (edition, kit, proc.stdout[-3000:],
                                                   proc.stderr[-3000:]))
    if build_book:
        shutil.copy2(os.path.join(kit, 'build', 'book.pdf'), os.path.join(kit, 'book.pdf'))
        shutil.copytree(os.path.join(kit, 'build', 'html'), os.path.join(kit, 'html'))
    shutil.rmtree(os.path.join(kit, 'build'), ignore_errors=True)
    if os.path.exists(os.path.join(kit, 'compile_commands.json')):
        os.remove(os.path.join(kit, 'compile_commands.json'))
    return kit, chosen


def tarball(out, edition):
    path = os.path.join(out, 'lrt-%s.tar.gz' % edition)
    kit = os.path.join(out, edition)
    with tarfile.open(path, 'w:gz') as tar:
        for top, dirs, files in os.walk(kit):
            dirs.sort()
            for name in sorted(files):
                full = os.path.join(top, name)
                tar.add(full, arcname=os.path.join('lrt-' + edition,
                                                   os.path.relpath(full, kit)))
    return path


def build(args):
    src = os.path.abspath(args.src)
    book = source_book(src)
    choice = Choice(book, args.chapters, args.plan and os.path.abspath(args.plan),
                    args.assignment)
    chosen_numbers = choice.numbers
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    for edition in EDITIONS:
        started = time.time()
        kit, chosen = write_kit(edition, src, out, book, choice, not args.no_book)
        path = tarball(out, edition)
        print('exercises: %s kit in %s, %s (%.0f s)' % (edition, shown(kit), shown(path),
                                                         time.time() - started))
    if choice.assignment:
        print('  assignment %s of %s' % (choice.assignment.name, shown(choice.plan)))
    for e in chosen:
        print('  %-8s %2g points  %s' % (e.id, choice.points[e.id], e.title))
    print('  %d exercises, %g points, chapters %s' % (
        len(chosen), sum(choice.points.values()), ' '.join(chosen_numbers)))
    later = sorted(choice.stubbed - set(choice.points))
    if later:
        print('  stubs also for the exercises of later assignments: %s' % ' '.join(later))
    stop_on(leaks(out, src), 'the student kit leaks solutions or hidden tests (%d findings)')
    print('exercises: leak check passed: no solution line or hidden test name in the '
          'student kit, its tangle, its book, its web pages or its tarball')


# ---------------------------------------------------------------------------
# The leak check

PDF_TEXT_FIXES = {'\u2019': "'", '\u2018': "'", '\u201c': '"', '\u201d': '"',
                  '\u2212': '-', '\u2217': '*', '\ufb01': 'fi', '\ufb02': 'fl',
                  '\u2013': '-', '\u2014': '-', '\u00a0': ' '}
WORD = r'(?<![A-Za-z0-9_])%s(?![A-Za-z0-9_])'


def compact(text):
    return re.sub(r'\s+', '', text)


def pdf_text(data):
    with tempfile.TemporaryDirectory() as tmp:
        pdf = os.path.join(tmp, 'book.pdf')
        with open(pdf, 'wb') as f:
            f.write(data)
        proc = subprocess.run(['pdftotext', '-enc', 'UTF-8', pdf, '-'],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            fail('pdftotext failed on a PDF of the kit: %s' % proc.stderr.strip())
    text = proc.stdout
    for bad, good in PDF_TEXT_FIXES.items():
        text = text.replace(bad, good)
    return text


def kit_files(out, edition):
    """(name, text) for every file of a kit and every member of its tarball;
    PDFs as their text."""
    kit = os.path.join(out, edition)
    for top, dirs, files in os.walk(kit):
        dirs.sort()
        for name in sorted(files):
            full = os.path.join(top, name)
            with open(full, 'rb') as f:
                data = f.read()
            yield os.path.relpath(full, out), data
    tar_path = os.path.join(out, 'lrt-%s.tar.gz' % edition)
    if os.path.exists(tar_path):
        with tarfile.open(tar_path) as tar:
            for member in tar.getmembers():
                if member.isfile():
                    yield ('%s:%s' % (os.path.relpath(tar_path, out), member.name),
                           tar.extractfile(member).read())


def decoded(name, data):
    if name.endswith('.pdf'):
        return pdf_text(data)
    text = data.decode('utf-8', errors='replace')
    if name.endswith('.html'):
        return html_text(text)
    return text


def html_text(text):
    """A web page's text as it reads: highlighted code is cut up by tags, so
    a solution line is whole only without them (a tag gives way to the line
    breaks inside it, so that line numbers stay those of the file)."""
    text = re.sub(r'<[^>]*>', lambda m: '\n' * m.group(0).count('\n'), text)
    return html.unescape(text)


# Two consecutive solution lines found together elsewhere are a leak even if
# each line alone is common: a later chapter that repeats the code, a test
# whose oracle is the solution, a sibling function written the same way.
MIN_PAIR_CHARS = 32


def leak_targets(src, manifest):
    """What must not be in the student kit: {compact text: (exercise,
    chapter path, line, text)} for the solution lines of the chosen exercises
    that appear nowhere else in the source, and for every pair of consecutive
    solution lines; and the hidden test names."""
    book = source_book(src)
    # The chosen exercises, and with a plan those of later assignments.
    chosen = {e['id'] for e in manifest['exercises']} | set(manifest.get('unreleased', []))
    kit_paths = set(manifest['chapters'])
    allowed = []
    solution = []    # (compact text, exercise, chapter path, line, text)
    pairs = []       # the same, for two consecutive lines
    for chapter in book.chapters:
        if chapter.path not in kit_paths:
            continue
        hidden_lines = set()
        for region in chapter.regions:
            if not (region.exercise and region.exercise.id in chosen):
                continue
            code = [(line, text) for line, text in region.solution
                    if compact(text) and not compact(text).startswith('//')]
            for line, text in region.solution:
                hidden_lines.add(line)
                solution.append((compact(text), region.exercise.id, chapter.path,
                                 line, text.strip()))
            for (line, a), (_, b) in zip(code, code[1:]):
                pairs.append((compact(a) + compact(b), region.exercise.id, chapter.path,
                              line, a.strip() + ' / ' + b.strip()))
        allowed.extend(text for n, text in enumerate(chapter.lines, 1)
                       if n not in hidden_lines)
    for path in sorted(glob.glob(os.path.join(src, 'tests', 'ch[0-9][0-9]', '*'))):
        with open(path, encoding='utf-8', errors='replace') as f:
            allowed.append(f.read())
    for name in ('book.md',):
        if os.path.exists(os.path.join(src, name)):
            with open(os.path.join(src, name), encoding='utf-8') as f:
                allowed.append(f.read())
    allowed_text = '\n'.join(allowed)
    allowed_compact = compact(allowed_text)
    lines = {}
    for key, exercise_id, path, line, text in solution:
        if len(key) < MIN_SOLUTION_CHARS or not re.search(r'[A-Za-z]', key):
            continue
        if key in allowed_compact:
            continue
        lines.setdefault(key, (exercise_id, path, line, text))
    for key, exercise_id, path, line, text in pairs:
        if len(key) >= MIN_PAIR_CHARS:
            lines.setdefault(key, (exercise_id, path, line, text))
    names = {}
    for path in sorted(glob.glob(os.path.join(src, 'tests', 'hidden', 'ch[0-9][0-9]'))):
        for suite, name, file, line in scan_tests(path):
            where = '%s:%d' % (os.path.relpath(file, src), line)
            names['%s.%s' % (suite, name)] = where
            for word in (suite, name):
                if not re.search(WORD % re.escape(word), allowed_text):
                    names.setdefault(word, where)
    return lines, names


def scan_tests(directory):
    found = []
    for path in sorted(glob.glob(os.path.join(directory, '*'))):
        with open(path, encoding='utf-8', errors='replace') as f:
            for n, text in enumerate(f, 1):
                match = markup.TEST_MACRO.match(text)
                if match:
                    found.append((match.group(2), match.group(3), path, n))
    return found


def leaks(out, src, edition='student'):
    manifest_path = os.path.join(out, edition, 'exercises.json')
    if not os.path.exists(manifest_path):
        fail('no kit in %s (run make exercises)' % os.path.join(out, edition))
    with open(manifest_path, encoding='utf-8') as f:
        manifest = json.load(f)
    lines, names = leak_targets(src, manifest)
    name_patterns = [(re.compile(WORD % re.escape(word)), word, where)
                     for word, where in names.items()]
    problems = []
    for name, data in kit_files(out, edition):
        if re.search(r'(^|[/:])(lrt-\w+/)?tests/hidden(/|$)', name):
            problems.append('leak: %s: a hidden test file' % name)
        text = decoded(name, data)
        text_compact = compact(text)
        file_lines = text.split('\n')
        for key, (exercise_id, path, line, solution_text) in lines.items():
            if key in text_compact:
                at = next((i for i, l in enumerate(file_lines, 1) if key in compact(l)), None)
                problems.append('leak: %s%s: solution of %s (%s:%d): %s' % (
                    name, ':%d' % at if at else ' (text)', exercise_id, path, line,
                    solution_text))
        for pattern, word, where in name_patterns:
            match = pattern.search(text)
            if match:
                at = text.count('\n', 0, match.start()) + 1
                problems.append('leak: %s:%d: hidden test name %s (%s)'
                                % (name, at, word, where))
    return problems


def leaks_command(args):
    problems = leaks(os.path.abspath(args.out), os.path.abspath(args.src), args.edition)
    stop_on(problems, '%%d leak(s) in the %s kit' % args.edition)
    print('exercises: no leaks in the %s kit' % args.edition)


# ---------------------------------------------------------------------------
# Validation

class Run:
    """One test's result in one binary: passed or not, and its failure text."""
    def __init__(self, label, suite, name, passed, output):
        self.label, self.suite, self.name = label, suite, name
        self.passed, self.output = passed, output

    @property
    def full_name(self):
        return '%s.%s' % (self.suite, self.name)


def gtest_json(binary, gtest_filter=None, timeout=TIME_LIMIT):
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, 'report.json')
        cmd = [binary, '--gtest_output=json:' + report]
        if gtest_filter:
            cmd.append('--gtest_filter=' + gtest_filter)
        env = clean_env()
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                                  env=env)
            output = proc.stdout + proc.stderr
        except subprocess.TimeoutExpired:
            return None, 'timed out after %d s' % timeout
        try:
            with open(report) as f:
                return json.load(f)['testsuites'], output
        except (OSError, ValueError, KeyError):
            return None, output


def run_binary(label, binary):
    suites, output = gtest_json(binary)
    if suites is None:
        # The binary died (a crash, an abort, a hang): run its tests one by one
        # so that each gets its own verdict.
        listing = subprocess.run([binary, '--gtest_list_tests'], capture_output=True,
                                 text=True, env=clean_env()).stdout
        names, suite = [], None
        for line in listing.splitlines():
            if not line.strip():
                continue
            if not line.startswith(' '):
                suite = line.split('#')[0].strip().rstrip('.')
            else:
                names.append((suite, line.split('#')[0].strip()))
        runs = []
        for suite, name in names:
            one, out = gtest_json(binary, '%s.%s' % (suite, name), TEST_TIME_LIMIT)
            passed = bool(one) and all(not t.get('failures') for s in one
                                       for t in s['testsuite'])
            runs.append(Run(label, suite, name, passed,
                            out if one is None else failure_text(one)))
        return runs
    runs = []
    for s in suites:
        for test in s['testsuite']:
            if test.get('result') == 'SKIPPED' or test.get('status') == 'NOTRUN':
                continue
            runs.append(Run(label, s['name'], test['name'], not test.get('failures'),
                            '\n'.join(f.get('failure', '') for f in
                                      test.get('failures', []))))
    return runs


def failure_text(suites):
    return '\n'.join(f.get('failure', '') for s in suites for t in s['testsuite']
                     for f in t.get('failures', []))


def build_and_run(kit, chapters, number, only, hidden, build_dir, jobs, run=True):
    """In directory kit, builds the code as of chapter `number` from the given
    chapter files, with the public tests of chapter `only` (of every chapter
    up to `number` if None) and the hidden tests from directory `hidden`, and
    runs them unless run is false. Returns (runs, errors)."""
    common = ['-f', 'tools/make/hidden.mk', 'CHAPTERS=' + ' '.join(chapters),
              'BUILD=' + build_dir, 'HIDDEN=' + hidden, 'ASOF=' + number] + \
             (['ONLY=' + only] if only else [])
    proc = make(kit, common + ['tangle'])
    if proc.returncode != 0:
        return [], ['as of chapter %s: the tangle failed:\n%s' % (number, proc.stderr)]
    proc = make(kit, common + ['-j%d' % jobs, 'lib', 'tests', 'hidden-tests'])
    if proc.returncode != 0:
        output = proc.stdout + proc.stderr
        first = [l for l in output.splitlines() if ': error' in l or 'Error' in l][:15]
        return [], ['as of chapter %s: the code or its tests do not compile (paths are '
                    'relative to %s):\n  %s' % (number, shown(kit), '\n  '.join(first))]
    runs = []
    if run:
        listing = make(kit, common + ['-s', 'list-tests', 'list-hidden-tests'])
        for item in listing.stdout.split():
            label, binary = item.split('=', 1)
            runs.extend(run_binary(label, os.path.join(kit, binary)))
    return runs, []


def read_bytes(path):
    with open(path, 'rb') as f:
        return f.read()


def judge(edition, runs, chosen, errors):
    """Checks each run against what the edition expects; returns the number of
    runs of chosen exercises' tests."""
    exercise_runs = 0
    for run in runs:
        exercise_id = markup.Book.suite_exercise(run.suite)
        if edition == 'solution' or exercise_id not in chosen:
            if not run.passed:
                errors.append('%s: %s %s fails%s:\n    %s' % (
                    edition, run.label, run.full_name, '' if edition == 'solution' else
                    ' (it belongs to no exercise of this set, so it must pass)',
                    run.output.strip().replace('\n', '\n    ')[:1500]))
        else:
            exercise_runs += 1
            if run.passed:
                errors.append('student: %s %s passes with the stub of %s: a stub must '
                              'fail every test of its exercise (does the test check '
                              'anything the stub does not?)' % (run.label, run.full_name,
                                                                exercise_id))
    return exercise_runs


def check_expected(edition, runs, exercise_list, errors):
    """Every test of every exercise ran; in the student edition, some failure
    of each exercise names it (the stub's message)."""
    seen = {}
    for run in runs:
        seen.setdefault(run.full_name, []).append(run)
    for e in exercise_list:
        expected = e['public_tests'] + e['hidden_tests']
        missing = sorted(set(expected) - set(seen))
        if missing:
            errors.append('%s: tests of %s never ran: %s' % (edition, e['id'],
                                                              ', '.join(missing)))
        failures = [r for name in expected for r in seen.get(name, []) if not r.passed]
        if edition == 'student' and failures and \
                not any(e['id'] in r.output for r in failures):
            errors.append('student: no failing test of %s names the exercise in its '
                          'output: a stub block should hold "// NOT IMPLEMENTED", which '
                          'becomes the throw that does' % e['id'])


def validate_solution(out, manifest, jobs):
    """Every public and hidden test passes: each chapter's as of that chapter,
    and every chapter's as of the last one."""
    kit = os.path.join(out, 'solution')
    chapters = manifest['chapters']
    runs, errors = [], []
    for chapter in chapters:
        number = markup.chapter_number(chapter)
        last = chapter == chapters[-1]
        r, e = build_and_run(kit, chapters, number, None if last else number,
                             'tests/hidden', os.path.join(out, 'validate', 'solution'), jobs)
        runs += r
        errors += ['solution: ' + x for x in e]
    judge('solution', runs, {}, errors)
    if not errors:
        check_expected('solution', runs, manifest['exercises'], errors)
    return runs, errors, ''


def validate_student(out, manifest, jobs):
    """The student kit compiles as of every chapter. For each chosen chapter N,
    the code as of N built as grading builds it (the student's chapter N, the
    reference text of the chapters before it) fails every test of chapter N's
    exercises, public and hidden, and passes chapter N's other tests."""
    kit = os.path.join(out, 'student')
    solution = os.path.join(out, 'solution')
    chapters = manifest['chapters']
    chosen = {e['id']: e for e in manifest['exercises']}
    # A plan's later assignments: stubs too, whose tests must fail as well.
    stubbed = dict(chosen, **{e: None for e in manifest.get('unreleased', [])})
    runs, errors = [], []
    hidden = os.path.join(solution, 'tests', 'hidden')
    # While the student's chapters are the solution's, so is the code: the
    # solution's validation covers it. At the first chosen chapter N, the kit
    # is the grading build of chapter N; after it, the kit is only compiled and
    # chapter N is tested in a build of its own.
    same_so_far = True
    for chapter in chapters:
        number = markup.chapter_number(chapter)
        same = read_bytes(os.path.join(kit, chapter)) == read_bytes(
            os.path.join(solution, chapter))
        graded = any(e['chapter'] == number for e in chosen.values())
        if same_so_far and same:
            continue
        r, e = build_and_run(kit, chapters, number, number, hidden,
                             os.path.join(out, 'validate', 'student'), jobs,
                             run=same_so_far and graded)
        runs += r
        errors += ['student: ' + x for x in e]
        if graded and not same_so_far:
            own = os.path.relpath(os.path.join(kit, chapter), solution)
            mixed = [c for c in chapters if markup.chapter_number(c) < number] + [own]
            r, e = build_and_run(solution, mixed, number, number, 'tests/hidden',
                                 os.path.join(out, 'validate', 'student-' + number), jobs)
            runs += r
            errors += ['student: ' + x for x in e]
        same_so_far = same_so_far and same
    exercise_runs = judge('student', runs, stubbed, errors)
    if not errors:
        check_expected('student', runs, manifest['exercises'], errors)
    return runs, errors, ', %d of them exercise tests that must fail' % exercise_runs


def validate_grading(out, manifest, jobs):
    """Grading, as tools/grading/grade.py does it, in the solution kit: for each chosen
    chapter, the book's chapter scores every point; and for each exercise, the
    chapter with that exercise alone stubbed (every other one solved) loses
    that exercise's points, every test of it failing, and keeps all others."""
    kit = os.path.join(out, 'solution')
    book = markup.load([os.path.join(kit, c) for c in manifest['chapters']], root=kit,
                          tests=False)
    chosen = {e['id']: e for e in manifest['exercises']}
    work = os.path.join(out, 'validate', 'grading')
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # One secret for all: verdicts of unchanged exercises are reused.
    seed = str(int.from_bytes(os.urandom(7), 'little'))
    runs, errors = [], []
    for chapter in book.chapters:
        mine = [e for e in chapter.exercises if e.id in chosen]
        if not mine:
            continue
        cases = [('solution', None)] + [('%s stubbed' % e.id, e) for e in mine]
        for label, stubbed in cases:
            name = re.sub(r'[^\w.-]', '_', '%s-%s' % (chapter.number, label))
            sub = os.path.join(work, 'submissions', name, 'chapters')
            os.makedirs(sub)
            lines = chapter.lines if stubbed is None else \
                markup.student_edition(chapter, only=stubbed)
            with open(os.path.join(sub, os.path.basename(chapter.path)), 'w',
                      encoding='utf-8') as f:
                f.write('\n'.join(lines))
            target = os.path.join(work, 'results', name)
            proc = subprocess.run([sys.executable, os.path.join(kit, 'tools', 'grading', 'grade.py'),
                                   '--root', kit, '--chapters', chapter.number,
                                   '--seed', seed, '--build-jobs', str(jobs),
                                   '--cache', os.path.join(out, 'validate', 'grade-cache'),
                                   '--out', target, '--quiet', os.path.dirname(sub)],
                                  capture_output=True, text=True, env=clean_env())
            try:
                with open(os.path.join(target, 'results.json'), encoding='utf-8') as f:
                    data = json.load(f)
            except (OSError, ValueError):
                errors.append('grading %s of chapter %s: no results (%s)' % (
                    label, chapter.number, (proc.stdout + proc.stderr)[-1500:]))
                continue
            for test in data['tests']:
                exercise_id, full = test['name'].split(' ', 1)
                status = test['tags'][0]
                lost = stubbed is not None and exercise_id == stubbed.id
                runs.append(Run('grading %s' % label, *full.split('.', 1),
                                passed=status == 'PASS', output=test['output']))
                if lost and status == 'PASS':
                    errors.append('grading with %s: %s passes with the stub: it does not '
                                  'reach the exercise\'s code through its exercise calls'
                                  % (label, full))
                elif not lost and status != 'PASS':
                    errors.append('grading %s of chapter %s: %s %s scores %s:\n    %s' % (
                        label, chapter.number, exercise_id, full, status,
                        test['output'].replace('\n', '\n    ')[:1500]))
            expected = sum(e.points for e in mine) - (stubbed.points if stubbed else 0)
            if abs(data['score'] - expected) > 1e-6:
                errors.append('grading %s of chapter %s scores %g, not %g' % (
                    label, chapter.number, data['score'], expected))
            if stubbed is not None and not any(
                    stubbed.id in t['output'] for t in data['tests']
                    if t['name'].startswith(stubbed.id + ' ')):
                errors.append('grading with %s: no failure names the exercise (the stub\'s '
                              'message)' % label)
    return runs, errors, ' (seed %s)' % seed


def validate(args):
    out = os.path.abspath(args.out)
    with open(os.path.join(out, 'solution', 'exercises.json'), encoding='utf-8') as f:
        manifest = json.load(f)
    errors = []
    for edition in args.edition or VALIDATIONS:
        if edition != 'solution' and errors:
            print('validate: %s not checked: fix the solution edition first' % edition)
            break
        started = time.time()
        runs, e, note = {'solution': validate_solution, 'student': validate_student,
                         'grading': validate_grading}[edition](out, manifest, args.jobs)
        passed = sum(1 for r in runs if r.passed)
        print('validate: %s: %d test runs, %d passed, %d failed%s (%.0f s)' % (
            edition + (' edition' if edition in EDITIONS else ''), len(runs), passed,
            len(runs) - passed, note, time.time() - started))
        errors += e
    stop_on(errors, 'validation failed (%d problems)')
    print('validate: the solutions pass every test; the stubs fail every test of their '
          'exercise (%d exercises) and only those, in the kits and in grading, one '
          'exercise stubbed at a time' % len(manifest['exercises']))


# ---------------------------------------------------------------------------
# Trying the kits as their readers do

def result_lines(output, kind):
    """runtests.py's 'FAILED: LABEL NAME' or 'SKIPPED: LABEL NAME: REASON'
    lines, as (label, name, reason)."""
    found = []
    for line in output.splitlines():
        if line.startswith(kind + ': '):
            label, _, rest = line[len(kind) + 2:].partition(' ')
            name, _, reason = rest.partition(': ')
            found.append((label, name, reason))
    return found


def kit_binary(kit, label):
    """The test binary that `make test` labelled asofNN/chMM (tools/make/asof.mk)."""
    asof = label.split('/')[0]
    chapters = sorted(glob.glob(os.path.join(kit, 'chapters', '[0-9][0-9]-*.md')))
    listing = make(kit, ['-s', '-f', 'tools/make/asof.mk', 'ASOF=' + asof[len('asof'):],
                         'CHAPTERS=' + ' '.join(os.path.relpath(c, kit) for c in chapters),
                         'BUILD=build', 'list-tests']).stdout
    for item in listing.split():
        if item.startswith(label + '='):
            return os.path.join(kit, item.split('=', 1)[1])
    return None


def same_as_source(out, src, manifest):
    """Problems if the solution kit's chapters or tests differ from the
    source's: then the source's own `make test` and `make validate-exercises`
    do not speak for them."""
    kit = os.path.join(out, 'solution')
    problems = []
    for top in manifest['chapters'] + ['tests']:
        for path in ([os.path.join(kit, top)] if top.endswith('.md') else
                     [os.path.join(d, f) for d, _, fs in os.walk(os.path.join(kit, top))
                      for f in fs]):
            rel = os.path.relpath(path, kit)
            origin = os.path.join(ROOT if rel.startswith(('tests/tools/', 'tests/calls/'))
                                  else src, rel)
            if not os.path.isfile(origin) or read_bytes(origin) != read_bytes(path):
                problems.append('solution: %s is not the source\'s %s' % (rel, origin))
    return problems


def try_student(out, manifest, make_args):
    """Runs `make test` with make_args in the student kit, as its reader
    would, and returns (summary, problems). A test may fail only because of
    the assignment's own stubs: a test of a chosen exercise, or a test whose
    failure names a chosen exercise's stub (a later chapter's test that uses
    that code); it may be skipped only by the stub of a later assignment's
    exercise (tests/calls/core.h); and each chosen exercise whose chapter's
    tests ran fails some test."""
    kit = os.path.join(out, 'student')
    proc = make(kit, ['test'] + make_args)
    output = proc.stdout + proc.stderr
    summary = ([l for l in proc.stdout.splitlines() if l.startswith('tests: ')] or
               ['no summary'])[-1]
    failed, skipped = result_lines(proc.stdout, 'FAILED'), result_lines(proc.stdout, 'SKIPPED')
    problems = []
    if not summary.startswith('tests: ') or summary.startswith('tests: 0 passed'):
        problems.append('student: make test %s ran no tests:\n%s' % (
            ' '.join(make_args), output[-3000:]))
    chosen = {e['id'] for e in manifest['exercises']}
    later = set(manifest.get('unreleased', []))
    for label, name, reason in skipped:
        match = re.match(r'Exercise (\S+) comes with a later assignment: ', reason)
        if not match or match.group(1) not in later:
            problems.append('student: %s %s is skipped (%s): only a later assignment\'s '
                            'stub may skip a test' % (label, name, reason))
    failed_exercises = set()
    for label, name, _ in failed:
        exercise_id = markup.Book.suite_exercise(name.split('.')[0])
        if exercise_id in chosen:
            failed_exercises.add(exercise_id)
            continue
        # Why did it fail? Its binary, run again for this test alone, says.
        binary = kit_binary(kit, label) if re.match(r'^asof\d+/ch\d+$', label) else None
        suites, text = gtest_json(binary, name) if binary else (None, output[-3000:])
        if suites is not None:
            text = failure_text(suites)
        names = set(re.findall(r'Exercise (\S+) is not done yet', text))
        if not names or not names <= chosen:
            problems.append('student: %s %s fails, and not only because of this '
                            'assignment\'s stubs:\n    %s' % (
                                label, name, text.strip().replace('\n', '\n    ')[:1500]))
    ran = set(re.findall(r'^asof\d+/ch(\d+) ', proc.stdout, re.M))
    for e in manifest['exercises']:
        if e['chapter'] in ran and e['id'] not in failed_exercises:
            problems.append('student: no test of %s fails: its stub is not reached'
                            % e['id'])
    return summary, problems


def try_command(args):
    out = os.path.abspath(args.out)
    with open(os.path.join(out, 'solution', 'exercises.json'), encoding='utf-8') as f:
        manifest = json.load(f)
    started = time.time()
    problems = same_as_source(out, os.path.abspath(args.src), manifest)
    summary, p = try_student(out, manifest, args.make_args)
    problems += p
    print('try: student kit: make test %s: %s (%.0f s)' % (
        ' '.join(args.make_args), summary, time.time() - started))
    stop_on(problems, 'the kits do not work as their READMEs say (%d problems)')
    print('try: in the student kit only the assignment\'s stubs fail tests, and only '
          'later assignments\' stubs skip them; the solution kit\'s chapters and tests '
          'are the source\'s, whose tests make test runs')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    sub = parser.add_subparsers(dest='command', required=True)
    p = sub.add_parser('build')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('--no-book', action='store_true',
                   help='build neither book.pdf nor the web pages (html/)')
    p.add_argument('--plan', help='a course plan (docs/course.md)')
    p.add_argument('--assignment', help='with --plan: the kits of this assignment')
    p.add_argument('chapters', nargs='*')
    p = sub.add_parser('leaks')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('--edition', default='student', choices=EDITIONS)
    p = sub.add_parser('try')
    p.add_argument('--out', required=True)
    p.add_argument('--src', default=ROOT)
    p.add_argument('make_args', nargs='*', metavar='MAKE_ARG',
                   help='for the kits\' make test, e.g. UPTO=last')
    p = sub.add_parser('validate')
    p.add_argument('--out', required=True)
    p.add_argument('--edition', action='append', choices=VALIDATIONS)
    p.add_argument('--jobs', type=int, default=os.cpu_count() or 1)
    args = parser.parse_args(argv)
    {'build': build, 'leaks': leaks_command, 'validate': validate,
     'try': try_command}[args.command](args)


if __name__ == '__main__':
    main()
