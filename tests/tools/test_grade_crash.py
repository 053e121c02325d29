"""A crash in one exercise costs no other exercise a point (docs/grading.md).

A chapter-5 submission whose ex-5.9 calls exit(0) in every call, and whose
other exercises are the book's code, must score exactly the other exercises'
points, however many workers the crashing exercise goes through. The grader
runs here under a parent that never reaps orphans, as in a container whose
first process is no init: whatever the sandboxes leave behind stays there,
counts against the sandbox user's process limit, and is counted by the test.
Both isolation modes: bubblewrap, and the fallback without namespaces (a
`bwrap` on PATH that fails, as where a container forbids namespaces)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import test_grade as tg  # noqa: E402

# Runs the grader as a child subreaper that never waits for anything but the
# grader: every process that a grading leaves becomes its child, and is
# listed, alive or a zombie, once the grading is over.
NEVER_REAPS = r'''
import ctypes, json, os, subprocess, sys
PR_SET_CHILD_SUBREAPER = 36
ctypes.CDLL(None).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
status = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL).returncode
left = []
for pid in filter(str.isdigit, os.listdir('/proc')):
    try:
        with open('/proc/%s/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
    except OSError:
        continue
    if int(fields[1]) == os.getpid():
        left.append(pid + ' ' + fields[0])
print(json.dumps({'status': status, 'left': left}))
'''


class CrashInOneExerciseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        book = tg.book_exercises()
        owner = {f: e for e, x in book.items() for f in x['fragments']}
        cls.crashing = owner[tg.F9]
        cls.others = {e: x['points'] for e, x in book.items()
                      if x['chapter'] == '05' and e != cls.crashing}
        cls.tmp = tempfile.mkdtemp(prefix='lrt-grade-crash-')
        chapter = os.path.join(cls.tmp, 'submission', tg.CHAPTER)
        os.makedirs(os.path.dirname(chapter))
        with open(chapter, 'w', encoding='utf-8') as f:
            f.write(tg.inject(tg.read(os.path.join(tg.ROOT, tg.CHAPTER)), tg.F9,
                              '__builtin_exit(0);'))
        # A failing bwrap, for the fallback.
        cls.no_bwrap = os.path.join(cls.tmp, 'no-bwrap')
        os.makedirs(cls.no_bwrap)
        with open(os.path.join(cls.no_bwrap, 'bwrap'), 'w') as f:
            f.write('#!/bin/sh\necho "bwrap: No permissions to create new namespace" >&2\n'
                    'exit 1\n')
        os.chmod(os.path.join(cls.no_bwrap, 'bwrap'), 0o755)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def grade(self, mode, fallback):
        out = os.path.join(self.tmp, mode)
        env = dict(os.environ)
        if fallback:
            env['PATH'] = self.no_bwrap + os.pathsep + env['PATH']
        proc = subprocess.run(
            [sys.executable, '-c', NEVER_REAPS, sys.executable, tg.GRADE,
             '--cache', os.path.join(self.tmp, 'cache-' + mode), '--out', out,
             '--chapters', '05', '--time-limit', str(tg.TIME_LIMIT),
             os.path.join(self.tmp, 'submission')],
            cwd=tg.ROOT, env=env, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        ended = json.loads(proc.stdout)
        self.assertEqual(ended['status'], 0, proc.stderr)
        with open(os.path.join(out, 'results.json'), encoding='utf-8') as f:
            results = json.load(f)
        self.assertIn(mode, results['output'])
        for test in results['tests']:
            exercise = test['name'].split()[0]
            if exercise == self.crashing:
                self.assertEqual(test['status'], 'failed', test['name'])
                self.assertIn('CRASH', test['output'], test['name'])
            else:
                self.assertEqual(test['status'], 'passed', (test['name'], test['output']))
        self.assertAlmostEqual(results['score'], sum(self.others.values()), places=3)
        # Nothing of the grading is left: no process and no zombie.
        self.assertEqual(ended['left'], [])

    @unittest.skipUnless(os.geteuid() == 0, 'the sandbox drops to its own user only as root')
    def test_bubblewrap(self):
        self.grade('bubblewrap', fallback=False)

    @unittest.skipUnless(os.geteuid() == 0, 'the fallback needs root')
    def test_fallback_without_namespaces(self):
        self.grade('unprivileged user', fallback=True)


if __name__ == '__main__':
    unittest.main()
