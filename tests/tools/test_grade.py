"""Tests of the classroom grader (tools/grade.py, DESIGN.md section 7).

Deliberately bad submissions are made from chapters/02-geometry.md by text
edits, in a temporary directory, and graded as one batch (two workers, one
shared build cache, so each distinct tangle is compiled once); each test then
asserts the exact scores and statuses in that submission's results.json.
Misbehaviours share a submission when they sit in different exercises (a
segfault in ex-2.12, an abort in ex-2.13, an exception in ex-2.14), since a
test of one exercise never calls another exercise's code.

Cases: the solutions (a zip), the untouched student edition, a compile error
(also in a spliced chapter), segfault / abort / exception, infinite loop /
huge allocation / exit(0), fake "[  PASSED  ]" output + exit(0), renamed,
deleted and duplicated exercise chunks, code changed outside the exercises
(restored; and with --allow-changes-outside-exercises), an archive with files
that try to replace tests plus unsafe members, an empty submission, and the
batch CSV. Six distinct codes are compiled; about 4 minutes on 2 cores.
"""
import csv
import io
import json
import os
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
TESTS = {'ex-2.12': 4, 'ex-2.13': 9, 'ex-2.14': 9}
POINTS = {'ex-2.12': 3, 'ex-2.13': 3, 'ex-2.14': 4}
TIME_LIMIT = 2


def read(path):
    with open(path, encoding='utf-8') as f:
        return f.read()


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


class GradeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
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
        proc = subprocess.run([sys.executable, GRADE, '--batch', cls.subs, '--out', cls.out,
                               '--cache', cls.cache, '--time-limit', str(TIME_LIMIT),
                               '--memory-limit', '512'],
                              cwd=ROOT, capture_output=True, text=True)
        cls.batch_output = proc.stdout + proc.stderr
        assert proc.returncode == 0, cls.batch_output

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def results(self, name, out=None):
        with open(os.path.join(out or self.out, name, 'results.json'), encoding='utf-8') as f:
            return json.load(f)

    def statuses(self, data):
        """{exercise: [status word per test]} from the tests' tags."""
        found = {}
        for test in data['tests']:
            found.setdefault(test['name'].split()[0], []).append(test['tags'][0])
        return found

    def assertExercise(self, data, exercise, status, contains=None):
        tests = [t for t in data['tests'] if t['name'].startswith(exercise + ' ')]
        self.assertEqual(len(tests), TESTS[exercise])
        for t in tests:
            self.assertEqual(t['tags'], [status], t)
            self.assertEqual(t['status'], 'passed' if status == 'PASS' else 'failed')
            self.assertAlmostEqual(t['score'], round(POINTS[exercise] / TESTS[exercise], 4)
                                   if status == 'PASS' else 0)
            self.assertIn('**%s**' % status, t['output'])
            if contains:
                self.assertIn(contains, t['output'], t)

    def assertScore(self, data, score):
        self.assertAlmostEqual(data['score'], score, places=3)
        self.assertEqual(data['max_score'], 10)

    def test_solution_full_marks(self):
        data = self.results('solution')
        self.assertScore(data, 10)
        for e in TESTS:
            self.assertExercise(data, e, 'PASS')
        self.assertEqual(data['stdout_visibility'], 'hidden')
        hidden = [t for t in data['tests'] if 'Hidden.' in t['name']]
        self.assertEqual(len(hidden), 8)
        self.assertTrue(all(t['visibility'] == 'after_published' for t in hidden))
        self.assertTrue(all(t['visibility'] == 'visible' for t in data['tests']
                            if t not in hidden))
        self.assertIn('ignored `lrt/README.txt`', data['output'])
        junit = read(os.path.join(self.out, 'solution', 'junit.xml'))
        self.assertEqual(junit.count('<testcase '), 22)
        self.assertNotIn('<failure', junit)
        table = read(os.path.join(self.out, 'solution', 'results.txt'))
        self.assertIn('total 10.00 / 10', table)

    def test_student_edition_zero(self):
        data = self.results('student')
        self.assertScore(data, 0)
        for e in TESTS:
            self.assertExercise(data, e, 'FAIL', 'Exercise %s is not done yet' % e)

    def test_compile_error(self):
        data = self.results('compile_error')
        self.assertScore(data, 0)
        for e in TESTS:
            self.assertExercise(data, e, 'COMPILE-ERROR')
        self.assertIn('chapters/02-geometry.md:%d' % self.broken_line, data['output'])

    def test_compile_error_after_splice(self):
        data = self.results('compile_error_spliced')
        self.assertScore(data, 0)
        for e in TESTS:
            self.assertExercise(data, e, 'COMPILE-ERROR')
        self.assertIn('chapters/02-geometry.md:%d' % self.spliced_line, data['output'])
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])

    def test_crash_abort_exception(self):
        data = self.results('crashes')
        self.assertScore(data, 0)
        self.assertExercise(data, 'ex-2.12', 'CRASH', 'SIGSEGV')
        self.assertExercise(data, 'ex-2.13', 'CRASH', 'SIGABRT')
        self.assertExercise(data, 'ex-2.14', 'FAIL', 'student bug')

    def test_timeout_oom_exit(self):
        data = self.results('hangs')
        self.assertScore(data, 0)
        self.assertExercise(data, 'ex-2.12', 'TIMEOUT')
        self.assertExercise(data, 'ex-2.13', 'OOM', 'bad_alloc')
        self.assertExercise(data, 'ex-2.14', 'FAIL', 'before reporting')

    def test_fake_gtest_output_counts_for_nothing(self):
        data = self.results('fake_pass')
        self.assertScore(data, 7)
        self.assertExercise(data, 'ex-2.12', 'FAIL', 'exited (status 0) before reporting')
        self.assertExercise(data, 'ex-2.13', 'PASS')
        self.assertExercise(data, 'ex-2.14', 'PASS')

    def test_renamed_chunk(self):
        data = self.results('renamed')
        self.assertScore(data, 7)
        self.assertExercise(data, 'ex-2.12', 'FAIL', 'Exercise ex-2.12 is not done yet')
        self.assertIn('chapters/02-geometry.md:%d: exercise chunk <<%s>> (ex-2.12) was '
                      'renamed to <<My own frame>>' % (self.renamed_line, F12), data['output'])

    def test_deleted_chunk(self):
        data = self.results('deleted')
        self.assertScore(data, 7)
        self.assertExercise(data, 'ex-2.12', 'FAIL', 'Exercise ex-2.12 is not done yet')
        self.assertIn('exercise chunk <<%s>> (ex-2.12) was deleted' % F12, data['output'])

    def test_duplicated_chunk(self):
        data = self.results('duplicated')
        self.assertScore(data, 10)
        self.assertIn('chapters/02-geometry.md:%d: exercise chunk <<%s>> (ex-2.14) is '
                      'defined 2 times' % (self.duplicate_line, F14[0]), data['output'])

    def test_change_outside_exercises_restored(self):
        data = self.results('changed_outside')
        self.assertScore(data, 10)
        self.assertIn('**Warning**: code outside the exercises was changed', data['output'])
        self.assertIn('the code of <<Geometry Inline Functions>> differs', data['output'])

    def test_tampering_files_ignored(self):
        data = self.results('tamper')
        self.assertScore(data, 10)
        for name in ('tests/ch02/test_x.cpp', 'tests/hidden/ch02/test_ex2_hidden.cpp'):
            self.assertIn('ignored `%s`: not a chapter file' % name, data['output'])
        self.assertIn('ignored `../01-introduction.md`: unsafe path', data['output'])
        self.assertIn('ignored `chapters/01-introduction.md`: not a regular file',
                      data['output'])
        names = [t['name'] for t in data['tests']]
        self.assertNotIn('Ex2_12_X.Y', ' '.join(names))

    def test_empty_submission(self):
        data = self.results('empty')
        self.assertScore(data, 0)
        for e in TESTS:
            self.assertExercise(data, e, 'NOT-RUN')
        self.assertIn('No chapter file found', data['output'])

    def test_batch_csv(self):
        with open(os.path.join(self.out, 'grades.csv')) as f:
            rows = list(csv.DictReader(f))
        totals = {}
        for row in rows:
            totals[row['student']] = totals.get(row['student'], 0) + float(row['points'])
        expected = {'solution': 10, 'student': 0, 'compile_error': 0, 'crashes': 0,
                    'hangs': 0, 'fake_pass': 7, 'renamed': 7, 'deleted': 7,
                    'duplicated': 10, 'changed_outside': 10, 'empty': 0, 'tamper': 10,
                    'compile_error_spliced': 0}
        self.assertEqual({k: round(v, 3) for k, v in totals.items()}, expected)
        self.assertEqual(len(rows), 3 * len(expected))
        self.assertIn('graded 13 submissions', self.batch_output)

    def grade_allowing_changes(self, name):
        out = os.path.join(self.tmp, 'allow-' + name)
        proc = subprocess.run([sys.executable, GRADE, os.path.join(self.subs, name),
                               '--out', out, '--cache', self.cache,
                               '--allow-changes-outside-exercises', '--quiet'],
                              cwd=ROOT, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(os.path.join(out, 'results.json')) as f:
            return json.load(f)

    def test_allow_changes_keeps_a_consistent_rename(self):
        # Definition and use renamed together: the student's code works, and
        # with the flag it is graded as written (the same code as the book's).
        data = self.grade_allowing_changes('renamed')
        self.assertScore(data, 10)
        self.assertIn('allowed; graded with your code', data['output'])
        self.assertIn('was renamed to <<My own frame>>', data['output'])

    def test_allow_changes_grades_the_students_code(self):
        # With the flag, a deleted exercise chunk is the student's text as
        # written: the tangle fails, and the chapter scores 0.
        data = self.grade_allowing_changes('deleted')
        self.assertScore(data, 0)
        for e in TESTS:
            self.assertExercise(data, e, 'COMPILE-ERROR')
        self.assertIn('allowed; graded with your code', data['output'])


if __name__ == '__main__':
    unittest.main()
