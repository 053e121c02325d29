"""Tests of the Gradescope autograder that `make gradescope` writes
(tools/grading/gradescope.py, gradescope/, docs/grading.md).

The zip is built for assignment "slabs" of the example course plan
(docs/course-example.toml: ex-5.9 and ex-5.11, 4 and 6 points, where the
chapter gives 2 and 3), unpacked into a fresh directory, and that directory is
mounted at /autograder in a bubblewrap sandbox that otherwise shows this
machine as it is, as Gradescope's container would: setup.sh runs there (its
package step finds everything installed; its cache warm-up grades the book's
chapter), then run_autograder, copied to /autograder/run_autograder as
Gradescope copies it, grades /autograder/submission into
/autograder/results/results.json, once with the book's chapter 5 and once
with its student edition. The expectations come from the plan file and the
test sources, read here on their own.
"""
import json
import os
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import tomllib
import unittest
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PLAN = os.path.join(ROOT, 'docs', 'course-example.toml')
ASSIGNMENT = 'slabs'
CHAPTER = 'chapters/05-slab-test.md'
TEST_LINE = re.compile(r'^\s*EXERCISE_TEST\s*\(\s*(Ex(\d+)_(\d+)_\w*)\s*,\s*(\w+)\s*\)')


def bwrap_usable():
    return os.geteuid() == 0 and shutil.which('bwrap') is not None


def tests_of(exercise):
    """{Suite.Name: hidden} of an exercise, from the test sources."""
    chapter, k = exercise[len('ex-'):].split('.')
    found = {}
    for hidden in (False, True):
        d = os.path.join(ROOT, 'tests', 'hidden' if hidden else '', 'ch%02d' % int(chapter))
        for name in sorted(os.listdir(d)):
            with open(os.path.join(d, name), encoding='utf-8') as f:
                for line in f:
                    m = TEST_LINE.match(line)
                    if m and (m.group(2), m.group(3)) == (chapter, k):
                        found['%s.%s' % (m.group(1), m.group(4))] = hidden
    return found


@unittest.skipUnless(bwrap_usable(), 'needs root and bubblewrap to lay out /autograder')
class GradescopeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with open(PLAN, 'rb') as f:
            plan = tomllib.load(f)
        cls.assignment = [a for a in plan['assignment'] if a['name'] == ASSIGNMENT][0]
        cls.tmp = tempfile.mkdtemp(prefix='lrt-gradescope-test-')
        cls.zip = os.path.join(cls.tmp, 'autograder.zip')
        proc = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'grading', 'gradescope.py'),
                               '--out', cls.zip, '--plan', PLAN, '--assignment', ASSIGNMENT,
                               '--', '--time-limit', '5'], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout + proc.stderr
        # Gradescope's layout: the zip unpacked in /autograder/source.
        cls.autograder = os.path.join(cls.tmp, 'autograder')
        source = os.path.join(cls.autograder, 'source')
        with zipfile.ZipFile(cls.zip) as z:
            cls.names = z.namelist()
            for info in z.infolist():
                z.extract(info, source)
                mode = (info.external_attr >> 16) & 0o777
                if mode:
                    os.chmod(os.path.join(source, info.filename), mode)
        cls.setup = cls.sandboxed(['bash', '/autograder/source/setup.sh'])
        shutil.copy(os.path.join(source, 'run_autograder'),
                    os.path.join(cls.autograder, 'run_autograder'))
        with open(os.path.join(ROOT, CHAPTER), encoding='utf-8') as f:
            solution = f.read()
        student = subprocess.run([sys.executable, os.path.join(ROOT, 'tools', 'exercises', 'markup.py'),
                                  'student', CHAPTER], cwd=ROOT, capture_output=True,
                                 text=True, check=True).stdout
        cls.solution = cls.grade({'chapters/05-slab-test.md': solution})
        cls.stub = cls.grade({'05-slab-test.md': student}, GRADE_FLAGS='--seed 4242')

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def sandboxed(cls, argv, **env):
        """Runs argv with cls.autograder mounted at /autograder and the rest
        of this machine as it is (its /tmp private)."""
        args = ['bwrap', '--die-with-parent', '--bind', '/proc', '/proc',
                '--dev-bind', '/dev', '/dev', '--tmpfs', '/tmp',
                '--bind', cls.autograder, '/autograder', '--chdir', '/']
        for name in sorted(os.listdir('/')):
            path = '/' + name
            if name in ('proc', 'dev', 'tmp', 'autograder'):
                continue
            if os.path.islink(path):
                args += ['--symlink', os.readlink(path), path]
            elif os.path.isdir(path):
                args += ['--bind', path, path]
        environment = {k: v for k, v in os.environ.items()
                       if not k.startswith(('MAKE', 'GRADE_'))}
        environment.update(env)
        return subprocess.run(args + argv, capture_output=True, text=True, env=environment)

    @classmethod
    def grade(cls, files, **env):
        """Puts files into /autograder/submission, runs run_autograder and
        returns (its process, results.json)."""
        for d in ('submission', 'results'):
            shutil.rmtree(os.path.join(cls.autograder, d), ignore_errors=True)
        for name, text in files.items():
            path = os.path.join(cls.autograder, 'submission', name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, 'w', encoding='utf-8') as f:
                f.write(text)
        proc = cls.sandboxed(['/autograder/run_autograder'], **env)
        try:
            with open(os.path.join(cls.autograder, 'results', 'results.json'),
                      encoding='utf-8') as f:
                return proc, json.load(f)
        except (OSError, ValueError):
            return proc, None

    def assertGradescopeFormat(self, data):
        self.assertIsInstance(data['score'], (int, float))
        for test in data['tests']:
            for key in ('name', 'score', 'max_score', 'output', 'visibility'):
                self.assertIn(key, test)
            self.assertIn(test['visibility'], ('visible', 'hidden', 'after_due_date',
                                               'after_published'))

    def expected_tests(self):
        return {'%s %s' % (e, name): hidden for e in self.assignment['exercises']
                for name, hidden in tests_of(e).items()}

    def test_zip_holds_the_scripts_at_its_top_and_what_is_graded(self):
        for name in ('setup.sh', 'run_autograder', 'grade_flags', 'course.toml',
                     'tools/grading/grade.py', 'tools/deps.sh', CHAPTER, 'tests/calls/judge.cpp'):
            self.assertIn(name, self.names)
        self.assertFalse([n for n in self.names if n.startswith(('tests/tools/', 'build/'))])
        with zipfile.ZipFile(self.zip) as z:
            flags = [line for line in z.read('grade_flags').decode().split('\n')
                     if line and not line.startswith('#')]
            for name in ('setup.sh', 'run_autograder'):
                self.assertTrue((z.getinfo(name).external_attr >> 16) & stat.S_IXUSR)
        self.assertEqual(flags, ['--plan', 'course.toml', '--assignment', ASSIGNMENT,
                                 '--time-limit', '5'])

    def test_setup_installs_nothing_more_and_warms_the_cache(self):
        self.assertEqual(self.setup.returncode, 0, self.setup.stdout + self.setup.stderr)
        total = sum(self.assignment['points'].get(e, 0) for e in self.assignment['exercises'])
        self.assertIn('score %g of %g' % (total, total), self.setup.stdout)
        cache = os.path.join(self.autograder, 'source', 'build', 'grade', 'cache')
        self.assertTrue([n for n in os.listdir(cache) if n.startswith('judge-05-')])
        self.assertTrue([n for n in os.listdir(cache) if n.startswith('worker-05-')])

    def test_solution_scores_the_plans_points(self):
        proc, data = self.solution
        self.assertIsNotNone(data, proc.stdout + proc.stderr)
        self.assertGradescopeFormat(data)
        points = self.assignment['points']
        self.assertEqual(data['max_score'], sum(points.values()))
        self.assertAlmostEqual(data['score'], sum(points.values()), places=3)
        expected = self.expected_tests()
        self.assertEqual(sorted(t['name'] for t in data['tests']), sorted(expected))
        for test in data['tests']:
            exercise = test['name'].split()[0]
            share = points[exercise] / len(tests_of(exercise))
            self.assertAlmostEqual(test['max_score'], share, places=3)
            self.assertAlmostEqual(test['score'], share, places=3)
            self.assertEqual(test['visibility'], 'after_published'
                             if expected[test['name']] else 'visible')

    def test_stub_scores_nothing_and_says_why(self):
        proc, data = self.stub
        self.assertIsNotNone(data, proc.stdout + proc.stderr)
        self.assertGradescopeFormat(data)
        self.assertEqual(data['score'], 0)
        self.assertEqual(data['max_score'], sum(self.assignment['points'].values()))
        self.assertEqual(sorted(t['name'] for t in data['tests']),
                         sorted(self.expected_tests()))
        for test in data['tests']:
            self.assertEqual(test['score'], 0)
            exercise = test['name'].split()[0]
            if not self.expected_tests()[test['name']]:
                self.assertIn('Exercise %s is not done yet' % exercise, test['output'])

    def test_grade_flags_from_the_environment(self):
        self.assertEqual(self.stub[1]['extra_data']['secret'], 4242)
        self.assertNotEqual(self.solution[1]['extra_data']['secret'], 4242)


if __name__ == '__main__':
    unittest.main()
