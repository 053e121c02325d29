"""Tests of the classroom grader (tools/grade.py, DESIGN.md section 7).

Deliberately bad submissions are made from chapters/02-geometry.md by text
edits, in a temporary directory, and graded as one batch (two workers, one
shared build cache, so each distinct tangle is compiled once); each test then
asserts the exact scores and statuses in that submission's results.json.
Misbehaviours share a submission when they sit in different exercises (a
segfault in one exercise, an abort in the next, an exception in the third),
since a test of one exercise never calls another exercise's code.

The expectations come from the book, not from the grader: the exercises and
their points from `tools/exercises.py list --json` (checked against the
exercise divs' own `points=`), and each exercise's tests from a scan of the
TEST() lines of tests/chNN/ and tests/hidden/chNN/. The batch grades every
chapter with exercises (`--chapters`, given explicitly), so the chapters
other than 2 are in max_score and their tests are NOT-RUN; adding exercises
to any chapter changes the numbers these tests expect, not the tests.

Cases: the solutions (a zip), the untouched student edition, a compile error
(also in a spliced chapter), segfault / abort / exception, infinite loop /
huge allocation / exit(0), fake "[  PASSED  ]" output + exit(0), a wrong
answer (its hidden tests' checks must not show), renamed, deleted and
duplicated exercise chunks, code changed outside the exercises (restored;
and with --allow-changes-outside-exercises), an archive with files that try
to replace tests plus unsafe members, an empty submission, the batch CSV,
and which chapters are graded (--chapters, a kit's exercises.json, the
default). Seven distinct codes are compiled; about 5 minutes on 2 cores.
"""
import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import unittest
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GRADE = os.path.join(ROOT, 'tools', 'grade.py')
CHAPTER = 'chapters/02-geometry.md'
F12 = 'Complete v1 to an orthonormal frame'
F13 = 'Transform n by the inverse transpose'
F14 = ('Compute the union of two boxes', 'Compute the intersection of two boxes')
TIME_LIMIT = 2
# What a student sees of a hidden test that failed a check (Hint aside).
HIDDEN_FAIL = '**FAIL** (hidden test)\n\n```\na hidden test failed (its checks are not shown)\n```'

# Read independently of tools/exercises.py, which the grader uses.
TEST_LINE = re.compile(r'^\s*(?:TEST|TEST_F|TEST_P)\s*\(\s*(\w+)\s*,\s*(\w+)\s*\)')
EXERCISE_SUITE = re.compile(r'^Ex(\d+)_(\d+)_\w+$')
EXERCISE_DIV = re.compile(r'^:{3,}\s*\{\.exercise\s+#(ex-\d+\.\d+)\s.*\bpoints=(\d+)')
CHAPTER_FILE = re.compile(r'^(\d\d)-.*\.md$')


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


def chapter_files():
    return sorted('chapters/' + f for f in os.listdir(os.path.join(ROOT, 'chapters'))
                  if CHAPTER_FILE.match(f))


def book_exercises():
    """{exercise id: its entry of `tools/exercises.py list --json`}."""
    out = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'exercises.py'),
                          'list', '--json'] + chapter_files(), cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    return {e['id']: e for e in json.loads(out)}


def div_points():
    """{exercise id: points} from the exercise divs of the chapters."""
    found = {}
    for path in chapter_files():
        for line in read(os.path.join(ROOT, path)).split('\n'):
            m = EXERCISE_DIV.match(line)
            if m:
                found[m.group(1)] = int(m.group(2))
    return found


def test_sources(number, hidden):
    d = os.path.join(ROOT, 'tests', 'hidden' if hidden else '', 'ch' + number)
    return sorted(os.path.join(d, f) for f in os.listdir(d)
                  if f.endswith(('.cpp', '.cc', '.h'))) if os.path.isdir(d) else []


def exercise_tests(numbers):
    """{exercise id: [(Suite.Name, hidden)]} from the TEST() lines of the test
    sources of the given chapters."""
    found = {}
    for number in numbers:
        for hidden in (False, True):
            for path in test_sources(number, hidden):
                for line in read(path).split('\n'):
                    m = TEST_LINE.match(line)
                    e = m and EXERCISE_SUITE.match(m.group(1))
                    if e:
                        ident = 'ex-%d.%d' % (int(e.group(1)), int(e.group(2)))
                        test = ('%s.%s' % m.groups(), hidden)
                        if test not in found.setdefault(ident, []):
                            found[ident].append(test)
    return found


def hidden_only_identifiers(numbers):
    """Identifiers of the hidden tests' code (comments and strings left out)
    that occur in no chapter, public test or test name: if one shows up in a
    grade, the grader has shown a hidden test's code or failure text."""
    code = ''
    for number in numbers:
        for path in test_sources(number, True):
            text = re.sub(r'"(?:[^"\\\n]|\\.)*"', '""', read(path))
            code += re.sub(r'//[^\n]*|/\*.*?\*/', '', text, flags=re.S)
    words = set(re.findall(r'\b[A-Za-z_]\w{4,}\b', code))
    public = ''.join(read(os.path.join(ROOT, p)) for p in chapter_files())
    for number in numbers:
        public += ''.join(read(p) for p in test_sources(number, False))
    names = set(re.findall(r'\b\w+\b', ' '.join(
        t for tests in exercise_tests(numbers).values() for t, _ in tests)))
    return sorted(w for w in words - names if not re.search(r'\b%s\b' % w, public))


def inject(text, fragment, code):
    """Puts code at the start of the solution region of <<fragment>>."""
    lines = text.split('\n')
    start = lines.index('<<%s>>=' % fragment)
    begin = lines.index('// BEGIN SOLUTION', start)
    lines[begin + 1:begin + 1] = code.split('\n')
    return '\n'.join(lines)


def line_of(text, needle):
    return text.split('\n').index(needle) + 1


def chunk_span(lines, fragment):
    start = lines.index('<<%s>>=' % fragment)
    end = start + 1
    while lines[end] != '@':
        end += 1
    return start, end


def run_grade(args, cwd=ROOT):
    return subprocess.run([sys.executable, GRADE] + args, cwd=cwd, capture_output=True,
                          text=True)


class GradeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # What the book says is to be graded, and what each test must find.
        cls.book = book_exercises()
        cls.points = {e: x['points'] for e, x in cls.book.items()}
        cls.chapters = sorted({x['chapter'] for x in cls.book.values()})
        cls.tests = exercise_tests(cls.chapters)
        cls.total = sum(cls.points.values())
        owner = {f: e for e, x in cls.book.items() for f in x['fragments']}
        cls.e12, cls.e13, cls.e14 = owner.get(F12), owner.get(F13), owner.get(F14[0])
        cls.ch2 = sorted(e for e, x in cls.book.items() if x['chapter'] == '02')
        cls.ch2_points = sum(cls.points[e] for e in cls.ch2)
        cls.hidden_words = hidden_only_identifiers(cls.chapters)

        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-test-')
        cls.subs = os.path.join(cls.tmp, 'submissions')
        cls.out = os.path.join(cls.tmp, 'out')
        cls.cache = os.path.join(cls.tmp, 'cache')
        os.makedirs(cls.subs)
        sol = read(os.path.join(ROOT, CHAPTER))
        cls.solution_text = sol
        student = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'exercises.py'),
                                  'student', CHAPTER], cwd=ROOT, capture_output=True,
                                 text=True, check=True).stdout
        both14 = lambda text, code: inject(inject(text, F14[0], code), F14[1], code)  # noqa
        cls.broken = inject(sol, F12, 'this is not C++;')
        crashes = inject(sol, F12, '{ volatile int *p = nullptr; *p = 1; }')
        crashes = inject(crashes, F13, '__builtin_abort();')
        crashes = both14(crashes, 'throw std::runtime_error("student bug");')
        hangs = inject(sol, F12, 'for (volatile unsigned i = 0;; i = i + 1) {}')
        hangs = inject(hangs, F13, '{ char *big = new char[1ul << 40]; big[0] = 1; '
                       'delete[] big; }')
        hangs = both14(hangs, '__builtin_exit(0);')
        fake = inject(sol, F12, '__builtin_printf("[       OK ] Ex2_12.All\\n'
                      '[  PASSED  ] 1 test.\\n");\n__builtin_exit(0);')
        # A frame that is not one: every check of the exercise fails.
        wrong = inject(sol, F12, '{ *v2 = v1; *v3 = v1; return; }')
        lines = sol.split('\n')
        renamed = sol.replace('<<%s>>' % F12, '<<My own frame>>')
        s, e = chunk_span(lines, F12)
        deleted = '\n'.join(lines[:s] + lines[e + 1:])
        s, e = chunk_span(lines, F14[0])
        duplicated = '\n'.join(lines[:e + 1] + [''] + lines[s:e + 1] + lines[e + 1:])
        cls.duplicate_line = e + 3
        # Outside the exercises: Inside() made to lie (restored by default).
        inside = 'return p.x >= b.pMin.x && p.x <= b.pMax.x && p.y >= b.pMin.y &&'
        assert inside in sol, 'the edit of Inside() no longer applies'
        changed = sol.replace(inside, 'return false && ' + inside[len('return '):], 1)
        cls.renamed_line = line_of(renamed, '<<My own frame>>=')
        cls.broken_line = line_of(cls.broken, 'this is not C++;')

        def put(name, text, where=CHAPTER):
            path = os.path.join(cls.subs, name, where)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, 'w', encoding='utf-8') as f:
                f.write(text)

        # The solutions, as a zip with the chapter in a folder of its own.
        with zipfile.ZipFile(os.path.join(cls.subs, 'solution.zip'), 'w') as z:
            z.writestr('lrt/chapters/02-geometry.md', sol)
            z.writestr('lrt/README.txt', 'my work')
        put('student', student, '02-geometry.md')        # no chapters/ folder
        put('compile_error', cls.broken)
        put('crashes', crashes)
        put('hangs', hangs)
        put('fake_pass', fake)
        put('wrong_answer', wrong)
        put('renamed', renamed)
        put('deleted', deleted)
        put('duplicated', duplicated)
        put('changed_outside', changed)
        # A compile error in a chapter that is spliced (code changed outside
        # the exercises): the error still names the student's line.
        spliced = inject(changed, F13, 'this is not C++ either;')
        cls.spliced_line = line_of(spliced, 'this is not C++ either;')
        put('compile_error_spliced', spliced)
        os.makedirs(os.path.join(cls.subs, 'empty'))
        # Files that try to replace tests, plus unsafe members.
        with tarfile.open(os.path.join(cls.subs, 'tamper.tar.gz'), 'w:gz') as t:
            def add(name, data, kind=tarfile.REGTYPE, link=''):
                info = tarfile.TarInfo(name)
                info.type, info.linkname = kind, link
                info.size = len(data) if kind == tarfile.REGTYPE else 0
                t.addfile(info, io.BytesIO(data) if kind == tarfile.REGTYPE else None)
            add('chapters/02-geometry.md', sol.encode())
            add('tests/ch02/test_x.cpp', b'#include <gtest/gtest.h>\nTEST(Ex2_12_X, Y) {}\n')
            add('tests/hidden/ch02/test_ex2_hidden.cpp', b'// nothing to see\n')
            add('../01-introduction.md', b'# escaped\n')
            add('chapters/01-introduction.md', b'', tarfile.SYMTYPE, '/etc/passwd')

        # What each submission must score: {exercise: (status, text in its
        # tests' output)} for chapter 2's exercises that do not pass.
        def every(status, text=None):
            return {e: (status, text % e if text and '%s' in text else text)
                    for e in cls.ch2}
        cls.expected = {
            'solution': {}, 'duplicated': {}, 'changed_outside': {}, 'tamper': {},
            'student': every('FAIL', 'Exercise %s is not done yet'),
            'compile_error': every('COMPILE-ERROR'),
            'compile_error_spliced': every('COMPILE-ERROR'),
            'empty': every('NOT-RUN', 'is not in the submission'),
            'crashes': {cls.e12: ('CRASH', 'SIGSEGV'), cls.e13: ('CRASH', 'SIGABRT'),
                        cls.e14: ('FAIL', 'student bug')},
            'hangs': {cls.e12: ('TIMEOUT', None), cls.e13: ('OOM', 'bad_alloc'),
                      cls.e14: ('FAIL', 'before reporting')},
            'fake_pass': {cls.e12: ('FAIL', 'exited (status 0) before reporting')},
            'wrong_answer': {cls.e12: ('FAIL', None)},
            'renamed': {cls.e12: ('FAIL', 'Exercise %s is not done yet' % cls.e12)},
            'deleted': {cls.e12: ('FAIL', 'Exercise %s is not done yet' % cls.e12)},
        }
        # Every chapter with exercises is graded, named explicitly so that a
        # kit's exercises.json (the default's source in a kit) changes nothing.
        cls.graded = ['--chapters', ' '.join(cls.chapters)]
        proc = subprocess.run([sys.executable, GRADE, '--batch', cls.subs, '--out', cls.out,
                               '--cache', cls.cache, '--time-limit', str(TIME_LIMIT),
                               '--memory-limit', '512'] + cls.graded,
                              cwd=ROOT, capture_output=True, text=True)
        cls.batch_output = proc.stdout + proc.stderr
        assert proc.returncode == 0, cls.batch_output

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def results(self, name, out=None):
        with open(os.path.join(out or self.out, name, 'results.json'), encoding='utf-8') as f:
            return json.load(f)

    def share(self, exercise):
        return round(self.points[exercise] / len(self.tests[exercise]), 4)

    def expected_score(self, expected):
        return sum(self.points[e] for e in self.ch2 if e not in expected)

    def assertExercise(self, data, exercise, status, contains=None):
        tests = [t for t in data['tests'] if t['name'].startswith(exercise + ' ')]
        self.assertEqual(sorted(t['name'] for t in tests),
                         sorted('%s %s' % (exercise, name) for name, _ in self.tests[exercise]))
        hidden = {name for name, h in self.tests[exercise] if h}
        for t in tests:
            self.assertEqual(t['tags'], [status], t)
            self.assertEqual(t['status'], 'passed' if status == 'PASS' else 'failed')
            self.assertAlmostEqual(t['max_score'], self.share(exercise), places=4)
            self.assertAlmostEqual(t['score'], self.share(exercise) if status == 'PASS' else 0,
                                   places=4)
            self.assertEqual(t['visibility'], 'after_published'
                             if t['name'].split()[1] in hidden else 'visible', t)
            self.assertIn('**%s**' % status, t['output'])
            if contains:
                self.assertIn(contains, t['output'], t)

    def assertGraded(self, data, expected, max_score=None):
        """Chapter 2's exercises as expected (the rest pass), the other
        chapters' exercises NOT-RUN, every test of the graded chapters listed
        once, and the points added up."""
        self.assertEqual(sorted(t['name'] for t in data['tests']),
                         sorted('%s %s' % (e, name) for e in self.tests
                                for name, _ in self.tests[e]))
        for e in self.ch2:
            self.assertExercise(data, e, *expected.get(e, ('PASS', None)))
        for e in self.tests:
            if e not in self.ch2:
                self.assertExercise(data, e, 'NOT-RUN', 'is not in the submission')
        score = self.expected_score(expected)
        self.assertAlmostEqual(data['score'], score, places=3)
        self.assertAlmostEqual(sum(t['score'] for t in data['tests']), score, places=2)
        self.assertEqual(data['max_score'], self.total if max_score is None else max_score)
        got = {x['exercise']: (x['points'], x['max_points'])
               for x in data['extra_data']['exercises']}
        self.assertEqual(set(got), set(self.tests))
        for e, (points, max_points) in got.items():
            self.assertEqual(max_points, self.points[e])
            self.assertAlmostEqual(points, self.points[e] if e in self.ch2 and
                                   e not in expected else 0, places=3)

    def assertSubmission(self, name):
        data = self.results(name)
        self.assertGraded(data, self.expected[name])
        return data

    def test_expectations_match_the_book(self):
        # The oracle itself: the listing's points are the divs', its tests are
        # those the test sources hold, and chapter 2's exercises are the
        # three whose fragments the submissions edit.
        self.assertEqual(self.points, div_points())
        self.assertEqual(set(self.tests), set(self.book))
        for e, x in self.book.items():
            self.assertEqual(sorted(n for n, h in self.tests[e] if not h),
                             sorted(x['public_tests']), e)
            self.assertEqual(sorted(n for n, h in self.tests[e] if h),
                             sorted(x['hidden_tests']), e)
            self.assertTrue(x['public_tests'] and x['hidden_tests'], e)
        edited = {self.e12, self.e13, self.e14}
        self.assertEqual(len(edited), 3)
        self.assertLessEqual(edited, set(self.ch2))
        self.assertTrue(self.hidden_words)

    def test_solution_full_marks(self):
        data = self.assertSubmission('solution')
        self.assertAlmostEqual(data['score'], self.ch2_points, places=3)
        self.assertEqual(data['stdout_visibility'], 'hidden')
        hidden = {'%s %s' % (e, n) for e in self.tests for n, h in self.tests[e] if h}
        self.assertEqual({t['name'] for t in data['tests']
                          if t['visibility'] == 'after_published'}, hidden)
        self.assertIn('ignored `lrt/README.txt`', data['output'])
        junit = read(os.path.join(self.out, 'solution', 'junit.xml'))
        count = sum(len(tests) for tests in self.tests.values())
        self.assertEqual(junit.count('<testcase '), count)
        self.assertNotIn('<failure', junit)
        self.assertEqual(junit.count('<skipped '), count - sum(
            len(self.tests[e]) for e in self.ch2))
        table = read(os.path.join(self.out, 'solution', 'results.txt'))
        self.assertIn('total %.2f / %d' % (self.ch2_points, self.total), table)

    def test_student_edition_zero(self):
        self.assertEqual(self.assertSubmission('student')['score'], 0)

    def test_compile_error(self):
        data = self.assertSubmission('compile_error')
        self.assertIn('chapters/02-geometry.md:%d' % self.broken_line, data['output'])

    def test_compile_error_after_splice(self):
        data = self.assertSubmission('compile_error_spliced')
        self.assertIn('chapters/02-geometry.md:%d' % self.spliced_line, data['output'])
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])

    def test_crash_abort_exception(self):
        self.assertSubmission('crashes')

    def test_timeout_oom_exit(self):
        self.assertSubmission('hangs')

    def test_fake_gtest_output_counts_for_nothing(self):
        data = self.assertSubmission('fake_pass')
        self.assertAlmostEqual(data['score'], self.ch2_points - self.points[self.e12],
                               places=3)

    def test_wrong_answer_shows_public_failures_and_hides_hidden_ones(self):
        data = self.assertSubmission('wrong_answer')
        public = [t for t in data['tests'] if t['name'].startswith(self.e12 + ' ') and
                  t['visibility'] == 'visible']
        hidden = [t for t in data['tests'] if t['name'].startswith(self.e12 + ' ') and
                  t['visibility'] == 'after_published']
        self.assertTrue(public and hidden)
        for t in public:     # the check that failed, where it is
            self.assertRegex(t['output'], r'tests/ch02/\w+\.cpp:\d+')
        hint = 'Hint: ' + self.hint(self.e12)
        for t in hidden:     # that it failed, and the hint; nothing of the test
            self.assertEqual(t['output'], HIDDEN_FAIL + '\n\n' + hint)
        for where in ('junit.xml', 'results.txt'):
            text = read(os.path.join(self.out, 'wrong_answer', where))
            self.assertNotIn('hidden/ch02', text)
            self.assertIn('its checks are not shown', text)

    def hint(self, exercise):
        lines = self.solution_text.split('\n')
        start = [n for n, l in enumerate(lines) if '#%s ' % exercise in l][0]
        begin = lines.index('::: hint', start)
        end = lines.index(':::', begin)
        return ' '.join(l.strip() for l in lines[begin + 1:end] if l.strip())

    def test_no_grade_shows_hidden_test_code(self):
        for name in self.expected:
            for where in ('results.json', 'junit.xml', 'results.txt'):
                text = read(os.path.join(self.out, name, where))
                for word in self.hidden_words:
                    self.assertNotRegex(text, r'\b%s\b' % word, '%s/%s' % (name, where))

    def test_renamed_chunk(self):
        data = self.assertSubmission('renamed')
        self.assertIn('chapters/02-geometry.md:%d: exercise chunk <<%s>> (%s) was '
                      'renamed to <<My own frame>>' % (self.renamed_line, F12, self.e12),
                      data['output'])

    def test_deleted_chunk(self):
        data = self.assertSubmission('deleted')
        self.assertIn('exercise chunk <<%s>> (%s) was deleted' % (F12, self.e12),
                      data['output'])

    def test_duplicated_chunk(self):
        data = self.assertSubmission('duplicated')
        self.assertIn('chapters/02-geometry.md:%d: exercise chunk <<%s>> (%s) is '
                      'defined 2 times' % (self.duplicate_line, F14[0], self.e14),
                      data['output'])

    def test_change_outside_exercises_restored(self):
        data = self.assertSubmission('changed_outside')
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])
        self.assertIn('the code of <<Geometry Inline Functions>> differs', data['output'])

    def test_tampering_files_ignored(self):
        data = self.assertSubmission('tamper')
        for name in ('tests/ch02/test_x.cpp', 'tests/hidden/ch02/test_ex2_hidden.cpp'):
            self.assertIn('ignored `%s`: not a chapter file' % name, data['output'])
        self.assertIn('ignored `../01-introduction.md`: unsafe path', data['output'])
        self.assertIn('ignored `chapters/01-introduction.md`: not a regular file',
                      data['output'])
        names = [t['name'] for t in data['tests']]
        self.assertNotIn('Ex2_12_X.Y', ' '.join(names))

    def test_empty_submission(self):
        data = self.assertSubmission('empty')
        self.assertIn('No chapter file found', data['output'])

    def test_batch_csv(self):
        with open(os.path.join(self.out, 'grades.csv')) as f:
            rows = list(csv.DictReader(f))
        totals, seen = {}, {}
        for row in rows:
            totals[row['student']] = totals.get(row['student'], 0) + float(row['points'])
            seen.setdefault(row['student'], []).append(row['exercise'])
            self.assertEqual(int(row['max_points']), self.points[row['exercise']], row)
            self.assertEqual(row['chapter'], self.book[row['exercise']]['chapter'], row)
        expected = {name: self.expected_score(e) for name, e in self.expected.items()}
        self.assertEqual({k: round(v, 3) for k, v in totals.items()}, expected)
        for student, exercises in seen.items():
            self.assertEqual(sorted(exercises), sorted(self.points), student)
        self.assertIn('graded %d submissions' % len(expected), self.batch_output)

    # -- Which chapters are graded ------------------------------------------

    def grade_one(self, name, args, root=None):
        out = tempfile.mkdtemp(dir=self.tmp)
        proc = run_grade([os.path.join(self.subs, name), '--out', out, '--cache', self.cache,
                          '--time-limit', str(TIME_LIMIT), '--quiet'] + args +
                         (['--root', root] if root else []))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        return json.loads(read(os.path.join(out, 'results.json')))

    def assertOnly(self, data, chapters):
        """data grades exactly the exercises of chapters (nothing else listed)."""
        exercises = sorted(e for e in self.tests if self.book[e]['chapter'] in chapters)
        self.assertEqual(sorted(t['name'] for t in data['tests']),
                         sorted('%s %s' % (e, n) for e in exercises for n, _ in self.tests[e]))
        self.assertEqual(data['max_score'], sum(self.points[e] for e in exercises))
        self.assertEqual(sorted(x['exercise'] for x in data['extra_data']['exercises']),
                         exercises)

    def test_chapters_option_grades_only_those(self):
        data = self.grade_one('solution.zip', ['--chapters', '2'])
        self.assertOnly(data, ['02'])
        self.assertAlmostEqual(data['score'], self.ch2_points, places=3)
        for e in self.ch2:
            self.assertExercise(data, e, 'PASS')

    def test_chapter_outside_the_assignment_is_left_alone(self):
        others = [c for c in self.chapters if c != '02']
        if not others:
            self.skipTest('no chapter but 2 has exercises')
        data = self.grade_one('solution.zip', ['--chapters', others[0]])
        self.assertOnly(data, [others[0]])
        self.assertEqual(data['score'], 0)
        self.assertIn('`lrt/chapters/02-geometry.md`: not graded in this assignment',
                      data['output'])
        self.assertTrue(all(t['tags'] == ['NOT-RUN'] for t in data['tests']))

    def test_chapters_option_rejects_what_it_cannot_grade(self):
        cases = [('99', 'there is no chapter 99'), ('two', 'names chapters by number')]
        numbers = [os.path.basename(p)[:2] for p in chapter_files()]
        cases += [(n, 'chapter %s has no exercises' % n) for n in numbers
                  if n not in self.chapters][:1]
        for chapters, message in cases:
            proc = run_grade([os.path.join(self.subs, 'empty'), '--out',
                              os.path.join(self.tmp, 'rejected'), '--chapters', chapters,
                              '--quiet'])
            self.assertNotEqual(proc.returncode, 0, chapters)
            self.assertIn(message, proc.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.tmp, 'rejected')))

    def kit(self, chosen):
        """A book that is a kit built for the chapters chosen: this book's
        chapters, tests and tools, and an exercises.json."""
        root = tempfile.mkdtemp(dir=self.tmp)
        for name in ('chapters', 'tests', 'tools'):
            os.symlink(os.path.join(ROOT, name), os.path.join(root, name))
        with open(os.path.join(root, 'exercises.json'), 'w') as f:
            json.dump({'edition': 'solution', 'chosen_chapters': chosen}, f)
        return root

    def test_kit_grades_the_chapters_it_was_built_for(self):
        # A kit for chapters 1 and 2: chapter 1 has no exercises.
        data = self.grade_one('empty', [], root=self.kit(['01', '02']))
        self.assertOnly(data, ['02'])
        others = [c for c in self.chapters if c != '02']
        if others:
            data = self.grade_one('empty', [], root=self.kit(others[-1:]))
            self.assertOnly(data, others[-1:])
            # --chapters wins over the kit's choice.
            data = self.grade_one('empty', ['--chapters', '02'], root=self.kit(others[-1:]))
            self.assertOnly(data, ['02'])

    def test_default_grades_every_chapter_with_exercises(self):
        data = self.grade_one('empty', [])
        manifest = os.path.join(ROOT, 'exercises.json')
        if os.path.exists(manifest):   # this book is a kit
            chosen = json.loads(read(manifest))['chosen_chapters']
            self.assertOnly(data, [c for c in self.chapters if c in chosen])
        else:
            self.assertOnly(data, self.chapters)

    # -- --allow-changes-outside-exercises ----------------------------------

    def grade_allowing_changes(self, name):
        return self.grade_one(name, self.graded + ['--allow-changes-outside-exercises'])

    def test_allow_changes_keeps_a_consistent_rename(self):
        # Definition and use renamed together: the student's code works, and
        # with the flag it is graded as written (the same code as the book's).
        data = self.grade_allowing_changes('renamed')
        self.assertGraded(data, {})
        self.assertIn('allowed; graded with your code', data['output'])
        self.assertIn('was renamed to <<My own frame>>', data['output'])

    def test_allow_changes_grades_the_students_code(self):
        # With the flag, a deleted exercise chunk is the student's text as
        # written: the tangle fails, and the chapter scores 0.
        data = self.grade_allowing_changes('deleted')
        self.assertGraded(data, self.expected['compile_error'])
        self.assertIn('allowed; graded with your code', data['output'])


if __name__ == '__main__':
    unittest.main()
